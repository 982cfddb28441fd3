"""RFT force evaluation speed: element evaluations per second on one core (numba and NumPy)."""

from __future__ import annotations

import time

import numba
import numpy as np

from terradyn import materials
from terradyn.geometry import SurfaceElements
from terradyn.kinematics import Pose2D, Twist2D
from terradyn.rft import rft_wrench


def _elements(n: int) -> SurfaceElements:
    # A circle of n elements, radius 0.1 m, half buried: about half the elements are active.
    phi = (np.arange(n) + 0.5) * 2 * np.pi / n
    nrm = np.column_stack((np.cos(phi), np.sin(phi)))
    return SurfaceElements(0.1 * nrm, nrm, np.full(n, 2 * np.pi * 0.1 / n), 0.05)


def _rate(fn, n: int, min_time: float = 0.4) -> float:
    fn()
    reps, t0 = 0, time.perf_counter()
    while True:
        fn()
        reps += 1
        dt = time.perf_counter() - t0
        if dt > min_time:
            return reps * n / dt


def main() -> None:
    numba.set_num_threads(1)
    mat = materials.get("MS")
    pose, twist = Pose2D(0.0, 0.02, 0.3), Twist2D(0.1, -0.01, 1.5)
    print(f"{'elements':>10} {'numba [elem/s]':>16} {'numpy [elem/s]':>16} {'speed-up':>9}")
    for n in (10**3, 10**4, 10**5, 10**6):
        el = _elements(n)
        r_nb = _rate(lambda el=el: rft_wrench(el, mat, pose, twist), n)
        r_np = _rate(lambda el=el: rft_wrench(el, mat, pose, twist, backend="numpy"), n)
        print(f"{n:>10} {r_nb:>16.3e} {r_np:>16.3e} {r_nb / r_np:>9.1f}")


if __name__ == "__main__":
    main()
