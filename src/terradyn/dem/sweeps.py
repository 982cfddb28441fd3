"""Sweeps of DEM intrusions: one settled bed, many (depth, angle, direction) cases, run in parallel.

The bed is poured once, sized for the widest path of the cases, and written as a LAMMPS restart file;
each case loads its own copy of it (so every case starts from the same grains) and runs
:func:`terradyn.dem.run_intrusion` in its own single-rank LAMMPS instance. The cases go through
:func:`terradyn.parallel.map_items`: serially, on local processes or on a Dask cluster, results in the
order of the cases whatever the backend. The bed travels to the workers as bytes, so a remote Dask
worker needs no shared file system, only the same terradyn and LAMMPS.
"""

from __future__ import annotations

import dataclasses
import math
import os
import tempfile
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import InputError
from ..geometry import Body
from ..materials import Material
from .bed import BedKind, BedSpec, Packing, load_bed, prepare_bed, save_bed
from .runs import DEMIntrusionResult, _check_direction, default_bed_spec, run_intrusion

__all__ = ["IntrusionCase", "IntrusionSweep", "intrusion_sweep", "sweep_bed_spec"]


@dataclass(frozen=True)
class IntrusionCase:
    """One intrusion of a sweep: final ``depth`` [m], ``direction`` [rad below +x], ``angle`` [rad]."""

    depth: float
    direction: float = math.pi / 2
    angle: float = 0.0


@dataclass(frozen=True, eq=False)
class IntrusionSweep:
    """The results of a sweep, in the order of its cases, and the shared bed's figures."""

    cases: list[IntrusionCase]
    results: list[DEMIntrusionResult]
    bed: dict[str, Any]

    def rows(self) -> list[dict[str, float]]:
        """One record per case: its parameters (degrees) and the summary forces [N, N m]."""
        return [
            {
                "depth_m": c.depth,
                # degrees as the user gave them (60, not 59.99999999999999 back from radians)
                "angle_deg": round(math.degrees(c.angle), 9),
                "direction_deg": round(math.degrees(c.direction), 9),
                **{k: r.summary[k] for k in ("force_x_N", "force_z_N", "torque_y_Nm")},
            }
            for c, r in zip(self.cases, self.results, strict=True)
        ]


def sweep_bed_spec(body: Body, cases: Sequence[IntrusionCase], *, grain_diameter: float,
                   kind: BedKind | str = BedKind.SLAB, packing: Packing | str = Packing.DENSE,
                   seed: int = 12345) -> BedSpec:  # fmt: skip
    """One bed for every case: the longest, deepest and tallest of their :func:`default_bed_spec`."""
    specs = [default_bed_spec(body, depth=c.depth, direction=c.direction, angle=c.angle,
                              grain_diameter=grain_diameter, kind=kind, packing=packing, seed=seed)
             for c in cases]  # fmt: skip
    return dataclasses.replace(
        specs[0],
        length=max(s.length for s in specs),
        depth=max(s.depth for s in specs),
        headroom=max(s.headroom or 0.0 for s in specs),
    )


@dataclass(frozen=True)
class _Task:
    """What a worker needs for one case (picklable: the bed travels as the bytes of its files)."""

    restart: bytes
    side: bytes
    body: Body
    material: Material
    case: IntrusionCase
    speed: float
    record_spacing: float | None


def _run_case(task: _Task) -> DEMIntrusionResult:
    """One case in a fresh single-rank LAMMPS instance, from a private copy of the bed."""
    with tempfile.TemporaryDirectory(prefix="terradyn-dem-case-") as tmp:
        path = Path(tmp) / "bed.restart"
        path.write_bytes(task.restart)
        path.with_name(path.name + ".json").write_bytes(task.side)
        c = task.case
        return run_intrusion(task.body, task.material, bed=load_bed(path), depth=c.depth,
                             direction=c.direction, angle=c.angle, speed=task.speed,
                             record_spacing=task.record_spacing)  # fmt: skip


def _mpi_size() -> int:
    for key in ("PMI_SIZE", "OMPI_COMM_WORLD_SIZE", "PMIX_SIZE", "MV2_COMM_WORLD_SIZE"):
        value = os.environ.get(key)
        if value is not None and value.isdigit():
            return int(value)
    return 1


def intrusion_sweep(
    body: Body,
    material: Material,
    cases: Sequence[IntrusionCase],
    *,
    speed: float = 0.02,
    grain_diameter: float | None = None,
    kind: BedKind | str = BedKind.SLAB,
    packing: Packing | str = Packing.DENSE,
    seed: int = 12345,
    bed_spec: BedSpec | None = None,
    record_spacing: float | None = None,
    scheduler: str = "serial",
    workers: int | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> IntrusionSweep:
    """Run ``body`` into one settled bed of ``material`` for every case.

    ``scheduler`` / ``workers`` are those of :func:`terradyn.parallel.map_items` (``serial``,
    ``processes``, ``local`` or a Dask address); every worker runs one single-rank LAMMPS at a time.
    A sweep under ``mpirun`` is refused: parallelism is across cases, one LAMMPS rank each.
    ``progress(done, total)`` is called after the bed and after each case (total = cases + 1)."""
    from ..parallel import map_items

    cases = [IntrusionCase(float(c.depth), _check_direction(float(c.direction)), float(c.angle))
             for c in cases]  # fmt: skip
    if not cases:
        raise InputError("cases", [], "at least one intrusion case")
    for c in cases:
        if not (math.isfinite(c.depth) and c.depth > 0):
            raise InputError("depth", c.depth, "a depth > 0 [m] below the surface")
        if not math.isfinite(c.angle):
            raise InputError("angle", c.angle, "a finite angle [rad]")
    if _mpi_size() > 1:
        raise InputError("scheduler", scheduler, "a sweep started without mpirun",
                         "each case runs one single-rank LAMMPS; use workers for parallel cases")  # fmt: skip
    d = grain_diameter if grain_diameter is not None else material.require_dem().grain_diameter
    spec = bed_spec or sweep_bed_spec(body, cases, grain_diameter=d, kind=kind, packing=packing, seed=seed)
    total = len(cases) + 1
    with tempfile.TemporaryDirectory(prefix="terradyn-dem-") as tmp:
        bed = prepare_bed(material, spec)
        try:
            bed_summary = bed.summary()
            path = save_bed(bed, Path(tmp) / "bed.restart")
        finally:
            bed.close()
        restart = path.read_bytes()
        side = path.with_name(path.name + ".json").read_bytes()
    if progress is not None:
        progress(1, total)
    tasks = [_Task(restart, side, body, material, c, speed, record_spacing) for c in cases]
    done = [1]

    def on_done(n: int) -> None:
        done[0] += n
        if progress is not None:
            progress(done[0], total)

    results = map_items(_run_case, tasks, scheduler=scheduler, workers=workers, on_done=on_done)
    return IntrusionSweep(cases, results, bed_summary)
