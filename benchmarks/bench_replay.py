"""Replay throughput: runs per second for a 387-run table.

* 3D RFT (``rft3d``) on a 50 000-facet smooth wheel read from an STL file (125 mm x 60 mm; 1000 rim
  quads x 10 across, two rings per side wall), MS, loads 13 / 20 / 30 N, 43 rig slips from -1 (locked)
  to 0.9, slip angles 0, 45 and 90 deg: 43 x 3 x 3 = 387 runs, load control. The 0 and 45 deg runs
  with omega > 0 and ``1 - V/(omega r)`` >= -1 take the compiled steady solve, the others (locked,
  deep skid, 90 deg) the twist-based solver of ``terradyn.replay.solve``.
* 3D slip-sinkage RFT (``rft3d-ss``, NumPy-level height field over the compiled facet tractions) on a
  43-run subset of that table, serially;
* plane RFT (``rft``) and plane slip-sinkage RFT (``rft-ss``) on the same wheel as a primitive
  (2D, 360 rim elements), 43 slips x 9 loads (12-28 N) = 387 runs.

Mesh facets the medium cannot reach are culled first, as by default (``wheel_contact_mesh``: the
40 000 rim facets stay at 0 deg, the rim and one side wall, 45 000, at a slip angle; once per wheel and
sign of the slip angle in each process, about 1 s). Each is run on 2 local worker processes
(``scheduler="processes"``, one numba thread each) and, for
the per-run cost, serially on a 43-run subset in this process. Printed: wall seconds and runs per
second. Warm numba cache assumed (``terradyn warmup``); worker start-up is included in the 2-core time.
"""

from __future__ import annotations

import os

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

import tempfile
import time
from pathlib import Path

import numpy as np

from terradyn.geometry3d import save_mesh, wheel_cylinder
from terradyn.replay import ReplayModel, replay, runs_from_records

SLIPS = np.round(np.linspace(-1.0, 0.9, 43), 10)
RADIUS, WIDTH = 0.0625, 0.06


def _table_3d(mesh_file: str) -> list[dict[str, object]]:
    return [
        {"run_id": f"W{w:g}-a{a:g}-s{s:+.4f}", "medium": "MS", "mesh_file": mesh_file, "load_N": w,
         "slip": float(s), "slip_angle_deg": a, "drawbar_pull_N": 0.0}
        for w in (13.0, 20.0, 30.0) for a in (0.0, 45.0, 90.0) for s in SLIPS
    ]  # fmt: skip


def _table_2d() -> list[dict[str, object]]:
    return [
        {"run_id": f"W{w:g}-s{s:+.4f}", "medium": "MS", "radius_m": RADIUS, "width_m": WIDTH,
         "load_N": float(w), "slip": float(s), "drawbar_pull_N": 0.0}
        for w in np.linspace(12.0, 28.0, 9) for s in SLIPS
    ]  # fmt: skip


def _time(
    records: list[dict[str, object]], model: str, scheduler: str, workers: int | None
) -> tuple[float, int]:
    table = runs_from_records(records)
    t0 = time.perf_counter()
    res = replay(table, ReplayModel(model), scheduler=scheduler, workers=workers)
    return time.perf_counter() - t0, sum(1 for r in res.runs if r["solved"])


def main() -> None:
    mesh = wheel_cylinder(
        RADIUS, WIDTH, circumferential_resolution=1000, axial_resolution=10, radial_resolution=2
    )
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "wheel_50k.stl"
        save_mesh(mesh, path)
        table_3d = _table_3d(str(path))
        cases = [("rft3d", table_3d, True), ("rft3d-ss", table_3d, False), ("rft", _table_2d(), True),
                 ("rft-ss", _table_2d(), True)]  # fmt: skip
        load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
        print(f"facets {mesh.facet_count}, runs per table {len(table_3d)}, cpu_count {os.cpu_count()}, "
              f"load average {load:.1f}")  # fmt: skip
        for model, records, whole in cases:
            _time(records[:2], model, "serial", None)  # warm up (mesh read, kernels loaded)
            subset = records[:: len(records) // 43][:43]
            t_serial, _ = _time(subset, model, "serial", None)
            if not whole:  # the Python-level 3D slip-sinkage path: the subset only
                rate = len(subset) / t_serial
                print(f"{model:8s} serial: {len(subset)} runs in {t_serial:.2f} s = {rate:.1f} runs/s")
                continue
            t_par, solved = _time(records, model, "processes", 2)
            print(
                f"{model:8s} serial: {len(subset)} runs in {t_serial:.2f} s = "
                f"{len(subset) / t_serial:.1f} runs/s | "
                f"2 processes: {len(records)} runs ({solved} solved) in {t_par:.2f} s = "
                f"{len(records) / t_par:.1f} runs/s"
            )


if __name__ == "__main__":
    main()
