"""Replay a runs table through a terrain model: per-run predictions, residuals, metrics, calibration.

Residual = predicted - measured, per quantity. Metrics per quantity (and per value of a group column):
``n``, ``mae`` (mean |residual|), ``rmse``, ``nrmse`` (RMSE / range of the measured values, None when
they do not vary), ``bias`` (mean residual) and ``pearson_r`` (correlation of predicted with measured,
None for fewer than 2 pairs or no variation). Runs the model cannot replay are kept, flagged
``solved = False`` with the reason, and left out of the metrics.

Calibration fits the model's scale (the factor on the medium's RFT zeta or 3D-RFT xi) and, for the
slip-sinkage models, their excavation and bulldozing coefficients on a subset of the runs, minimising
the sum over runs and quantities of (residual / sigma)^2, sigma the run's standard deviation when the
table gives one (> 0), else the root-mean-square of that quantity's measured values in the subset.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..errors import InputError, check_range
from ..parallel import map_items
from .predict import Prediction, ReplayModel, check_meshes, check_rows_for, predict_task
from .table import QUANTITIES, RunRow, RunsTable

__all__ = [
    "CalibrationResult",
    "ReplayResult",
    "calibrate",
    "calibrate_table",
    "metrics",
    "replay",
    "split_runs",
]

_TRUE = ("1", "true", "yes", "y", "t")
_FALSE = ("0", "false", "no", "n", "f", "")
#: objective contribution of a run the model cannot replay, per measured quantity
_FAILED_PENALTY = 100.0


@dataclass(frozen=True)
class ReplayResult:
    """Per-run records and metrics of one replay.

    ``runs``: one dict per run (run_id, row, set, solved, reason, slip, slip_angle_deg, the group
    columns, and per quantity ``measured_*``, ``std_*``, ``predicted_*``, ``residual_*``);
    ``metrics``: one dict per (set, group, quantity); ``model``: the model replayed (fitted when
    calibrated); ``calibration``: the fit, or None.
    """

    runs: list[dict[str, Any]]
    metrics: list[dict[str, Any]]
    model: ReplayModel
    calibration: CalibrationResult | None = None
    metadata: dict[str, Any] = field(default_factory=dict)

    @property
    def failures(self) -> list[str]:
        return [f"{r['run_id']}: {r['reason']}" for r in self.runs if not r["solved"]]


@dataclass(frozen=True)
class CalibrationResult:
    """Fitted parameters (name -> value), the objective at the fit, evaluations, the subset's run ids."""

    parameters: dict[str, float]
    objective: float
    evaluations: int
    calibration_runs: tuple[str, ...]
    held_out_runs: tuple[str, ...]


def _predict(
    rows: Sequence[RunRow], model: ReplayModel, scheduler: str, workers: int | None,
    on_done: Callable[[int], None] | None,
) -> list[Prediction]:  # fmt: skip
    return map_items(
        predict_task, [(r, model) for r in rows], scheduler=scheduler, workers=workers, on_done=on_done
    )


def _records(
    rows: Sequence[RunRow], preds: Sequence[Prediction], sets: dict[int, str], extra: Sequence[str]
) -> list[dict[str, Any]]:
    out = []
    for row, p in zip(rows, preds, strict=True):
        rec: dict[str, Any] = {
            "run_id": row.run_id, "row": row.index, "set": sets.get(row.index, "all"), "solved": p.solved,
            "reason": p.reason, "medium": row.medium, "slip": row.slip,
            "slip_angle_deg": round(math.degrees(row.slip_angle), 10),
            "load_N": row.load, "prescribed_sinkage_m": row.prescribed_sinkage,
        }  # fmt: skip
        for col in extra:
            rec[col] = row.extra.get(col, "")
        for q in QUANTITIES:
            m = row.measured.get(q)
            pv = p.values.get(q) if p.solved else None
            rec[f"measured_{q}"] = m
            rec[f"std_{q}"] = row.std.get(q)
            rec[f"predicted_{q}"] = pv
            rec[f"residual_{q}"] = None if (m is None or pv is None) else pv - m
        rec["predicted_vertical_force_N"] = p.values.get("vertical_force_N") if p.solved else None
        out.append(rec)
    return out


def _stats(measured: np.ndarray, predicted: np.ndarray) -> dict[str, Any]:
    r = predicted - measured
    n = int(r.size)
    rmse = float(np.sqrt(np.mean(r**2)))
    span = float(measured.max() - measured.min())
    pearson = None
    if n >= 2 and np.std(measured) > 0 and np.std(predicted) > 0:
        pearson = float(np.corrcoef(measured, predicted)[0, 1])
    return {
        "n": n, "mae": float(np.mean(np.abs(r))), "rmse": rmse,
        "nrmse": rmse / span if span > 0 else None, "bias": float(np.mean(r)), "pearson_r": pearson,
    }  # fmt: skip


