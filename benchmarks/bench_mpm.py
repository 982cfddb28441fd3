"""MPM speed: particle-steps per second of the full step on 1 and 2 threads, and a plate-intrusion wall time.

What is counted: the compiled step loop (:func:`terradyn.mpm._kernels.advance`) on a consolidated bed
(geostatic stress, Dunatunga-Kamrin model, 2 x 2 particles per 5 mm cell) with a rigid body under the
default two-field contact; one step is the body geometry (near particles, band nodes), p2g with the
two grain fields, the grid update with walls, the two-field frictional contact, g2p with the stress
update, and the particle projection off the body. The figure is particles x steps / wall seconds of
``Runner._advance`` after a warm-up run (compiled code loaded, caches warm), the median of
``REPEATS`` runs of at least ``min_time`` s each, 1- and 2-thread runs interleaved. Both use the
scratch of a ``--threads 2`` run (two p2g grid copies); the thread count is forced, bypassing the
runner's own choice (:data:`terradyn.mpm.solver.PARALLEL_MIN_PARTICLES`). Bodies: a 5 cm plate at rest
21 mm deep, and a 65 mm wheel rolling and sinking through the surface (its 164-segment outline makes
the contact geometry a large part of the step). The 1-minute load average is printed with each row:
on a shared machine the figures measure the share of the cores this process got.

Run: ``python benchmarks/bench_mpm.py [--quick] [--wheel-only] [--studies]``; ``--studies`` (or
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
from terradyn.geometry import Plate, WheelCircular
from terradyn.mpm import GranularModel, run_intrusion
from terradyn.mpm.bodies import BodyState, ContactScheme, body_segments, effective_body
from terradyn.mpm.solver import BedGrid, Phase, Runner, make_bed, stable_time_step

REPEATS = 3


def _runner(n_particles: int, model: GranularModel, body: str = "plate") -> Runner:
    h = 0.005
    cells = n_particles / 4.0  # 2 x 2 particles per cell
    ncz = max(8, int(np.sqrt(cells / 4.0)))
    ncx = round(cells / ncz)
    grid = BedGrid(ncx * h, ncz * h, 0.05, h, -0.5 * ncx * h)
    p = make_bed(model, grid)
    if body == "plate":
        shape = effective_body(Plate(0.05, 0.1), h, ContactScheme.TWO_FIELD)
        pose, twist = [0.0011, -0.0213, 0.0], [0.0, 0.0, 0.0]  # off the grid lines
    else:  # a wheel rolling forward and sinking, prescribed (no body dynamics)
        shape = WheelCircular(0.065, 0.1)
        pose, twist = [0.0, 0.045, 0.0], [0.02, -0.01, -1.0]
    state = BodyState(
        seg=body_segments(shape, h),
        pose=np.array(pose),
        twist=np.array(twist),
        free=np.zeros(3, dtype=np.bool_),
        mass=1.0,
        load=np.zeros(3),
        friction=0.4,
        width=0.1,
        contact=ContactScheme.TWO_FIELD,
    )
    dt = stable_time_step(model, h)
    runner = Runner(model, grid, p, state, dt, [Phase("bench", 1)], record_every=1)
    threads = numba.get_num_threads()
    numba.set_num_threads(min(2, numba.config.NUMBA_NUM_THREADS))
    try:
        runner.prepare()  # scratch as for --threads 2
    finally:
        numba.set_num_threads(threads)
    return runner


def _timed(runner: Runner, steps: int, threads: int) -> float:
    """Wall seconds of ``steps`` steps on ``threads`` threads (the state advances)."""
    forces = np.zeros((steps, 3))
    old = numba.get_num_threads()
    numba.set_num_threads(threads)
    try:
        t0 = time.perf_counter()
        runner._advance(steps, 0.0, forces)
        return time.perf_counter() - t0
    finally:
        numba.set_num_threads(old)


def particle_steps_per_second(
    n_particles: int, model: GranularModel, body: str = "plate", min_time: float = 2.0
) -> tuple[int, dict[int, float]]:
    """(particles, {threads: median particle-steps/s}) for 1 and 2 threads on a bed of about
    ``n_particles`` with ``body`` ("plate" or "wheel") in it (see the module docstring)."""
    counts = [1, 2] if numba.config.NUMBA_NUM_THREADS >= 2 else [1]
    runner = _runner(n_particles, model, body)
    for t in counts:
        _timed(runner, 2, t)  # warm-up: compiled code loaded, caches warm
    steps = 2
    while _timed(runner, steps, 1) < 0.25 * min_time and steps < 100000:
        steps *= 2
    steps = max(2, int(steps * min_time / max(_timed(runner, steps, 1), 1e-6)))
    times: dict[int, list[float]] = {t: [] for t in counts}
    for rep in range(REPEATS):
        for t in counts if rep % 2 == 0 else counts[::-1]:
            times[t].append(_timed(runner, steps, t))
    n = len(runner.particles)
    return n, {t: n * steps / float(np.median(v)) for t, v in times.items()}


def main() -> None:
    quick = "--quick" in sys.argv
    if "--wheel-only" in sys.argv:
        default_wheel()
        return
    model = GranularModel.from_material(materials.get("MS"))
    print(f"numba threads available: {numba.config.NUMBA_NUM_THREADS}")
    print(f"{'particles':>10} {'body':>6} {'1 thread':>12} {'2 threads':>12} {'2/1':>6}  [particle-steps/s]")
    cases = [(10**4, "plate"), (10**4, "wheel"), (10**5, "plate"), (10**5, "wheel")]
    if not quick:
        cases.append((10**6, "plate"))
    for n, body in cases:
        count, rate = particle_steps_per_second(n, model, body, min_time=1.0 if quick else 2.0)
        two = rate.get(2, float("nan"))
        print(
            f"{count:>10d} {body:>6} {rate[1]:>12.3e} {two:>12.3e} {two / rate[1]:>6.2f}"
            f"  load {os.getloadavg()[0]:.1f}",
            flush=True,
        )
    print(f"numba threading layer: {numba.threading_layer()}")
    if quick:
        return
    t0 = time.perf_counter()
    res = run_intrusion(Plate(0.05, 0.1), materials.get("MS"), depth=0.05)
    wall = time.perf_counter() - t0
    md = res.metadata
    print(
        f"plate intrusion (MS, plate 0.05 m, depth 0.05 m, defaults, {numba.get_num_threads()} threads "
        f"allowed): {wall:.1f} s wall, {md['particles']} particles, {md['steps']} steps, "
        f"cell {md['cell_size_m'] * 1e3:.2f} mm, F_z = {res.summary['force_z_N']:.2f} N, "
        f"load {os.getloadavg()[0]:.1f}"
    )
    default_wheel()
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


def default_wheel(drive_seconds: float = 0.2) -> None:
    """The default wheel case (0.13 m x 0.16 m wheel, MS, 130 N, omega 1 rad/s, slip 0.3, default cell
    size and moving window): particle-steps/s of a short run with the default grid and window (its
    settling and sinking cut short, compiled code warm), and the wall time the full default run would
    take at that rate. The projection is labelled as such: the full run (about 3e5 steps) is not made
    here."""
    from terradyn.geometry import WheelCircular
    from terradyn.mpm import Bed, Drive, run_wheel
    from terradyn.mpm.runs import settle_time
    from terradyn.mpm.wheel_runs import DRIVE_RADIANS

    wheel, ms = WheelCircular(0.13, 0.16), materials.get("MS")
    short = dict(load=130.0, omega=1.0, slip=0.3, bed=Bed(settle_time=0.01), drive=Drive(sink_time=0.01))
    run_wheel(wheel, ms, **{**short, "drive": Drive(sink_time=0.01, duration=0.01)})  # warm-up
    t0 = time.perf_counter()
    res = run_wheel(wheel, ms, **{**short, "drive": Drive(sink_time=0.01, duration=drive_seconds)})
    wall = time.perf_counter() - t0
    md = res.metadata
    rate = md["stepped_particles"] * md["steps"] / wall
    dt = md["dt_s"]
    model = GranularModel.from_material(ms)
    full_steps = (
        round(settle_time(model, Bed(), md["bed_depth_m"]) / dt)
        + round(3.0 * np.sqrt(0.13 / 9.81) / dt)
        + round(DRIVE_RADIANS / 1.0 / dt)
    )
    print(
        f"default wheel (MS, 0.13 m x 0.16 m, 130 N, slip 0.3, cell {md['cell_size_m'] * 1e3:.2f} mm, "
        f"window {md['window_m']:.3f} m of a {md['bed_width_m']:.3f} m bed): {md['stepped_particles']} of "
        f"{md['particles']} particles stepped, {rate:.3e} particle-steps/s over {md['steps']} steps, "
        f"{numba.get_num_threads()} threads allowed; the full default run ({full_steps} steps) would take "
        f"about {full_steps * md['stepped_particles'] / rate / 60:.0f} min at this rate "
        "(projected, not run); "
        f"load {os.getloadavg()[0]:.1f}"
    )


if __name__ == "__main__":
    main()
