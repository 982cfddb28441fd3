"""Library entry points: :func:`run_intrusion` with a frozen result, and the pieces every run is built
from (wheels: :mod:`terradyn.mpm.wheel_runs`, drags: :mod:`terradyn.mpm.drag`).

All inputs are SI (angles in rad). The bed, the resolution, the outputs and the run length come as
specs (:mod:`terradyn.mpm.specs`: :class:`Bed`, :class:`Resolution`, :class:`Outputs`, :class:`Stroke`,
:class:`Drive`); shared helpers here build the bed, the settling phases and the runner from them, so a
new case is a new spec and a short function. Every bad input raises
:class:`~terradyn.errors.InputError` naming the field. Forces are the grains' force on the body [N]
(the 2D per-width value times the body width); torques are about +y through the body's reference
point [N m].
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, cast

import numpy as np

from ..errors import InputError, check_positive, check_range
from ..geometry import Body
from ..materials import Material
from .bodies import BodyState, ContactScheme, body_segments, effective_body, lowest_point
from .checkpoint import plain
from .model import BedPacking, GranularModel, Walls, default_settle_time, resolve_model
from .solver import BedGrid, ParticleState, Phase, Runner, make_bed, stable_time_step
from .specs import Bed, Drive, Outputs, Resolution, Stroke, apply_legacy

__all__ = ["IntrusionResult", "prescribed_body_setup", "run_intrusion"]


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


@dataclass(frozen=True)
class _Common:
    """The specs of a run after checking them against the body, with the model they resolve to."""

    model: GranularModel
    cell_size: float
    bed: Bed
    resolution: Resolution

    @property
    def contact(self) -> ContactScheme:
        return cast(ContactScheme, self.resolution.contact)  # coerced by Resolution

    @property
    def packing(self) -> BedPacking:
        return cast(BedPacking, self.bed.packing)  # coerced by Bed

    @property
    def walls(self) -> Walls:
        return cast(Walls, self.bed.walls)  # coerced by Bed

    @property
    def gravity(self) -> float:
        return self.bed.gravity


#: Default cells across an intruder's diameter. Measured on the snapped default bed (60 mm plate at
#: 40 mm depth, MS, classical update; docs/mpm.md, "Resolution"): 226.0 / 209.9 / 203.7 / 189.3 / 171.9
#: / 178.8 N at 6 / 8 / 12 / 16 / 20 / 24 cells across. The finest three ring (no Richardson value);
#: a least-squares fit F_0 + C h^2 gives F_0 = 164.7 +- 6.5 N over the finest four and 178.7 +- 5.3 N
#: over all six. 16 cells across read 15 % and 6 % above those limits, 20 cells 4 % above and 4 %
#: below: 20 is the coarsest level within the 10 % goal by both estimates (about twice the cost of 16).
INTRUSION_CELLS_ACROSS = 20


#: Clearance of the walls beside the path and of the floor below it, as multiples of the Prandtl
#: mechanism's heave extent and depth (see :func:`mechanism_clearance`).
WALL_MARGIN = 1.25
FLOOR_MARGIN = 2.5


def mechanism_clearance(friction_coefficient: float, width: float) -> tuple[float, float]:
    """Grains [m] to keep beside and below a body of ``width`` [m]: :data:`WALL_MARGIN` times the heave
    extent and :data:`FLOOR_MARGIN` times the depth of the Prandtl mechanism of a strip footing of that
    width, at Davis' friction angle ``atan(mu_s)`` (the plane-strain isochoric cone's collapse angle).

    Measured (60 mm plate at 40 mm depth, MS, 10 mm cells, 0.05 m/s): with the walls 0.18 m from the
    plate edges (0.73 heave extents, the earlier rule of six body radii) a 1.5x wider bed lowered the
    force by 12.4 %; at 1.25 extents (0.68 m bed) a 1.5x wider one changed it by +0.7 %. With the floor
    1.25 mechanism depths below the stroke (0.21 m bed) a 0.32 m bed raised the force by 17.9 %, and
    0.32 to 0.48 m changed it by -0.1 %. With both margins (0.68 m x 0.33 m bed, 226.4 N), a 1.5x wider
    bed changes the force by -1.1 % and a 1.5x deeper one by -0.1 %.
    """
    from ..plasticity.slipline import prandtl_extent

    extent = prandtl_extent(width, math.atan(friction_coefficient))
    return WALL_MARGIN * extent["heave_extent"], FLOOR_MARGIN * extent["max_depth"]


def _common(
    body: Body,
    material: Any,
    bed: Bed,
    resolution: Resolution,
    overrides: dict[str, Any],
    min_cells: int,
    default_cells: int,
) -> tuple[_Common, Body]:
    """Resolve the model, the cell size (default rule: body diameter / ``default_cells``, see
    :data:`INTRUSION_CELLS_ACROSS` and :data:`~terradyn.mpm.wheel_runs.WHEEL_CELLS_ACROSS`) and the
    MPM body."""
    model = resolve_model(material, **overrides)
    if not isinstance(body, Body):
        raise InputError("body", body, "a terradyn.geometry Body")
    diameter = 2.0 * body.bounding_radius
    cell_size = diameter / default_cells if resolution.cell_size is None else resolution.cell_size
    check_positive("cell_size", cell_size)
    n_min = min_cells if resolution.min_cells_across is None else resolution.min_cells_across
    if diameter / cell_size < n_min:
        raise InputError(
            "cell_size",
            cell_size,
            f"at most {diameter / n_min:.4g} m",
            f"put at least {n_min} cells across the body (size {diameter:.4g} m)",
        )
    common = _Common(model, float(cell_size), bed, resolution)
    return common, effective_body(body, float(cell_size), common.contact)


def _specs(function: str, legacy: dict[str, Any], exclude: str, **specs: Any) -> tuple[dict, dict]:
    """The specs with the flat keywords folded in (one table, :data:`terradyn.mpm.specs.LEGACY`)."""
    kinds = {"bed": Bed, "resolution": Resolution, "outputs": Outputs, "stroke": Stroke, "drive": Drive}
    for name, spec in specs.items():
        if not isinstance(spec, kinds[name]):
            raise InputError(name, spec, f"a terradyn.mpm.{kinds[name].__name__}")
    return apply_legacy(function, legacy, specs, exclude=frozenset({exclude}))


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
        "cfl": c.resolution.cfl,
        "gravity": c.bed.gravity,
        "packing": c.packing,
        "bed_density": c.bed.density,
        "particles_per_cell": c.resolution.particles_per_cell,
        "walls": c.walls,
        "contact": c.contact.value,
        # only when not the classical update, so checkpoints of earlier releases still resume
        **({"volumetric": c.resolution.volumetric} if c.resolution.volumetric != "point" else {}),
        **({"flip": c.resolution.flip} if c.resolution.flip else {}),
    }


def _derived_inputs(runner: Runner, eff: Body) -> dict[str, Any]:
    """Quantities the run computes from its inputs; a checkpoint must match them too."""
    return {
        "mpm_body": eff,
        "grid": runner.grid,
        "dt": runner.dt,
        "record_every": runner.record_every,
        "frame_every": runner.frame_every,
        "phases": [
            [p.name, p.n_steps, p.damping, p.twist, p.free, *([p.ramp_steps] if p.ramp_steps else [])]
            for p in runner.phases
        ],
        "particles": len(runner.particles),
        "pose": runner.body.pose,
        "load": runner.body.load,
        "mass": runner.body.mass,
        "inertia": runner.body.inertia,
        **({"window": runner.window} if runner.window > 0 else {}),
        **({"window_clearance": runner.window_clearance} if runner.window_clearance > 0 else {}),
    }


def _settle_phases(c: _Common, depth: float, dt: float) -> tuple[list[Phase], float]:
    """Damped settling of the bed under gravity (the body waits above the surface), and its time."""
    settle = settle_time(c.model, c.bed, depth)
    wave = c.model.wave_speed()
    n = max(1, round(settle / dt))
    return [Phase("settle", n, damping=wave / depth, twist=(0.0, 0.0, 0.0), free=(False, False))], settle


def settle_time(model: GranularModel, bed: Bed, depth: float) -> float:
    """The bed's settling time [s]: ``bed.settle_time`` or the default for a bed ``depth`` [m] deep."""
    if bed.settle_time is not None:
        return float(bed.settle_time)
    return default_settle_time(model, depth, BedPacking(bed.packing), bed.gravity)


