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

Checkpoints and ``resume`` are those of :func:`terradyn.dem.run_intrusion` (the same chunked loop,
:func:`terradyn.dem.runs.run_chunks`): a resumed run repeats the uninterrupted one bit for bit on one
rank. The restart file keeps the atoms (positions, velocities, spins, masses, the ``body`` group) and
the contact histories, not the fixes; ``fix rigid`` is re-issued after it with the same arguments.
That is exact because ``fix rigid`` (its default ``reinit yes``) recomputes the body's centre of mass,
inertia, orientation and velocities from its atoms at the start of every ``run``, in the uninterrupted
run too, and the restart file holds those atoms exactly as the uninterrupted run's next ``run``
finds them; its forces and torques are recomputed by the setup of that ``run`` as every chunk's are.
"""

from __future__ import annotations

import dataclasses
import json
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import InputError, check_finite, check_positive
from ..geometry import Body
from ..materials import Material
from .bed import BODY_TYPE, Bed, BedKind, BedSpec, Packing
from .fields import FieldRecorder, frame_every, rows_between
from .intruders import MeshIntruder, body_spheres, rotated_extent
from .runs import (
    RunHooks,
    _add_atoms,
    _dem_dict,
    _mesh_bed,
    _settled_bed,
    _start_gap,
    as_intruder,
    newton_setting,
    read_checkpoint,
    restore_lammps,
    run_chunks,
)

if TYPE_CHECKING:
    from ..geometry3d import TriangleMesh

__all__ = ["DEMWheelResult", "default_wheel_bed", "run_wheel", "wheel_radius"]

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


def wheel_radius(body: Body | MeshIntruder) -> float:
    """Nominal (outer) radius [m] of a DEM wheel body; an InputError for a body that is not a wheel."""
    r = getattr(body, "outer_radius", None)
    if r is None:
        raise InputError("body", body, "a wheel (WheelCircular, WheelGrousered, WheelFlapped)")
    return float(r)


def default_wheel_bed(body: Body | MeshIntruder | TriangleMesh, *, travel: float, grain_diameter: float,
                      kind: BedKind | str = BedKind.SLAB, packing: Packing | str = Packing.DENSE,
                      seed: int = 12345) -> BedSpec:  # fmt: skip
    """A bed for a wheel rolling ``travel`` [m] from x = -travel/2 to +travel/2 (as :func:`run_wheel`
    places it), 1.5 radii deep. It reaches ``travel + r + margin`` either side of x = 0 (margin =
    max(r, 6 grains)), so beyond the wheel's path it keeps ``travel / 2 + margin`` of grains at each
    end: more than the margin needs (about twice the grains of a bed sized to the path for a travel of
    several radii); kept so that measured DEM wheel figures stay comparable."""
    body = as_intruder(body)
    r = wheel_radius(body)
    margin = max(r, 6 * grain_diameter)
    length = 2.0 * (travel + r + margin) + 0.0
    kind = BedKind.coerce(kind)
    thickness = None
    if isinstance(body, MeshIntruder):  # a 3D wheel: the same margin beside it across
        _mesh_bed(kind)
        thickness = body.width + 2.0 * margin
    return BedSpec(length=length, depth=max(1.5 * r, 10 * grain_diameter), kind=kind, thickness=thickness,
                   packing=Packing.coerce(packing), headroom=2.5 * r, grain_diameter=grain_diameter,
                   seed=seed)  # fmt: skip


def _bed_gravity(bed: Bed | None, gravity: float | None) -> float:
    """g [m/s^2] of the run: a prepared bed's own (a ``gravity`` that differs from it is refused), else
    ``gravity`` (default 9.81)."""
    if bed is not None:
        if gravity is not None and not math.isclose(gravity, bed.spec.gravity, rel_tol=1e-12):
            raise InputError("gravity", gravity, f"the prepared bed's {bed.spec.gravity:g} m/s^2",
                             "a bed keeps the gravity it settled at; leave gravity out")  # fmt: skip
        gravity = bed.spec.gravity
    return check_positive("gravity", 9.81 if gravity is None else gravity)


def _field_outputs(
    snapshot_dir: str | Path | None, snapshot_interval: float | None, frame_count: int
) -> dict[str, Any]:
    """The snapshot folder, interval [s] and frame count of a wheel run, checked."""
    if snapshot_interval is not None:
        snapshot_interval = check_positive("snapshot_interval", snapshot_interval)
    if not isinstance(frame_count, int) or not 0 <= frame_count <= 500:
        raise InputError("frame_count", frame_count, "an integer in [0, 500]")
    return {"snapshot_dir": None if snapshot_dir is None else Path(snapshot_dir),
            "snapshot_interval": snapshot_interval, "frame_count": frame_count}  # fmt: skip


def run_wheel(
    body: Body | MeshIntruder | TriangleMesh,
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
    seed: int = 12345,
    record_interval: float | None = None,
    gravity: float | None = None,
    checkpoint_path: str | Path | None = None,
    checkpoint_interval: float = 60.0,
    resume: bool = False,
    progress: Callable[[float, float], None] | None = None,
    stop_after_rows: int | None = None,
    snapshot_dir: str | Path | None = None,
    snapshot_interval: float | None = None,
    frame_count: int = 0,
) -> DEMWheelResult:
    """Roll ``body`` at spin ``omega`` [rad/s] and slip ``slip`` under ``load`` [N] for ``duration`` [s].

    The wheel starts at x = -travel/2 (travel = V duration) and ends near x = +travel/2. Gravity
    [m/s^2] is that of the bed: a fresh bed is settled at ``gravity`` (default 9.81); a prepared
    ``bed`` keeps its own (``BedSpec.gravity``), and a ``gravity`` that differs from it is refused. The
    wheel's mass is ``load / gravity``. ``snapshot_dir``:
    per-grain NetCDF snapshots every ``snapshot_interval`` [s] (default duration / 20);
    ``frame_count`` animation frames over the run (``result.frames``).

    ``checkpoint_path``: a LAMMPS restart file and its side files (:func:`terradyn.dem.runs.checkpoint_files`)
    written every ``checkpoint_interval`` wall-clock seconds [s] at a row boundary and when the run is
    interrupted; ``resume=True`` continues the run saved there (refused, naming them, if the inputs
    differ from the checkpoint's). ``stop_after_rows`` stops early (after writing a checkpoint), as an
    interruption would; tests use it.

    A 3D wheel is a :class:`~terradyn.geometry3d.TriangleMesh` (or a
    :class:`~terradyn.dem.intruders.MeshIntruder`) centred on its axle, the y axis; it needs
    ``kind="3d"`` (or a 3d ``bed``) and its radius is the largest vertex distance from the axle."""
    body = as_intruder(body)
    if isinstance(body, MeshIntruder) and not resume:
        _mesh_bed(bed.spec.kind if bed is not None else BedKind.coerce(kind))
    r = wheel_radius(body)
    gravity = _bed_gravity(bed, gravity)
    load = check_positive("load", load)
    omega = check_finite("omega", omega)
    if not omega > 0:
        raise InputError("omega", omega, "a spin rate > 0 [rad/s]")
    slip = check_finite("slip", slip)
    if not -1.0 <= slip < 1.0:
        raise InputError("slip", slip, "a slip in [-1, 1)")
    duration = check_positive("duration", duration)
    if record_interval is not None:
        record_interval = check_positive("record_interval", record_interval)
    outputs = _field_outputs(snapshot_dir, snapshot_interval, frame_count)
    velocity = (1.0 - slip) * omega * r
    travel = abs(velocity) * duration
    dem = material.require_dem()
    d = grain_diameter if grain_diameter is not None else dem.grain_diameter
    inputs = _inputs(body, material, bed, load=load, omega=omega, slip=slip, duration=duration,
                     record_interval=record_interval, kind=kind, packing=packing, grain_diameter=d,
                     seed=seed, gravity=gravity)  # fmt: skip
    ckpt = Path(checkpoint_path) if checkpoint_path is not None else None
    if resume:
        if ckpt is None:
            raise InputError("checkpoint_path", checkpoint_path, "an existing checkpoint with resume")
        return _resume(ckpt, inputs, body, outputs, checkpoint_interval, progress, stop_after_rows)
    if bed is None:
        spec = default_wheel_bed(body, travel=travel, grain_diameter=d, kind=kind, packing=packing, seed=seed)
        spec = dataclasses.replace(spec, gravity=gravity)
        bed = _settled_bed(material, spec, progress)
    lmp = bed.lmp
    try:
        params = _place_wheel(bed, body, r, load, omega, velocity, slip, duration, travel, record_interval,
                              material.name, inputs)  # fmt: skip
        recorder = _recorder(params, body, outputs)
        history: dict[str, list[float]] = {k: [] for k in WHEEL_HISTORY}
        final = run_chunks(lmp, params, history, 0, ckpt, checkpoint_interval, progress, stop_after_rows,
                           recorder, WHEEL_HOOKS)  # fmt: skip
        return _result(params, history, recorder, final)
    finally:
        bed.lmp = None
        lmp.close()


def _inputs(body: Body | MeshIntruder, material: Material, bed: Bed | None, **values: Any) -> dict[str, Any]:
    """The inputs that identify a wheel run (a resume must repeat them), as JSON loads them back.
    The bed's preparation counts only when this call prepares it."""
    from ..runrecords import plain

    bed_made = {k: values.pop(k) for k in ("kind", "packing", "grain_diameter", "seed", "gravity")}
    dem = {k: v for k, v in plain(material.require_dem()).items() if k != "notes"}  # numbers only
    described = body.describe() if isinstance(body, MeshIntruder) else plain(body)
    out = {"run": "dem wheel", "body": described, "material": material.name, "dem": dem, **values,
           "bed": "given" if bed is not None else plain(bed_made)}  # fmt: skip
    loaded: dict[str, Any] = json.loads(json.dumps(out, sort_keys=True))
    return loaded


def _check_inputs(ckpt: Path, saved: dict[str, Any], current: dict[str, Any]) -> None:
    from ..runrecords import input_differences

    current = dict(current)
    if saved.get("bed") == "given":  # a bed given to the first call: nothing to compare
        current["bed"] = "given"
    diffs = input_differences(saved, current)
    if diffs:
        more = f" and {len(diffs) - 4} more" if len(diffs) > 4 else ""
        raise InputError("checkpoint_path", str(ckpt), "a checkpoint of a run with the same inputs",
                         f"it differs in {'; '.join(diffs[:4])}{more}; rerun with the checkpoint's "
                         "inputs or remove the file")  # fmt: skip


def _resume(ckpt: Path, inputs: dict[str, Any], body: Body | MeshIntruder, outputs: dict[str, Any],
            interval: float, progress: Callable[[float, float], None] | None,
            stop_after_rows: int | None) -> DEMWheelResult:  # fmt: skip
    params, history, step, frames = read_checkpoint(ckpt, "dem wheel")
    _check_inputs(ckpt, params["inputs"], inputs)
    lmp = restore_lammps(ckpt, params)
    try:
        _wheel_fixes(lmp, params)
        recorder = _recorder(params, body, outputs)
        recorder.frames = frames if recorder.frame_every > 0 else []
        final = run_chunks(lmp, params, history, step, ckpt, interval, progress, stop_after_rows, recorder,
                           WHEEL_HOOKS)  # fmt: skip
        return _result(params, history, recorder, final)
    finally:
        lmp.close()


def _place_wheel(bed: Bed, body: Body | MeshIntruder, r: float, load: float, omega: float, velocity: float,
                 slip: float, duration: float, travel: float, record_interval: float | None,
                 material_name: str, inputs: dict[str, Any]) -> dict[str, Any]:  # fmt: skip
    """Add the wheel's spheres above the bed, spinning and moving forward; its fixes; the run's
    parameters (what a resume needs)."""
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
    ):
        lmp.command(line)
    params: dict[str, Any] = {
        "run": "dem wheel",
        "inputs": inputs,
        "chunk": chunk,
        "rows": rows,
        "dt": dt,
        "radius": r,
        "omega": omega,
        "slip": slip,
        "load": load,
        "velocity": velocity,
        "duration": duration,
        "scale": scale,
        "surface": bed.surface,
        "gravity": g,
        "grain_diameter": d,
        "grain_count": n0,
        "material": material_name,
        "dem": _dem_dict(bed),
        "box": list(bed.box),
        "newton": newton_setting(lmp),
        "bed_kind": bed.spec.kind.value,
        "bed_thickness": bed.thickness,
        "bed": bed.summary(),
    }
    _wheel_fixes(lmp, params)
    return params