def metrics(runs: Sequence[dict[str, Any]], *, group_by: str | None = None) -> list[dict[str, Any]]:
    """Metrics per (set, group, quantity) of per-run records (as :attr:`ReplayResult.runs`)."""
    out = []
    sets = sorted({r["set"] for r in runs}, key=lambda s: ("calibration", "held-out", "all").index(s))
    for name in sets:
        subset = [r for r in runs if r["set"] == name]
        groups: list[tuple[str, list[dict[str, Any]]]] = [("all", subset)]
        if group_by is not None:
            values = sorted({str(r.get(group_by, "")) for r in subset})
            groups += [(v, [r for r in subset if str(r.get(group_by, "")) == v]) for v in values]
        for gname, members in groups:
            for q in QUANTITIES:
                pairs = [
                    (r[f"measured_{q}"], r[f"predicted_{q}"])
                    for r in members
                    if r[f"residual_{q}"] is not None
                ]
                if not pairs:
                    continue
                m, p = (np.array(v, dtype=float) for v in zip(*pairs, strict=True))
                rec: dict[str, Any] = {"set": name}
                if group_by is not None:
                    rec[group_by] = gname
                rec["quantity"] = q
                rec.update(_stats(m, p))
                out.append(rec)
    return out


def split_runs(table: RunsTable, calibrate_on: float | str, *, seed: int = 0) -> tuple[list[int], list[int]]:
    """(calibration row indices, held-out row indices): a seeded random fraction, or the rows where a
    boolean column is true."""
    indices = [r.index for r in table.rows]
    if isinstance(calibrate_on, str):
        col = calibrate_on
        if col not in table.extra_columns:
            raise InputError(
                "calibrate_on",
                col,
                f"a fraction in (0, 1) or a boolean column of the table {list(table.extra_columns)}",
            )
        cal = []
        for r in table.rows:
            v = r.extra.get(col, "").strip().lower()
            if v not in _TRUE + _FALSE:
                raise InputError(
                    f"{table.source} row {r.index} column {col}", r.extra.get(col, ""),
                    f"a boolean ({'/'.join(_TRUE[:3])} or {'/'.join(_FALSE[:3])}) for calibrate_on",
                )  # fmt: skip
            if v in _TRUE:
                cal.append(r.index)
    else:
        frac = check_range("calibrate_on", float(calibrate_on), 0.0, 1.0)
        if not 0.0 < frac < 1.0:
            raise InputError(
                "calibrate_on", calibrate_on, "a fraction strictly between 0 and 1, or a column name"
            )
        count = min(len(indices) - 1, max(1, round(frac * len(indices))))
        order = np.random.default_rng(seed).permutation(len(indices))
        cal = sorted(indices[i] for i in order[:count])
    held = [i for i in indices if i not in set(cal)]
    if not cal or not held:
        raise InputError(
            "calibrate_on", calibrate_on, "a choice that leaves runs both to calibrate on and to hold out",
            f"{len(cal)} calibration and {len(held)} held-out runs of {len(indices)}",
        )  # fmt: skip
    return cal, held


def _fit_names(model: ReplayModel) -> tuple[str, ...]:
    if model.is_user_model:
        raise InputError(
            "model", model.name, "a terradyn RFT-family model for calibration (a user's model has no scale)"
        )
    if model.name == "wong-reece":
        raise InputError(
            "model", model.name, "an RFT-family model for calibration (rft, drft, rft3d, rft-ss, rft3d-ss)"
        )
    if model.name in ("rft-ss", "rft3d-ss"):
        return ("scale", "excavation", "bulldozing")
    return ("scale",)


def _objective(rows: Sequence[RunRow], preds: Sequence[Prediction]) -> float:
    spread = {}
    for q in QUANTITIES:
        vals = np.array([r.measured[q] for r in rows if q in r.measured])
        spread[q] = float(np.sqrt(np.mean(vals**2))) if vals.size and np.any(vals != 0) else 1.0
    total = 0.0
    for row, p in zip(rows, preds, strict=True):
        for q, m in row.measured.items():
            pv = p.values.get(q) if p.solved else None
            if not p.solved:
                total += _FAILED_PENALTY
                continue
            if pv is None:
                continue
            sigma = row.std.get(q) or spread[q]
            total += ((pv - m) / sigma) ** 2
    return total