def _frame_every(frame_count: int, motion_steps: int, record_every: int) -> int:
    """Recorded rows between animation frames so that the motion phase gives about ``frame_count``."""
    if frame_count == 0:
        return 0
    return max(1, round(motion_steps / record_every / frame_count))


def _output_every(outputs: Outputs, dt: float, speed: float | None, default_row: float, default_snap: float):
    """``(record_every, snapshot_every)`` in steps and rows. Intervals are simulated time [s]; with a
    ``speed`` [m/s] (an intrusion) spacings [m] of travel are taken too, and the defaults are spacings."""
    o = outputs
    if speed is None:
        for name in ("record_spacing", "snapshot_spacing"):
            if getattr(o, name) is not None:
                interval = name.replace("spacing", "interval")
                raise InputError(name, getattr(o, name), f"None for a wheel run: give {interval} [s]")
        row = default_row if o.record_interval is None else o.record_interval
        record_every = max(1, round(row / dt))
        snap = default_snap if o.snapshot_interval is None else o.snapshot_interval
        snap_every = max(1, round(snap / (record_every * dt)))
    else:
        given = o.record_spacing if o.record_interval is None else o.record_interval * speed
        row = default_row if given is None else given
        record_every = max(1, round(row / speed / dt))
        given = o.snapshot_spacing if o.snapshot_interval is None else o.snapshot_interval * speed
        snap = default_snap if given is None else given
        snap_every = max(1, round(snap / (record_every * dt * speed)))
    return record_every, snap_every if o.snapshot_dir is not None else 0


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


