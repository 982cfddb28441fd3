"""Animation of a body moving through the medium with its RFT traction arrows (GIF or MP4)."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError

__all__ = ["animate_body", "check_animation_path", "plot_time_series", "save_animation"]


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def plot_time_series(result: Any, *, axes: Any = None) -> Any:
    """Forward speed, spin, slip, sinkage and forces of a wheel simulation versus time."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    if axes is None:
        _, axes = plt.subplots(2, 2, figsize=(11, 6.5), sharex=True)
    a = np.asarray(axes).ravel()
    a[0].plot(result.t, result.vx, label="V_x [m/s]")
    a[0].plot(result.t, result.omega * result.nominal_radius, label=r"$\omega r$ [m/s]")
    a[1].plot(result.t, result.slip)
    a[2].plot(result.t, result.sinkage * 1e3)
    a[3].plot(result.t, result.fx, label="F_x (drawbar pull)")
    a[3].plot(result.t, result.fz, label="F_z")
    for ax, lab in zip(a, ("speed [m/s]", "slip [-]", "sinkage [mm]", "force [N]"), strict=True):
        ax.set_ylabel(lab)
    a[0].legend(fontsize=8)
    a[3].legend(fontsize=8)
    for ax in a[2:]:
        ax.set_xlabel("t [s]")
    return axes


def animate_body(
    body: Any,
    material: Any,
    result: Any,
    path: str | Path,
    *,
    frames: int = 80,
    fps: int = 20,
) -> Path:
    """Write an animation of ``body`` following the poses of a simulation ``result`` (GIF or MP4).

    Each frame draws the outline, the free surface and the RFT force on every loaded element.
    The file is written atomically; MP4 needs the ``imageio-ffmpeg`` extra.
    """
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation

    from ..kinematics import Pose2D, Twist2D, to_world
    from ..rft import rft_element_forces

    p = check_animation_path(path)
    if not (isinstance(frames, int) and 2 <= frames <= 2000):
        raise InputError("frames", frames, "an integer in [2, 2000]")
    idx = np.unique(np.linspace(0, len(result.t) - 1, frames).round().astype(int))
    outline = body.outline()
    radius = body.bounding_radius
    fig, ax = plt.subplots(figsize=(7, 3.5))
    forces_scale = max(float(np.max(np.abs(result.fz))), 1e-9)

    def draw(k: int) -> None:
        i = idx[k]
        ax.clear()
        pose = Pose2D(result.x[i], result.z[i], result.theta[i])
        twist = Twist2D(result.vx[i], result.vz[i], result.omega[i])
        el = rft_element_forces(body, material, pose, twist)
        for poly in outline:
            w = to_world(np.asarray(poly), pose)
            w = np.vstack((w, w[:1]))
            ax.plot(w[:, 0], w[:, 1], "k-", lw=1)
        act = el.active
        if np.any(act):
            f = el.forces[act] / forces_scale * radius * 40
            ax.quiver(
                el.positions[act, 0],
                el.positions[act, 1],
                f[:, 0],
                f[:, 1],
                color="tab:red",
                angles="xy",
                scale_units="xy",
                scale=1,
                width=0.003,
            )
        ax.axhline(0.0, color="tab:brown")
        ax.set_xlim(result.x[i] - 3 * radius, result.x[i] + 3 * radius)
        ax.set_ylim(-1.5 * radius, 1.5 * radius)
        ax.set_aspect("equal")
        ax.set_title(f"t = {result.t[i]:.3f} s, slip = {result.slip[i]:.3f}")

    anim = FuncAnimation(fig, draw, frames=len(idx))
    try:
        return save_animation(anim, p, fps=fps, field="--animate")
    finally:
        plt.close(fig)


def check_animation_path(path: str | Path, field: str = "--animate") -> Path:
    """``path`` as a Path if it ends in .gif/.mp4 and its folder exists (check before computing)."""
    p = Path(path)
    if p.suffix.lower() not in (".gif", ".mp4"):
        raise InputError(field, str(path), "a file ending in .gif or .mp4")
    if p.parent and not p.parent.exists():
        raise InputError(field, str(path), "a path in an existing folder")
    return p


def save_animation(anim: Any, path: str | Path, *, fps: int, field: str) -> Path:
    """Save a matplotlib animation as GIF (Pillow) or MP4 (imageio-ffmpeg) atomically."""
    import matplotlib
    from matplotlib.animation import FFMpegWriter, PillowWriter

    p = check_animation_path(path, field)
    suffix = p.suffix.lower()
    if not (isinstance(fps, int) and 1 <= fps <= 120):
        raise InputError("fps", fps, "an integer in [1, 120]")
    if suffix == ".gif":
        writer: Any = PillowWriter(fps=fps)
    else:
        try:
            import imageio_ffmpeg

            matplotlib.rcParams["animation.ffmpeg_path"] = imageio_ffmpeg.get_ffmpeg_exe()
        except ImportError:
            raise InputError(field, str(path), "a .gif, or install terradyn[video] for MP4") from None
        writer = FFMpegWriter(fps=fps)
    fd, tmp = tempfile.mkstemp(prefix=f".{p.stem}.", suffix=suffix, dir=p.parent or Path("."))
    os.close(fd)
    try:
        anim.save(tmp, writer=writer)
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, p)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return p
