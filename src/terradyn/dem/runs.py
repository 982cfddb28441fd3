"""DEM runs: a rigid body pushed at constant velocity into a settled bed (force and torque history).

The bed is prepared (:func:`terradyn.dem.bed.prepare_bed`) around the body unless one is given; the
body starts with its lowest point half a grain above the free surface and moves along ``direction``
(below +x) at ``speed`` until its reference point is ``depth`` below the surface, ending at x = 0.
Each history row is the mean over one record interval of the contact force (and torque about the
reference point) on the body, at the mean position of the interval.

Checkpoints are LAMMPS restart files (atoms, contact histories, fix states) beside a JSON file of the
run's parameters and the history so far (and the animation frames, ``.frames.npz``); ``resume=True``
continues from them and repeats the uninterrupted run bit for bit. Why that needs care: every LAMMPS
``run`` starts with a setup whose force evaluation uses full-step velocities (not the half-step ones
of a normal step) and, in ``pair granular`` and ``fix wall/gran``, rescales the tangential history of
sliding contacts to the Coulomb limit with them; a setup therefore changes the state at round-off
level, and a run with one more setup than another diverges from it. Here every chunk boundary has
exactly one extra setup (:func:`_boundary`) in every run, snapshots and checkpoints are taken right
after it, and a resumed run starts with the next chunk without repeating it.
"""

from __future__ import annotations

import json
import math
import os
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import InputError, check_finite
from ..geometry import Body
from ..materials import Material
from . import bed as _bed
from ._lammps import is_root, new_lammps
from .bed import BODY_TYPE, Bed, BedKind, BedSpec, Packing, check_speed, prepare_bed
from .fields import FieldRecorder, frame_every, rows_between
from .intruders import WALL_DIAMETER_FRACTION, MeshIntruder, body_spheres, rotated_extent

if TYPE_CHECKING:
    from ..geometry3d import TriangleMesh

__all__ = ["DEMIntrusionResult", "default_bed_spec", "run_intrusion"]

HISTORY_KEYS = ("time_s", "depth_m", "x_m", "z_m", "force_x_N", "force_z_N", "torque_y_Nm")


@dataclass(frozen=True, eq=False)
class DEMIntrusionResult:
    """Force and torque on a body pushed into a DEM bed (SI; forces on the body, z up).

    ``history`` maps each of :data:`HISTORY_KEYS` to an array (one row per record interval);
    ``summary`` holds ``force_x_N``, ``force_z_N``, ``torque_y_Nm`` as the reference point passes
    ``depth`` (mean over the last grain diameter of travel) and the run's parameters;
    in a slab bed, forces and torques are per unit width times the body's width (as plane models
    report them) and ``dem_width_m`` is the slab's thickness; ``bed`` the
    settled bed's figures (grain count, packing fraction, coordination, ...).
    """

    history: dict[str, np.ndarray]
    summary: dict[str, Any]
    bed: dict[str, Any] = field(default_factory=dict)
    #: per-grain fields at the end of the run (:func:`terradyn.dem.fields.grain_fields`)
    final_particles: dict[str, np.ndarray] | None = None
    #: animation frames over the run and the last state, as :func:`terradyn.plotting.mpm.animate_frames`
    #: draws them
    frames: list[dict[str, np.ndarray]] = field(default_factory=list)
    final_frame: dict[str, np.ndarray] | None = None
    #: snapshot files written by this call (a resumed run lists only its own)
    snapshots: list[Path] = field(default_factory=list)

    def to_dataframe(self) -> Any:
        import pandas as pd

        return pd.DataFrame({k: self.history[k] for k in HISTORY_KEYS})