def _direction_vector(direction: float) -> tuple[float, float]:
    """``(cos, sin)`` of a motion direction [rad], exact at multiples of 90 deg: math.cos(pi / 2) is
    6e-17, which would start a body pushed straight down 1e-17 m off its axis and drift it sideways,
    so that a symmetric case is not its own mirror image."""
    c, s = math.cos(direction), math.sin(direction)
    if abs(c) < 1e-15:
        return 0.0, math.copysign(1.0, s)
    if abs(s) < 1e-15:
        return math.copysign(1.0, c), 0.0
    return c, s


def _intrusion_bed(seg, c: _Common, depth, window, direction, angle):
    """Bed and start pose for an intrusion: returns ``(grid, start pose (3,), travel [m])``.

    The body starts with its lowest point half a cell above the surface and moves along
    ``(cos d, -sin d)``; the bed is centred on where the reference point reaches ``depth``.
    """
    h = c.cell_size
    reach = float(np.max(np.hypot(seg[:, 0], seg[:, 1])))
    z_start = -lowest_point(seg, np.array([0.0, 0.0, angle])) + 0.5 * h
    z_end = -(depth + 0.5 * window)
    cos_d, sin_d = _direction_vector(direction)
    travel = (z_start - z_end) / sin_d
    x_at_depth = (z_start + depth) / sin_d * cos_d
    # Free-slip walls must lie beyond the failure mechanism; closer walls give it a frictionless slip
    # surface. Its size is the Prandtl mechanism of a strip of the body's width at Davis' angle
    # atan(mu_s) of the isochoric cone (see mechanism_clearance).
    side, below = mechanism_clearance(c.model.friction_coefficient, 2.0 * reach)
    side = max(side, 2.5 * depth, 4.0 * h)
    below = max(below, 1.5 * depth, 4.0 * h)
    bed_depth, bed_width = c.bed.depth, c.bed.width
    bed_depth = depth + 0.5 * window + reach + below if bed_depth is None else bed_depth
    x_path = sorted([-x_at_depth, -x_at_depth + travel * cos_d])
    if bed_width is None:
        bed_width = x_path[1] - x_path[0] + 2 * (reach + side)
    check_positive("bed_width", bed_width)
    x_left = 0.5 * (x_path[0] + x_path[1]) - 0.5 * bed_width
    grid = BedGrid(bed_width, bed_depth, z_start + reach + 4 * h, h, x_left, c.walls, c.bed.surface_offset)
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


