"""Horizontal drag of a buried body: :func:`run_drag` (plowing, cylinder lift and drag).

The body is placed with its reference point at ``depth`` in the fresh bed before it settles: the
grains whose centres lie inside its outline are removed and the bed settles under gravity around the
body, which is held still; then the body moves at a constant horizontal velocity. Removing grains
rather than pushing the body in from the surface keeps the bed above the body undisturbed, as in the
experiments this case reproduces (Ding et al. 2011 and Gravish et al. 2010 prepare the bed with the
body already buried, by fluidising it); an inserted body would leave a crater and a column of sheared
grains above it that the drag would then plough through. A zero-thickness plate has no inside, so
nothing is removed: the plate is a cut in the bed.

Built from the pieces of :mod:`terradyn.mpm.runs` (specs, the settling phase, the runner, the moving
window of :class:`~terradyn.mpm.solver.Runner`); forces are the grains' force on the body [N].
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import InputError, check_positive, check_range
from ..geometry import Body
from ..materials import Material
from ._contact_kernels import polygon_sdf
from .bodies import body_segments
from .model import GranularModel
from .runs import (
    WALL_MARGIN,
    _body_state,
    _Common,
    _execute,
    _metadata,
    _MPMResult,
    _output_every,
    _run_inputs,
    _runner,
    _series,
    _settle_phases,
    mechanism_clearance,
    prescribed_body_setup,
)
from .solver import BedGrid, ParticleState, Phase, stable_time_step
from .specs import Bed, Outputs, Resolution, Stroke

__all__ = ["DragResult", "drag_clearance", "remove_grains_inside", "run_drag"]


@dataclass(frozen=True, eq=False)
class DragResult(_MPMResult):
    """Result of :func:`run_drag`.

    ``series`` adds ``distance_m`` (travel of the reference point), ``drag_N`` (grain force opposing
    the motion) and ``lift_N`` (vertical grain force, + up) to the run columns. ``summary``: the means
    over the steady window of ``drag_N``, ``lift_N``, ``force_x_N``, ``force_z_N``, ``torque_y_Nm``,
    the standard deviation ``drag_std_N``, and the inputs ``depth_m``, ``speed_m_s`` (signed),
    ``distance_m``, ``angle_rad``, ``averaging_window_m``.
    """


def drag_clearance(model: GranularModel, reach: float, depth: float) -> tuple[float, float]:
    """Grains [m] a drag bed keeps ahead of (and behind) a body of ``reach`` [m] at ``depth`` [m],
    and below it.

    Ahead: :data:`~terradyn.mpm.runs.WALL_MARGIN` times the horizontal extent of Rankine's passive
    wedge from the body's lowest point to the surface, ``(depth + reach) tan(pi/4 + phi/2)`` at
    Davis' angle ``phi = atan(mu_s)`` (the angle :func:`~terradyn.mpm.runs.mechanism_clearance`
    uses), and at least the intrusion rule's clearance beside a strip of the body's diameter (the
    body bears on the grains ahead as a footing does on those below). Below: the intrusion rule's
    floor clearance, ``FLOOR_MARGIN`` mechanism depths of that strip. A choice, not measured for the
    drag case (the intrusion rule is measured, see ``mechanism_clearance``).
    """
    phi = math.atan(model.friction_coefficient)
    side, below = mechanism_clearance(model.friction_coefficient, 2.0 * reach)
    wedge = WALL_MARGIN * (depth + reach) * math.tan(0.25 * math.pi + 0.5 * phi)
    return max(side, wedge), below


def remove_grains_inside(particles: ParticleState, seg: np.ndarray, pose: np.ndarray) -> ParticleState:
    """The particles whose centres lie outside the closed outline ``seg`` (S, 4) at ``pose`` (x, z,
    theta); an outline without an inside (a zero-thickness plate) removes none."""
    c, s = math.cos(pose[2]), math.sin(pose[2])
    rx = particles.pos[:, 0] - pose[0]
    rz = particles.pos[:, 1] - pose[1]
    reach = float(np.max(np.hypot(seg[:, :2][:, 0], seg[:, :2][:, 1])))
    keep = np.ones(len(particles), dtype=bool)
    for p in np.flatnonzero(rx * rx + rz * rz <= reach * reach):
        phi, _, _ = polygon_sdf(c * rx[p] - s * rz[p], s * rx[p] + c * rz[p], seg)
        keep[p] = phi >= 0.0
    return ParticleState(
        **{k: np.ascontiguousarray(getattr(particles, k)[keep]) for k in ParticleState.NAMES}
    )


def _drag_window(c: _Common, reach: float, ahead: float) -> float:
    """Length [m] of the moving window: ``bed.window``, or by default the body with the clearance
    ahead on either side (the bed a body that does not travel gets)."""
    h = c.cell_size
    smallest = 2.0 * reach + 8.0 * h
    if c.bed.window is None:
        return 2.0 * (reach + ahead)
    if 0.0 < c.bed.window < smallest:
        raise InputError(
            "window",
            c.bed.window,
            f"0 (the whole bed) or at least {smallest:.4g} m",
            "the body and 4 cells each side",
        )
    return c.bed.window


def _drag_bed(seg: np.ndarray, c: _Common, depth: float, distance: float, sense: float, angle: float):
    """Bed, start pose (3,) and window [m] of a drag: the path is centred on x = 0."""
    h = c.cell_size
    reach = float(np.max(np.hypot(seg[:, 0], seg[:, 1])))
    ahead, below = drag_clearance(c.model, reach, depth)
    ahead, below = max(ahead, 4.0 * h), max(below, 4.0 * h)
    window = _drag_window(c, reach, ahead)
    bed_depth, bed_length = c.bed.depth, c.bed.width
    bed_depth = depth + reach + below if bed_depth is None else bed_depth
    bed_length = distance + 2.0 * (reach + ahead) if bed_length is None else bed_length
    check_positive("bed_width", bed_length)
    grid = BedGrid(
        bed_length, bed_depth, 2.0 * reach + 4.0 * h, h, -0.5 * bed_length, c.walls, c.bed.surface_offset
    )
    if -depth - reach < -grid.depth + h:
        raise InputError(
            "bed_depth",
            bed_depth,
            f"deeper than {depth + reach + h:.4g} m",
            "the body must stay inside the bed",
        )
    if 0.5 * distance + reach > 0.5 * grid.width:
        raise InputError(
            "bed_width", bed_length, f"at least {distance + 2 * reach:.4g} m", "the body leaves the bed"
        )
    return grid, np.array([-0.5 * distance * sense, -depth, angle]), window


@dataclass(frozen=True)
class _DragPath:
    """The checked drag: ``depth`` [m] of the reference point, ``distance`` [m], signed ``speed``
    [m/s], body ``angle`` [rad] and the summary's averaging ``window`` [m] of travel."""

    depth: float
    distance: float
    speed: float
    angle: float
    window: float

    @property
    def sense(self) -> float:
        """+1 along +x, -1 along -x."""
        return math.copysign(1.0, self.speed)