def default_bed_spec(
    body: Body | MeshIntruder | TriangleMesh, *, depth: float, direction: float, angle: float,
    grain_diameter: float, kind: BedKind | str = BedKind.SLAB, packing: Packing | str = Packing.DENSE,
    seed: int = 12345,
) -> BedSpec:  # fmt: skip
    """A bed around the body's path: the body's extent plus 6 grains (or one body size) of grains on
    each side and below, and room above for its start. A 3D (mesh) body needs ``kind="3d"``; its bed
    keeps the same margin beside it across (y) too."""
    body = as_intruder(body)
    xmin, xmax, zmin, zmax = rotated_extent(body, angle)
    s = math.sin(direction)
    travel = (0.5 * grain_diameter + depth - zmin) / s
    tx = travel * math.cos(direction)
    span = max(xmax - xmin, zmax - zmin)
    margin = max(6.0 * grain_diameter, span)
    x_lo = min(xmin, xmin - tx) - margin
    x_hi = max(xmax, xmax - tx) + margin
    length = 2.0 * max(abs(x_lo), abs(x_hi))
    bed_depth = depth - zmin + margin
    headroom = zmax - zmin + 5.0 * grain_diameter
    kind = BedKind.coerce(kind)
    thickness = None
    if isinstance(body, MeshIntruder):
        _mesh_bed(kind)
        thickness = body.width + 2.0 * margin
    return BedSpec(length=length, depth=bed_depth, kind=kind, headroom=headroom, thickness=thickness,
                   packing=Packing.coerce(packing), grain_diameter=grain_diameter, seed=seed)  # fmt: skip


def as_intruder(body: Any) -> Body | MeshIntruder:
    """``body`` as run_intrusion takes it: a plane :class:`~terradyn.geometry.Body`, or a
    :class:`MeshIntruder` (a :class:`~terradyn.geometry3d.TriangleMesh` is centred into one)."""
    from ..geometry3d import TriangleMesh

    return MeshIntruder.from_mesh(body) if isinstance(body, TriangleMesh) else body


def _mesh_bed(kind: BedKind) -> None:
    if kind is not BedKind.THREE_D:
        raise InputError("kind", kind.value, "3d for a 3D (mesh) body (a slab is periodic across)")


def _start_gap(bed: Bed, body: Body | MeshIntruder, depth: float, direction: float, angle: float) -> float:
    """Height [m] above the surface of the body's lowest point at the start: clear of the highest grain
    under its path by a quarter grain (the top layer of a bed is looser than its interior)."""
    d = bed.dem.grain_diameter
    xmin, xmax, _zmin, _zmax = rotated_extent(body, angle)
    x, r, t = bed.grain_arrays()
    g = t == _bed.GRAIN_TYPE
    travel_x = (depth + 4 * d) / math.tan(direction)
    lo = min(xmin, xmin - travel_x) - d
    hi = max(xmax, xmax - travel_x) + d
    under = g & (x[:, 0] >= lo) & (x[:, 0] <= hi)
    top = float((x[under, 2] + r[under]).max()) if under.any() else bed.surface
    return max(0.5 * d, top - bed.surface + 0.25 * d + 0.5 * WALL_DIAMETER_FRACTION * d)


def _check_direction(direction: float) -> float:
    direction = check_finite("direction", direction)
    if not 0.05 <= direction <= math.pi - 0.05:
        raise InputError(
            "direction", direction, "a direction in [0.05, pi - 0.05] rad (3-177 deg) below +x",
            "the body must move into the bed",
        )  # fmt: skip
    return direction


def _state(params: dict[str, Any], history: dict[str, list[float]], step: int) -> str:
    return json.dumps({"params": params, "history": history, "step": step})


def checkpoint_files(path: str | Path) -> tuple[Path, Path, Path]:
    """The files of a DEM checkpoint: LAMMPS restart, JSON side file, animation frames (.npz)."""
    p = Path(path)
    return p, p.with_name(p.name + ".json"), p.with_name(p.name + ".frames.npz")