def bed_particles(model: GranularModel, grid: BedGrid, bed: Bed, resolution: Resolution) -> ParticleState:
    """A fresh (unsettled) bed of ``model`` filling ``grid`` as ``bed`` and ``resolution`` say."""
    return make_bed(
        model,
        grid,
        packing=BedPacking(bed.packing),
        density=bed.density,
        particles_per_cell=resolution.particles_per_cell,
        gravity=bed.gravity,
    )


def _runner(c: _Common, grid, state, dt, phases, every, reference_speed, outputs: Outputs, key) -> Runner:
    """A :class:`Runner` over a fresh bed made from ``c``; ``every`` = (record_every, snapshot_every)
    as from :func:`_output_every`; ``key`` = the inputs that identify the run."""
    record_every, snapshot_every = every
    runner = Runner(
        c.model,
        grid,
        bed_particles(c.model, grid, c.bed, c.resolution),
        state,
        dt,
        phases,
        gravity=c.gravity,
        record_every=record_every,
        reference_speed=reference_speed,
        fingerprint=key,
        checkpoint_path=outputs.checkpoint_path,
        checkpoint_interval=outputs.checkpoint_interval,
        snapshot_dir=outputs.snapshot_dir,
        snapshot_every=snapshot_every,
        progress=outputs.progress,
        averaged_divergence=c.resolution.volumetric == "patch",
        flip=c.resolution.flip,
    )
    runner.frame_every = _frame_every(outputs.frame_count, phases[-1].n_steps, record_every)
    return runner


def prescribed_body_setup(
    function: str,
    body: Body,
    material: Material | GranularModel,
    legacy: dict[str, Any],
    bed: Bed,
    resolution: Resolution,
    outputs: Outputs,
    stroke: Stroke,
) -> tuple[dict[str, Any], _Common, Body]:
    """The specs (flat keywords folded in), the shared settings and the effective body of a run that
    moves a body along a prescribed path (``run_intrusion``, ``run_drag``): at least 6 cells and by
    default :data:`INTRUSION_CELLS_ACROSS` across the body."""
    specs, overrides = _specs(
        function, legacy, "bed_length", bed=bed, resolution=resolution, outputs=outputs, stroke=stroke
    )
    c, eff = _common(
        body,
        material,
        specs["bed"],
        specs["resolution"],
        overrides,
        min_cells=6,
        default_cells=INTRUSION_CELLS_ACROSS,
    )
    return specs, c, eff


@dataclass(frozen=True)
class _IntrusionPath:
    """The checked intrusion: ``depth`` [m] of the reading, ``direction`` [rad] below +x, body
    ``angle`` [rad], ``speed`` [m/s] and the averaging ``window`` [m] of depth centred on ``depth``."""

    depth: float
    direction: float
    angle: float
    speed: float
    window: float


def _intrusion_path(
    depth: float, direction: float, angle: float, speed: float, averaging_window: float | None, h: float
) -> _IntrusionPath:
    """The intrusion's inputs checked; the window defaults to max(4 cells, 0.2 depth) (cell ``h`` [m])."""
    check_positive("depth", depth)
    hint = "the body must enter the bed from the surface"
    check_range("direction", direction, math.radians(5.0), math.radians(175.0), unit="rad", hint=hint)
    angle = check_range("angle", angle, -2 * math.pi, 2 * math.pi, unit="rad")
    check_positive("speed", speed)
    window = max(4.0 * h, 0.2 * depth) if averaging_window is None else averaging_window
    return _IntrusionPath(depth, direction, angle, speed, window)


def _intrusion_inputs(path: _IntrusionPath, settle: float, grid: BedGrid, frame_count: int) -> dict[str, Any]:
    """The run's inputs as its record keeps them (:func:`_run_inputs`)."""
    return dict(
        run="intrusion",
        depth=path.depth,
        direction=path.direction,
        angle=path.angle,
        speed=path.speed,
        averaging_window=path.window,
        settle_time=settle,
        bed_width=grid.width,
        bed_depth=grid.depth,
        frame_count=frame_count,
    )