def _wheel_fixes(lmp: Any, params: dict[str, Any]) -> None:
    """The wheel's weight, its rigid-body integration with only z free, and the soil force and torque
    averaging (fresh runs, and after a restart: LAMMPS restart files keep no fixes, computes or
    variables)."""
    g, k = params["gravity"], params["chunk"]
    for line in (
        f"fix td_wgrav body gravity {g:.17g} vector 0 0 -1",
        "fix td_rigid body rigid single force * off off on torque * off off off",
        "compute td_tqa body property/atom tqy",
        "variable td_xr equal xcm(body,x)",
        "variable td_zr equal xcm(body,z)",
        "variable td_tq atom (z-v_td_zr)*fx-(x-v_td_xr)*fz+c_td_tqa",
        # soil forces only: the atoms' forces less their weight
        f"variable td_fz atom fz+mass*{g:.17g}",
        "compute td_f body reduce sum fx v_td_fz v_td_tq",
        f"fix td_avg all ave/time 1 {k} {k} c_td_f[1] c_td_f[2] c_td_f[3]",
    ):
        lmp.command(line)


def _wheel_pose(lmp: Any, params: dict[str, Any], time_s: float) -> tuple[float, float, float]:
    """Axle x, z (terradyn's frame) and the wheel's rotation about +y at ``time_s``."""
    x = float(lmp.extract_variable("td_xr"))
    return (x, float(lmp.extract_variable("td_zr")) - params["surface"], params["omega"] * time_s)


