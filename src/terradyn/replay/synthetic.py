"""Synthetic runs tables made by terradyn's own models (for tests, examples and benchmarks).

:func:`synthetic_records` takes the input columns of runs (wheel, medium, load or sinkage, slip or
speeds, slip angle), predicts them with a model and writes the predictions as the "measured" columns,
optionally with seeded Gaussian noise whose standard deviation also fills the ``*_std_*`` columns.
Replaying such a table with the same model gives zero residual; with noise it tests calibration.
"""

from __future__ import annotations

import csv
import io
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..errors import InputError
from .predict import ReplayModel, predict_run
from .table import QUANTITIES, runs_from_records

__all__ = ["design_runs", "records_to_csv", "synthetic_records"]


def design_runs(
    *,
    medium: str = "MS",
    loads: Sequence[float] = (15.0, 25.0),
    slips: Sequence[float] = (-0.6, -0.3, 0.0, 0.2, 0.4, 0.6, 0.8),
    radius: float = 0.0625,
    width: float = 0.06,
    grousered: bool = True,
    slip_angles_deg: Sequence[float] = (0.0,),
) -> list[dict[str, Any]]:
    """Input records of a small single-wheel campaign: smooth (and grousered) wheel x loads x slips
    x slip angles; each record carries ``wheel_type`` (smooth/grousered) as a group column."""
    wheels: list[dict[str, Any]] = [{"wheel_type": "smooth", "shape": "circular"}]
    if grousered:
        wheels.append(
            {"wheel_type": "grousered", "shape": "grousered", "grouser_count": 12,
             "grouser_height_m": 0.1 * radius, "grouser_thickness_m": 0.05 * radius}
        )  # fmt: skip
    out = []
    for w in wheels:
        for load in loads:
            for angle in slip_angles_deg:
                for s in slips:
                    run_id = f"{w['wheel_type']}-W{load:g}-a{angle:g}-s{s:+.2f}"
                    out.append(
                        {"run_id": run_id, **w, "medium": medium, "radius_m": radius, "width_m": width,
                         "load_N": load, "slip": s, "slip_angle_deg": angle}
                    )  # fmt: skip
    return out


def synthetic_records(
    model: ReplayModel,
    runs: Sequence[dict[str, Any]],
    *,
    noise: dict[str, float] | None = None,
    seed: int = 0,
) -> list[dict[str, Any]]:
    """Records with the model's predictions as measured columns (+ seeded noise, std columns).

    ``noise`` maps quantity names (``drawbar_pull_N``, ``drive_torque_Nm``, ``sinkage_m``,
    ``side_force_N``) to the standard deviation [their unit] of the added Gaussian noise. Runs the
    model cannot solve are left out. Side force is written only for 3D models.
    """
    noise = dict(noise or {})
    for q, sd in noise.items():
        if q not in QUANTITIES or not (isinstance(sd, int | float) and sd >= 0):
            raise InputError(f"noise[{q}]", sd, f"a standard deviation >= 0 of one of {list(QUANTITIES)}")
    rng = np.random.default_rng(seed)
    staged = [{**r, "drawbar_pull_N": 0.0} for r in runs]
    table = runs_from_records(staged, source="synthetic")
    out = []
    for rec, row in zip(runs, table.rows, strict=True):
        pred = predict_run(row, model)
        if not pred.solved:
            continue
        new = dict(rec)
        for q, (std_col, _) in QUANTITIES.items():
            value = pred.values.get(q)
            if value is None:
                continue
            sd = noise.get(q, 0.0)
            new[q] = float(value + (rng.normal(0.0, sd) if sd > 0 else 0.0))
            if q == "sinkage_m":
                new[q] = max(new[q], 0.0)
            if sd > 0:
                new[std_col] = sd
        out.append(new)
    return out


def records_to_csv(records: Sequence[dict[str, Any]]) -> str:
    """CSV text of records (columns in first-seen order, empty cells for missing values)."""
    keys: list[str] = []
    for r in records:
        keys += [k for k in r if k not in keys]
    buf = io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=keys, restval="", lineterminator="\n")
    writer.writeheader()
    for r in records:
        writer.writerow({k: (repr(v) if isinstance(v, float) else v) for k, v in r.items()})
    return buf.getvalue()