def _intrusion_summary(series: dict[str, np.ndarray], path: _IntrusionPath) -> dict[str, Any]:
    """Force and torque averaged over the rows whose depth is within the window, and the inputs."""
    sel = np.abs(series["depth_m"] - path.depth) <= 0.5 * path.window
    if not np.any(sel):  # pragma: no cover - the run always passes the window
        raise InputError("averaging_window", path.window, "a window containing recorded rows", "widen it")
    return {
        "depth_m": float(path.depth),
        **{k: float(series[k][sel].mean()) for k in ("force_x_N", "force_z_N", "torque_y_Nm")},
        "direction_rad": float(path.direction),
        "angle_rad": float(path.angle),
        "speed_m_s": float(path.speed),
        "averaging_window_m": float(path.window),
    }


def run_intrusion(
    body: Body,
    material: Material | GranularModel,
    *,
    depth: float,
    direction: float = math.pi / 2,
    angle: float = 0.0,
    speed: float = 0.05,
    bed: Bed = Bed(),
    resolution: Resolution = Resolution(),
    outputs: Outputs = Outputs(),
    stroke: Stroke = Stroke(),
    **legacy: Any,
) -> IntrusionResult:
    """Push ``body`` at constant velocity into a settled bed and report the force at ``depth``.

    The body, rotated by ``angle`` [rad] about +y, starts with its lowest point just above the free
    surface (z = 0) and moves at ``speed`` [m/s] along ``direction`` [rad] below the +x axis
    (pi/2 = straight down). The summary averages force and torque over the rows where the reference
    point's depth is within ``stroke.averaging_window`` [m] (default ``max(4 cell_size, 0.2 depth)``)
    centred on ``depth`` [m]; the run stops when the window has been passed.

    Specs (:mod:`terradyn.mpm.specs`)
    ---------------------------------
    bed : :class:`Bed`. Sizing rule for ``depth``/``width`` left None: beside the path the larger of
        2.5 depths and 1.25 heave extents of the Prandtl mechanism of a strip of the body's diameter at
        Davis' angle atan(mu_s); below it the larger of 1.5 depths and 2.5 mechanism depths
        (:func:`mechanism_clearance`); nearer free-slip walls cut the failure mechanism.
    resolution : :class:`Resolution`; cell size default body diameter / 20
        (:data:`INTRUSION_CELLS_ACROSS`), at least
        ``min_cells_across`` (default 6) cells across the body. Contact ``"two-field"`` (default;
        bodies need no thickness, composites and placed bodies as bare ones) or the legacy ``"cover"``
        (plates thickened to three cells).
    outputs : :class:`Outputs`; one recorded row per ``record_spacing`` [m] of travel (or
        ``record_interval`` [s]; default cell_size / 4), snapshots every ``snapshot_spacing`` [m]
        (default 4 cells), checkpoints, progress ``(simulated_time_s, fraction_done)`` and
        ``frame_count`` light copies of the state during the motion (``result.frames``, for
        :func:`terradyn.plotting.mpm.animate_frames`).
    stroke : :class:`Stroke`, the averaging window.
    **legacy : the flat keywords of earlier releases (``cell_size=``, ``bed_depth=``,
        ``checkpoint_path=``..., each a field of one spec, see :data:`terradyn.mpm.specs.LEGACY`) and
        the model overrides ``youngs_modulus``, ``poisson_ratio``, ``friction_coefficient``,
        ``surface_friction``, ``rate_dependent``, ``dilatancy`` (single continuum parameters of the
        material). An unknown keyword raises TypeError.

    Checkpoints: an existing ``checkpoint_path`` is never overwritten or removed by a fresh run
    (:class:`~terradyn.errors.InputError` unless ``resume``); a finished run keeps its final
    checkpoint, and resuming it returns the result without stepping. A checkpoint only resumes a run
    with the same inputs (output settings such as ``checkpoint_interval``, ``snapshot_dir`` and
    ``progress`` may change). On KeyboardInterrupt the state at the end of the last completed chunk
    is checkpointed and :class:`~terradyn.mpm.solver.RunInterrupted` is raised.
    """
    specs, c, eff = prescribed_body_setup(
        "run_intrusion", body, material, legacy, bed, resolution, outputs, stroke
    )
    outputs, h = specs["outputs"], c.cell_size
    path = _intrusion_path(depth, direction, angle, speed, specs["stroke"].averaging_window, h)
    seg = body_segments(eff, h)
    grid, pose0, travel = _intrusion_bed(seg, c, depth, path.window, direction, path.angle)
    dt = stable_time_step(c.model, h, cfl=c.resolution.cfl, speed=speed)
    settle_phases, settle = _settle_phases(c, grid.depth, dt)
    cos_d, sin_d = _direction_vector(direction)
    vel = (speed * cos_d, -speed * sin_d, 0.0)
    phases = [
        *settle_phases,
        Phase("intrude", max(1, math.ceil(travel / speed / dt)), twist=vel, free=(False, False)),
    ]
    every = _output_every(outputs, dt, speed, 0.25 * h, 4 * h)
    state = _body_state(c, seg, pose0, np.zeros(2, dtype=np.bool_), 1.0, np.zeros(2), body.width)
    named = _intrusion_inputs(path, settle, grid, outputs.frame_count)
    runner = _runner(c, grid, state, dt, phases, every, speed, outputs, _run_inputs(c, body, named))
    runner.window = c.bed.window or 0.0
    wall = _execute(runner, outputs.resume, eff)
    series = _series(runner, body.width, skip_phases=1)
    series = {"depth_m": -series["z_m"], **series}
    summary = _intrusion_summary(series, path)
    meta = _metadata(runner, c.model, body, eff, wall)
    return IntrusionResult(series, summary, meta, runner.particles.fields(), runner.frames, runner.frame())


