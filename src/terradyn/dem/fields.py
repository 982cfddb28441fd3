"""Per-grain fields of a DEM run: NetCDF snapshots, animation frames and the final state.

Everything is in terradyn's frame (x forward, z up, free surface at z = 0; y across the bed from its
side at y = 0) and SI. A snapshot holds every grain (not the body spheres): position, velocity, spin,
radius, the force on the grain (contacts, walls and gravity at the end of the step) and, when asked
for, its mean stress: LAMMPS's per-atom contact virial (``compute stress/atom ... pair``, half of each
contact's ``r_ij f_ij`` given to each grain) divided by the grain's own volume, tension positive
(``pressure = -(s_xx + s_yy + s_zz) / 3`` is positive in compression). The bulk stress of a region is
the solid fraction times the mean of these over its grains. Snapshots go through the same NetCDF
writer as MPM's (:func:`terradyn.mpm.checkpoint.write_snapshot`), atomically.

Frames (for animations) are light float32 copies of the grains in the middle of the bed (the whole
slab, or a slice four grains thick in a 3d bed) with the body outline as segments, in the layout
:func:`terradyn.plotting.mpm.animate_frames` draws.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..geometry import Body
from ._lammps import is_root
from .bed import GRAIN_TYPE

if TYPE_CHECKING:
    from .intruders import MeshIntruder

__all__ = ["GRAIN_UNITS", "FieldRecorder", "body_segments", "grain_fields"]

#: units of the per-grain fields of a DEM snapshot
GRAIN_UNITS = {
    "x": "m", "y": "m", "z": "m",
    "vx": "m/s", "vy": "m/s", "vz": "m/s",
    "omega_x": "rad/s", "omega_y": "rad/s", "omega_z": "rad/s",
    "radius": "m", "id": "1",
    "fx": "N", "fy": "N", "fz": "N",
    "stress_xx": "Pa", "stress_yy": "Pa", "stress_zz": "Pa", "stress_xz": "Pa",
    "stress_xy": "Pa", "stress_yz": "Pa", "pressure": "Pa", "contacts": "1",
}  # fmt: skip

_STRESS_ID = "td_snap_stress"

Fields = dict[str, np.ndarray]
Pose = tuple[float, float, float]


def _gather(lmp: Any, name: str, kind: int, count: int) -> np.ndarray:
    n = int(lmp.get_natoms())
    raw = lmp.gather_atoms(name, kind, count)
    return np.ctypeslib.as_array(raw, shape=(count * n,)).reshape(n, count).copy()


def grain_fields(lmp: Any, surface: float, *, stress_compute: str | None = None) -> dict[str, np.ndarray]:
    """Per-grain arrays (grains only, ordered by atom id) in terradyn's frame [SI].

    ``stress_compute`` is the id of a ``compute stress/atom`` evaluated at the current step (defined
    before the last LAMMPS setup, as :meth:`FieldRecorder.prepare` does); without it no stress."""
    x = _gather(lmp, "x", 1, 3)
    v = _gather(lmp, "v", 1, 3)
    w = _gather(lmp, "omega", 1, 3)
    f = _gather(lmp, "f", 1, 3)
    r = _gather(lmp, "radius", 1, 1)[:, 0]
    t = _gather(lmp, "type", 0, 1)[:, 0]
    ids = _gather(lmp, "id", 0, 1)[:, 0]
    g = t == GRAIN_TYPE
    out = {
        "id": ids[g].astype(np.int64),
        "x": x[g, 0], "y": x[g, 1], "z": x[g, 2] - surface,
        "vx": v[g, 0], "vy": v[g, 1], "vz": v[g, 2],
        "omega_x": w[g, 0], "omega_y": w[g, 1], "omega_z": w[g, 2],
        "radius": r[g],
        "fx": f[g, 0], "fy": f[g, 1], "fz": f[g, 2],
    }  # fmt: skip
    if stress_compute is not None:
        n = int(lmp.get_natoms())
        raw = lmp.gather(f"c_{stress_compute}", 1, 6)
        s = np.ctypeslib.as_array(raw, shape=(6 * n,)).reshape(n, 6)
        s = s[g] / (4.0 / 3.0 * math.pi * r[g, None] ** 3)
        # LAMMPS order: xx, yy, zz, xy, xz, yz
        out.update(stress_xx=s[:, 0], stress_yy=s[:, 1], stress_zz=s[:, 2], stress_xy=s[:, 3],
                   stress_xz=s[:, 4], stress_yz=s[:, 5],
                   pressure=-(s[:, 0] + s[:, 1] + s[:, 2]) / 3.0)  # fmt: skip
    return out


def body_segments(body: Body | MeshIntruder, pose: tuple[float, float, float], spacing: float) -> np.ndarray:
    """Body outline (S, 2, 2) [m] at ``pose`` = (x, z, theta) in terradyn's frame."""
    x, z, theta = pose
    c, s = math.cos(theta), math.sin(theta)
    segs = []
    for poly in body.outline(min(spacing, body.size)):
        p = np.asarray(poly, dtype=float)
        if len(p) > 2 and not np.allclose(p[0], p[-1]):
            p = np.vstack([p, p[:1]])
        wx = x + c * p[:, 0] + s * p[:, 1]
        wz = z - s * p[:, 0] + c * p[:, 1]
        w = np.column_stack((wx, wz))
        segs.append(np.stack((w[:-1], w[1:]), axis=1))
    return np.concatenate(segs) if segs else np.zeros((0, 2, 2))