def _write_checkpoint(lmp: Any, path: Path, params: dict[str, Any], history: dict[str, list[float]],
                      step: int, frames: list[dict[str, np.ndarray]] | None = None) -> None:  # fmt: skip
    """Restart file, JSON side file (and the animation frames so far), each written to a temporary
    name and moved into place. Called right after a chunk-boundary setup (:func:`_boundary`): that
    setup copies the contact histories into the per-atom arrays the restart file holds."""
    _restart, side, frames_path = checkpoint_files(path)
    tmp = path.with_name(f".{path.name}.tmp")
    lmp.command(f"write_restart {tmp}")
    if is_root(lmp):
        side_tmp = side.with_name(f".{side.name}.tmp")
        side_tmp.write_text(_state(params, history, step), encoding="utf-8")
        if frames:
            frames_tmp = frames_path.with_name(f".{frames_path.name}.tmp")
            with open(frames_tmp, "wb") as fh:
                np.savez(fh, **_stack_frames(frames))  # type: ignore[arg-type]
            os.replace(frames_tmp, frames_path)
        os.replace(tmp, path)
        os.replace(side_tmp, side)


def _stack_frames(frames: list[dict[str, np.ndarray]]) -> dict[str, np.ndarray]:
    """Frames as flat arrays: ``k<i>_<key>`` for frame i (the grain count of a frame may differ)."""
    return {f"k{i}_{key}": np.asarray(v) for i, fr in enumerate(frames) for key, v in fr.items()}


def _load_frames(path: Path) -> list[dict[str, np.ndarray]]:
    if not path.is_file():
        return []
    with np.load(path, allow_pickle=False) as data:
        out: dict[int, dict[str, np.ndarray]] = {}
        for name in data.files:
            head, key = name.split("_", 1)
            out.setdefault(int(head[1:]), {})[key] = data[name]
    return [out[i] for i in sorted(out)]


def _boundary(lmp: Any) -> None:
    """A LAMMPS setup at a chunk boundary, in fresh and resumed runs alike (see the module notes)."""
    lmp.command("run 0 post no")


def _body_fixes(lmp: Any, params: dict[str, Any]) -> None:
    """Motion, force/torque computes and averaging of the body (fresh runs and after a restart)."""
    vx, vz = params["velocity"]
    ox, oz = params["ref_offset"]
    k = params["chunk"]
    for line in (
        f"fix td_move body move linear {vx:.17g} 0 {vz:.17g}",
        "compute td_tqa body property/atom tqy",
        f"variable td_xr equal xcm(body,x)+({ox:.17g})",
        f"variable td_zr equal xcm(body,z)+({oz:.17g})",
        "variable td_tq atom (z-v_td_zr)*fx-(x-v_td_xr)*fz+c_td_tqa",
        "compute td_f body reduce sum fx fz v_td_tq",
        f"fix td_avg all ave/time 1 {k} {k} c_td_f[1] c_td_f[2] c_td_f[3]",
    ):
        lmp.command(line)


@dataclass(frozen=True)
class _Motion:
    """The prescribed motion: ``depth`` [m] of the reference point at the end, ``direction`` [rad below
    +x], body ``angle`` [rad] and ``speed`` [m/s]."""

    depth: float
    direction: float
    angle: float
    speed: float


@dataclass(frozen=True, eq=False)
class _Placement:
    """The body at its start in a bed: its spheres (x, y, z [m]) and their diameter [m], the start pose
    (x, z below the surface [m], angle [rad]), the travel [m] to the end and the width [m] the forces
    act over (the slab's thickness in a periodic bed, else the body's width)."""

    pts: np.ndarray
    sphere_diameter: float
    start: tuple[float, float, float]
    travel: float
    width: float


def _settled_bed(
    material: Material, spec: BedSpec, progress: Callable[[float, float], None] | None, share: float = 0.3
) -> Bed:
    """Pour and settle the bed of ``spec``; its settling is the first ``share`` of ``progress``."""

    def settle_progress(t: float, f: float) -> None:
        if progress is not None:
            progress(0.0, share * f)

    return prepare_bed(material, spec, progress=settle_progress)