def _drag_path(
    depth: float, distance: float, speed: float, angle: float, averaging_window: float | None
) -> _DragPath:
    """The drag's inputs checked (a nonzero speed, an averaging window within the distance)."""
    check_positive("depth", depth)
    check_positive("distance", distance)
    speed = float(check_range("speed", speed, -10.0, 10.0, unit="m/s"))
    if speed == 0.0:
        raise InputError("speed", speed, "a nonzero velocity [m/s]", "+ drags along +x, - along -x")
    angle = check_range("angle", angle, -2 * math.pi, 2 * math.pi, unit="rad")
    window = 0.5 * distance if averaging_window is None else averaging_window
    if window > distance:
        raise InputError("averaging_window", window, f"at most the distance {distance:g} m")
    return _DragPath(depth, distance, speed, angle, window)


def _drag_phases(c: _Common, bed_depth: float, path: _DragPath, dt: float) -> tuple[list[Phase], float]:
    """The settling phases around the still body, then the drag at constant velocity; and the
    settling time [s]."""
    settle_phases, settle = _settle_phases(c, bed_depth, dt)
    phases = [
        *settle_phases,
        Phase(
            "drag",
            max(1, math.ceil(path.distance / abs(path.speed) / dt)),
            twist=(path.speed, 0.0, 0.0),
            free=(False, False),
        ),
    ]
    return phases, settle


def _drag_inputs(
    path: _DragPath, settle: float, grid: BedGrid, bed_window: float, frame_count: int
) -> dict[str, Any]:
    """The run's inputs as its record keeps them (:func:`terradyn.mpm.runs._run_inputs`)."""
    return dict(
        run="drag",
        depth=path.depth,
        distance=path.distance,
        speed=path.speed,
        angle=path.angle,
        averaging_window=path.window,
        settle_time=settle,
        bed_length=grid.width,
        bed_depth=grid.depth,
        window=bed_window,
        frame_count=frame_count,
    )


def _drag_series(runner: Any, width: float, x0: float, sense: float) -> dict[str, np.ndarray]:
    """The run's series with the travel from ``x0`` [m] (``distance_m``), ``drag_N`` and ``lift_N``."""
    series = _series(runner, width, skip_phases=1)
    return {
        "distance_m": np.abs(series["x_m"] - x0),
        **series,
        "drag_N": -sense * series["force_x_N"],
        "lift_N": series["force_z_N"].copy(),
    }


