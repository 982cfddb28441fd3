"""A wheel on a DEM bed: prescribed spin and slip, free vertical motion under a load.

The wheel is a clump of body spheres (as :mod:`terradyn.dem.intruders`) integrated by LAMMPS's
``fix rigid`` with only the vertical translation free: its forward speed ``V = (1 - s) omega r`` and
its spin ``omega`` stay as set, its height follows the soil's vertical force against the load (its
weight, mass ``load / g``). It starts just above the surface and rolls for ``duration``; the summary
is the mean over the last half of the run. Keys and signs are those of every terradyn wheel command:
drawbar pull = horizontal soil force (positive forward), drive torque = -(soil torque about +y),
sinkage = depth of the lowest point of the rim below the undisturbed surface. In a slab bed the wheel
spans the slab, the load is applied per unit width (``load * slab / width``) and forces and torques are
reported for the wheel's width.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError, check_finite, check_positive
from ..geometry import Body
from ..materials import Material
from .bed import BODY_TYPE, Bed, BedKind, BedSpec, Packing, prepare_bed
from .fields import FieldRecorder, frame_every, rows_between
from .intruders import body_spheres, rotated_extent
from .runs import _add_atoms, _start_gap

__all__ = ["DEMWheelResult", "default_wheel_bed", "run_wheel"]

WHEEL_HISTORY = ("time_s", "x_m", "z_m", "sinkage_m", "drawbar_pull_N", "vertical_force_N", "drive_torque_Nm")


@dataclass(frozen=True, eq=False)
class DEMWheelResult:
    """History (one row per record interval) and summary of a DEM wheel run (SI)."""

    history: dict[str, np.ndarray]
    summary: dict[str, Any]
    bed: dict[str, Any] = field(default_factory=dict)
    #: per-grain fields at the end (:func:`terradyn.dem.fields.grain_fields`), animation frames and the
    #: last state (as :func:`terradyn.plotting.mpm.animate_frames` draws them), snapshot files written
    final_particles: dict[str, np.ndarray] | None = None
    frames: list[dict[str, np.ndarray]] = field(default_factory=list)
    final_frame: dict[str, np.ndarray] | None = None
    snapshots: list[Path] = field(default_factory=list)

    def to_dataframe(self) -> Any:
        import pandas as pd

        return pd.DataFrame({k: self.history[k] for k in WHEEL_HISTORY})


def _radius(body: Body) -> float:
    r = getattr(body, "outer_radius", None)
    if r is None:
        raise InputError("body", body, "a wheel (WheelCircular, WheelGrousered, WheelFlapped)")
    return float(r)


def default_wheel_bed(body: Body, *, travel: float, grain_diameter: float,
                      kind: BedKind | str = BedKind.SLAB, packing: Packing | str = Packing.DENSE,
                      seed: int = 12345) -> BedSpec:  # fmt: skip
    """A bed for a wheel rolling ``travel`` [m] forward from x = 0: one radius of grains behind and
    two in front, 1.5 radii deep."""
    r = _radius(body)
    margin = max(r, 6 * grain_diameter)
    length = 2.0 * (travel + r + margin) + 0.0
    return BedSpec(length=length, depth=max(1.5 * r, 10 * grain_diameter), kind=BedKind.coerce(kind),
                   packing=Packing.coerce(packing), headroom=2.5 * r, grain_diameter=grain_diameter,
                   seed=seed)  # fmt: skip


def run_wheel(
    body: Body,
    material: Material,
    *,
    load: float,
    omega: float,
    slip: float,
    duration: float,
    bed: Bed | None = None,
    kind: BedKind | str = BedKind.SLAB,
    packing: Packing | str = Packing.DENSE,
    grain_diameter: float | None = None,
    record_interval: float | None = None,
    gravity: float = 9.81,
    progress: Callable[[float, float], None] | None = None,
    snapshot_dir: str | Path | None = None,
    snapshot_interval: float | None = None,
    frame_count: int = 0,
) -> DEMWheelResult:
    """Roll ``body`` at spin ``omega`` [rad/s] and slip ``slip`` under ``load`` [N] for ``duration`` [s].

    The wheel starts at x = -travel/2 (travel = V duration) and ends near x = +travel/2. Gravity is
    that of the bed (``BedSpec.gravity``); the wheel's mass is ``load / gravity``. ``snapshot_dir``:
    per-grain NetCDF snapshots every ``snapshot_interval`` [s] (default duration / 20);
    ``frame_count`` animation frames over the run (``result.frames``)."""
    r = _radius(body)
    load = check_positive("load", load)
    omega = check_finite("omega", omega)
    if not omega > 0:
        raise InputError("omega", omega, "a spin rate > 0 [rad/s]")
    slip = check_finite("slip", slip)
    if not -1.0 <= slip < 1.0:
        raise InputError("slip", slip, "a slip in [-1, 1)")
    duration = check_positive("duration", duration)
    if snapshot_interval is not None:
        snapshot_interval = check_positive("snapshot_interval", snapshot_interval)
    if not isinstance(frame_count, int) or not 0 <= frame_count <= 500:
        raise InputError("frame_count", frame_count, "an integer in [0, 500]")
    outputs = {"snapshot_dir": None if snapshot_dir is None else Path(snapshot_dir),
               "snapshot_interval": snapshot_interval, "frame_count": frame_count}  # fmt: skip
    velocity = (1.0 - slip) * omega * r
    travel = abs(velocity) * duration
    dem = material.require_dem()
    d = grain_diameter if grain_diameter is not None else dem.grain_diameter
    if bed is None:
        spec = default_wheel_bed(body, travel=travel, grain_diameter=d, kind=kind, packing=packing)
        spec = dataclasses.replace(spec, gravity=gravity)

        def settle(t: float, f: float) -> None:
            if progress is not None:
                progress(0.0, 0.3 * f)

        bed = prepare_bed(material, spec, progress=settle)
    lmp = bed.lmp
    try:
        return _roll(bed, body, r, load, omega, velocity, slip, duration, travel, record_interval, progress,
                     material.name, outputs)  # fmt: skip
    finally:
        bed.lmp = None
        lmp.close()


def _roll(bed: Bed, body: Body, r: float, load: float, omega: float, velocity: float, slip: float,
          duration: float, travel: float, record_interval: float | None,
          progress: Callable[[float, float], None] | None, material_name: str,
          outputs: dict[str, Any]) -> DEMWheelResult:  # fmt: skip
    lmp, d, dt = bed.lmp, bed.dem.grain_diameter, bed.dt
    x_start = -0.5 * travel
    if x_start - r < bed.box[0] + 2 * d or 0.5 * travel + r > bed.box[1] - 2 * d:
        raise InputError("bed length", bed.box[1] - bed.box[0], f"at least {travel + 2 * r + 4 * d:.4g} m")
    periodic = bed.spec.kind is BedKind.SLAB
    mid = 0.5 * (bed.box[2] + bed.box[3])
    y_range = (bed.box[2], bed.box[3]) if periodic else (mid - 0.5 * body.width, mid + 0.5 * body.width)
    width = bed.thickness if periodic else body.width
    gap = _start_gap(bed, body, 1e-9, math.pi / 2, 0.0)
    _xmin, _xmax, zmin, _zmax = rotated_extent(body, 0.0)
    z_start = gap - zmin  # axle height above the surface
    pts, d_w = body_spheres(body, d, (x_start, z_start, 0.0), bed.surface, y_range, periodic=periodic)
    if pts[:, 2].max() > bed.box[5] - d:
        raise InputError("bed headroom", bed.box[5] - bed.surface, f"at least {2 * r + gap + d:.4g} m")
    n0 = int(lmp.get_natoms())
    _add_atoms(lmp, pts, n0)
    scale = body.width / width
    applied = load / scale  # load on the slab's share of the wheel [N]
    g = bed.spec.gravity
    mass_atom = applied / g / len(pts)
    density = mass_atom / (math.pi / 6.0 * d_w**3)
    xc, zc = x_start, bed.surface + z_start
    rows = max(1, round(duration / (record_interval or duration / 100.0)))
    chunk = max(10, round(duration / rows / dt))
    rows = math.ceil(duration / (chunk * dt))
    for line in (
        "group body clear",
        f"group body type {BODY_TYPE}",
        f"set type {BODY_TYPE} diameter {d_w:.17g}",
        f"set type {BODY_TYPE} density {density:.17g}",
        "reset_timestep 0",
        f"variable td_vx atom {velocity:.17g}+{omega:.17g}*(z-({zc:.17g}))",
        f"variable td_vz atom -{omega:.17g}*(x-({xc:.17g}))",
        "velocity body set v_td_vx 0.0 v_td_vz units box",
        f"fix td_wgrav body gravity {g:.17g} vector 0 0 -1",
        "fix td_rigid body rigid single force * off off on torque * off off off",
        "compute td_tqa body property/atom tqy",
        "variable td_xr equal xcm(body,x)",
        "variable td_zr equal xcm(body,z)",
        "variable td_tq atom (z-v_td_zr)*fx-(x-v_td_xr)*fz+c_td_tqa",
        # soil forces only: the atoms' forces less their weight
        f"variable td_fz atom fz+mass*{g:.17g}",
        "compute td_f body reduce sum fx v_td_fz v_td_tq",
        f"fix td_avg all ave/time 1 {chunk} {chunk} c_td_f[1] c_td_f[2] c_td_f[3]",
    ):
        lmp.command(line)
    hist: dict[str, list[float]] = {k: [] for k in WHEEL_HISTORY}
    recorder = _recorder(bed, body, outputs, chunk * dt, rows, duration, material_name, velocity, omega)
    recorder.prepare(lmp)

    def pose(t: float) -> tuple[float, float, float]:
        x = float(lmp.extract_variable("td_xr"))
        return (x, float(lmp.extract_variable("td_zr")) - bed.surface, omega * t)

    step = 0
    for row in range(rows):
        # one setup at every chunk boundary, snapshots right after it (they do not perturb the run)
        lmp.command("run 0 post no")
        if row > 0:
            recorder.row(lmp, row, step, step * dt, pose(step * dt))
        lmp.command(f"run {chunk}")
        step += chunk
        fx = float(lmp.extract_fix("td_avg", 0, 1, 0)) * scale
        fz = float(lmp.extract_fix("td_avg", 0, 1, 1)) * scale
        ty = float(lmp.extract_fix("td_avg", 0, 1, 2)) * scale
        x = float(lmp.extract_variable("td_xr"))
        z = float(lmp.extract_variable("td_zr")) - bed.surface
        values = (step * dt, x, z, r - z, fx, fz, -ty)
        for key, value in zip(WHEEL_HISTORY, values, strict=True):
            hist[key].append(value)
        if progress is not None:
            progress(step * dt, 0.3 + 0.7 * (row + 1) / rows)
    lmp.command("run 0 post no")
    recorder.row(lmp, rows, step, step * dt, pose(step * dt))
    final = recorder.final(lmp, step, step * dt, pose(step * dt))
    h = {k: np.asarray(v) for k, v in hist.items()}
    late = h["time_s"] > 0.5 * duration
    summary = {
        "sinkage_m": float(h["sinkage_m"][late].mean()),
        "drawbar_pull_N": float(h["drawbar_pull_N"][late].mean()),
        "drive_torque_Nm": float(h["drive_torque_Nm"][late].mean()),
        "vertical_force_N": float(h["vertical_force_N"][late].mean()),
        "slip": slip,
        "load_N": load,
        "omega_rad_s": omega,
        "forward_velocity_m_s": velocity,
        "grain_count": n0,
        "material": material_name,
    }
    return DEMWheelResult(h, summary, bed.summary(), final_particles=final[0], frames=list(recorder.frames),
                          final_frame=final[1], snapshots=list(recorder.written))  # fmt: skip


def _recorder(bed: Bed, body: Body, outputs: dict[str, Any], row_time: float, rows: int, duration: float,
              material_name: str, velocity: float, omega: float) -> FieldRecorder:  # fmt: skip
    d = bed.dem.grain_diameter
    mid = 0.5 * (bed.box[2] + bed.box[3])
    folder = outputs["snapshot_dir"]
    attrs = {
        "run": "dem wheel",
        "material": material_name,
        "grain_diameter_m": d,
        "bed_kind": bed.spec.kind.value,
        "bed_thickness_m": bed.thickness,
        "forward_velocity_m_s": velocity,
        "omega_rad_s": omega,
        "gravity_m_s2": bed.spec.gravity,
        "body_pose": "axle x, z [m] and wheel rotation theta about +y [rad]",
    }
    every = rows_between(outputs["snapshot_interval"], row_time, duration / 20.0) if folder is not None else 0
    return FieldRecorder(
        body, bed.surface, d, snapshot_dir=folder, snapshot_every=every,
        frame_every=frame_every(outputs["frame_count"], rows),
        y_slice=None if bed.spec.kind is BedKind.SLAB else (mid - 2.0 * d, mid + 2.0 * d), attrs=attrs,
    )  # fmt: skip
