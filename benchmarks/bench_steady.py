"""Steady wheel solves: one (W, s) point and the whole demo sweep (4 media x 4 loads x 15 slips)."""

from __future__ import annotations

import time

import numba
import numpy as np

from terradyn import materials
from terradyn.geometry import WheelCircular
from terradyn.locomotion import force_slip_sweep, wheel_steady
from terradyn.locomotion.models import ModelSpec


def main() -> None:
    numba.set_num_threads(1)
    wheel = WheelCircular(0.13, 0.16)
    ms = materials.get("MS")
    wheel_steady(wheel, ms, 130.0, 0.3)
    n, t0 = 0, time.perf_counter()
    while time.perf_counter() - t0 < 1.0:
        wheel_steady(wheel, ms, 130.0, 0.1 + 0.5 * (n % 7) / 7)
        n += 1
    per_point = (time.perf_counter() - t0) / n
    print(
        f"RFT steady point, circular wheel, {wheel.discretize().element_count} elements: "
        f"{per_point * 1e3:.3f} ms"
    )
    media = [materials.get(m) for m in ("MS", "MMS", "LPS", "CPS")]
    loads = [80.0, 130.0, 150.0, 190.0]
    slips = list(np.linspace(-0.7, 0.7, 15))
    models: dict[str, ModelSpec] = {"rft": ModelSpec("rft")}
    try:
        models["wong-reece"] = ModelSpec("wong-reece")
        models["wong-reece"](media[0])
    except ImportError:
        del models["wong-reece"]
    for name, spec in models.items():
        force_slip_sweep(wheel, media[:1], {name: spec}, loads[:1], slips[:2])  # warm up
        t0 = time.perf_counter()
        table = force_slip_sweep(wheel, media, {name: spec}, loads, slips)
        dt = time.perf_counter() - t0
        print(f"demo sweep, {name}: {len(table)} points in {dt:.3f} s ({dt / len(table) * 1e3:.3f} ms/point)")
    t0 = time.perf_counter()
    table = force_slip_sweep(wheel, media, models, loads, slips)
    print(f"whole demo sweep ({' + '.join(models)}): {len(table)} points in {time.perf_counter() - t0:.3f} s")


if __name__ == "__main__":
    main()