def _place(bed: Bed, body: Body | MeshIntruder, motion: _Motion) -> _Placement:
    """The body's start clear of the grains under its path and its spheres there; closes the bed and
    raises one :class:`InputError` line if the bed is too low, too narrow or too short for it."""
    d = bed.dem.grain_diameter
    depth, direction, angle = motion.depth, motion.direction, motion.angle
    _xmin, _xmax, zmin, zmax = rotated_extent(body, angle)
    ux, uz = math.cos(direction), -math.sin(direction)
    gap = _start_gap(bed, body, depth, direction, angle)
    travel = (gap + depth - zmin) / math.sin(direction)
    start = (-travel * ux, -depth - travel * uz, angle)
    if bed.box[5] - bed.surface < zmax - zmin + gap + 0.5 * d:
        bed.close()
        raise InputError(
            "bed headroom", bed.box[5] - bed.surface, f"at least {zmax - zmin + gap + 0.5 * d:.4g} m"
        )
    periodic = bed.spec.kind is BedKind.SLAB
    y_range = (bed.box[2], bed.box[3]) if periodic else (
        0.5 * (bed.box[2] + bed.box[3]) - 0.5 * body.width, 0.5 * (bed.box[2] + bed.box[3]) + 0.5 * body.width
    )  # fmt: skip
    if not periodic and body.width > bed.thickness - 4 * d:
        bed.close()
        raise InputError(
            "width", body.width, f"below {bed.thickness - 4 * d:.4g} m (the 3d bed's width less 4 grains)"
        )
    pts, d_w = body_spheres(body, d, start, bed.surface, y_range, periodic=periodic)
    if pts[:, 0].min() < bed.box[0] + d or pts[:, 0].max() > bed.box[1] - d:
        bed.close()
        raise InputError("bed length", bed.box[1] - bed.box[0], "a bed longer than the body's path")
    width = bed.thickness if periodic else body.width
    return _Placement(pts, d_w, start, travel, width)


def _insert_body(bed: Bed, placement: _Placement) -> int:
    """Add the body's spheres to the bed as group ``body`` and restart the step count; returns the
    bed's atom count before."""
    lmp = bed.lmp
    n0 = int(lmp.get_natoms())
    _add_atoms(lmp, placement.pts, n0)
    for line in (
        "group body clear",
        f"group body type {BODY_TYPE}",
        f"set type {BODY_TYPE} diameter {placement.sphere_diameter:.17g}",
        f"set type {BODY_TYPE} density {bed.dem.grain_density:.17g}",
        "reset_timestep 0",
    ):
        lmp.command(line)
    return n0


def _run_params(
    bed: Bed, body: Body | MeshIntruder, material: Material, motion: _Motion, placement: _Placement,
    spacing: float, grain_count: int,
) -> dict[str, Any]:  # fmt: skip
    """The run's parameters as its checkpoint keeps them: motion, chunking (a history row per
    ``spacing`` [m] of travel), bed, grains and the LAMMPS settings a resume restores."""
    speed, direction, start = motion.speed, motion.direction, placement.start
    ux, uz = math.cos(direction), -math.sin(direction)
    dt = bed.dt
    chunk = max(10, round(spacing / (speed * dt)))
    total_steps = math.ceil(placement.travel / (speed * dt))
    centroid = placement.pts[:, [0, 2]].mean(axis=0)
    ref0 = np.array([start[0], bed.surface + start[1]])
    return {
        "velocity": [speed * ux, speed * uz],
        "ref_offset": (ref0 - centroid).tolist(),
        "start": list(start),
        "surface": bed.surface,
        "chunk": chunk,
        "rows": max(1, math.ceil(total_steps / chunk)),
        "dt": dt,
        "speed": speed,
        "depth": motion.depth,
        "direction": direction,
        "angle": motion.angle,
        "width": placement.width,
        "force_scale": body.width / placement.width,
        "grain_diameter": bed.dem.grain_diameter,
        "body_spheres": len(placement.pts),
        "grain_count": grain_count,
        "bed": bed.summary(),
        "bed_kind": bed.spec.kind.value,
        "gravity": bed.spec.gravity,
        "material": material.name,
        "dem": _dem_dict(bed),
        "box": list(bed.box),
        "newton": newton_setting(bed.lmp),
    }


