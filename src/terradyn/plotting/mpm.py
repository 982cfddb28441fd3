"""MPM fields: particle velocity magnitude and pressure maps, and animations of a run's frames."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError

__all__ = ["animate_frames", "plot_fields"]

_LABELS = {
    "speed": ("|v| [m/s]", "viridis"),
    "pressure": ("pressure [kPa]", "magma"),
    "plastic_shear_rate": ("plastic shear rate [1/s]", "inferno"),
    "density": ("density [kg/m^3]", "cividis"),
}


def _values(fields: dict[str, Any], quantity: str) -> np.ndarray:
    if quantity == "speed":
        if "speed" in fields:
            return np.asarray(fields["speed"], dtype=float)
        return np.hypot(np.asarray(fields["vx"], dtype=float), np.asarray(fields["vz"], dtype=float))
    if quantity not in fields:
        raise InputError("quantity", quantity, f"one of {sorted(_LABELS)} present in the fields")
    v = np.asarray(fields[quantity], dtype=float)
    return v / 1e3 if quantity == "pressure" else v


def _draw(ax: Any, fields: dict[str, Any], quantity: str, segments: Any, vmax: float | None) -> Any:
    from matplotlib.collections import LineCollection

    label, cmap = _LABELS.get(quantity, (quantity, "viridis"))
    v = _values(fields, quantity)
    hi = vmax if vmax is not None else float(np.percentile(v, 99.5)) if len(v) else 1.0
    lo = 0.0 if quantity in ("speed", "pressure", "plastic_shear_rate") else float(np.min(v))
    sc = ax.scatter(
        np.asarray(fields["x"]),
        np.asarray(fields["z"]),
        c=v,
        s=2.0,
        cmap=cmap,
        vmin=lo,
        vmax=max(hi, lo + 1e-12),
        linewidths=0,
        rasterized=True,
    )
    if segments is not None and len(segments):
        ax.add_collection(LineCollection(list(np.asarray(segments)), colors="k", linewidths=1.2))
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    return sc, label


def plot_fields(
    fields: dict[str, Any],
    *,
    segments: Any = None,
    quantities: tuple[str, ...] = ("speed", "pressure"),
    title: str | None = None,
    window: tuple[float, float, float, float] | None = None,
) -> Any:
    """A figure with one particle map per quantity (``speed``, ``pressure``, ``plastic_shear_rate``,
    ``density``); ``segments`` (S, 2, 2) is the body outline in the world; ``window`` =
    (x_min, x_max, z_min, z_max) [m] crops the view."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    if not quantities:
        raise InputError("quantities", quantities, "at least one quantity")
    fig, axes = plt.subplots(len(quantities), 1, figsize=(8, 3.2 * len(quantities)), squeeze=False)
    for ax, q in zip(axes[:, 0], quantities, strict=True):
        sc, label = _draw(ax, fields, q, segments, None)
        fig.colorbar(sc, ax=ax, label=label, shrink=0.9)
        if window is not None:
            ax.set_xlim(window[0], window[1])
            ax.set_ylim(window[2], window[3])
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    return fig


def animate_frames(
    frames: list[dict[str, Any]],
    path: str | Path,
    *,
    quantity: str = "speed",
    fps: int = 12,
    window: tuple[float, float, float, float] | None = None,
) -> Path:
    """Write the frames of an MPM run (``result.frames``) as a GIF or MP4 of one particle quantity.

    The colour scale is fixed over the whole animation (99.5th percentile of all frames). The file is
    written atomically; MP4 needs the ``imageio-ffmpeg`` extra.
    """
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation

    from .animation import check_animation_path, save_animation

    check_animation_path(path, "--animate")
    if len(frames) < 2:
        raise InputError("frames", len(frames), "at least 2 frames (run with frame_count >= 2)")
    vmax = max(float(np.percentile(_values(f, quantity), 99.5)) for f in frames)
    fig, ax = plt.subplots(figsize=(8, 3.5))
    label = _LABELS.get(quantity, (quantity, ""))[0]
    first = _draw(ax, frames[0], quantity, frames[0].get("segments"), vmax)[0]
    fig.colorbar(first, ax=ax, label=label, shrink=0.9)

    def draw(k: int) -> None:
        f = frames[k]
        for coll in list(ax.collections):
            coll.remove()
        _draw(ax, f, quantity, f.get("segments"), vmax)
        if window is not None:
            ax.set_xlim(window[0], window[1])
            ax.set_ylim(window[2], window[3])
        ax.set_title(f"t = {float(f['time_s']):.3f} s")

    draw(0)
    anim = FuncAnimation(fig, draw, frames=len(frames))
    try:
        return save_animation(anim, path, fps=fps, field="--animate")
    finally:
        plt.close(fig)
