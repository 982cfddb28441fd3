"""Library entry point :func:`run_wheel`: a rigid wheel driven through a settled bed, with a frozen
result; built from the pieces of :mod:`terradyn.mpm.runs` (specs, settling phases, the runner).

All inputs are SI (angles in rad). Forces are the grains' force on the wheel [N] (the 2D per-width
value times the wheel width); torques are about +y through the axle [N m].
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import InputError, check_positive, check_range
from ..geometry import Body
from ..materials import Material
from .bodies import body_segments, lowest_point
from .model import GranularModel
from .runs import (
    _body_state,
    _Common,
    _common,
    _execute,
    _metadata,
    _MPMResult,
    _output_every,
    _run_inputs,
    _runner,
    _series,
    _settle_phases,
    _specs,
    heap_metadata,
)
from .solver import BedGrid, Phase, stable_time_step
from .specs import Bed, Drive, Outputs, Resolution

__all__ = ["WHEEL_CELLS_ACROSS", "WheelResult", "bed_limits", "run_wheel"]


@dataclass(frozen=True, eq=False)
class WheelResult(_MPMResult):
    """Result of :func:`run_wheel`; summary adds ``sinkage_m``, ``drawbar_pull_N``, ``drive_torque_Nm``."""


#: Default cells across a wheel's diameter. Measured on the 0.13 m x 0.16 m wheel in MS under 130 N at
#: slip 0.3 (docs/mpm.md) at 16 / 24 / 32 cells across: sinkage below the bed surface 0.5 / 16.6 /
#: 16.6 mm (runs made before the bed snapped to whole cells, corrected for their surface offsets of
#: -8 / -3 / 0 mm), drive torque 5.30 / 5.39 / 5.43 N m, drawbar pull -1.9 / -2.0 / -0.7 N. At 16 cells
#: the wheel barely sank, so the default is 32.
WHEEL_CELLS_ACROSS = 32
#: Default drive of a spinning wheel [rad of rotation]. Measured on the wheel above at 8 mm cells: the
#: pull averaged over 0.5 rad windows starting 1, 1.5, 1.9, 2.25 and 3 rad into the drive is 1.2, 0.2,
#: -0.4, -0.7 and -0.8 N (within 0.1 N of its final value from about 2.25 rad); the sinkage stays within
#: 0.6 mm of its final value from 1 rad. With 4.5 rad the averaged last half starts at 2.25 rad.
DRIVE_RADIANS = 4.5


def _nominal_radius(wheel: Body) -> float:
    r = getattr(wheel, "outer_radius", None)
    return float(r) if r is not None else float(wheel.bounding_radius)


def _wheel_margin(reach: float, cell_size: float) -> float:
    """Grains [m] a wheel bed keeps beyond the wheel's reach on either side of its path."""
    return max(2.0 * reach, 4.0 * cell_size)


#: Grains [reaches] below the deepest point a wheel reached under which its bed's floor is flagged
#: (``floor_near``). Measured (docs/mpm.md, "The floor under a wheel that sinks"): with 3.2 and 3.4
#: reaches left (a locked wheel towed at 0.8 radii of sinkage; the frictional rim of the high-speed
#: study) a deeper bed moved the pull by under 2 % of the load; the frictionless rim read within 6 %
#: of the load with 3.8 reaches left and 4 % with 4.9, and on the default bed, with 2.9 left at the
#: depth where the deeper beds held it, it dug itself in through the floor. A rule for the cases
#: measured, not a bound.
FLOOR_CLEARANCE_REACHES = 3.0


def floor_metadata(sinkage: np.ndarray, bed_depth: float, reach: float) -> dict[str, Any]:
    """How close the wheel came to the bed's floor: its deepest sinkage [m] over the run, the grains
    left below it, and ``floor_near`` when they are fewer than :data:`FLOOR_CLEARANCE_REACHES`
    reaches (deepen the bed)."""
    deepest = float(np.max(sinkage)) if len(sinkage) else 0.0
    below = bed_depth - deepest
    return {
        "deepest_sinkage_m": deepest,
        "floor_below_wheel_m": below,
        "floor_near": bool(below < FLOOR_CLEARANCE_REACHES * reach),
    }