def run_intrusion(
    body: Body | MeshIntruder | TriangleMesh,
    material: Material,
    *,
    depth: float,
    direction: float = math.pi / 2,
    angle: float = 0.0,
    speed: float = 0.02,
    bed: Bed | None = None,
    bed_spec: BedSpec | None = None,
    kind: BedKind | str = BedKind.SLAB,
    packing: Packing | str = Packing.DENSE,
    grain_diameter: float | None = None,
    record_spacing: float | None = None,
    checkpoint_path: str | Path | None = None,
    checkpoint_interval: float = 60.0,
    resume: bool = False,
    progress: Callable[[float, float], None] | None = None,
    stop_after_rows: int | None = None,
    snapshot_dir: str | Path | None = None,
    snapshot_interval: float | None = None,
    frame_count: int = 0,
) -> DEMIntrusionResult:
    """Push ``body`` at ``speed`` [m/s] along ``direction`` [rad below +x], rotated by ``angle`` [rad],
    until its reference point is ``depth`` [m] below the surface of a DEM bed of ``material``.

    ``snapshot_dir``: per-grain NetCDF snapshots (fields extra) every ``snapshot_interval`` [s] of
    simulated time (default: two grain diameters of travel); ``frame_count`` light frames over the
    run for an animation (``result.frames``). The final grain fields are in ``result.final_particles``.

    ``bed`` is a prepared bed (it is consumed: the body is added to it); else ``bed_spec`` or
    :func:`default_bed_spec` is poured and settled. ``record_spacing`` is the travel [m] per history row
    (default a tenth of a grain). ``stop_after_rows`` stops early (after writing a checkpoint), as an
    interruption would; tests use it.
    """
    body = as_intruder(body)
    speed = check_speed(speed)
    depth = check_finite("depth", depth)
    if not depth > 0:
        raise InputError("depth", depth, "a depth > 0 [m] below the surface")
    if isinstance(body, MeshIntruder) and not resume:
        _mesh_bed(bed.spec.kind if bed is not None else bed_spec.kind if bed_spec is not None
                  else BedKind.coerce(kind))  # fmt: skip
    direction = _check_direction(direction)
    angle = check_finite("angle", angle)
    ckpt = Path(checkpoint_path) if checkpoint_path is not None else None
    if resume:
        if ckpt is None or not ckpt.is_file():
            raise InputError("checkpoint_path", checkpoint_path, "an existing checkpoint with resume")
        outputs = {"snapshot_dir": snapshot_dir, "snapshot_interval": snapshot_interval,
                   "frame_count": frame_count}  # fmt: skip
        return _resume(ckpt, checkpoint_interval, progress, stop_after_rows, body, outputs)
    dem = material.require_dem()
    if bed is None:
        d = grain_diameter if grain_diameter is not None else dem.grain_diameter
        spec = bed_spec or default_bed_spec(
            body, depth=depth, direction=direction, angle=angle, grain_diameter=d, kind=kind, packing=packing
        )
        bed = _settled_bed(material, spec, progress)
    motion = _Motion(depth, direction, angle, speed)
    placement = _place(bed, body, motion)
    spacing = record_spacing if record_spacing is not None else 0.1 * bed.dem.grain_diameter
    if not spacing > 0 or not math.isfinite(spacing):
        raise InputError("record_spacing", spacing, "a travel > 0 [m] per history row")
    lmp = bed.lmp
    n0 = _insert_body(bed, placement)
    params = _run_params(bed, body, material, motion, placement, spacing, n0)
    _body_fixes(lmp, params)
    history: dict[str, list[float]] = {k: [] for k in HISTORY_KEYS}
    try:
        recorder = _recorder(body, params, snapshot_dir, snapshot_interval, frame_count)
        final = run_chunks(lmp, params, history, 0, ckpt, checkpoint_interval, progress, stop_after_rows,
                           recorder, INTRUSION_HOOKS)  # fmt: skip
        return _result(params, history, recorder, final)
    finally:
        bed.lmp = None
        lmp.close()


