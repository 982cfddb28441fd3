"""Time-integration speed: simulated seconds per wall-clock second on one core.

A 570-element grousered wheel (15 lugs, 14 rim and 8 face elements each; Agarwal et al., Sci. Adv. 7,
eabe0631 (2021)) and a 360-element circular wheel, 10 s of simulated time each, RFT and DRFT, at the
default time step (see :func:`terradyn.locomotion.dynamics.stable_time_step`) and at 1 ms; best of
three runs.
Goal: >= 100x real time.
"""

from __future__ import annotations

import math
import time

import numba

from terradyn import materials
from terradyn.geometry import WheelCircular, WheelGrousered
from terradyn.locomotion.dynamics import simulate_wheel

DURATION = 10.0
REPEATS = 3


def _cases():
    poppy = materials.get("poppy-cp")
    grousered = WheelGrousered(0.106 - 0.006, 0.05, 15, 0.006, 0.004)
    elements = grousered.discretize_counts(14, 8)
    mass = 6.0 * 638.0 * 0.212**2 * 0.05
    circular = WheelCircular(0.13, 0.16)
    yield "grousered 570", grousered, poppy, {"elements": elements, "mass": mass, "omega": 6.0}
    yield "circular 360", circular, materials.get("MS"), {"mass": 130.0 / 9.81, "omega": 5.0}


def main() -> None:
    numba.set_num_threads(1)
    print(f"{'wheel':>14} {'model':>5} {'dt [ms]':>8} {'steps':>7} {'evals/step':>10} {'us/eval':>9} "
          f"{'wall [s]':>9} {'x real time':>12}")
    for label, body, material, kwargs in _cases():
        for model in ("rft", "drft"):
            for dt in (None, 1e-3):
                simulate_wheel(body, material, model=model, duration=0.05, dt=dt, **kwargs)  # compile
                wall = math.inf
                for _ in range(REPEATS):  # best of a few: the machine may be shared
                    t0 = time.perf_counter()
                    r = simulate_wheel(body, material, model=model, duration=DURATION, dt=dt, output_every=10,
                                       **kwargs)
                    wall = min(wall, time.perf_counter() - t0)
                steps, evals = r.stats["steps"], r.stats["force_evaluations"]
                print(f"{label:>14} {model:>5} {r.dt * 1e3:>8.3f} {steps:>7.0f} {evals / steps:>10.2f} "
                      f"{wall / evals * 1e6:>9.2f} {wall:>9.3f} {DURATION / wall:>12.0f}")


if __name__ == "__main__":
    main()