def _drag_summary(series: dict[str, np.ndarray], path: _DragPath) -> dict[str, Any]:
    """The forces averaged over the last ``path.window`` of travel, the drag's spread and the inputs."""
    sel = series["distance_m"] >= path.distance - path.window - 1e-12
    if not np.any(sel):  # pragma: no cover - the run always ends past the window
        raise InputError("averaging_window", path.window, "a window containing recorded rows", "widen it")
    return {
        **{
            k: float(series[k][sel].mean())
            for k in ("drag_N", "lift_N", "force_x_N", "force_z_N", "torque_y_Nm")
        },
        "drag_std_N": float(series["drag_N"][sel].std()),
        "depth_m": float(path.depth),
        "speed_m_s": path.speed,
        "distance_m": float(path.distance),
        "angle_rad": float(path.angle),
        "averaging_window_m": float(path.window),
    }


def run_drag(
    body: Body,
    material: Material | GranularModel,
    *,
    depth: float,
    distance: float,
    speed: float = 0.05,
    angle: float = 0.0,
    bed: Bed = Bed(),
    resolution: Resolution = Resolution(),
    outputs: Outputs = Outputs(),
    stroke: Stroke = Stroke(),
    **legacy: Any,
) -> DragResult:
    """Drag a buried body horizontally through a settled bed and report drag and lift.

    The body, rotated by ``angle`` [rad] about +y, has its reference point at ``depth`` [m] below the
    free surface (z = 0); a body larger than its depth sticks out of the surface. Grains inside its
    outline are removed and the bed settles around the still body (module docstring: why), then the
    body moves ``distance`` [m] at the constant horizontal velocity ``speed`` [m/s] (+ along +x, -
    along -x). ``drag_N`` is the grains' force opposing the motion, ``-force_x sign(speed)``, and
    ``lift_N`` the vertical force ``force_z`` (+ up); the summary averages them over the last
    ``stroke.averaging_window`` [m] of travel (default half the distance: the force rises from rest
    over a travel of about the body's size).

    Specs (:mod:`terradyn.mpm.specs`) as in :func:`~terradyn.mpm.run_intrusion`, except the bed's
    sizing rule: ``bed.width`` (the bed length along x) defaults to the distance plus the body and
    :func:`drag_clearance` ahead and behind, ``bed.depth`` to the body's depth, its reach and the
    clearance below. ``bed.window`` None steps a moving window of the body and that clearance on
    either side (the bed of a body that does not travel), so the cost does not grow with the
    distance; 0 steps the whole bed. ``outputs`` spacings are in metres of travel (default one row
    per quarter cell). The flat keywords of earlier releases and the model overrides
    (``dilatancy=``, ``friction_coefficient=``...) work as in :func:`~terradyn.mpm.run_intrusion`.
    """
    specs, c, eff = prescribed_body_setup(
        "run_drag", body, material, legacy, bed, resolution, outputs, stroke
    )
    outputs, h = specs["outputs"], c.cell_size
    path = _drag_path(depth, distance, speed, angle, specs["stroke"].averaging_window)
    seg = body_segments(eff, h)
    grid, pose0, bed_window = _drag_bed(seg, c, depth, distance, path.sense, path.angle)
    dt = stable_time_step(c.model, h, cfl=c.resolution.cfl, speed=abs(path.speed))
    phases, settle = _drag_phases(c, grid.depth, path, dt)
    every = _output_every(outputs, dt, abs(path.speed), 0.25 * h, 4 * h)
    # the kernels move the body's pose in place: keep pose0 as the start
    state = _body_state(c, seg, pose0.copy(), np.zeros(2, dtype=np.bool_), 1.0, np.zeros(2), body.width)
    named = _drag_inputs(path, settle, grid, bed_window, outputs.frame_count)
    runner = _runner(c, grid, state, dt, phases, every, abs(path.speed), outputs, _run_inputs(c, body, named))
    bed_count = len(runner.particles)
    runner.particles = remove_grains_inside(runner.particles, seg, pose0)
    runner.window = bed_window
    wall = _execute(runner, outputs.resume, eff)
    series = _drag_series(runner, body.width, pose0[0], path.sense)
    summary = _drag_summary(series, path)
    meta = _metadata(runner, c.model, body, eff, wall)
    meta["removed_particles"] = bed_count - len(runner.particles)
    meta["placement"] = "grains inside the body removed before settling"
    return DragResult(series, summary, meta, runner.particles.fields(), runner.frames, runner.frame())
