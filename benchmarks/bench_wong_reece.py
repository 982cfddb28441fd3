"""Wong-Reece wheel speed: one steady point (load -> sinkage, forces) and a 4 x 4 x 15 sweep.

The 0.13 m x 0.16 m wheel on MS, MMS, LPS and CPS at loads 80, 130, 150, 190 N and slips -0.7 ... 0.7
(15 values): 240 steady solves. Also times the force integrals at one entry angle (compiled kernel and
NumPy reference) and prints the sinkage and drawbar pull at 130 N, slips 0 and 0.3.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np

from terradyn.errors import SolverError
from terradyn.materials import get
from terradyn.terramechanics import _kernels as wrk
from terradyn.terramechanics import wong_reece as wr
from terradyn.terramechanics import wong_reece_wheel

RADIUS, WIDTH = 0.13, 0.16
MEDIA = ("MS", "MMS", "LPS", "CPS")
LOADS = (80.0, 130.0, 150.0, 190.0)
SLIPS = np.linspace(-0.7, 0.7, 15)


def _per_call(fn: Callable[[], object], min_time: float = 0.3) -> float:
    """Mean wall time of one call [s] (after a warm-up call)."""
    fn()
    reps, t0 = 0, time.perf_counter()
    while True:
        fn()
        reps += 1
        dt = time.perf_counter() - t0
        if dt > min_time:
            return dt / reps


def _sweep() -> int:
    failures = 0
    for medium in MEDIA:
        soil = get(medium).require_bekker()
        for load in LOADS:
            for slip in SLIPS:
                try:
                    wong_reece_wheel(RADIUS, WIDTH, soil, float(slip), load)
                except SolverError:
                    failures += 1
    return failures


def main() -> None:
    soil = get("MS").require_bekker()
    t_point = _per_call(lambda: wong_reece_wheel(RADIUS, WIDTH, soil, 0.3, 130.0))
    args = (
        np.array([0.4]),
        0.0,
        RADIUS,
        WIDTH,
        soil.k_c / WIDTH + soil.k_phi,
        soil.n,
        soil.cohesion,
        np.tan(soil.friction_angle),
        soil.shear_modulus,
        0.3,
        0.43 + 0.32 * 0.3,
        wr.DEFAULT_NODE_COUNT,
    )
    t_kernel = _per_call(lambda: wrk._wong_reece_integrals_many(*args))
    t_ref = _per_call(lambda: wrk._wong_reece_integrals_reference(*args))
    failures = _sweep()  # warm
    best = min(_per_call(_sweep, min_time=0.0) for _ in range(3))
    points = len(MEDIA) * len(LOADS) * len(SLIPS)
    print(f"one steady point (solve theta_1 from W, MS, s = 0.3, 130 N): {t_point * 1e3:8.3f} ms")
    print(f"force integrals at one entry angle, compiled kernel:          {t_kernel * 1e6:8.2f} us")
    print(f"force integrals at one entry angle, NumPy reference:          {t_ref * 1e6:8.2f} us")
    print(
        f"sweep {len(MEDIA)} media x {len(LOADS)} loads x {len(SLIPS)} slips = {points} points: "
        f"{best:.3f} s ({best / points * 1e3:.3f} ms per point, {failures} without equilibrium)"
    )
    print(f"{'medium':>6} {'slip':>5} {'sinkage [mm]':>13} {'DP [N]':>9} {'torque [N m]':>13}   at 130 N")
    for medium in MEDIA:
        for slip in (0.0, 0.3):
            res = wong_reece_wheel(RADIUS, WIDTH, medium, slip, 130.0)
            print(
                f"{medium:>6} {slip:>5.1f} {res.sinkage * 1e3:>13.3f} {res.drawbar_pull:>9.2f} "
                f"{res.drive_torque:>13.3f}"
            )


if __name__ == "__main__":
    main()
