"""Replay a table of single-wheel experiments through any terrain model (``terradyn replay``).

:func:`read_runs` reads and checks a runs table (columns in :data:`COLUMNS`, ``docs/replay.md``);
:func:`replay` predicts every run with a :class:`ReplayModel`, optionally after calibrating it on a
subset, and returns per-run residuals and metrics (MAE, RMSE, NRMSE, bias, Pearson r).
"""

from .core import CalibrationResult, ReplayResult, calibrate, calibrate_table, metrics, replay, split_runs
from .predict import REPLAY_MODELS, Prediction, ReplayModel, predict_run
from .table import COLUMNS, QUANTITIES, RunRow, RunsTable, WheelSpec, read_runs, rig_slip, runs_from_records

__all__ = [
    "COLUMNS",
    "QUANTITIES",
    "REPLAY_MODELS",
    "CalibrationResult",
    "Prediction",
    "ReplayModel",
    "ReplayResult",
    "RunRow",
    "RunsTable",
    "WheelSpec",
    "calibrate",
    "calibrate_table",
    "metrics",
    "predict_run",
    "read_runs",
    "replay",
    "rig_slip",
    "runs_from_records",
    "split_runs",
]
