"""Library entry points: :func:`run_intrusion` and :func:`run_wheel` with frozen results.

All inputs are SI (angles in rad). Every bad input raises :class:`~terradyn.errors.InputError` naming
the field. Forces are the grains' force on the body [N] (the 2D per-width value times the body width);
torques are about +y through the body's reference point [N m].
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError, check_positive, check_range
from ..geometry import Body
from ..materials import Material
from .bodies import BodyState, ContactScheme, body_segments, effective_body, lowest_point
from .checkpoint import plain
from .model import BedPacking, GranularModel, Walls, default_settle_time, resolve_model
from .solver import BedGrid, Phase, ProgressCallback, Runner, make_bed, stable_time_step

__all__ = ["IntrusionResult", "WheelResult", "run_intrusion", "run_wheel"]


@dataclass(frozen=True, eq=False)
class _MPMResult:
    """Time series (``series``: unit-suffixed columns), a ``summary`` (JSON-able SI) and ``metadata``."""

    series: dict[str, np.ndarray]
    summary: dict[str, float]
    metadata: dict[str, Any] = field(default_factory=dict)
    final_particles: dict[str, np.ndarray] | None = None
    frames: list[dict[str, np.ndarray]] = field(default_factory=list)
    final_frame: dict[str, np.ndarray] | None = None

    def to_dataframe(self) -> Any:
        """The time series as a pandas DataFrame (metadata in ``attrs``)."""
        import pandas as pd

        df = pd.DataFrame({k: np.asarray(v) for k, v in self.series.items()})
        df.attrs.update(self.metadata)
        return df

    def to_dict(self) -> dict[str, Any]:
        """Summary and metadata as plain JSON-able values."""
        return {"summary": dict(self.summary), "metadata": dict(self.metadata)}


@dataclass(frozen=True, eq=False)
class IntrusionResult(_MPMResult):
    """Result of :func:`run_intrusion`; summary keys ``force_x_N``, ``force_z_N``, ``torque_y_Nm``."""


@dataclass(frozen=True, eq=False)
class WheelResult(_MPMResult):
    """Result of :func:`run_wheel`; summary adds ``sinkage_m``, ``drawbar_pull_N``, ``drive_torque_Nm``."""


@dataclass(frozen=True)
class _Common:
    """Validated settings shared by the run functions."""

    model: GranularModel
    cell_size: float
    cfl: float
    gravity: float
    packing: BedPacking
    bed_density: float | None
    particles_per_cell: int
    walls: Walls
    contact: ContactScheme


def _common(
    body,
    material,
    cell_size,
    cfl,
    gravity,
    packing,
    bed_density,
    particles_per_cell,
    walls,
    min_cells_across,
    overrides,
    contact=ContactScheme.TWO_FIELD,
) -> tuple[_Common, Body]:
    model = resolve_model(material, **overrides)
    scheme = ContactScheme.coerce(contact)
    if not isinstance(body, Body):
        raise InputError("body", body, "a terradyn.geometry Body")
    diameter = 2.0 * body.bounding_radius
    if cell_size is None:
        cell_size = diameter / 16.0
    check_positive("cell_size", cell_size)
    if int(min_cells_across) < 2:
        raise InputError("min_cells_across", min_cells_across, "an integer >= 2")
    if diameter / cell_size < min_cells_across:
        raise InputError(
            "cell_size",
            cell_size,
            f"at most {diameter / min_cells_across:.4g} m",
            f"put at least {min_cells_across} cells across the body (size {diameter:.4g} m)",
        )
    check_range("gravity", gravity, 0.01, 100.0, unit="m/s^2")
    check_range("cfl", cfl, 1e-3, 0.5, hint="explicit MPM is stable for cfl <= 0.5")
    try:
        packing = BedPacking(packing)
    except ValueError:
        raise InputError("packing", packing, "'consolidated' or 'unconsolidated'") from None
    common = _Common(
        model,
        float(cell_size),
        float(cfl),
        float(gravity),
        packing,
        bed_density,
        int(particles_per_cell),
        Walls.coerce(walls),
        scheme,
    )
    return common, effective_body(body, float(cell_size), scheme)


def _run_inputs(c: _Common, body: Body, named: dict[str, Any]) -> dict[str, Any]:
    """The inputs that identify a run (stored in its checkpoint): ``named`` inputs of the run
    function, then the shared settings. Output-only settings (checkpoint interval, snapshots,
    progress) and post-processing ones (the wheel's ``average_fraction``) are left out: they may
    change on resume."""
    return {
        **named,
        "body": body,
        "model": c.model,
        "cell_size": c.cell_size,
        "cfl": c.cfl,
        "gravity": c.gravity,
        "packing": c.packing,
        "bed_density": c.bed_density,
        "particles_per_cell": c.particles_per_cell,
        "walls": c.walls,
        "contact": c.contact.value,
    }


def _derived_inputs(runner: Runner, eff: Body) -> dict[str, Any]:
    """Quantities the run computes from its inputs; a checkpoint must match them too."""
    return {
        "mpm_body": eff,
        "grid": runner.grid,
        "dt": runner.dt,
        "record_every": runner.record_every,
        "frame_every": runner.frame_every,
        "phases": [[p.name, p.n_steps, p.damping, p.twist, p.free] for p in runner.phases],
        "particles": len(runner.particles),
        "pose": runner.body.pose,
        "load": runner.body.load,
        "mass": runner.body.mass,
        "inertia": runner.body.inertia,
    }


def _settle_time(c: _Common, depth: float, settle_time: float | None) -> float:
    if settle_time is None:
        settle_time = default_settle_time(c.model, depth, c.packing, c.gravity)
    return check_positive("settle_time", settle_time, allow_zero=True)


def _settle_phases(c: _Common, depth: float, settle_time: float, dt: float) -> list[Phase]:
    """Damped settling of the bed under gravity (the body waits above the surface)."""
    wave = c.model.wave_speed()
    n = max(1, round(settle_time / dt))
    return [Phase("settle", n, damping=wave / depth, twist=(0.0, 0.0, 0.0), free=(False, False))]


def _frame_every(frame_count: int, motion_steps: int, record_every: int) -> int:
    """Recorded rows between animation frames so that the motion phase gives about ``frame_count``."""
    if not (isinstance(frame_count, int | np.integer) and 0 <= frame_count <= 2000):
        raise InputError("frame_count", frame_count, "an integer in [0, 2000]")
    if frame_count == 0:
        return 0
    return max(1, round(motion_steps / record_every / frame_count))


def _execute(runner: Runner, resume: bool, eff: Body) -> float:
    """Run (or resume) ``runner``; returns the wall time [s]. A checkpoint is never removed here: one
    left by an earlier run is continued with ``resume`` or refused."""
    t0 = time.perf_counter()
    path = runner.checkpoint_path
    if isinstance(runner.fingerprint, dict):
        runner.fingerprint = plain({**runner.fingerprint, "derived": _derived_inputs(runner, eff)})
    if path is not None and path.is_dir():
        raise InputError(
            "checkpoint_path", str(path), "a file path, not a directory", "give a file such as run.npz"
        )
    if resume:
        if path is None:
            raise InputError("resume", True, "resume together with checkpoint_path", "give the file")
        runner.resume()
    elif path is not None and path.exists():
        raise InputError(
            "checkpoint_path",
            str(path),
            "a path with no checkpoint when resume is off",
            "a checkpoint of an earlier run is there; pass resume=True (CLI flag --resume) to "
            "continue it, or remove the file to start afresh",
        )
    runner.run()
    return time.perf_counter() - t0


def _series(runner: Runner, width: float, skip_phases: int) -> dict[str, np.ndarray]:
    tab = runner.table()
    keep = tab["phase"] >= skip_phases
    names = [p.name for p in runner.phases]
    out = {
        "time_s": tab["time_s"][keep],
        "phase": np.array([names[int(k)] for k in tab["phase"][keep]]),
        "x_m": tab["x_m"][keep],
        "z_m": tab["z_m"][keep],
        "theta_rad": tab["theta_rad"][keep],
        "vx_m_s": tab["vx_m_s"][keep],
        "vz_m_s": tab["vz_m_s"][keep],
        "omega_rad_s": tab["omega_rad_s"][keep],
        "force_x_N": tab["fx_per_width"][keep] * width,
        "force_z_N": tab["fz_per_width"][keep] * width,
        "torque_y_Nm": tab["ty_per_width"][keep] * width,
    }
    for name, col in out.items():
        if col.dtype.kind == "f" and not np.all(np.isfinite(col)):
            raise InputError(name, "non-finite values", "finite results")  # never leave silently
    return out


def _intrusion_bed(seg, c: _Common, depth, window, direction, angle, bed_depth, bed_width):
    """Bed and start pose for an intrusion: returns ``(grid, start pose (3,), travel [m])``.

    The body starts with its lowest point half a cell above the surface and moves along
    ``(cos d, -sin d)``; the bed is centred on where the reference point reaches ``depth``.
    """
    h = c.cell_size
    reach = float(np.max(np.hypot(seg[:, 0], seg[:, 1])))
    z_start = -lowest_point(seg, np.array([0.0, 0.0, angle])) + 0.5 * h
    z_end = -(depth + 0.5 * window)
    sin_d, cos_d = math.sin(direction), math.cos(direction)
    travel = (z_start - z_end) / sin_d
    x_at_depth = (z_start + depth) / sin_d * cos_d
    # Free-slip walls must lie beyond the failure mechanism (log-spiral fans reach several body sizes
    # and grow with depth); closer walls give the mechanism a frictionless slip surface.
    side = max(6.0 * reach, 2.5 * depth, 4.0 * h)
    below = max(4.0 * reach, 1.5 * depth, 4.0 * h)
    bed_depth = depth + 0.5 * window + reach + below if bed_depth is None else bed_depth
    x_path = sorted([-x_at_depth, -x_at_depth + travel * cos_d])
    if bed_width is None:
        bed_width = x_path[1] - x_path[0] + 2 * (reach + side)
    check_positive("bed_width", bed_width)
    x_left = 0.5 * (x_path[0] + x_path[1]) - 0.5 * bed_width
    grid = BedGrid(bed_width, bed_depth, z_start + reach + 4 * h, h, x_left, c.walls)
    if -(depth + 0.5 * window) - reach < -bed_depth + h:
        raise InputError(
            "bed_depth",
            bed_depth,
            f"deeper than {depth + 0.5 * window + reach + h:.4g} m",
            "the body must stay inside the bed",
        )
    if x_path[0] - reach < grid.x_left or x_path[1] + reach > grid.x_right:
        raise InputError("bed_width", bed_width, "wide enough for the body's path", "increase it")
    return grid, np.array([-x_at_depth, z_start, angle]), travel


def _runner(c: _Common, grid, state, dt, phases, record_every, reference_speed, io, key) -> Runner:
    """A :class:`Runner` with the bed made from ``c``; ``io`` = (snapshot_dir, snapshot_every,
    checkpoint_path, checkpoint_interval, progress); ``key`` = inputs that identify the run."""
    snap, snap_every, ckpt, interval, progress = io
    particles = make_bed(
        c.model,
        grid,
        packing=c.packing,
        density=c.bed_density,
        particles_per_cell=c.particles_per_cell,
        gravity=c.gravity,
    )
    return Runner(
        c.model,
        grid,
        particles,
        state,
        dt,
        phases,
        gravity=c.gravity,
        record_every=record_every,
        reference_speed=reference_speed,
        fingerprint=key,
        checkpoint_path=None if ckpt is None else Path(ckpt),
        checkpoint_interval=check_positive("checkpoint_interval", interval),
        snapshot_dir=None if snap is None else Path(snap),
        snapshot_every=snap_every,
        progress=progress,
    )


def run_intrusion(
    body: Body,
    material: Material | GranularModel,
    *,
    depth: float,
    direction: float = math.pi / 2,
    angle: float = 0.0,
    speed: float = 0.05,
    cell_size: float | None = None,
    bed_depth: float | None = None,
    bed_width: float | None = None,
    packing: BedPacking | str = BedPacking.CONSOLIDATED,
    bed_density: float | None = None,
    walls: Walls | str | None = None,
    youngs_modulus: float | None = None,
    poisson_ratio: float | None = None,
    friction_coefficient: float | None = None,
    surface_friction: float | None = None,
    rate_dependent: bool = False,
    contact: ContactScheme | str = ContactScheme.TWO_FIELD,
    averaging_window: float | None = None,
    settle_time: float | None = None,
    cfl: float = 0.3,
    gravity: float = 9.81,
    particles_per_cell: int = 2,
    min_cells_across: int = 6,
    record_spacing: float | None = None,
    snapshot_dir: str | Path | None = None,
    snapshot_spacing: float | None = None,
    checkpoint_path: str | Path | None = None,
    checkpoint_interval: float = 60.0,
    resume: bool = False,
    progress: ProgressCallback | None = None,
    frame_count: int = 0,
) -> IntrusionResult:
    """Push ``body`` at constant velocity into a settled bed and report the force at ``depth``.

    The body, rotated by ``angle`` [rad] about +y, starts with its lowest point just above the free
    surface (z = 0) and moves at ``speed`` [m/s] along ``direction`` [rad] below the +x axis
    (pi/2 = straight down). The summary averages force and torque over the rows where the reference
    point's depth is within ``averaging_window`` [m] (default ``max(4 cell_size, 0.2 depth)``) centred on
    ``depth`` [m]; the run stops when the window has been passed.

    Parameters (others)
    -------------------
    cell_size : grid spacing [m]; default body diameter / 16; at least ``min_cells_across`` cells across.
    bed_depth, bed_width : bed size [m]; defaults leave max(6 body radii, 2.5 depth) of grains beside the
        path and max(4 radii, 1.5 depth) below it: nearer free-slip walls cut the failure mechanism
        and lower the force at depth (checked: walls 5 plate lengths away already do).
    packing, bed_density : initial state (:class:`BedPacking`) and density [kg/m^3].
    walls : :class:`Walls` or one kind for all sides ('free-slip', 'no-slip', 'frictional').
    youngs_modulus, poisson_ratio, friction_coefficient, surface_friction, rate_dependent : overrides of
        the material's continuum parameters.
    contact : grid contact scheme (:class:`~terradyn.mpm.bodies.ContactScheme`): ``"two-field"``
        (default; bodies need no thickness, composites and placed bodies as bare ones) or the legacy
        ``"cover"`` (plates thickened to three cells).
    record_spacing : travel [m] per recorded row (forces are averaged over it); default cell_size / 4.
    snapshot_dir, snapshot_spacing : write particle NetCDF snapshots every ``snapshot_spacing`` [m] of travel.
    checkpoint_path, checkpoint_interval, resume : checkpoint file (.npz), wall-clock seconds between
        checkpoints, and whether to continue from an existing checkpoint.
    progress : callable ``(simulated_time_s, fraction_done)``.
    frame_count : keep about this many light copies of the state during the motion (``result.frames``,
        for :func:`terradyn.plotting.mpm.animate_frames`); 0 keeps none. Frames are checkpointed.

    Checkpoints: an existing ``checkpoint_path`` is never overwritten or removed by a fresh run
    (:class:`~terradyn.errors.InputError` unless ``resume``); a finished run keeps its final
    checkpoint, and resuming it returns the result without stepping. A checkpoint only resumes a run
    with the same inputs (output settings such as ``checkpoint_interval``, ``snapshot_dir`` and
    ``progress`` may change). On KeyboardInterrupt the state at the end of the last completed chunk
    is checkpointed and :class:`~terradyn.mpm.solver.RunInterrupted` is raised.
    """
    overrides = dict(
        youngs_modulus=youngs_modulus,
        poisson_ratio=poisson_ratio,
        friction_coefficient=friction_coefficient,
        surface_friction=surface_friction,
        rate_dependent=rate_dependent,
    )
    shared = (cell_size, cfl, gravity, packing, bed_density, particles_per_cell, walls, min_cells_across)
    c, eff = _common(body, material, *shared, overrides, contact)
    h = c.cell_size
    check_positive("depth", depth)
    check_range(
        "direction",
        direction,
        math.radians(5.0),
        math.radians(175.0),
        unit="rad",
        hint="the body must enter the bed from the surface",
    )
    angle = check_range("angle", angle, -2 * math.pi, 2 * math.pi, unit="rad")
    check_positive("speed", speed)
    window = max(4.0 * h, 0.2 * depth) if averaging_window is None else averaging_window
    check_positive("averaging_window", window)
    seg = body_segments(eff, h)
    grid, pose0, travel = _intrusion_bed(seg, c, depth, window, direction, angle, bed_depth, bed_width)
    sin_d, cos_d = math.sin(direction), math.cos(direction)
    model = c.model
    dt = stable_time_step(model, h, cfl=c.cfl, speed=speed)
    settle = _settle_time(c, grid.depth, settle_time)
    vel = (speed * cos_d, -speed * sin_d, 0.0)
    n_move = max(1, math.ceil(travel / speed / dt))
    phases = [
        *_settle_phases(c, grid.depth, settle, dt),
        Phase("intrude", n_move, twist=vel, free=(False, False)),
    ]
    spacing = 0.25 * h if record_spacing is None else check_positive("record_spacing", record_spacing)
    record_every = max(1, round(spacing / speed / dt))
    state = BodyState(
        seg=seg,
        pose=pose0,
        twist=np.zeros(3),
        free=np.zeros(2, dtype=np.bool_),
        mass=1.0,
        load=np.zeros(2),
        friction=model.surface_friction,
        width=body.width,
        contact=c.contact,
    )
    snap_every = 0
    if snapshot_dir is not None:
        s_sp = 4 * h if snapshot_spacing is None else check_positive("snapshot_spacing", snapshot_spacing)
        snap_every = max(1, round(s_sp / (record_every * dt * speed)))
    io = (snapshot_dir, snap_every, checkpoint_path, checkpoint_interval, progress)
    named = dict(
        run="intrusion",
        depth=depth,
        direction=direction,
        angle=angle,
        speed=speed,
        averaging_window=window,
        settle_time=settle,
        bed_width=grid.width,
        bed_depth=grid.depth,
        frame_count=frame_count,
    )
    key = _run_inputs(c, body, named)
    runner = _runner(c, grid, state, dt, phases, record_every, speed, io, key)
    runner.frame_every = _frame_every(frame_count, phases[-1].n_steps, record_every)
    wall = _execute(runner, resume, eff)
    series = _series(runner, body.width, skip_phases=1)
    series = {"depth_m": -series["z_m"], **series}
    sel = np.abs(series["depth_m"] - depth) <= 0.5 * window
    if not np.any(sel):  # pragma: no cover - the run always passes the window
        raise InputError("averaging_window", window, "a window containing recorded rows", "widen it")
    summary = {
        "depth_m": float(depth),
        "force_x_N": float(series["force_x_N"][sel].mean()),
        "force_z_N": float(series["force_z_N"][sel].mean()),
        "torque_y_Nm": float(series["torque_y_Nm"][sel].mean()),
        "direction_rad": float(direction),
        "angle_rad": float(angle),
        "speed_m_s": float(speed),
        "averaging_window_m": float(window),
    }
    meta = _metadata(runner, model, body, eff, wall)
    return IntrusionResult(series, summary, meta, runner.particles.fields(), runner.frames, runner.frame())


def _metadata(runner: Runner, model: GranularModel, body: Body, eff: Body, wall: float) -> dict[str, Any]:
    g = runner.grid
    return {
        "model": "terradyn MPM (plane strain, Dunatunga-Kamrin granular model, APIC, quadratic B-splines)",
        "citation": "S. Dunatunga, K. Kamrin, J. Fluid Mech. 779 (2015), doi:10.1017/jfm.2015.383",
        "friction_mapping": "mu = sin(phi) (plane-strain Drucker-Prager matched to Mohr-Coulomb)",
        "body": repr(body),
        "mpm_body": repr(eff),
        "granular_model": repr(model),
        "cell_size_m": g.cell_size,
        "contact": runner.body.contact.value,
        "bed_width_m": g.width,
        "bed_depth_m": g.depth,
        "walls": repr(g.walls),
        "particles": len(runner.particles),
        "dt_s": runner.dt,
        "steps": runner.step,
        "wall_time_s": wall,
        "width_m": body.width,
    }


def _nominal_radius(wheel: Body) -> float:
    r = getattr(wheel, "outer_radius", None)
    return float(r) if r is not None else float(wheel.bounding_radius)


def _wheel_bed(seg, c: _Common, travel, v_forward, bed_depth, bed_length):
    """Bed for a wheel run and its start pose (lowest point half a cell above the surface)."""
    h = c.cell_size
    reach = float(np.max(np.hypot(seg[:, 0], seg[:, 1])))
    margin = max(2.0 * reach, 4 * h)
    bed_depth = 2.0 * reach + margin if bed_depth is None else bed_depth
    bed_length = travel + 2.0 * (reach + margin) if bed_length is None else bed_length
    check_positive("bed_length", bed_length)
    x_start = -0.5 * travel if v_forward >= 0 else 0.5 * travel
    grid = BedGrid(bed_length, bed_depth, 2.0 * reach + 4 * h, h, -0.5 * bed_length, c.walls)
    if 0.5 * travel + reach > 0.5 * bed_length:
        raise InputError(
            "bed_length", bed_length, f"at least {travel + 2 * reach:.4g} m", "the wheel leaves the bed"
        )
    pose0 = np.array([x_start, 0.0, 0.0])
    pose0[1] = -lowest_point(seg, pose0) + 0.5 * h
    return grid, pose0


def _wheel_summary(runner, width, seg, average_fraction, radius, load):
    """Time series with wheel columns, and the summary averaged over the end of the drive."""
    series = _series(runner, width, skip_phases=1)
    poses = zip(series["x_m"], series["z_m"], series["theta_rad"], strict=True)
    lows = np.array([lowest_point(seg, np.array(pose)) for pose in poses])
    series = {
        **series,
        "sinkage_m": -lows,
        "drawbar_pull_N": series["force_x_N"],
        "drive_torque_Nm": -series["torque_y_Nm"],
    }
    drive = np.flatnonzero(series["phase"] == "drive")
    sel = drive[int(len(drive) * (1.0 - average_fraction)) :]
    vx = float(series["vx_m_s"][sel].mean())
    omega = float(series["omega_rad_s"][sel].mean())
    summary = {
        "sinkage_m": float(series["sinkage_m"][sel].mean()),
        "drawbar_pull_N": float(series["drawbar_pull_N"][sel].mean()),
        "drive_torque_Nm": float(series["drive_torque_Nm"][sel].mean()),
        "force_z_N": float(series["force_z_N"][sel].mean()),
        "load_N": float(load),
        "omega_rad_s": omega,
        "forward_velocity_m_s": vx,
    }
    if omega != 0:
        summary["slip"] = float(1.0 - vx / (omega * radius))
    return series, summary


def run_wheel(
    wheel: Body,
    material: Material | GranularModel,
    *,
    load: float,
    omega: float | None = None,
    slip: float | None = None,
    drive_torque: float | None = None,
    drawbar_load: float = 0.0,
    max_omega: float = 5.0,
    inertia: float | None = None,
    duration: float | None = None,
    sink_time: float | None = None,
    average_fraction: float = 0.5,
    cell_size: float | None = None,
    bed_depth: float | None = None,
    bed_length: float | None = None,
    packing: BedPacking | str = BedPacking.CONSOLIDATED,
    bed_density: float | None = None,
    walls: Walls | str | None = None,
    youngs_modulus: float | None = None,
    poisson_ratio: float | None = None,
    friction_coefficient: float | None = None,
    surface_friction: float | None = None,
    rate_dependent: bool = False,
    contact: ContactScheme | str = ContactScheme.TWO_FIELD,
    settle_time: float | None = None,
    cfl: float = 0.3,
    gravity: float = 9.81,
    particles_per_cell: int = 2,
    min_cells_across: int = 8,
    record_interval: float | None = None,
    snapshot_dir: str | Path | None = None,
    snapshot_interval: float | None = None,
    checkpoint_path: str | Path | None = None,
    checkpoint_interval: float = 60.0,
    resume: bool = False,
    progress: ProgressCallback | None = None,
    frame_count: int = 0,
) -> WheelResult:
    """Drive a wheel (any body) over a settled bed under a vertical ``load`` [N].

    The wheel first sinks under its load for ``sink_time`` [s] (not spinning, vertical motion free,
    grains damped), then spins at ``omega`` [rad/s] about +y for ``duration`` [s]. With ``slip`` given
    the forward speed is prescribed, ``vx = (1 - slip) omega r`` (r: nominal outer radius), and the
    vertical motion is free under the load; with ``slip=None`` both translations are free
    (self-propelled). ``omega = 0`` with ``slip=None`` leaves a body resting under its load. The
    default ``duration`` is ``3 / |omega|``: starting from the pit it sank into, a wheel's pull and
    sinkage settle after about two radians of rotation (measured for a 0.13 m wheel on MS).

    Torque control: give ``drive_torque`` [N m] (+ drives forward) instead of ``omega``; the spin is
    then free, with moment of inertia ``inertia`` [kg m^2] (default a uniform disc of the load's mass,
    ``load / g r^2 / 2``), starting from rest, and the forward motion is free. The time step is sized
    for spins up to ``max_omega`` [rad/s]; a wheel that spins up beyond it (a torque the bed cannot
    resist) stops the run with :class:`~terradyn.mpm.MPMInstabilityError`. The default duration is
    then ``20 sqrt(r / g)``. ``drawbar_load`` [N] is a horizontal resisting force on the axle (a towed
    load, + backwards) whenever the forward motion is free.

    The summary averages the last ``average_fraction`` of the drive: ``sinkage_m`` (depth of the
    lowest point below z = 0), ``drawbar_pull_N`` (horizontal soil force, + forward),
    ``drive_torque_Nm`` (= -soil torque about +y at the axle), ``force_z_N``, ``slip`` (measured).
    Other keywords as in :func:`run_intrusion`; ``record_interval`` and ``snapshot_interval`` are in
    seconds of simulated time.
    """
    overrides = dict(
        youngs_modulus=youngs_modulus,
        poisson_ratio=poisson_ratio,
        friction_coefficient=friction_coefficient,
        surface_friction=surface_friction,
        rate_dependent=rate_dependent,
    )
    shared = (cell_size, cfl, gravity, packing, bed_density, particles_per_cell, walls, min_cells_across)
    c, eff = _common(wheel, material, *shared, overrides, contact)
    h = c.cell_size
    check_positive("load", load)
    torque_mode = drive_torque is not None
    if (omega is None) == (drive_torque is None):
        raise InputError("omega", omega, "exactly one of omega or drive_torque", "give one of them")
    torque, omega_cmd = 0.0, 0.0
    if drive_torque is not None:
        torque = check_range("drive_torque", drive_torque, -1e6, 1e6, unit="N m")
        if slip is not None:
            raise InputError("slip", slip, "None with drive_torque", "the spin is free under a torque")
        check_range("max_omega", max_omega, 1e-3, 200.0, unit="rad/s")
    elif omega is not None:
        omega_cmd = check_range("omega", omega, -200.0, 200.0, unit="rad/s")
    if slip is not None:
        slip = check_range("slip", slip, -1.0, 1.0)
        if drawbar_load != 0.0:
            raise InputError(
                "drawbar_load", drawbar_load, "0 when slip is given", "the forward speed is imposed"
            )
    check_range("drawbar_load", drawbar_load, -10.0 * load, 10.0 * load, unit="N")
    check_range("average_fraction", average_fraction, 0.05, 1.0)
    radius = _nominal_radius(wheel)
    seg = body_segments(eff, h)
    reach = float(np.max(np.hypot(seg[:, 0], seg[:, 1])))
    spin = max_omega if torque_mode else abs(omega_cmd)  # the largest spin the step must resolve
    if duration is None:
        duration = 3.0 / spin if not torque_mode and spin != 0 else 20.0 * math.sqrt(reach / c.gravity)
    check_positive("duration", duration)
    sink_time = 3.0 * math.sqrt(reach / c.gravity) if sink_time is None else sink_time
    check_positive("sink_time", sink_time, allow_zero=True)
    if torque_mode:
        v_forward = 0.0
        travel = spin * radius * duration
    else:
        v_forward = (1.0 - slip) * omega_cmd * radius if slip is not None else omega_cmd * radius
        travel = abs(v_forward) * duration
    direction = v_forward if not torque_mode else (1.0 if torque >= 0 else -1.0)
    grid, pose0 = _wheel_bed(seg, c, travel, direction, bed_depth, bed_length)
    model = c.model
    v_max = spin * reach + (spin * radius if torque_mode else abs(v_forward)) + math.sqrt(2 * c.gravity * h)
    dt = stable_time_step(model, h, cfl=c.cfl, speed=v_max)
    mass = load / c.gravity / wheel.width
    inertia_w = (
        0.5 * mass * radius**2 if inertia is None else check_positive("inertia", inertia) / wheel.width
    )
    state = BodyState(
        seg=seg,
        pose=pose0,
        twist=np.zeros(3),
        free=np.zeros(3, dtype=np.bool_),
        mass=mass,
        load=np.array([-drawbar_load / wheel.width, -load / wheel.width, torque / wheel.width]),
        friction=model.surface_friction,
        width=wheel.width,
        inertia=inertia_w,
        contact=c.contact,
    )
    wave = model.wave_speed()
    drive_twist = (v_forward if slip is not None else 0.0, 0.0, omega_cmd)
    settle = _settle_time(c, grid.depth, settle_time)
    phases = [
        *_settle_phases(c, grid.depth, settle, dt),
        Phase("sink", max(1, round(sink_time / dt)), damping=wave / grid.depth, free=(False, True, False)),
        Phase(
            "drive",
            max(1, round(duration / dt)),
            twist=drive_twist,
            free=(slip is None, True, torque_mode),
        ),
    ]
    interval = (
        duration / 200.0 if record_interval is None else check_positive("record_interval", record_interval)
    )
    record_every = max(1, round(interval / dt))
    snap_every = 0
    if snapshot_dir is not None:
        s_int = duration / 20.0 if snapshot_interval is None else snapshot_interval
        snap_every = max(1, round(check_positive("snapshot_interval", s_int) / (record_every * dt)))
    io = (snapshot_dir, snap_every, checkpoint_path, checkpoint_interval, progress)
    named = dict(
        run="wheel",
        load=load,
        omega=omega,
        slip=slip,
        drive_torque=drive_torque,
        drawbar_load=drawbar_load,
        max_omega=max_omega if torque_mode else None,
        inertia=inertia_w * wheel.width,
        duration=duration,
        sink_time=sink_time,
        settle_time=settle,
        bed_length=grid.width,
        bed_depth=grid.depth,
        frame_count=frame_count,
    )
    key = _run_inputs(c, wheel, named)
    runner = _runner(c, grid, state, dt, phases, record_every, v_max, io, key)
    runner.frame_every = _frame_every(frame_count, phases[-1].n_steps, record_every)
    wall = _execute(runner, resume, eff)
    series, summary = _wheel_summary(runner, wheel.width, seg, average_fraction, radius, load)
    summary["drawbar_load_N"] = float(drawbar_load)
    if torque_mode:
        summary["applied_torque_Nm"] = torque
    meta = _metadata(runner, model, wheel, eff, wall)
    meta["mode"] = "torque-driven" if torque_mode else "forced-slip" if slip is not None else "self-propelled"
    return WheelResult(series, summary, meta, runner.particles.fields(), runner.frames, runner.frame())