def _frame(fields: dict[str, np.ndarray], segments: np.ndarray, time_s: float, step: int,
           y_slice: tuple[float, float] | None) -> dict[str, np.ndarray]:  # fmt: skip
    sel = slice(None) if y_slice is None else (fields["y"] >= y_slice[0]) & (fields["y"] <= y_slice[1])
    speed = np.sqrt(fields["vx"] ** 2 + fields["vy"] ** 2 + fields["vz"] ** 2)
    out = {
        "time_s": np.array(time_s),
        "step": np.array(step),
        "segments": np.asarray(segments, dtype=float),
        "x": fields["x"][sel].astype(np.float32),
        "z": fields["z"][sel].astype(np.float32),
        "speed": speed[sel].astype(np.float32),
    }
    if "pressure" in fields:
        out["pressure"] = fields["pressure"][sel].astype(np.float32)
    return out


@dataclass
class FieldRecorder:
    """Writes snapshots every ``snapshot_every`` rows and keeps a frame every ``frame_every`` rows.

    ``pose(time_s)`` is the body's pose (x, z, theta) in terradyn's frame; ``attrs`` are the run's
    constant attributes (units, bed, body) written into every snapshot beside time, step and pose."""

    body: Body | MeshIntruder
    surface: float
    grain_diameter: float
    snapshot_dir: Path | None = None
    snapshot_every: int = 0
    frame_every: int = 0
    y_slice: tuple[float, float] | None = None
    attrs: dict[str, Any] = field(default_factory=dict)
    frames: list[dict[str, np.ndarray]] = field(default_factory=list)
    written: list[Path] = field(default_factory=list)
    stress_compute: str | None = None

    def prepare(self, lmp: Any) -> None:
        """Define the per-atom stress compute; every later LAMMPS setup evaluates it (it adds no
        work to the steps in between, which never invoke it)."""
        lmp.command(f"compute {_STRESS_ID} all stress/atom NULL pair")
        self.stress_compute = _STRESS_ID

    @property
    def active(self) -> bool:
        return (self.snapshot_dir is not None and self.snapshot_every > 0) or self.frame_every > 0

    def segments(self, pose: tuple[float, float, float]) -> np.ndarray:
        return body_segments(self.body, pose, 0.25 * self.grain_diameter)

    def row(self, lmp: Any, row: int, step: int, time_s: float,
            pose: tuple[float, float, float]) -> None:  # fmt: skip
        """After history row ``row`` (1-based) ending at ``step`` and the setup that follows it: a
        snapshot and/or a frame if due."""
        snap = self.snapshot_dir is not None and self.snapshot_every > 0 and row % self.snapshot_every == 0
        frame = self.frame_every > 0 and row % self.frame_every == 0
        if not (snap or frame):
            return
        fields = grain_fields(lmp, self.surface, stress_compute=self.stress_compute)
        if snap:
            self.snapshot(lmp, fields, step, time_s, pose)
        if frame:
            self.frames.append(_frame(fields, self.segments(pose), time_s, step, self.y_slice))

    def snapshot(self, lmp: Any, fields: dict[str, np.ndarray], step: int, time_s: float,
                 pose: tuple[float, float, float]) -> Path | None:  # fmt: skip
        if self.snapshot_dir is None or not is_root(lmp):
            return None
        from ..runrecords import write_snapshot

        attrs = {
            "time_s": time_s,
            "step": step,
            "body_x_m": pose[0],
            "body_z_m": pose[1],
            "body_theta_rad": pose[2],
            "frame": "terradyn: x forward, z up, free surface at z = 0, y across the bed from its side",
            "stress": "per-grain contact virial / grain volume, tension positive",
            **self.attrs,
        }
        name = f"particles_{step:09d}.nc"  # as the MPM snapshots
        path = write_snapshot(self.snapshot_dir / name, fields, attrs, units=GRAIN_UNITS)
        self.written.append(path)
        return path

    def final(self, lmp: Any, step: int, time_s: float, pose: Pose) -> tuple[Fields, Fields]:
        """(final grain fields, final frame) at the end of the run (after a setup)."""
        fields = grain_fields(lmp, self.surface, stress_compute=self.stress_compute)
        return fields, _frame(fields, self.segments(pose), time_s, step, self.y_slice)


def rows_between(interval: float | None, row_time: float, default: float) -> int:
    """History rows per ``interval`` [s] of simulated time (``default`` when None), at least one."""
    t = default if interval is None else interval
    return max(1, round(t / row_time))


def frame_every(frame_count: int, rows: int) -> int:
    """Rows between animation frames: at least ``frame_count`` frames over ``rows`` rows (0 = none)."""
    if frame_count <= 0:
        return 0
    return max(1, rows // frame_count)