def _recorder(body: Body | MeshIntruder, params: dict[str, Any], snapshot_dir: str | Path | None,
              snapshot_interval: float | None, frame_count: int) -> FieldRecorder:  # fmt: skip
    """Snapshots and frames of an intrusion (every row a whole number of history rows apart)."""
    d, row_time = params["grain_diameter"], params["chunk"] * params["dt"]
    if snapshot_interval is not None:
        snapshot_interval = check_finite("snapshot_interval", snapshot_interval)
        if not snapshot_interval > 0:
            raise InputError("snapshot_interval", snapshot_interval, "a time > 0 [s]")
    if not isinstance(frame_count, int) or not 0 <= frame_count <= 500:
        raise InputError("frame_count", frame_count, "an integer in [0, 500]")
    folder = Path(snapshot_dir) if snapshot_dir is not None else None
    box = params["box"]
    mid = 0.5 * (box[2] + box[3])
    y_slice = None if params["bed_kind"] == BedKind.SLAB.value else (mid - 2.0 * d, mid + 2.0 * d)
    attrs = {
        "run": "dem intrusion",
        "material": params["material"],
        "grain_diameter_m": d,
        "bed_kind": params["bed_kind"],
        "bed_thickness_m": box[3] - box[2],
        "speed_m_s": params["speed"],
        "direction_rad": params["direction"],
        "gravity_m_s2": params["gravity"],
        "body_pose": "reference point x, z [m] and rotation theta about +y [rad]",
    }
    return FieldRecorder(
        body, params["surface"], d, snapshot_dir=folder,
        snapshot_every=rows_between(snapshot_interval, row_time, 2.0 * d / params["speed"]) if folder else 0,
        frame_every=frame_every(frame_count, params["rows"]), y_slice=y_slice, attrs=attrs,
    )  # fmt: skip


def _resume(ckpt: Path, interval: float, progress: Callable[[float, float], None] | None,
            stop_after_rows: int | None, body: Body | MeshIntruder,
            outputs: dict[str, Any]) -> DEMIntrusionResult:  # fmt: skip
    params, history, step, frames = read_checkpoint(ckpt, "dem intrusion")
    lmp = restore_lammps(ckpt, params)
    try:
        _body_fixes(lmp, params)
        recorder = _recorder(body, params, **outputs)
        recorder.frames = frames if recorder.frame_every > 0 else []
        final = run_chunks(lmp, params, history, step, ckpt, interval, progress, stop_after_rows, recorder,
                           INTRUSION_HOOKS)  # fmt: skip
        return _result(params, history, recorder, final)
    finally:
        lmp.close()


def read_checkpoint(ckpt: Path, run: str) -> tuple[dict[str, Any], dict[str, list[float]], int,
                                                   list[dict[str, np.ndarray]]]:  # fmt: skip
    """Parameters, history, step and animation frames of the checkpoint of a ``run`` ("dem intrusion",
    "dem wheel") at ``ckpt``; one :class:`InputError` line if it is missing, unreadable or another
    kind of run's."""
    _restart, side, frames_path = checkpoint_files(ckpt)
    if not ckpt.is_file():
        raise InputError("checkpoint_path", str(ckpt), "an existing checkpoint with resume",
                         "no such file: run without resume to start")  # fmt: skip
    try:
        state = json.loads(side.read_text(encoding="utf-8"))
        params, history, step = state["params"], state["history"], int(state["step"])
        frames = _load_frames(frames_path)
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise InputError("checkpoint", str(ckpt), "a terradyn DEM checkpoint with its .json file",
                         " ".join(str(exc).split())[:100]) from None  # fmt: skip
    saved = params.get("run", "dem intrusion") if isinstance(params, dict) else None
    if saved != run:
        raise InputError("checkpoint", str(ckpt), f"a checkpoint of a {run} run", f"it holds a {saved} run")
    return params, history, step, frames


def newton_setting(lmp: Any) -> list[int]:
    """LAMMPS's ``newton`` pair and bond settings (1 on, 0 off). A bed poured here runs with
    ``newton off``, one read from a restart file with the default pair setting ``on``; the two sum
    ghost-pair forces in another order, so a resume restores the setting of the run it continues."""
    return [int(lmp.extract_setting("newton_pair")), int(lmp.extract_setting("newton_bond"))]