def _body_state(c: _Common, seg, pose, free, mass, load, width, inertia=None) -> BodyState:
    """The rigid body at rest at ``pose`` with the model's surface friction and the run's contact."""
    extra = {} if inertia is None else {"inertia": inertia}
    return BodyState(
        seg=seg,
        pose=pose,
        twist=np.zeros(3),
        free=free,
        mass=mass,
        load=load,
        friction=c.model.surface_friction,
        width=width,
        contact=c.contact,
        **extra,
    )


def _window_metadata(runner: Runner) -> dict[str, Any]:
    """A windowed run's bow-wave bookkeeping at its end: the window's length and clearance, with
    :func:`heap_metadata` at that clearance."""
    if runner.window <= 0.0 or runner.window_clearance <= 0.0:
        return {}
    return {
        "window_clearance_m": runner.window_clearance,
        "window_final_m": runner.grid.width,
        **heap_metadata(runner, runner.window_clearance),
    }


def heap_metadata(runner: Runner, clearance: float) -> dict[str, Any]:
    """How far ahead of the body grains are heaped at the end of a run, and how much bed is left beyond
    them; less than ``clearance`` [m] means the heap has reached the end of the bed, whose wall then
    holds it (lengthen the bed). Empty when nothing is heaped ahead."""
    x_body = float(runner.body.pose[0])
    toe = runner.heap_toe(x_body)
    if toe is None:
        return {}
    bed = runner.bed_grid
    end = bed.x_left + bed.width if toe > x_body else bed.x_left
    return {
        "heap_ahead_m": abs(toe - x_body),
        "bed_beyond_heap_m": abs(end - toe),
        "heap_reached_bed_end": bool(abs(end - toe) < clearance),
    }


def _metadata(runner: Runner, model: GranularModel, body: Body, eff: Body, wall: float) -> dict[str, Any]:
    g = runner.bed_grid
    transfer = "APIC" if runner.flip == 0 else f"FLIP {runner.flip:g} / APIC blend"
    return {
        "model": (
            f"terradyn MPM (plane strain, Dunatunga-Kamrin granular model, {transfer}, quadratic B-splines)"
        ),
        "flip": runner.flip,
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
        "window_m": runner.window,  # 0: the whole bed was stepped
        "stepped_particles": runner.stepped_particles,  # in the window at the end of the run
        **_window_metadata(runner),
        "dt_s": runner.dt,
        "steps": runner.step,
        "wall_time_s": wall,
        "width_m": body.width,
    }
