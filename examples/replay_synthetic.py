"""Make the synthetic runs table that ships with terradyn, then replay it with calibration.

The table (``terradyn/replay/data/example_runs.csv``) is made by terradyn itself: plane RFT on medium MS
with its scale x 1.2, a 125 mm smooth and a 12-grouser wheel, 60 mm wide, loads 15 and 25 N, slips
-0.6 to 0.8, with seeded Gaussian noise (0.1 N on drawbar pull, 5 mN m on torque, 0.3 mm on sinkage)
whose standard deviations fill the ``*_std_*`` columns. Replaying it with ``--calibrate-on 0.5``
recovers the factor 1.2.

Run: python examples/replay_synthetic.py            (replay the shipped table)
     python examples/replay_synthetic.py --write    (regenerate the shipped table)
"""

from __future__ import annotations

import csv
import io
import math
import sys
from importlib import resources
from pathlib import Path

from terradyn.replay import ReplayModel, read_runs, replay, runs_from_records
from terradyn.replay.synthetic import design_runs, records_to_csv, synthetic_records

TRUE_SCALE = 1.2
NOISE = {"drawbar_pull_N": 0.1, "drive_torque_Nm": 5e-3, "sinkage_m": 3e-4}


def make_table() -> str:
    """CSV text of the example table (deterministic: seeded noise)."""
    runs = design_runs(loads=(15.0, 25.0), slips=(-0.6, -0.3, 0.0, 0.2, 0.4, 0.6, 0.8))
    records = synthetic_records(ReplayModel("rft", scale=TRUE_SCALE), runs, noise=NOISE, seed=2026)
    header = (
        "# Synthetic single-wheel runs made by terradyn (examples/replay_synthetic.py):\n"
        f"# plane RFT, medium MS, RFT scale x {TRUE_SCALE}, seeded Gaussian noise; not measurements.\n"
    )
    return header + records_to_csv(records)


def _body(text: str) -> str:
    return "\n".join(line for line in text.splitlines() if not line.startswith("#"))


def shipped_table() -> Path:
    return Path(str(resources.files("terradyn.replay").joinpath("data/example_runs.csv")))


def main() -> dict[str, float]:
    table = read_runs(shipped_table())
    remade = runs_from_records([dict(r) for r in csv.DictReader(io.StringIO(_body(make_table())))])
    for a, b in zip(table.rows, remade.rows, strict=True):  # the shipped table is what this script makes
        assert a.run_id == b.run_id
        for q, value in a.measured.items():
            assert math.isclose(value, b.measured[q], rel_tol=1e-9, abs_tol=1e-12), (a.run_id, q)
    res = replay(table, ReplayModel("rft"), calibrate_on=0.5, seed=0)
    held = {m["quantity"]: m for m in res.metrics if m["set"] == "held-out"}
    print(f"fitted RFT scale factor {res.model.scale:.4f} (made with {TRUE_SCALE})")
    for q, m in held.items():
        print(f"  held-out {q}: RMSE {m['rmse']:.4g}, r = {m['pearson_r']:.4f}")
    assert abs(res.model.scale / TRUE_SCALE - 1) < 0.03
    return {"scale": res.model.scale}


if __name__ == "__main__":
    if "--write" in sys.argv[1:]:
        shipped_table().write_text(make_table())
        print(f"wrote {shipped_table()}")
    else:
        main()