def bed_limits(metadata: dict[str, Any]) -> list[tuple[str, str, float]]:
    """Each way a wheel run (its ``metadata``) outgrew its bed, as (what happened, the bed size to
    enlarge: ``"length"`` or ``"depth"``, its present value [m]): the heap the wheel pushed reached
    the end of the bed, which then held it like a wall (docs/mpm.md, "The bow wave and the window's
    wall"), or the wheel sank closer to the floor than :data:`FLOOR_CLEARANCE_REACHES` ("The floor
    under a wheel that sinks"). Empty when neither happened."""
    out = []
    if metadata.get("heap_reached_bed_end"):
        out.append((
            f"the grains heaped {metadata['heap_ahead_m']:.3g} m ahead of the wheel reached the end of the "
            "bed, which held them like a wall",
            "length",
            float(metadata["bed_width_m"]),
        ))  # fmt: skip
    if metadata.get("floor_near"):
        out.append((
            f"the wheel sank {metadata['deepest_sinkage_m']:.3g} m, leaving "
            f"{metadata['floor_below_wheel_m']:.3g} m of grains above the floor, less than the depth "
            "rule was checked for",
            "depth",
            float(metadata["bed_depth_m"]),
        ))  # fmt: skip
    return out


def _bow_wave_allowance(reach: float, travel: float) -> float:
    """Bed [m] a wheel bed keeps ahead of the wheel's final position beyond its margin, for the heap
    it pushes: in plane strain grains cannot flow round the wheel, so a wheel that leaves a rut drives a
    heap that grows with the distance travelled. Measured (docs/mpm.md "Moving window"): heaps reach
    4.6 reaches ahead of the axle (a locked 0.04 m wheel towed 0.15 m at 0.9 radii of sinkage) and
    4.4-6.6 (a smooth rim of 0.106 m at slip 0.5 on poppy seeds after 1.8 m of travel, at 9 and 6.5
    mm cells: 0.47 and 0.70 m, inside this allowance of 0.9 m)."""
    return max(4.0 * reach, 0.5 * travel)


def _wheel_bed(seg, c: _Common, travel, v_forward):
    """Bed for a wheel run and its start pose (lowest point half a cell above the surface). By default
    the bed keeps the wheel's margin behind its start and ahead of its end, and
    :func:`_bow_wave_allowance` more ahead; a given bed length keeps up to the margin behind."""
    h = c.cell_size
    reach = float(np.max(np.hypot(seg[:, 0], seg[:, 1])))
    margin = _wheel_margin(reach, h)
    bed_depth, bed_length = c.bed.depth, c.bed.width
    bed_depth = 2.0 * reach + margin if bed_depth is None else bed_depth
    if bed_length is None:
        bed_length = travel + 2.0 * (reach + margin) + _bow_wave_allowance(reach, travel)
    check_positive("bed_length", bed_length)
    back = max(0.0, min(reach + margin, 0.5 * (bed_length - travel)))
    x_start = -0.5 * bed_length + back if v_forward >= 0 else 0.5 * bed_length - back
    grid = BedGrid(
        bed_length, bed_depth, 2.0 * reach + 4 * h, h, -0.5 * bed_length, c.walls, c.bed.surface_offset
    )
    if 0.5 * travel + reach > 0.5 * bed_length:
        raise InputError(
            "bed_length", bed_length, f"at least {travel + 2 * reach:.4g} m", "the wheel leaves the bed"
        )
    pose0 = np.array([x_start, 0.0, 0.0])
    pose0[1] = -lowest_point(seg, pose0) + 0.5 * h
    return grid, pose0


def _wheel_window(c: _Common, reach: float) -> float:
    """Length [m] of the moving window of a wheel run: ``bed.window``, or by default the wheel and the
    bed margin of :func:`_wheel_bed` on either side (the bed a wheel that does not travel gets).

    Measured in docs/mpm.md ("Moving window"): the window changes the forces of the forced-slip wheel
    study by as much as moving the walls does, and saves the grains beyond it.
    """
    h = c.cell_size
    smallest = 2.0 * reach + 8.0 * h
    if c.bed.window is None:
        return 2.0 * (reach + _wheel_margin(reach, h))
    if 0.0 < c.bed.window < smallest:
        raise InputError(
            "window",
            c.bed.window,
            f"0 (the whole bed) or at least {smallest:.4g} m",
            "the wheel and 4 cells each side",
        )
    return c.bed.window


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


@dataclass(frozen=True)
class _WheelMotion:
    """The checked drive of a wheel run: commands, the largest spin, forward speed and run length."""

    torque_mode: bool
    torque: float
    omega: float
    slip: float | None
    towed: bool
    spin: float
    v_forward: float
    travel: float
    duration: float
    sink_time: float

    @property
    def direction(self) -> float:
        return self.v_forward if not self.torque_mode else (1.0 if self.torque >= 0 else -1.0)

    @property
    def mode(self) -> str:
        """torque-driven, forced-slip, towed or self-propelled (the run's metadata ``mode``)."""
        modes = (
            (self.torque_mode, "torque-driven"),
            (self.slip is not None, "forced-slip"),
            (self.towed, "towed"),
        )
        return next((name for on, name in modes if on), "self-propelled")


