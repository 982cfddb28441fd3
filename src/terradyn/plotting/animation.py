"""Animation of a body moving through the medium with its RFT traction arrows (GIF or MP4)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError
from .core import _nice, bin_arrows

__all__ = [
    "animate_body",
    "check_animation_path",
    "plot_body_frame",
    "plot_time_series",
    "save_animation",
]


def plot_time_series(result: Any, *, axes: Any = None) -> Any:
    """Speeds, spin, slip, sinkage, soil forces and motor torque of a wheel simulation versus time.

    ``result`` is a :class:`~terradyn.locomotion.dynamics.WheelDynamicsResult`. Returns the (3, 2)
    array of axes (pass ``axes`` with six entries to draw into existing ones).
    """
    if axes is None:
        from .core import new_figure

        _, axes = new_figure(3, 2, figsize=(11.0, 7.5), sharex=True)
    a = np.asarray(axes).ravel()
    t = np.asarray(result.t)
    a[0].plot(t, result.vx, label="forward speed $V_x$")
    a[0].plot(t, result.omega * result.nominal_radius, "--", label=r"rim speed $\omega r$")
    a[0].set_ylabel("speed [m/s]")
    a[1].plot(t, result.omega, color="C2", label=r"spin $\omega$")
    a[1].set_ylabel("spin [rad/s]")
    a[2].plot(t, result.slip, color="C4", label=r"slip $1 - V_x / (\omega r)$")
    a[2].set_ylabel("slip [-]")
    a[3].plot(t, np.asarray(result.sinkage) * 1e3, color="C3", label="sinkage")
    a[3].set_ylabel("sinkage [mm]")
    a[4].plot(t, result.fx, label="soil $F_x$ (drawbar pull)")
    a[4].plot(t, result.fz, label="soil $F_z$")
    weight = result.mass * result.gravity
    a[4].axhline(weight, color="C1", ls="--", lw=0.9, label=f"weight m g = {weight:.4g} N")
    a[4].set_ylabel("force [N]")
    a[5].plot(t, result.torque, color="C5", label="motor torque")
    a[5].set_ylabel("torque [N m]")
    for ax in a:
        ax.axhline(0.0, color="0.6", lw=0.8)
        ax.grid(True, alpha=0.35)
        ax.legend(fontsize=8, loc="best")
    for ax in a[-2:]:
        ax.set_xlabel("time [s]")
    return axes


_MAX_ARROWS = 12


class _BodyFrames:
    """Draws one frame of a body following a simulation: outline, rotation marker, tractions."""

    def __init__(self, body: Any, material: Any, result: Any) -> None:
        self.body, self.material, self.result = body, material, result
        self.outline = [np.asarray(poly) for poly in body.outline()]
        self.radius = float(getattr(result, "nominal_radius", None) or body.bounding_radius)
        # one vertical window for the whole run (the surface stays put), following the wheel in x
        z = np.asarray(result.z, dtype=float)
        self.zlim = (
            min(float(z.min()) - 1.6 * self.radius, -0.5 * self.radius),
            float(z.max()) + 1.4 * self.radius,
        )
        # arrows: the largest element force seen on a few sampled frames is drawn 0.4 radius long
        sample = np.unique(np.linspace(0, len(result.t) - 1, 12).round().astype(int))
        peak = max(float(np.max(np.hypot(*self._arrows(int(i))[1].T), initial=0.0)) for i in sample)
        peak = peak if peak > 0 else 1.0
        self.metres_per_newton = 0.4 * self.radius / peak
        self.key_force = _nice(0.5 * peak)

    def _forces(self, i: int) -> Any:
        from ..kinematics import Pose2D, Twist2D
        from ..rft import rft_element_forces

        r = self.result
        pose = Pose2D(float(r.x[i]), float(r.z[i]), float(r.theta[i]))
        return rft_element_forces(
            self.body, self.material, pose, Twist2D(float(r.vx[i]), float(r.vz[i]), float(r.omega[i]))
        )

    def _arrows(self, i: int) -> tuple[np.ndarray, np.ndarray, int]:
        """Loaded elements of row ``i`` summed in runs of ``k`` neighbours (see :func:`bin_arrows`)."""
        el = self._forces(i)
        return bin_arrows(el.positions[el.active], el.forces[el.active], _MAX_ARROWS)

    def draw(self, ax: Any, i: int) -> None:
        from ..kinematics import Pose2D, to_world

        r, res, rad = self.result, self.result, self.radius
        ax.clear()
        pose = Pose2D(float(r.x[i]), float(r.z[i]), float(r.theta[i]))
        ax.axhspan(self.zlim[0] - rad, 0.0, color="tan", alpha=0.35, lw=0, zorder=0)
        ax.axhline(0.0, color="saddlebrown", lw=1.2, label="free surface", zorder=1)
        ax.plot(res.x[: i + 1], res.z[: i + 1], color="0.4", ls=":", lw=1.0, label="axle path")
        for poly in self.outline:
            w = to_world(poly, pose)
            ax.fill(w[:, 0], w[:, 1], facecolor="0.85", edgecolor="k", lw=1.0, zorder=2)
        # a spoke from the axle to the rim and a dot on it: at theta = 0 it points straight down and it
        # turns with the wheel (clockwise in this view when it rolls forward)
        spoke = to_world(np.array([[0.0, 0.0], [0.0, -0.92 * rad]]), pose)
        ax.plot(spoke[:, 0], spoke[:, 1], color="tab:blue", lw=2.0, zorder=3, gid="rotation-marker")
        ax.plot(spoke[1:, 0], spoke[1:, 1], "o", color="tab:blue", ms=6, zorder=3, gid="rotation-dot")
        ax.plot([pose.x], [pose.z], "k+", ms=8, zorder=3)
        pos, force, k = self._arrows(i)
        if len(force):
            f = force * self.metres_per_newton
            q = ax.quiver(
                pos[:, 0],
                pos[:, 1],
                f[:, 0],
                f[:, 1],
                color="tab:red",
                angles="xy",
                scale_units="xy",
                scale=1,
                width=0.004,
                zorder=4,
            )
            per = "element" if k == 1 else f"{k} elements"
            ax.quiverkey(
                q,
                0.84,
                0.08,
                self.key_force * self.metres_per_newton,
                f"RFT force, {self.key_force:g} N per {per}",
                labelpos="N",
                coordinates="axes",
                fontproperties={"size": 8},
            )
        ax.set_xlim(pose.x - 3 * rad, pose.x + 3 * rad)
        ax.set_ylim(*self.zlim)
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("z [m]")
        ax.text(
            0.02,
            0.95,
            f"t = {float(r.t[i]):.3f} s",
            transform=ax.transAxes,
            va="top",
            family="monospace",
            bbox={"facecolor": "white", "alpha": 0.8, "lw": 0},
        )
        ax.set_title(
            f"slip = {float(r.slip[i]):.3f}, sinkage = {float(r.sinkage[i]) * 1e3:.1f} mm, "
            f"$V_x$ = {float(r.vx[i]):.3f} m/s"
        )
        ax.legend(loc="upper right", fontsize=8)


def plot_body_frame(body: Any, material: Any, result: Any, index: int, *, ax: Any = None) -> Any:
    """One frame of :func:`animate_body`: ``body`` at row ``index`` of a simulation ``result``.

    Draws the outline in the world [m], the free surface and the bed, the axle path so far, a spoke
    that turns with the wheel angle (``gid="rotation-marker"``), the RFT force on every loaded element
    with a scale arrow, and a time stamp. Returns the axes.
    """
    from .core import new_axes

    n = len(result.t)
    if not (isinstance(index, int | np.integer) and -n <= int(index) < n):
        raise InputError("index", index, f"an integer row of the result in [0, {n - 1}]")
    ax = new_axes(ax, figsize=(7.5, 4.0))
    _BodyFrames(body, material, result).draw(ax, int(index) % n)
    return ax


def animate_body(
    body: Any,
    material: Any,
    result: Any,
    path: str | Path,
    *,
    frames: int = 80,
    fps: int = 20,
    progress: Callable[[int, int], None] | None = None,
) -> Path:
    """Write an animation of ``body`` following the poses of a simulation ``result`` (GIF or MP4);
    ``progress(frame, frames)`` is called as frames are rendered.

    Each frame is :func:`plot_body_frame`: outline, free surface, rotation marker, RFT force on every
    loaded element, time stamp. The file is written atomically; MP4 needs the ``imageio-ffmpeg`` extra.
    """
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation

    p = check_animation_path(path)
    if not (isinstance(frames, int) and 2 <= frames <= 2000):
        raise InputError("frames", frames, "an integer in [2, 2000]")
    idx = np.unique(np.linspace(0, len(result.t) - 1, frames).round().astype(int))
    fig, ax = plt.subplots(figsize=(7.5, 4.0), layout="constrained")
    painter = _BodyFrames(body, material, result)
    anim = FuncAnimation(fig, lambda k: painter.draw(ax, int(idx[k])), frames=len(idx))
    try:
        return save_animation(anim, p, fps=fps, field="--animate", progress=progress)
    finally:
        plt.close(fig)


def check_animation_path(path: str | Path, field: str = "--animate") -> Path:
    """``path`` as a Path if an animation (.gif/.mp4) can be written there (check before computing)."""
    from ..io import check_output_file

    return check_output_file(field, path, suffixes=(".gif", ".mp4"), what="animation file")


def save_animation(
    anim: Any, path: str | Path, *, fps: int, field: str, progress: Callable[[int, int], None] | None = None
) -> Path:
    """Save a matplotlib animation as GIF (Pillow) or MP4 (imageio-ffmpeg) atomically (through
    :mod:`terradyn.io`, so inside a command it is part of the command's output set)."""
    import matplotlib
    from matplotlib.animation import FFMpegWriter, PillowWriter

    from ..io import atomic_write

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

    def _write(tmp: str) -> None:
        anim.save(tmp, writer=writer, progress_callback=progress)

    return atomic_write(p, _write, suffix=suffix, field_name=field)
