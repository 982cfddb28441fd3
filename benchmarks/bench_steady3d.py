"""Steady 3D-RFT wheel solves: whole force-slip curves (15 slips) of ~50k-facet wheels.

Wheels of 0.26 m diameter x 0.16 m on MS at 80 N and a 5 deg slip angle, slips -0.7 .. 0.7:

* a cylinder (1000 rim quads x 10 across, two rings on each side wall: 50 000 triangles), one phase;
* a grousered wheel (15 lugs 10 mm x 5 mm, 800 x 9 quads: 50 370 triangles), averaged over 4 wheel
  angles of one lug pitch (period detected from the mesh).

Each solve scans 17 axle heights in one batched kernel call (parallel over the states), root-finds
with one state per call, then finds the contact patch once. Printed: the cylinder's curve, wall time
per curve and per point, and the facet evaluations per second of the kernel calls (every facet of
every wheel state counts as one evaluation) and of the whole solve, in wall time with numba's
default thread count.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any

import numba
import numpy as np

import terradyn.rft.rft3d as rft3d
from terradyn import materials
from terradyn.geometry3d import TriangleMesh, wheel_cylinder, wheel_grousered
from terradyn.locomotion.steady3d import WheelSteady3DResult, wheel_steady_3d

SLIPS = np.round(np.linspace(-0.7, 0.7, 15), 10)
LOAD = 80.0
SLIP_ANGLE = math.radians(5.0)


def _curve(mesh: TriangleMesh, phase_count: int) -> tuple[list[WheelSteady3DResult], float, int, float]:
    """(results, wall seconds, wheel states evaluated, seconds inside the batched kernel calls)."""
    ms = materials.get("MS")
    wheel_steady_3d(mesh, ms, LOAD, 0.3, slip_angle=SLIP_ANGLE, phase_count=phase_count)  # warm up
    original: Callable[..., Any] = rft3d.rft3d_wrench_many
    counts = {"states": 0, "seconds": 0.0}

    def counted(*args: Any, **kwargs: Any) -> Any:
        t0 = time.perf_counter()
        out = original(*args, **kwargs)
        counts["seconds"] += time.perf_counter() - t0
        counts["states"] += out.shape[0]
        return out

    rft3d.rft3d_wrench_many = counted
    try:
        t0 = time.perf_counter()
        rows = [
            wheel_steady_3d(mesh, ms, LOAD, float(s), slip_angle=SLIP_ANGLE, phase_count=phase_count)
            for s in SLIPS
        ]
        elapsed = time.perf_counter() - t0
    finally:
        rft3d.rft3d_wrench_many = original
    return rows, elapsed, int(counts["states"]), float(counts["seconds"])


def _report(name: str, mesh: TriangleMesh, elapsed: float, states: int, kernel: float) -> None:
    evaluations = states * mesh.facet_count
    print(
        f"{name}: {mesh.facet_count} facets, curve {elapsed:.2f} s wall "
        f"({elapsed / len(SLIPS) * 1e3:.0f} ms per point, {states / len(SLIPS):.0f} wheel states per point); "
        f"kernel {evaluations / kernel / 1e6:.1f} million facet evaluations/s, whole solve "
        f"{evaluations / elapsed / 1e6:.1f} million/s"
    )


def main() -> None:
    print(f"numba threads: {numba.get_num_threads()}; MS, {LOAD:g} N, slip angle 5 deg, 15 slips")
    cylinder = wheel_cylinder(
        0.13, 0.16, circumferential_resolution=1000, axial_resolution=10, radial_resolution=2
    )
    rows, elapsed, states, kernel = _curve(cylinder, 1)
    print(f"{'slip':>6} {'sinkage mm':>11} {'DP N':>8} {'side N':>8} {'torque N m':>11} {'M_z N m':>8}")
    for r in rows:
        print(
            f"{r.slip:6.2f} {r.sinkage_m * 1e3:11.3f} {r.drawbar_pull_N:8.2f} {r.side_force_N:8.2f} "
            f"{r.drive_torque_Nm:11.3f} {r.aligning_moment_Nm:8.3f}"
        )
    _report("cylinder, 1 phase", cylinder, elapsed, states, kernel)
    grousered = wheel_grousered(
        0.13, 0.16, grouser_count=15, grouser_height=0.01, grouser_thickness=0.005,
        circumferential_resolution=800, axial_resolution=9, radial_resolution=2,
    )  # fmt: skip
    rows, elapsed, states, kernel = _curve(grousered, 4)
    dp = np.array([r.drawbar_pull_N for r in rows])
    print(f"grousered: drawbar pull {dp.min():.2f} .. {dp.max():.2f} N over the slips")
    _report("grousered, 4 phases", grousered, elapsed, states, kernel)


if __name__ == "__main__":
    main()