@dataclass(frozen=True)
class _WheelCommand:
    """The run as the caller asked for it: ``load`` [N], spin ``omega`` [rad/s], ``slip``,
    ``drive_torque`` [N m], ``drawbar_load`` [N], ``max_omega`` [rad/s] under a torque, ``inertia``
    [kg m^2] (None: a uniform disc) and ``forward_speed`` [m/s] of a towed body."""

    load: float
    omega: float | None
    slip: float | None
    drive_torque: float | None
    drawbar_load: float
    max_omega: float
    inertia: float | None
    forward_speed: float | None


def _wheel_motion(c: _Common, drive: Drive, radius: float, reach: float, cmd: _WheelCommand) -> _WheelMotion:
    """The checked drive of ``cmd`` for a wheel of nominal ``radius`` and ``reach`` [m]: one
    :class:`InputError` line for the first inconsistent or out-of-range command."""
    load, omega, slip, drive_torque = cmd.load, cmd.omega, cmd.slip, cmd.drive_torque
    drawbar_load, max_omega = cmd.drawbar_load, cmd.max_omega
    forward_speed: Any = cmd.forward_speed  # a number where ``towed`` is true
    check_positive("load", load)
    torque_mode = drive_torque is not None
    towed = forward_speed is not None
    if towed:
        forward_speed = check_range("forward_speed", forward_speed, -100.0, 100.0, unit="m/s")
        if omega is None:
            raise InputError(
                "forward_speed",
                forward_speed,
                "given with a spin rate omega",
                "omega = 0 tows a locked wheel or a sled",
            )
        for field, value, given in (
            ("slip", slip, slip is not None),
            ("drawbar_load", drawbar_load, drawbar_load != 0.0),
            ("initial_speed", drive.initial_speed, drive.initial_speed != 0),
        ):
            if given:
                allowed = "not given with a forward speed" if field == "slip" else "0 with a forward speed"
                raise InputError(field, value, allowed, "the forward speed is imposed")
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
    spin = max_omega if torque_mode else abs(omega_cmd)  # the largest spin the step must resolve
    if drive.spin_up > 0 and (torque_mode or omega_cmd == 0):
        raise InputError(
            "spin_up",
            drive.spin_up,
            "0 unless a nonzero omega is prescribed",
            "the spin-up ramps the prescribed spin",
        )
    if drive.initial_speed != 0 and slip is not None:
        raise InputError(
            "initial_speed", drive.initial_speed, "0 when slip is given", "the forward speed is imposed"
        )
    duration = drive.duration
    if duration is None:
        steady = not torque_mode and spin != 0
        duration = drive.spin_up + DRIVE_RADIANS / spin if steady else 20.0 * math.sqrt(reach / c.gravity)
        if towed and spin == 0 and forward_speed != 0:  # a towed body: two reaches of travel, or more
            duration = max(duration, 2.0 * reach / abs(forward_speed))
    check_positive("duration", duration)
    ramp_end = duration * (1.0 - drive.average_fraction)
    if drive.spin_up > ramp_end * (1.0 + 1e-12):
        raise InputError(
            "spin_up",
            drive.spin_up,
            f"at most {ramp_end:.4g} s",
            f"it must end before the averaged last {drive.average_fraction:g} of the {duration:.4g} s drive",
        )
    sink_time = 3.0 * math.sqrt(reach / c.gravity) if drive.sink_time is None else drive.sink_time
    if torque_mode:
        v_forward, travel = 0.0, spin * radius * duration
    elif towed:
        v_forward = float(forward_speed)
        travel = abs(v_forward) * duration
    else:
        v_forward = (1.0 - slip) * omega_cmd * radius if slip is not None else omega_cmd * radius
        travel = abs(v_forward) * duration
    return _WheelMotion(
        torque_mode, torque, omega_cmd, slip, towed, spin, v_forward, travel, duration, sink_time
    )


@dataclass(frozen=True, eq=False)
class _WheelShape:
    """The wheel as the grid sees it: its boundary ``segments`` [m] (body frame), nominal ``radius``
    [m], ``reach`` [m] (farthest segment end from the axle) and ``width`` [m] out of plane."""

    segments: np.ndarray
    radius: float
    reach: float
    width: float