def restore_lammps(ckpt: Path, params: dict[str, Any]) -> Any:
    """A LAMMPS instance holding the checkpoint's restart file, with the grains' interactions
    re-issued (``pair granular`` comes back from a restart file with a zero cut-off; re-issuing it
    unchanged keeps the contact histories). The body's fixes are the caller's to re-issue."""
    lmp = new_lammps()
    try:
        lmp.command("atom_modify map array")
        lmp.command(f"read_restart {ckpt}")
        pair, bond = params.get("newton", (None, None))
        if pair is not None:  # a restart file does not carry the pair setting (see newton_setting)
            lmp.command(f"newton {'on' if pair else 'off'} {'on' if bond else 'off'}")
    except Exception as exc:  # LAMMPS raises a bare Exception for a damaged file
        lmp.close()
        raise InputError("checkpoint", str(ckpt), "a LAMMPS restart file written by terradyn",
                         " ".join(str(exc).split())[:100]) from None  # fmt: skip
    try:
        from ..materials import DEMParameters

        dem = DEMParameters(**{k: v for k, v in params["dem"].items()})
        _bed.setup_interactions(lmp, tuple(params["box"]), dem, BedKind(params["bed_kind"]), pair=True,
                                friction=dem.friction, rolling=dem.rolling_friction,
                                gravity=params.get("gravity", 9.81))  # fmt: skip
    except BaseException:
        lmp.close()
        raise
    return lmp


def _pose(params: dict[str, Any], time_s: float) -> tuple[float, float, float]:
    """The body's reference point and rotation (x, z, theta) in terradyn's frame at ``time_s``."""
    vx, vz = params["velocity"]
    x0, z0, theta = params["start"]
    return (x0 + vx * time_s, z0 + vz * time_s, theta)


def _record_row(lmp: Any, params: dict[str, Any], history: dict[str, list[float]], step: int) -> None:
    """The history row of the chunk that ended at ``step`` (means of the force averaging fix)."""
    chunk, dt = params["chunk"], params["dt"]
    t_mid = (step - 0.5 * chunk) * dt
    fx = float(lmp.extract_fix("td_avg", 0, 1, 0))
    fz = float(lmp.extract_fix("td_avg", 0, 1, 1))
    ty = float(lmp.extract_fix("td_avg", 0, 1, 2))
    x, z, _theta = _pose(params, t_mid)
    values = (t_mid, -z, x, z, fx, fz, ty)
    for key, value in zip(HISTORY_KEYS, values, strict=True):
        history[key].append(value)


@dataclass(frozen=True)
class RunHooks:
    """What a chunked run records: ``record_row(lmp, params, history, step)`` appends the row of the
    chunk that ended at ``step``; ``pose(lmp, params, time_s)`` is the body's (x, z, theta) for
    snapshots and frames; ``progress_key`` the history column the progress callback is given."""

    record_row: Callable[[Any, dict[str, Any], dict[str, list[float]], int], None]
    pose: Callable[[Any, dict[str, Any], float], tuple[float, float, float]]
    progress_key: str


INTRUSION_HOOKS = RunHooks(_record_row, lambda lmp, params, t: _pose(params, t), "depth_m")


