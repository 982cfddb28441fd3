"""MPM fields: particle velocity magnitude and pressure maps, and animations of a run's frames."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError

__all__ = ["animate_frames", "plot_fields", "plot_mpm_history"]

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


def _marker_area(ax: Any, fields: dict[str, Any]) -> float:
    """Scatter marker area [pt^2] so that particles about touch (spacing from the bed's extent)."""
    x, z = np.asarray(fields["x"], dtype=float), np.asarray(fields["z"], dtype=float)
    if len(x) < 2:
        return 4.0
    spacing = np.sqrt(max(float(np.ptp(x) * np.ptp(z)), 1e-12) / len(x))
    width_pt = ax.get_position().width * ax.figure.get_figwidth() * 72.0
    pt_per_m = width_pt / max(float(np.ptp(x)), 1e-9)
    return float(np.clip((0.7 * spacing * pt_per_m) ** 2, 0.5, 30.0))


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
        s=_marker_area(ax, fields),
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


def _clip_window(
    fields: dict[str, Any], window: tuple[float, float, float, float] | None, segments: Any = None
) -> tuple[float, float, float, float] | None:
    """``window`` cut to the extent of the particles and the body (plus 5 %): no empty margins."""
    if window is None or not len(fields["x"]):
        return window
    x, z = np.asarray(fields["x"], dtype=float), np.asarray(fields["z"], dtype=float)
    if segments is not None and len(segments):
        pts = np.asarray(segments, dtype=float).reshape(-1, 2)
        x, z = np.concatenate((x, pts[:, 0])), np.concatenate((z, pts[:, 1]))
    pad = 0.05 * max(float(np.ptp(x)), float(np.ptp(z)), 1e-9)
    lo_x, hi_x = max(window[0], float(x.min()) - pad), min(window[1], float(x.max()) + pad)
    lo_z, hi_z = max(window[2], float(z.min()) - pad), min(window[3], float(z.max()) + pad)
    if lo_x >= hi_x or lo_z >= hi_z:
        return window
    return (lo_x, hi_x, lo_z, hi_z)


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
    fig, axes = plt.subplots(
        len(quantities), 1, figsize=(8, 3.2 * len(quantities)), squeeze=False, layout="constrained"
    )
    window = _clip_window(fields, window, segments)
    for ax, q in zip(axes[:, 0], quantities, strict=True):
        sc, label = _draw(ax, fields, q, segments, None)
        fig.colorbar(sc, ax=ax, label=label, shrink=0.9)
        if window is not None:
            ax.set_xlim(window[0], window[1])
            ax.set_ylim(window[2], window[3])
    if title:
        fig.suptitle(title)
    return fig


def animate_frames(
    frames: list[dict[str, Any]],
    path: str | Path,
    *,
    quantity: str = "speed",
    fps: int = 12,
    window: tuple[float, float, float, float] | None = None,
    progress: Any = None,
    vmax: float | None = None,
) -> Path:
    """Write the frames of an MPM run (``result.frames``) as a GIF or MP4 of one particle quantity.

    The colour scale is fixed over the whole animation: 0 to ``vmax`` (in the quantity's plotted
    unit), by default the 99.5th percentile of all frames. The file is written atomically; MP4 needs
    the ``imageio-ffmpeg`` extra.
    """
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation

    from .animation import check_animation_path, save_animation

    check_animation_path(path, "--animate")
    if len(frames) < 2:
        raise InputError("frames", len(frames), "at least 2 frames (run with frame_count >= 2)")
    if vmax is None:
        vmax = max(float(np.percentile(_values(f, quantity), 99.5)) for f in frames)
    fig, ax = plt.subplots(figsize=(8, 3.5), layout="constrained")
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
        return save_animation(anim, path, fps=fps, field="--animate", progress=progress)
    finally:
        plt.close(fig)


def _wheel_radius(result: Any, radius: float | None) -> float | None:
    """The wheel's nominal radius [m]: given, in the metadata, or recovered from the summary's slip."""
    if radius is not None:
        return float(radius)
    meta = getattr(result, "metadata", {}) or {}
    if meta.get("nominal_radius_m") is not None:
        return float(meta["nominal_radius_m"])
    s = result.summary
    if all(k in s for k in ("slip", "forward_velocity_m_s", "omega_rad_s")):
        # slip = 1 - V / (omega r): r follows wherever the wheel both spins and moves
        denom = float(s["omega_rad_s"]) * (1.0 - float(s["slip"]))
        if abs(denom) > 1e-12 and float(s["forward_velocity_m_s"]) != 0.0:
            r = float(s["forward_velocity_m_s"]) / denom
            return r if r > 0 else None
    return None


def _phase_marks(ax: Any, t: np.ndarray, phase: np.ndarray, *, names: bool) -> None:
    """Dotted lines where the run changes phase (e.g. sink -> drive), the phase names on top."""
    starts = np.concatenate(([0], np.flatnonzero(phase[1:] != phase[:-1]) + 1))
    for k in starts[1:]:
        ax.axvline(t[k], color="0.5", ls=":", lw=0.9)
    if names:
        for k in starts:
            ax.annotate(
                f" {phase[k]}",
                (t[k], 1.0),
                xycoords=("data", "axes fraction"),
                va="bottom",
                ha="left",
                fontsize=8,
                color="0.35",
            )


def plot_mpm_history(
    result: Any,
    *,
    kind: str = "wheel",
    title: str | None = None,
    radius: float | None = None,
) -> Any:
    """Time histories of an MPM run (:func:`terradyn.mpm.run_wheel` or ``run_intrusion``) as a Figure.

    One panel per quantity family, sharing the x axis:

    - ``kind="wheel"``: forces [N] (drawbar pull, vertical force, the load as a dashed line), drive
      torque [N m], sinkage [mm], slip [-] versus time [s]. Slip needs the nominal radius: ``radius`` [m],
      ``metadata["nominal_radius_m"]`` or, failing those, the one implied by the summary's slip.
      Dotted lines mark the phase changes (sinking in under the load, driving), named above the top
      panel.
    - ``kind="intrusion"``: forces F_x, F_z [N] and torque [N m] versus the depth of the body's
      reference point [mm], with the averaging window of the summary shaded.
    """
    if kind not in ("wheel", "intrusion"):
        raise InputError("kind", kind, "'wheel' or 'intrusion'")
    c = result.series
    if kind == "intrusion":
        fig = _intrusion_history(result, c)
    else:
        fig = _wheel_history(result, c, _wheel_radius(result, radius))
    if title is None:
        title = f"MPM {'wheel' if kind == 'wheel' else 'intrusion'}"
    if title:
        fig.suptitle(title)
    return fig


def _intrusion_history(result: Any, c: dict[str, np.ndarray]) -> Any:
    from .core import new_figure

    if "depth_m" not in c:
        raise InputError("result", "series without depth_m", "an intrusion result (run_intrusion)")
    fig, axes = new_figure(2, 1, figsize=(7.0, 5.6), sharex=True)
    a_force, a_torque = axes[:, 0]
    depth_mm = np.asarray(c["depth_m"]) * 1e3
    a_force.plot(depth_mm, c["force_x_N"], label="$F_x$ (horizontal)")
    a_force.plot(depth_mm, c["force_z_N"], label="$F_z$ (vertical)")
    a_torque.plot(depth_mm, c["torque_y_Nm"], color="C2", label="$T_y$ about +y")
    s = result.summary
    window = s.get("averaging_window_m")
    for ax in (a_force, a_torque):
        ax.axhline(0.0, color="0.6", lw=0.8)
        named = ax is a_torque  # the shared markers are named once, in the lower legend
        ax.axvline(0.0, color="tab:brown", lw=0.9, ls="--", label="free surface" if named else None)
        if window is not None and "depth_m" in s:
            lo, hi = (float(s["depth_m"]) + sgn * 0.5 * float(window) for sgn in (-1, 1))
            band = "averaging window" if named else None
            ax.axvspan(lo * 1e3, hi * 1e3, color="0.85", zorder=0, label=band)
        ax.grid(True, alpha=0.35)
        ax.legend(fontsize=8, loc="best")
    if "depth_m" in s:
        for key, style, lab in (("force_x_N", "C0o", None), ("force_z_N", "C1o", "summary (window mean)")):
            if key in s:
                a_force.plot([float(s["depth_m"]) * 1e3], [s[key]], style, ms=6, mec="k", label=lab)
        a_force.legend(fontsize=8, loc="best")
    a_force.set_ylabel("force on body [N]")
    a_torque.set_ylabel("torque [N m]")
    a_torque.set_xlabel("depth of reference point below the surface [mm]")
    return fig


def _wheel_history(result: Any, c: dict[str, np.ndarray], radius: float | None) -> Any:
    from .core import new_figure

    for key in ("time_s", "drawbar_pull_N", "force_z_N", "drive_torque_Nm", "sinkage_m"):
        if key not in c:
            raise InputError("result", f"series without {key}", "a wheel result (run_wheel)")
    t = np.asarray(c["time_s"], dtype=float)
    panels = 4 if radius is not None else 3
    fig, axes = new_figure(panels, 1, figsize=(7.5, 2.1 * panels + 0.6), sharex=True)
    a = axes[:, 0]
    a[0].plot(t, c["drawbar_pull_N"], label="drawbar pull $F_x$")
    a[0].plot(t, c["force_z_N"], label="vertical force $F_z$")
    load = result.summary.get("load_N")
    if load is not None:
        a[0].axhline(float(load), color="C1", ls="--", lw=0.9, label=f"load W = {float(load):g} N")
    a[0].set_ylabel("force [N]")
    a[1].plot(t, c["drive_torque_Nm"], color="C2", label="drive torque")
    a[1].set_ylabel("torque [N m]")
    a[2].plot(t, np.asarray(c["sinkage_m"]) * 1e3, color="C3", label="sinkage")
    a[2].set_ylabel("sinkage [mm]")
    if radius is not None:
        vx = np.asarray(c["vx_m_s"], dtype=float)
        wr = np.asarray(c["omega_rad_s"], dtype=float) * radius
        spinning = np.abs(wr) > 1e-9
        slip = np.full_like(wr, np.nan)
        slip[spinning] = 1.0 - vx[spinning] / wr[spinning]
        a[3].plot(t, slip, color="C4", label=f"slip $1 - V_x/(\\omega r)$, r = {radius * 1e3:.4g} mm")
        a[3].set_ylabel("slip [-]")
    phase = np.asarray(c["phase"]) if "phase" in c else None
    for ax in a:
        ax.axhline(0.0, color="0.6", lw=0.8)
        if phase is not None and phase.size:
            _phase_marks(ax, t, phase, names=ax is a[0])
        ax.grid(True, alpha=0.35)
        ax.legend(fontsize=8, loc="best")
    a[-1].set_xlabel("time [s]")
    return fig
