"""DEM (LAMMPS) speed: particle-steps per second on 1 and 2 MPI ranks, and a virtual plate test's wall time.

Throughput: a bed of N grains (MS contact parameters with 1 mm monodisperse grains, slab 4 grains
thick, three times as long as deep) on a simple-cubic lattice in contact under gravity, so every grain
has contacts from the first step (the mean count is printed; settled beds have 4.5-6.6). The figure is
N x steps / wall seconds of ``run`` (Hertz-Mindlin pair with rolling resistance, walls, gravity,
nve/sphere, neighbour lists) after 100 warm-up steps. Two ranks run the same script under the mpich
wheel's ``mpirun -np 2`` (LAMMPS domain decomposition).

Virtual plate test: ``virtual_plate_test`` of the generic medium (1 mm grains), a 10 mm plate pushed
straight down to 10 mm, bed poured and settled, at the defaults of ``terradyn calibrate rft
--from-dem`` (dense bed, 0.02 m/s).

Run: ``python benchmarks/bench_dem.py [--quick]`` (``--quick``: 1e4 grains only, no plate test).
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np


def _throughput(n: int, steps: int) -> tuple[int, float, float]:
    from terradyn import materials
    from terradyn.dem import bed as B
    from terradyn.dem._lammps import new_lammps

    dem = materials.get("MS").require_dem()
    import dataclasses

    dem = dataclasses.replace(dem, grain_diameter=1e-3, diameter_spread=0.0)
    d = dem.grain_diameter
    a = 0.9999 * d  # simple-cubic lattice in contact: six contacts per grain from the first step
    ny = 4
    nz = max(4, round((n / ny / 3.0) ** 0.5))  # three times as long as deep
    nx = math.ceil(n / (ny * nz))
    length, thickness, height = nx * a, ny * a, (nz + 2) * a
    box = (-0.5 * length, 0.5 * length, 0.0, thickness, 0.0, height)
    lmp = new_lammps()
    for line in (
        "units si", "atom_style sphere", "boundary f p f", "newton off", "atom_modify map array",
        f"region td_box block {box[0]} {box[1]} 0 {thickness} 0 {height} units box", "create_box 2 td_box",
    ):  # fmt: skip
        lmp.command(line)
    k = np.arange(nx * ny * nz)
    pos = np.column_stack(
        (box[0] + (k % nx + 0.5) * a, ((k // nx) % ny + 0.5) * a, (k // (nx * ny) + 0.5) * a)
    )
    lmp.create_atoms(len(pos), None, [B.GRAIN_TYPE] * len(pos), pos.ravel().tolist())
    for line in (
        "group grains type 1",
        "group body type 2",
        f"set type 1 diameter {d}",
        f"set type 1 density {dem.grain_density}",
        f"timestep {B.time_step(dem)}",
    ):
        lmp.command(line)
    B.setup_interactions(lmp, box, dem, B.BedKind.SLAB, friction=dem.friction, rolling=dem.rolling_friction)
    lmp.command("run 100")  # warm-up
    t0 = time.perf_counter()
    lmp.command(f"run {steps} pre no")
    wall = time.perf_counter() - t0
    count = int(lmp.get_natoms())
    contacts = float(lmp.extract_compute("td_zsum", 0, 0)) / count
    lmp.close()
    return count, count * steps / wall, contacts


def _worker(n: int, steps: int) -> None:
    count, rate, contacts = _throughput(n, steps)
    from terradyn.dem._lammps import mpi_rank

    if mpi_rank() == 0:
        print(f"RESULT {count} {rate} {contacts}", flush=True)


def _two_ranks(n: int, steps: int) -> tuple[int, float, float] | None:
    mpirun = Path(sys.prefix) / "bin" / "mpirun"
    if not mpirun.is_file():
        return None
    cmd = [str(mpirun), "-np", "2", sys.executable, __file__, "--worker", str(n), str(steps)]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=900, env={**os.environ})
    for line in proc.stdout.splitlines():
        if line.startswith("RESULT"):
            _, count, rate, contacts = line.split()
            return int(count), float(rate), float(contacts)
    print("   2-rank run failed:", (proc.stderr or proc.stdout).strip()[-300:])
    return None


def main() -> None:
    quick = "--quick" in sys.argv
    from terradyn.dem import DEMUnavailable, load_lammps

    try:
        load_lammps()
    except DEMUnavailable as exc:
        print(f"skipped: {exc}")
        return
    print("particle-steps/s = grains x time steps / wall seconds of LAMMPS 'run' (body-free bed)")
    print(f"{'grains':>8} {'ranks':>6} {'steps':>6} {'contacts/grain':>15} {'particle-steps/s':>18}")
    sizes = (10_000,) if quick else (10_000, 100_000)
    for n in sizes:
        steps = 1000 if n <= 10_000 else 200
        count, rate, contacts = _throughput(n, steps)
        print(f"{count:>8d} {1:>6d} {steps:>6d} {contacts:>15.2f} {rate:>18.3e}", flush=True)
        two = _two_ranks(n, steps)
        if two is not None:
            print(f"{two[0]:>8d} {2:>6d} {steps:>6d} {two[2]:>15.2f} {two[1]:>18.3e}", flush=True)
    if quick:
        return
    from terradyn import materials
    from terradyn.dem.calibration import virtual_plate_test

    t0 = time.perf_counter()
    test = virtual_plate_test(materials.get("generic"), plate_length=0.01, plate_width=0.01, depth=0.01)
    wall = time.perf_counter() - t0
    print(
        f"virtual plate test (generic, 1 mm grains, plate 10 mm to 10 mm, dense, 0.02 m/s): {wall:.0f} s "
        f"wall, {test.bed['grain_count']} grains, settled in {test.bed['settle_time_s']:.3f} s simulated, "
        f"F_z at 10 mm = {test.cases[0]['force_z_N']:.3f} N"
    )


if __name__ == "__main__":
    if len(sys.argv) >= 4 and sys.argv[1] == "--worker":
        _worker(int(sys.argv[2]), int(sys.argv[3]))
    else:
        main()