def _wheel_state(
    c: _Common, shape: _WheelShape, pose0: np.ndarray, cmd: _WheelCommand, m: _WheelMotion
) -> tuple[Any, float]:
    """The wheel's rigid-body state at its start pose (per unit width: mass of the load, the spin's
    moment of inertia, load, drawbar load and drive torque) and that moment of inertia [kg m]."""
    w, g = shape.width, c.gravity
    mass = cmd.load / g / w
    inertia_w = (
        0.5 * mass * shape.radius**2 if cmd.inertia is None else check_positive("inertia", cmd.inertia) / w
    )
    load_w = np.array([-cmd.drawbar_load / w, -cmd.load / w, m.torque / w])
    state = _body_state(c, shape.segments, pose0, np.zeros(3, dtype=np.bool_), mass, load_w, w, inertia_w)
    return state, inertia_w


def _wheel_phases(
    c: _Common, bed_depth: float, m: _WheelMotion, drive: Drive, dt: float
) -> tuple[list[Phase], float]:
    """The run's phases (the bed's settling, the wheel sinking under its load, the drive) and the
    settling time [s]."""
    settle_phases, settle = _settle_phases(c, bed_depth, dt)
    damping = c.model.wave_speed() / bed_depth
    imposed = m.slip is not None or m.towed
    drive_twist = (m.v_forward if imposed else drive.initial_speed, 0.0, m.omega)
    phases = [
        *settle_phases,
        Phase("sink", max(1, round(m.sink_time / dt)), damping=damping, free=(False, True, False)),
        Phase("drive", max(1, round(m.duration / dt)), twist=drive_twist,
              free=(not imposed, True, m.torque_mode), ramp_steps=round(drive.spin_up / dt)),
    ]  # fmt: skip
    return phases, settle


def _wheel_inputs(
    cmd: _WheelCommand, m: _WheelMotion, drive: Drive, inertia: float, settle: float, grid: BedGrid,
    frame_count: int,
) -> dict[str, Any]:  # fmt: skip
    """The run's inputs as its record keeps them (:func:`terradyn.mpm.runs._run_inputs`)."""
    return dict(
        run="wheel",
        load=cmd.load,
        omega=cmd.omega,
        slip=cmd.slip,
        **({"forward_speed": m.v_forward} if m.towed else {}),
        drive_torque=cmd.drive_torque,
        drawbar_load=cmd.drawbar_load,
        max_omega=cmd.max_omega if m.torque_mode else None,
        inertia=inertia,
        duration=m.duration,
        sink_time=m.sink_time,
        **({"spin_up": drive.spin_up} if drive.spin_up else {}),
        **({"initial_speed": drive.initial_speed} if drive.initial_speed else {}),
        settle_time=settle,
        bed_length=grid.width,
        bed_depth=grid.depth,
        frame_count=frame_count,
    )


