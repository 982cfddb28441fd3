"""DEM (LAMMPS) speed: particle-steps per second on 1 and 2 MPI ranks, and a virtual plate test's wall time.

Throughput: a bed of N grains (MS contact parameters, 1 mm grains with +-20% spread, slab 4 grains
thick) built on a lattice in contact under gravity, so every grain has neighbours and contacts as in a
settled bed; the figure is N x steps / wall seconds of ``run`` (Hertz-Mindlin pair with rolling
resistance, walls, gravity, nve/sphere, neighbour lists), after 100 warm-up steps. Two ranks run the
same script under the mpich wheel's ``mpirun -np 2`` (LAMMPS domain decomposition along x).

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


def _throughput(n: int, steps: int) -> tuple[int, float]:
    from terradyn import materials
    from terradyn.dem import bed as B
    from terradyn.dem._lammps import new_lammps

    dem = materials.get("MS").require_dem()
    import dataclasses

    dem = dataclasses.replace(dem, grain_diameter=1e-3)
    d = dem.grain_diameter
    dmax = d * (1 + dem.diameter_spread)
    thickness = 4 * d
    length = math.sqrt(n * (1.05 * dmax) ** 3 / thickness * 3.0)  # 3 x as long as deep
    per_layer = int((length - dmax) / (1.05 * dmax)) * int(thickness / (1.05 * dmax))
    height = (math.ceil(n / per_layer) + 2) * 1.05 * dmax
    box = (-0.5 * length, 0.5 * length, 0.0, thickness, 0.0, height)
    lmp = new_lammps()
    for line in (
        "units si", "atom_style sphere", "boundary f p f", "newton off", "atom_modify map array",
        f"region td_box block {box[0]} {box[1]} 0 {thickness} 0 {height} units box", "create_box 2 td_box",
    ):  # fmt: skip
        lmp.command(line)
    pos = B._lattice(n, box, dmax, 0.0, 1)
    lmp.create_atoms(n, None, [B.GRAIN_TYPE] * n, pos.ravel().tolist())
    for line in (
        "group grains type 1",
        "group body type 2",
        f"variable td_d atom {d}*(1.0+{dem.diameter_spread}*(2.0*random(0,1,7)-1.0))",
        "set type 1 diameter v_td_d",
        f"set type 1 density {dem.grain_density}",
        f"timestep {B.time_step(dem)}",
    ):
        lmp.command(line)
    B.setup_interactions(lmp, box, dem, B.BedKind.SLAB, friction=dem.friction, rolling=dem.rolling_friction)
    lmp.command("run 100")  # warm-up: grains fall into contact
    t0 = time.perf_counter()
    lmp.command(f"run {steps} pre no")
    wall = time.perf_counter() - t0
    count = int(lmp.get_natoms())
    lmp.close()
    return count, count * steps / wall


def _worker(n: int, steps: int) -> None:
    count, rate = _throughput(n, steps)
    from terradyn.dem._lammps import mpi_rank

    if mpi_rank() == 0:
        print(f"RESULT {count} {rate}", flush=True)


def _two_ranks(n: int, steps: int) -> tuple[int, float] | None:
    mpirun = Path(sys.prefix) / "bin" / "mpirun"
    if not mpirun.is_file():
        return None
    cmd = [str(mpirun), "-np", "2", sys.executable, __file__, "--worker", str(n), str(steps)]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=900, env={**os.environ})
    for line in proc.stdout.splitlines():
        if line.startswith("RESULT"):
            _, count, rate = line.split()
            return int(count), float(rate)
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
    print(f"{'grains':>8} {'ranks':>6} {'steps':>6} {'particle-steps/s':>18}")
    sizes = (10_000,) if quick else (10_000, 100_000)
    for n in sizes:
        steps = 1000 if n <= 10_000 else 200
        count, rate = _throughput(n, steps)
        print(f"{count:>8d} {1:>6d} {steps:>6d} {rate:>18.3e}", flush=True)
        two = _two_ranks(n, steps)
        if two is not None:
            print(f"{two[0]:>8d} {2:>6d} {steps:>6d} {two[1]:>18.3e}", flush=True)
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