def calibrate(
    rows: Sequence[RunRow], model: ReplayModel, *, on_evaluation: Callable[[int], None] | None = None,
    max_evaluations: int = 120,
) -> tuple[ReplayModel, CalibrationResult]:  # fmt: skip
    """Fit the model's parameters on ``rows`` (in this process); (fitted model, the fit)."""
    from scipy.optimize import minimize, minimize_scalar

    names = _fit_names(model)
    count = [0]
    base = model.slip_sinkage() if model.name in ("rft-ss", "rft3d-ss") else None

    def build(x: np.ndarray) -> ReplayModel:
        changes: dict[str, Any] = {"scale": float(math.exp(x[0]))}
        for name, value in zip(names[1:], x[1:], strict=True):
            changes[name] = float(max(value, 0.0))
        return replace(model, **changes)

    def objective(x: np.ndarray) -> float:
        m = build(np.atleast_1d(x))
        preds = [predict_task((r, m)) for r in rows]
        count[0] += 1
        if on_evaluation is not None:
            on_evaluation(count[0])
        return _objective(rows, preds)

    if len(names) == 1:
        res = minimize_scalar(
            lambda t: objective(np.array([t])), bounds=(math.log(0.05), math.log(20.0)), method="bounded",
            options={"xatol": 1e-5, "maxiter": max_evaluations},
        )  # fmt: skip
        x = np.array([res.x])
        value = float(res.fun)
    else:
        assert base is not None
        x0 = np.array([math.log(model.scale), base.excavation, base.bulldozing])
        bounds = [(math.log(0.05), math.log(20.0)), (0.0, 5.0), (0.0, 5.0)]
        res = minimize(
            objective, x0, method="Nelder-Mead", bounds=bounds,
            options={
                "maxfev": max_evaluations, "xatol": 1e-4, "fatol": 1e-9, "initial_simplex": _simplex(x0),
            },
        )  # fmt: skip
        x = np.asarray(res.x)
        value = float(res.fun)
    fitted = build(x)
    params = {n: float(getattr(fitted, n)) for n in names}
    return fitted, CalibrationResult(params, value, count[0], tuple(r.run_id for r in rows), ())


def _simplex(x0: np.ndarray) -> np.ndarray:
    steps = np.array([0.3, 0.3, 0.3])
    pts = [x0.copy()]
    for i in range(x0.size):
        p = x0.copy()
        p[i] += steps[i]
        pts.append(p)
    return np.array(pts)


def calibrate_table(
    table: RunsTable,
    model: ReplayModel,
    calibrate_on: float | str,
    *,
    seed: int = 0,
    on_evaluation: Callable[[int], None] | None = None,
    max_evaluations: int = 120,
) -> tuple[ReplayModel, CalibrationResult]:
    """Split the table (:func:`split_runs`) and fit the model on the calibration runs."""
    check_rows_for(model, table.rows)
    if model.is_3d:
        check_meshes(table.rows, table.source)
    cal, _ = split_runs(table, calibrate_on, seed=seed)
    cal_set = set(cal)
    fitted, fit = calibrate(
        [r for r in table.rows if r.index in cal_set], model, on_evaluation=on_evaluation,
        max_evaluations=max_evaluations,
    )  # fmt: skip
    held_ids = tuple(r.run_id for r in table.rows if r.index not in cal_set)
    return fitted, replace(fit, held_out_runs=held_ids)


def replay(
    table: RunsTable,
    model: ReplayModel,
    *,
    calibrate_on: float | str | None = None,
    calibration: CalibrationResult | None = None,
    seed: int = 0,
    group_by: str | None = None,
    scheduler: str = "serial",
    workers: int | None = None,
    on_done: Callable[[int], None] | None = None,
    on_evaluation: Callable[[int], None] | None = None,
) -> ReplayResult:
    """Replay every run of ``table`` through ``model`` (after calibrating it on a subset, if asked).

    ``calibrate_on``: fit first (:func:`calibrate_table`, seeded by ``seed``); or pass the result of
    an earlier :func:`calibrate_table` as ``calibration`` with its fitted model. ``scheduler`` and
    ``workers`` as :func:`terradyn.parallel.map_items` ("serial", "processes" on local cores, "local"
    Dask cluster or a Dask scheduler address); ``on_done(n)`` reports finished runs. Calibration
    evaluations run in this process. With a calibration the metrics are given for the calibration
    and the held-out sets; otherwise for all runs.
    """
    if not isinstance(table, RunsTable):
        raise InputError("table", type(table).__name__, "a RunsTable (terradyn.replay.read_runs)")
    if group_by is not None and group_by not in table.extra_columns and group_by != "medium":
        raise InputError("group_by", group_by, f"a column of the table: {[*table.extra_columns, 'medium']}")
    check_rows_for(model, table.rows)
    if model.is_3d:
        check_meshes(table.rows, table.source)
    if calibrate_on is not None and calibration is not None:
        raise InputError("calibration", "given twice", "calibrate_on or an earlier calibration, not both")
    if calibrate_on is not None:
        model, calibration = calibrate_table(
            table, model, calibrate_on, seed=seed, on_evaluation=on_evaluation
        )
    sets: dict[int, str] = {}
    if calibration is not None:
        cal_ids = set(calibration.calibration_runs)
        sets = {r.index: "calibration" if r.run_id in cal_ids else "held-out" for r in table.rows}
    preds = _predict(table.rows, model, scheduler, workers, on_done)
    runs = _records(table.rows, preds, sets, table.extra_columns)
    return ReplayResult(
        runs, metrics(runs, group_by=group_by), model, calibration,
        {"source": table.source, "model": model.name, "scale": model.scale, "run_count": len(table)},
    )  # fmt: skip