def _wheel_row(lmp: Any, params: dict[str, Any], history: dict[str, list[float]], step: int) -> None:
    """The history row of the chunk that ended at ``step``: soil forces averaged over it, the axle's
    position at its end."""
    scale = params["scale"]
    fx = float(lmp.extract_fix("td_avg", 0, 1, 0)) * scale
    fz = float(lmp.extract_fix("td_avg", 0, 1, 1)) * scale
    ty = float(lmp.extract_fix("td_avg", 0, 1, 2)) * scale
    x, z, _theta = _wheel_pose(lmp, params, step * params["dt"])
    values = (step * params["dt"], x, z, params["radius"] - z, fx, fz, -ty)
    for key, value in zip(WHEEL_HISTORY, values, strict=True):
        history[key].append(value)


WHEEL_HOOKS = RunHooks(_wheel_row, _wheel_pose, "time_s")


def _result(params: dict[str, Any], history: dict[str, list[float]], recorder: FieldRecorder,
            final: tuple[dict[str, np.ndarray], dict[str, np.ndarray]]) -> DEMWheelResult:  # fmt: skip
    h = {k: np.asarray(v, dtype=float) for k, v in history.items()}
    late = h["time_s"] > 0.5 * params["duration"]
    summary = {
        "sinkage_m": float(h["sinkage_m"][late].mean()),
        "drawbar_pull_N": float(h["drawbar_pull_N"][late].mean()),
        "drive_torque_Nm": float(h["drive_torque_Nm"][late].mean()),
        "vertical_force_N": float(h["vertical_force_N"][late].mean()),
        "slip": params["slip"],
        "load_N": params["load"],
        "omega_rad_s": params["omega"],
        "forward_velocity_m_s": params["velocity"],
        "grain_count": params["grain_count"],
        "material": params["material"],
    }
    return DEMWheelResult(h, summary, dict(params["bed"]), final_particles=final[0],
                          frames=list(recorder.frames), final_frame=final[1],
                          snapshots=list(recorder.written))  # fmt: skip


def _recorder(params: dict[str, Any], body: Body | MeshIntruder, outputs: dict[str, Any]) -> FieldRecorder:
    d, box = params["grain_diameter"], params["box"]
    mid = 0.5 * (box[2] + box[3])
    folder = outputs["snapshot_dir"]
    attrs = {
        "run": "dem wheel",
        "material": params["material"],
        "grain_diameter_m": d,
        "bed_kind": params["bed_kind"],
        "bed_thickness_m": params["bed_thickness"],
        "forward_velocity_m_s": params["velocity"],
        "omega_rad_s": params["omega"],
        "gravity_m_s2": params["gravity"],
        "body_pose": "axle x, z [m] and wheel rotation theta about +y [rad]",
    }
    row_time, default = params["chunk"] * params["dt"], params["duration"] / 20.0
    every = rows_between(outputs["snapshot_interval"], row_time, default) if folder is not None else 0
    return FieldRecorder(
        body, params["surface"], d, snapshot_dir=folder, snapshot_every=every,
        frame_every=frame_every(outputs["frame_count"], params["rows"]),
        y_slice=None if params["bed_kind"] == BedKind.SLAB.value else (mid - 2.0 * d, mid + 2.0 * d),
        attrs=attrs,
    )  # fmt: skip