def _bed_bounds_metadata(
    runner: Any, sinkage: np.ndarray, bed_depth: float, shape: _WheelShape, h: float
) -> dict[str, Any]:
    """Whether the wheel outgrew its bed: the heap reached a bed end (whole-bed runs) and the floor's
    clearance (:func:`floor_metadata`)."""
    meta: dict[str, Any] = {}
    if runner.window <= 0.0:  # the whole bed: its ends hold a heap as a window's wall did
        meta.update(heap_metadata(runner, _wheel_margin(shape.reach, h)))
    meta.update(floor_metadata(sinkage, bed_depth, shape.reach))
    return meta


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
    forward_speed: float | None = None,
    bed: Bed = Bed(),
    resolution: Resolution = Resolution(),
    outputs: Outputs = Outputs(),
    drive: Drive = Drive(),
    **legacy: Any,
) -> WheelResult:
    """Drive a wheel (any body) over a settled bed under a vertical ``load`` [N].

    The wheel first sinks under its load for ``drive.sink_time`` [s] (not spinning, vertical motion
    free, grains damped), then spins at ``omega`` [rad/s] about +y for ``drive.duration`` [s]
    (reached after ``drive.spin_up`` [s] of a linear ramp from rest, 0 by default; a free forward
    motion starts at ``drive.initial_speed``). With
    ``slip`` given the forward speed is prescribed, ``vx = (1 - slip) omega r`` (r: nominal outer
    radius), and the vertical motion is free under the load; with ``slip=None`` both translations are
    free (self-propelled). ``omega = 0`` with ``slip=None`` leaves a body resting under its load. With
    ``forward_speed`` [m/s] instead of ``slip`` the forward speed is prescribed as given (towed): with
    ``omega = 0`` a locked wheel, or any body such as a sled, dragged over the bed (default duration
    ``max(20 sqrt(reach / g), 2 reach / |forward_speed|)``). The
    default duration is ``spin_up + 4.5 / |omega|`` (:data:`DRIVE_RADIANS`): starting from the pit it sank
    into, a wheel's pull settles after about 2.25 rad of rotation (measured for a 0.13 m wheel on MS at
    slip 0.3), so the averaged last half of the drive is steady.

    Torque control: give ``drive_torque`` [N m] (+ drives forward) instead of ``omega``; the spin is
    then free, with moment of inertia ``inertia`` [kg m^2] (default a uniform disc of the load's mass,
    ``load / g r^2 / 2``), starting from rest, and the forward motion is free. The time step is sized
    for spins up to ``max_omega`` [rad/s]; a wheel that spins up beyond it (a torque the bed cannot
    resist) stops the run with :class:`~terradyn.mpm.MPMInstabilityError`. The default duration is
    then ``20 sqrt(r / g)``. ``drawbar_load`` [N] is a horizontal resisting force on the axle (a towed
    load, + backwards) whenever the forward motion is free.

    The summary averages the last ``drive.average_fraction`` of the drive: ``sinkage_m`` (depth of
    the lowest point below z = 0), ``drawbar_pull_N`` (horizontal soil force, + forward),
    ``drive_torque_Nm`` (= -soil torque about +y at the axle), ``force_z_N``, ``slip`` (measured).

    Specs as in :func:`run_intrusion`, with :class:`Drive` for the run length. The bed's sizing rule
    leaves max(2 reaches, 4 cells) of grains beyond the wheel's path and below two reaches, and
    max(4 reaches, travel / 2) more ahead for the heap the wheel pushes; its ``width`` is the bed
    length. The moving window (``bed.window``) grows ahead of that heap; the metadata's
    ``heap_reached_bed_end`` is true when the heap has reached the end of the bed (lengthen it);
    ``floor_near`` when the wheel sank to within :data:`FLOOR_CLEARANCE_REACHES` reaches of the
    bed's floor (deepen it: ``Bed(depth=...)``).
    The resolution needs 8 cells across the wheel by default.
    ``outputs`` intervals are in seconds of simulated time (record: duration / 200, snapshots:
    duration / 20). The flat keywords of earlier releases (``cell_size=``, ``duration=``,
    ``bed_length=``...) and the model overrides work as in :func:`run_intrusion`.
    """
    specs, overrides = _specs(
        "run_wheel", legacy, "bed_width", bed=bed, resolution=resolution, outputs=outputs, drive=drive
    )
    c, eff = _common(
        wheel,
        material,
        specs["bed"],
        specs["resolution"],
        overrides,
        min_cells=8,
        default_cells=WHEEL_CELLS_ACROSS,
    )
    outputs, drive, h, g = specs["outputs"], specs["drive"], c.cell_size, c.gravity
    radius = _nominal_radius(wheel)
    seg = body_segments(eff, h)
    reach = float(np.max(np.hypot(seg[:, 0], seg[:, 1])))
    shape = _WheelShape(seg, radius, reach, wheel.width)
    cmd = _WheelCommand(load, omega, slip, drive_torque, drawbar_load, max_omega, inertia, forward_speed)
    m = _wheel_motion(c, drive, radius, reach, cmd)
    grid, pose0 = _wheel_bed(seg, c, m.travel, m.direction)
    v_max = m.spin * reach + (m.spin * radius if m.torque_mode else abs(m.v_forward)) + math.sqrt(2 * g * h)
    dt = stable_time_step(c.model, h, cfl=c.resolution.cfl, speed=v_max)
    state, inertia_w = _wheel_state(c, shape, pose0, cmd, m)
    phases, settle = _wheel_phases(c, grid.depth, m, drive, dt)
    every = _output_every(outputs, dt, None, m.duration / 200.0, m.duration / 20.0)
    named = _wheel_inputs(cmd, m, drive, inertia_w * shape.width, settle, grid, outputs.frame_count)
    runner = _runner(c, grid, state, dt, phases, every, v_max, outputs, _run_inputs(c, wheel, named))
    runner.window = _wheel_window(c, reach)
    runner.window_clearance = _wheel_margin(reach, h) if runner.window > 0 else 0.0
    wall = _execute(runner, outputs.resume, eff)
    series, summary = _wheel_summary(runner, shape.width, seg, drive.average_fraction, radius, load)
    summary["drawbar_load_N"] = float(drawbar_load)
    if m.torque_mode:
        summary["applied_torque_Nm"] = m.torque
    meta = _metadata(runner, c.model, wheel, eff, wall)
    meta.update(_bed_bounds_metadata(runner, series["sinkage_m"], grid.depth, shape, h))
    meta["mode"] = m.mode
    return WheelResult(series, summary, meta, runner.particles.fields(), runner.frames, runner.frame())
