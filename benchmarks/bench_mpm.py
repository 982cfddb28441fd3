"""MPM speed: particle-steps per second of the full granular model, and a plate-intrusion wall time.

Each size is a settled-looking bed (geostatic stress, Dunatunga-Kamrin model, rate-independent) with a
rigid plate resting in it, advanced by the compiled step loop; the figure is particles x steps / seconds
after a warm-up. Run: ``python benchmarks/bench_mpm.py [--quick] [--studies]``; ``--studies`` (or
``TERRADYN_BENCH_STUDIES=1`` under ``make bench``) also times the mpm-wheel and mpm-alpha studies at
their default resolution.
"""

from __future__ import annotations

import os
import sys
import time

import numba
import numpy as np

from terradyn import materials
from terradyn.geometry import Plate
from terradyn.mpm import GranularModel, run_intrusion
from terradyn.mpm.bodies import BodyState, ContactScheme, body_segments, effective_body
from terradyn.mpm.solver import BedGrid, Phase, Runner, make_bed, stable_time_step


def _runner(n_particles: int, model: GranularModel, steps: int, contact: str = "two-field") -> Runner:
    h = 0.005
    cells = n_particles / 4.0  # 2 x 2 particles per cell
    ncz = max(8, int(np.sqrt(cells / 4.0)))
    ncx = round(cells / ncz)
    grid = BedGrid(ncx * h, ncz * h, 0.05, h, -0.5 * ncx * h)
    p = make_bed(model, grid)
    plate = effective_body(Plate(0.05, 0.1), h, contact)
    seg = body_segments(plate, h)
    body = BodyState(
        seg=seg,
        pose=np.array([0.0, -0.02, 0.0]),
        twist=np.zeros(3),
        free=np.zeros(2, dtype=np.bool_),
        mass=1.0,
        load=np.zeros(2),
        friction=0.4,
        width=0.1,
        contact=ContactScheme(contact),
    )
    dt = stable_time_step(model, h)
    return Runner(model, grid, p, body, dt, [Phase("bench", steps)], record_every=steps)


def particle_steps_per_second(
    n_particles: int, model: GranularModel, min_time: float = 3.0, contact: str = "two-field"
) -> tuple[int, float]:
    """(particles, particle-steps/s) of the compiled step loop on a bed of about ``n_particles`` with
    a plate resting in it under ``contact``."""
    _runner(n_particles, model, 2, contact).run()  # warm-up / compile
    steps = 20
    while True:
        r = _runner(n_particles, model, steps, contact)
        t0 = time.perf_counter()
        r.run()
        dt = time.perf_counter() - t0
        if dt > min_time or steps > 100000:
            return len(r.particles), len(r.particles) * steps / dt
        steps = int(steps * max(2.0, 1.2 * min_time / max(dt, 1e-3)))


def main() -> None:
    quick = "--quick" in sys.argv
    model = GranularModel.from_material(materials.get("MS"))
    print(f"numba threads: {numba.get_num_threads()}")
    print(f"{'particles':>10} {'contact':>10} {'particle-steps/s':>18}")
    sizes = (10**4, 10**5) if quick else (10**4, 10**5, 10**6)
    for n in sizes:
        for contact in ("two-field", "cover"):
            count, rate = particle_steps_per_second(n, model, min_time=2.0 if quick else 5.0, contact=contact)
            print(f"{count:>10d} {contact:>10} {rate:>18.3e}")
    if quick:
        return
    t0 = time.perf_counter()
    res = run_intrusion(Plate(0.05, 0.1), materials.get("MS"), depth=0.05)
    wall = time.perf_counter() - t0
    md = res.metadata
    print(
        f"plate intrusion (MS, plate 0.05 m, depth 0.05 m, defaults): {wall:.1f} s wall, "
        f"{md['particles']} particles, {md['steps']} steps, cell {md['cell_size_m'] * 1e3:.2f} mm, "
        f"F_z = {res.summary['force_z_N']:.2f} N"
    )
    if "--studies" not in sys.argv and os.environ.get("TERRADYN_BENCH_STUDIES") != "1":
        print("(study wall times: run with --studies or TERRADYN_BENCH_STUDIES=1; about 18 min)")
        return
    from terradyn.studies.registry import run_study

    for name in ("mpm-wheel", "mpm-alpha"):
        t0 = time.perf_counter()
        _, out = run_study(name)
        wall = time.perf_counter() - t0
        print(f"study {name} at its default resolution (2 worker processes): {wall:.0f} s wall")
        for rec in out.summary:
            print("   ", {k: round(v, 4) if isinstance(v, float) else v for k, v in rec.items()})


if __name__ == "__main__":
    main()
