"""DEM drag: a rigid body held at a fixed depth and dragged horizontally through a settled bed (plowing).

The experiments of chapter 9 (Gravish et al. 2010 plowing, Ding et al. 2011 lift and drag) bury the
body before the bed is prepared. The DEM run does the same: the bed is poured and settled
(:func:`terradyn.dem.bed.prepare_bed`), the body's spheres are added with its reference point at
``depth`` below the surface and ``distance / 2`` behind x = 0, every grain that overlaps a body sphere
is deleted (``delete_atoms overlap``), the bed settles around the still body for ``settle_time``, and
the body then moves along +x at ``speed`` for ``distance``. A body that reaches above the surface
(a plowing plate) ploughs the surface grains; a buried one passes through them.

Each history row is the mean contact force on the body over one record interval (as in
:func:`terradyn.dem.run_intrusion`); ``drag_N`` is the force opposing the motion (-F_x) and ``lift_N``
the vertical force (+ up), both per unit width times the body's width in a slab bed.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import InputError, check_finite, check_positive, check_range
from ..materials import Material
from .bed import BODY_TYPE, Bed, BedKind, BedSpec, Packing, check_speed
from .intruders import MeshIntruder, body_spheres, rotated_extent
from .runs import (
    HISTORY_KEYS,
    INTRUSION_HOOKS,
    RunHooks,
    _add_atoms,
    _body_fixes,
    _dem_dict,
    _recorder,
    _settled_bed,
    as_intruder,
    newton_setting,
    run_chunks,
)

__all__ = ["DEMDragResult", "drag_bed_spec", "run_drag"]

#: settling time with the body in place, in units of sqrt(d / g) (grain free-fall times)
SETTLE_TIMES = 10.0


@dataclass(frozen=True, eq=False)
class DEMDragResult:
    """Drag and lift on a body dragged through a DEM bed (SI; forces on the body, z up).

    ``history``: ``time_s``, ``travel_m`` (distance moved since the drag started), ``x_m``, ``z_m`` (the
    reference point, surface at z = 0), ``drag_N`` (-F_x), ``lift_N`` (F_z), ``torque_y_Nm``;
    ``summary``: ``drag_N``, ``lift_N`` (means over the last ``average_fraction`` of the travel),
    ``drag_std_N``, ``averaging_window_m``, ``depth_m``, ``distance_m``, ``speed_m_s``, ``width_m``,
    ``grain_count`` (after the deletion), ``deleted_grains``, ``body_spheres``; ``bed`` the settled bed's
    figures (packing fraction, coordination, ...) before the body was placed.
    """

    history: dict[str, np.ndarray]
    summary: dict[str, Any]
    bed: dict[str, Any] = field(default_factory=dict)


def drag_bed_spec(body: Any, *, depth: float, distance: float, grain_diameter: float, angle: float = 0.0,
                  packing: Packing | str = Packing.DENSE, seed: int = 12345) -> BedSpec:  # fmt: skip
    """A slab bed for a drag: the path's extent plus max(6 grains, the body's size) of grains ahead,
    behind and below, and room above for a body that reaches out of the bed."""
    body = as_intruder(body)
    xmin, xmax, zmin, zmax = rotated_extent(body, angle)
    margin = max(6.0 * grain_diameter, zmax - zmin, xmax - xmin)
    half = 0.5 * distance + max(abs(xmin), abs(xmax)) + margin
    top = zmax - depth  # the body's highest point relative to the surface
    return BedSpec(
        length=2.0 * half,
        depth=depth - zmin + margin,
        kind=BedKind.SLAB,
        headroom=max(5.0 * grain_diameter, top + 3.0 * grain_diameter),
        packing=Packing.coerce(packing),
        grain_diameter=grain_diameter,
        seed=seed,
    )


#: the intrusion's history rows and body pose (the drag is a motion at vz = 0), the progress read from x
DRAG_HOOKS = RunHooks(INTRUSION_HOOKS.record_row, INTRUSION_HOOKS.pose, "x_m")


@dataclass(frozen=True)
class _Drag:
    """The checked drag: reference point ``depth`` [m] below the surface, ``distance`` [m] and
    ``speed`` [m/s] along +x, body ``angle`` [rad]."""

    depth: float
    distance: float
    speed: float
    angle: float

    @property
    def start(self) -> tuple[float, float, float]:
        """The start pose: ``distance / 2`` behind x = 0 at ``depth``, rotated by ``angle``."""
        return (-0.5 * self.distance, -self.depth, self.angle)


def _place_body(bed: Bed, body: Any, drag: _Drag) -> tuple[np.ndarray, int, int]:
    """Add the body's spheres at the start to the bed and delete every grain that overlaps them;
    returns the spheres, the bed's atom count before and the grains left. One :class:`InputError`
    line for a bed too short for the path or a body too near the floor."""
    lmp, d = bed.lmp, bed.dem.grain_diameter
    pts, d_w = body_spheres(body, d, drag.start, bed.surface, (bed.box[2], bed.box[3]), periodic=True)
    if pts[:, 0].min() < bed.box[0] + d or pts[:, 0].max() + drag.distance > bed.box[1] - d:
        raise InputError("bed length", bed.box[1] - bed.box[0], "a bed longer than the body's path")
    if pts[:, 2].min() < 2.0 * d:
        raise InputError("depth", drag.depth, "a body clear of the floor by two grains")
    n_bed = int(lmp.get_natoms())
    _add_atoms(lmp, pts, n_bed)
    r_max = 0.5 * d * (1.0 + bed.dem.diameter_spread)
    for line in (
        "group body clear",
        f"group body type {BODY_TYPE}",
        f"set type {BODY_TYPE} diameter {d_w:.17g}",
        f"set type {BODY_TYPE} density {bed.dem.grain_density:.17g}",
        # every grain that overlaps a body sphere goes (it would be inside the body)
        f"delete_atoms overlap {0.5 * d_w + r_max:.17g} grains body",
        "reset_timestep 0",
    ):
        lmp.command(line)
    return pts, n_bed, int(lmp.get_natoms()) - len(pts)


def _settle_around_body(bed: Bed, settle_time: float | None) -> None:
    """Let the bed settle around the still body for ``settle_time`` [s] (default
    :data:`SETTLE_TIMES` free-fall times sqrt(d / g)); the step count restarts after."""
    lmp, d, dt = bed.lmp, bed.dem.grain_diameter, bed.dt
    t_settle = SETTLE_TIMES * math.sqrt(d / bed.spec.gravity) if settle_time is None else settle_time
    check_positive("settle_time", t_settle, allow_zero=True)
    if t_settle > 0:
        lmp.command(f"run {max(1, round(t_settle / dt))}")
    lmp.command("reset_timestep 0")


def _drag_params(
    bed: Bed, body: Any, material: Material, drag: _Drag, pts: np.ndarray, n_grains: int,
    record_spacing: float | None,
) -> dict[str, Any]:  # fmt: skip
    """The run's parameters as the chunked run takes them: motion, chunking (a history row per
    ``record_spacing`` [m] of travel, default a tenth of a grain), bed and grains."""
    lmp, d, dt, speed, start = bed.lmp, bed.dem.grain_diameter, bed.dt, drag.speed, drag.start
    spacing = record_spacing if record_spacing is not None else 0.1 * d
    if not spacing > 0 or not math.isfinite(spacing):
        raise InputError("record_spacing", spacing, "a travel > 0 [m] per history row")
    chunk = max(10, round(spacing / (speed * dt)))
    rows = max(1, math.ceil(math.ceil(drag.distance / (speed * dt)) / chunk))
    centroid = pts[:, [0, 2]].mean(axis=0)
    ref0 = np.array([start[0], bed.surface + start[1]])
    width = bed.thickness
    return {
        "run": "dem drag", "velocity": [speed, 0.0], "ref_offset": (ref0 - centroid).tolist(),
        "start": list(start), "surface": bed.surface, "chunk": chunk, "rows": rows, "dt": dt,
        "speed": speed, "depth": drag.depth, "direction": 0.0, "angle": drag.angle, "width": width,
        "force_scale": body.width / width, "grain_diameter": d, "body_spheres": len(pts),
        "grain_count": n_grains, "bed": bed.summary(), "bed_kind": BedKind.SLAB.value,
        "gravity": bed.spec.gravity, "material": material.name, "dem": _dem_dict(bed), "box": list(bed.box),
        "newton": newton_setting(lmp),
    }  # fmt: skip


def run_drag(
    body: Any,
    material: Material,
    *,
    depth: float,
    distance: float,
    speed: float = 0.05,
    angle: float = 0.0,
    packing: Packing | str = Packing.DENSE,
    grain_diameter: float | None = None,
    bed_spec: BedSpec | None = None,
    seed: int = 12345,
    settle_time: float | None = None,
    record_spacing: float | None = None,
    average_fraction: float = 0.5,
    progress: Callable[[float, float], None] | None = None,
) -> DEMDragResult:
    """Drag ``body`` (a plane body rotated by ``angle`` [rad]; its reference point ``depth`` [m] below the
    surface) along +x at
    ``speed`` [m/s] for ``distance`` [m] through a slab bed of ``material``'s grains (``packing``,
    ``grain_diameter`` [m] coarse-graining, ``seed``; or ``bed_spec``). The bed settles around the
    placed body for ``settle_time`` [s] (default ten free-fall times sqrt(d / g)) first.
    ``record_spacing``: travel [m] per history row (default a tenth of a grain)."""
    body = as_intruder(body)
    if isinstance(body, MeshIntruder):
        raise InputError("body", "mesh", "a plane body (a drag runs in a slab bed)")
    depth = check_finite("depth", depth)
    distance = check_positive("distance", distance)
    speed = check_speed(speed)
    average_fraction = check_range("average_fraction", average_fraction, 0.05, 1.0)
    angle = check_finite("angle", angle)
    dem = material.require_dem()
    d = grain_diameter if grain_diameter is not None else dem.grain_diameter
    _xmin, _xmax, zmin, _zmax = rotated_extent(body, angle)
    if not depth - zmin > 0:  # the lowest point of the body must be in the bed
        raise InputError("depth", depth, f"above {zmin:.4g} m: the body's lowest point below the surface")
    spec = bed_spec or drag_bed_spec(body, depth=depth, distance=distance, grain_diameter=d, angle=angle,
                                     packing=packing, seed=seed)  # fmt: skip
    if spec.kind is not BedKind.SLAB:
        raise InputError("bed_spec.kind", spec.kind.value, "'slab' (a drag runs in a slab bed)")
    drag = _Drag(depth, distance, speed, angle)
    bed = _settled_bed(material, spec, progress, 0.25)
    lmp = bed.lmp
    try:
        pts, n_bed, n_grains = _place_body(bed, body, drag)
        _settle_around_body(bed, settle_time)
        params = _drag_params(bed, body, material, drag, pts, n_grains, record_spacing)
        _body_fixes(lmp, params)
        history: dict[str, list[float]] = {k: [] for k in HISTORY_KEYS}
        recorder = _recorder(body, params, None, None, 0)

        def drag_progress(x: float, fraction: float) -> None:
            if progress is not None:
                progress(x - drag.start[0], 0.25 + 0.75 * (fraction - 0.3) / 0.7)

        run_chunks(lmp, params, history, 0, None, 60.0, drag_progress, None, recorder, DRAG_HOOKS)
    finally:
        bed.lmp = None
        lmp.close()
    return _drag_result(params, history, n_bed - n_grains, distance, average_fraction)


def _drag_result(params: dict[str, Any], history: dict[str, list[float]], deleted: int, distance: float,
                 average_fraction: float) -> DEMDragResult:  # fmt: skip
    h = {k: np.asarray(v, dtype=float) for k, v in history.items()}
    scale = params["force_scale"]
    travel = h["x_m"] - params["start"][0]
    out = {
        "time_s": h["time_s"],
        "travel_m": travel,
        "x_m": h["x_m"],
        "z_m": h["z_m"],
        "drag_N": -h["force_x_N"] * scale,
        "lift_N": h["force_z_N"] * scale,
        "torque_y_Nm": h["torque_y_Nm"] * scale,
    }
    window = average_fraction * distance
    late = travel >= distance - window - 1e-12
    if not late.any():
        late[-1] = True
    summary = {
        "drag_N": float(out["drag_N"][late].mean()),
        "lift_N": float(out["lift_N"][late].mean()),
        "drag_std_N": float(out["drag_N"][late].std()),
        "averaging_window_m": window,
        "depth_m": params["depth"],
        "distance_m": distance,
        "speed_m_s": params["speed"],
        "width_m": params["width"] * scale,
        "dem_width_m": params["width"],
        "grain_count": params["grain_count"],
        "deleted_grains": deleted,
        "body_spheres": params["body_spheres"],
    }
    return DEMDragResult(out, summary, dict(params["bed"]))
