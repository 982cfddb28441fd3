"""``terradyn replay RUNS.csv``: predict a table of single-wheel runs with a terrain model and compare."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import typer

from ..errors import InputError
from ..models import model_entry, model_names
from ._common import OutputFormat, atomic_write, emit, fraction_progress, progress
from .options import FORMAT, OUT_FOLDER_HELP, PHASES, input_file, out_folder

_MODELS = ", ".join(f"{n} ({model_entry(n).title})" for n in model_names(use="replay"))


def replay(
    runs: str = typer.Argument(..., help="Runs table (CSV, columns in docs/replay.md)."),
    model: str = typer.Option("rft", "--model", help=f"Terrain model: {_MODELS}."),
    out: str | None = typer.Option(
        None, "--out", help=OUT_FOLDER_HELP + " Writes predictions.csv, metrics.csv and replay.json."
    ),
    calibrate_on: str | None = typer.Option(
        None,
        "--calibrate-on",
        help="Fit the model's scale (and slip-sinkage parameters) on a fraction of the runs (e.g. 0.5, "
        "chosen with --seed) or on the rows where a boolean column is true; metrics on the rest.",
    ),
    seed: int = typer.Option(0, "--seed", help="Seed of the --calibrate-on fraction."),
    group_by: str | None = typer.Option(
        None, "--group-by", help="Also give metrics per value of this column."
    ),
    scale: float = typer.Option(1.0, "--scale", help="Factor on the medium's RFT scale (zeta, 3D: xi) [-]."),
    excavation: float | None = typer.Option(
        None, "--excavation", help="Slip-sinkage excavation coefficient [-] (rft-ss, rft3d-ss)."
    ),
    bulldozing: float | None = typer.Option(
        None, "--bulldozing", help="Slip-sinkage bulldozing coefficient [-] (rft-ss, rft3d-ss)."
    ),
    phases: int = PHASES,
    cull: bool = typer.Option(
        True, "--cull/--no-cull", help="Drop mesh facets the medium cannot reach (hub, inner rim)."
    ),
    scheduler: str = typer.Option(
        "serial",
        "--scheduler",
        help="serial, processes (local cores), local (Dask) or a Dask scheduler address.",
    ),
    workers: int | None = typer.Option(None, "--workers", help="Worker processes (default: one per core)."),
    fmt: OutputFormat = FORMAT,
    plot: bool = typer.Option(False, "--plot", help="Also write parity and residual plots (PNG) into --out."),
) -> None:
    """Replay every run of a table through a terrain model: predictions, residuals and metrics."""
    from ..replay import ReplayModel, read_runs
    from ..replay import replay as run_replay
    from ..replay.core import calibrate_table

    path = input_file("RUNS", runs)
    folder = out_folder("--out", out)
    if folder is not None and path is not None:
        _check_not_input(folder, path, out)
    if plot and folder is None:
        raise InputError("--plot", "set", "--out DIR as well (the plots are written into it)")
    if workers is not None and not 1 <= workers <= 256:
        raise InputError("--workers", workers, "an integer in [1, 256]")
    target = _calibrate_on(calibrate_on)
    spec = ReplayModel(
        model, scale=scale, excavation=excavation, bulldozing=bulldozing, phase_count=phases, cull=cull
    )
    table = read_runs(path)  # type: ignore[arg-type]
    if group_by is not None and group_by not in (*table.extra_columns, "medium"):
        raise InputError("--group-by", group_by, f"a column of the table: {[*table.extra_columns, 'medium']}")
    calibration = None
    if target is not None:
        # progress against the evaluation budget (the fit usually stops before it: the ETA is an upper bound)
        with fraction_progress(f"calibrating {spec.name}", "evaluations") as update:
            spec, calibration = calibrate_table(
                table, spec, target, seed=seed, on_evaluation=lambda n: update(n, n / MAX_EVALUATIONS),
                max_evaluations=MAX_EVALUATIONS,
            )  # fmt: skip
    with progress(len(table), f"replay ({spec.name})") as advance:
        result = run_replay(
            table, spec, calibration=calibration, group_by=group_by, scheduler=scheduler, workers=workers,
            on_done=advance,
        )  # fmt: skip
    failures = result.failures
    if all(not r["solved"] for r in result.runs):
        from ..errors import SolverError

        raise SolverError(f"no run of {path} could be replayed with {spec.name}: {failures[0]}")
    if failures:
        typer.echo(
            f"terradyn: {len(failures)} of {len(table)} run(s) not replayed, e.g. {failures[0]}", err=True
        )
    summary = _summary(result, len(table))
    if folder is not None:
        _write(folder, result, summary, plot)
    if fmt is OutputFormat.json:
        emit(summary, fmt, None)
    else:
        emit(
            result.metrics,
            fmt,
            None,
            title=f"replay {spec.name}: {summary['replayed_runs']}/{len(table)} runs",
        )


#: evaluations of the model the calibration may spend
MAX_EVALUATIONS = 120

#: the files --out DIR gets
OUTPUT_NAMES = (
    "predictions.csv", "metrics.csv", "replay.json", "parity.png", "residuals_vs_slip.png",
    "residuals_vs_slip_angle.png",
)  # fmt: skip


def _check_not_input(folder: Path, table: Path, text: str | None) -> None:
    """Refuse an output folder where a file terradyn writes is the runs table itself."""
    target = table.resolve()
    for name in OUTPUT_NAMES:
        if (folder / name).resolve() == target:
            raise InputError(
                "--out", text, "a folder where no output overwrites the runs table", f"{name} is RUNS"
            )


def _calibrate_on(text: str | None) -> float | str | None:
    if text is None:
        return None
    value = text.strip()
    try:
        frac = float(value)
    except ValueError:
        if not value:
            raise InputError("--calibrate-on", text, "a fraction in (0, 1) or a column name") from None
        return value
    if not (math.isfinite(frac) and 0.0 < frac < 1.0):
        raise InputError("--calibrate-on", text, "a fraction strictly between 0 and 1, or a column name")
    return frac


def _summary(result: Any, count: int) -> dict[str, Any]:
    fit = result.calibration
    return {
        "model": result.model.name,
        "scale": result.model.scale,
        "slip_sinkage": _ss(result.model),
        "run_count": count,
        "replayed_runs": sum(1 for r in result.runs if r["solved"]),
        "calibration": None
        if fit is None
        else {
            "parameters": fit.parameters,
            "objective": fit.objective,
            "evaluations": fit.evaluations,
            "calibration_runs": len(fit.calibration_runs),
            "held_out_runs": len(fit.held_out_runs),
        },
        "failures": result.failures,
        "metrics": result.metrics,
    }


def _ss(model: Any) -> dict[str, float] | None:
    if model.name not in ("rft-ss", "rft3d-ss"):
        return None
    p = model.slip_sinkage()
    return {
        "excavation": p.excavation,
        "bulldozing": p.bulldozing,
        "repose_angle_deg": math.degrees(p.repose_angle),
    }


def _write(folder: Path, result: Any, summary: dict[str, Any], plot: bool) -> None:
    from ..io import OutputFormat as Fmt
    from ..io import atomic_write_text, format_output, save_figure

    atomic_write_text(folder / "predictions.csv", format_output(result.runs, Fmt.csv), field_name="--out")
    if result.metrics:
        atomic_write_text(folder / "metrics.csv", format_output(result.metrics, Fmt.csv), field_name="--out")
    text = json.dumps(format_json(summary), indent=2) + "\n"
    atomic_write(
        folder / "replay.json", lambda tmp: Path(tmp).write_text(text), suffix=".json", field_name="--out"
    )
    if plot:
        import matplotlib

        matplotlib.use("Agg")
        from ..replay.plots import plot_parity, plot_residuals

        save_figure(plot_parity(result.runs), folder / "parity.png", field_name="--plot")
        save_figure(
            plot_residuals(result.runs, against="slip"), folder / "residuals_vs_slip.png", field_name="--plot"
        )
        if any(r["slip_angle_deg"] != 0 for r in result.runs):
            save_figure(
                plot_residuals(result.runs, against="slip_angle_deg"),
                folder / "residuals_vs_slip_angle.png", field_name="--plot",
            )  # fmt: skip


def format_json(value: Any) -> Any:
    """``value`` with non-finite floats refused (they never leave terradyn) and tuples as lists."""
    if isinstance(value, dict):
        return {k: format_json(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [format_json(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        raise InputError("output", value, "finite numbers", "a computation produced a non-finite value")
    return value