def run_chunks(lmp: Any, params: dict[str, Any], history: dict[str, list[float]], step: int,
               ckpt: Path | None, interval: float, progress: Callable[[float, float], None] | None,
               stop_after_rows: int | None, recorder: FieldRecorder,
               hooks: RunHooks) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray]]:  # fmt: skip
    """Chunks of ``params["chunk"]`` steps up to ``params["rows"]`` rows, one history row each;
    returns the final grain fields and frame (:meth:`FieldRecorder.final`).

    Every chunk boundary has one LAMMPS setup (:func:`_boundary`) before the next chunk's own, and
    snapshots, frames and checkpoints are taken right after it: a run that writes them follows the
    same trajectory as one that does not. A checkpoint holds the state after that setup, so a resumed
    run (``step > 0``) starts with the chunk directly: it repeats the uninterrupted run bit for bit."""
    chunk, rows, dt = params["chunk"], params["rows"], params["dt"]
    last_save = time.perf_counter()
    done_here = 0
    row = len(history["time_s"])
    step0, row0 = step, row
    # a resumed run starts from the state after the boundary setup and the snapshot of its step
    boundary_at, recorded = (step, row) if row > 0 else (-1, 0)
    recorder.prepare(lmp)

    def settle_boundary() -> None:
        nonlocal boundary_at, recorded
        if boundary_at != step:
            _boundary(lmp)
            boundary_at = step
        if row > 0 and recorded != row:
            recorder.row(lmp, row, step, step * dt, hooks.pose(lmp, params, step * dt))
            recorded = row

    try:
        while row < rows:
            settle_boundary()
            if ckpt is not None and row > 0 and time.perf_counter() - last_save > interval:
                _write_checkpoint(lmp, ckpt, params, history, step, recorder.frames)
                last_save = time.perf_counter()
            lmp.command(f"run {chunk}")
            step += chunk
            hooks.record_row(lmp, params, history, step)
            row += 1
            done_here += 1
            if progress is not None:
                progress(history[hooks.progress_key][-1], 0.3 + 0.7 * row / rows)
            if stop_after_rows is not None and done_here >= stop_after_rows and row < rows:
                raise KeyboardInterrupt
        settle_boundary()
        final = recorder.final(lmp, step, step * dt, hooks.pose(lmp, params, step * dt))
    except KeyboardInterrupt as exc:
        # the rows recorded say where the run is; an interrupt that lands between the end of a chunk
        # and its row records that row first
        row = len(history["time_s"])
        step = step0 + (row - row0) * chunk
        if int(lmp.extract_global("ntimestep")) == step + chunk:
            step += chunk
            hooks.record_row(lmp, params, history, step)
            row += 1
        if ckpt is not None:
            settle_boundary()
            _write_checkpoint(lmp, ckpt, params, history, step, recorder.frames)
            exc.checkpoint_path = ckpt  # type: ignore[attr-defined]
        exc.time_s = step * dt  # type: ignore[attr-defined]
        raise
    return final


def _result(params: dict[str, Any], history: dict[str, list[float]], recorder: FieldRecorder,
            final: tuple[dict[str, np.ndarray], dict[str, np.ndarray]]) -> DEMIntrusionResult:  # fmt: skip
    h = {k: np.asarray(v, dtype=float) for k, v in history.items()}
    for key in ("force_x_N", "force_z_N", "torque_y_Nm"):
        h[key] = h[key] * params["force_scale"]
    d = params["grain_diameter"]
    last = h["depth_m"] >= params["depth"] - d - 1e-12
    if not last.any():
        last = np.zeros(len(h["depth_m"]), dtype=bool)
        last[-1] = True
    summary = {
        "force_x_N": float(h["force_x_N"][last].mean()),
        "force_z_N": float(h["force_z_N"][last].mean()),
        "torque_y_Nm": float(h["torque_y_Nm"][last].mean()),
        "depth_m": params["depth"],
        "speed_m_s": params["speed"],
        "width_m": params["width"] * params["force_scale"],
        "dem_width_m": params["width"],
        "grain_count": params["grain_count"],
        "body_spheres": params["body_spheres"],
    }
    return DEMIntrusionResult(h, summary, dict(params["bed"]), final_particles=final[0],
                              frames=list(recorder.frames), final_frame=final[1],
                              snapshots=list(recorder.written))  # fmt: skip


def _dem_dict(bed: Bed) -> dict[str, Any]:
    return {k: v for k, v in asdict(bed.dem).items()}


def _add_atoms(lmp: Any, pts: np.ndarray, n0: int) -> None:
    """Body spheres as new atoms of type BODY_TYPE (the ``create_atoms single`` command keeps every
    fix's per-atom arrays in step)."""
    lmp.commands_list(
        [f"create_atoms {BODY_TYPE} single {x:.17g} {y:.17g} {z:.17g} units box" for x, y, z in pts]
    )
    if int(lmp.get_natoms()) != n0 + len(pts):
        raise InputError("body", len(pts), "body spheres inside the bed's box")
