"""``terradyn reproduce``: every thesis item of the chosen chapters, as one HTML and Markdown report."""

from __future__ import annotations

import os

import typer

from ..errors import InputError
from .options import QUICK, out_folder


def reproduce(
    chapter: str = typer.Option("all", "--chapter", help="Thesis chapter: 3, 4, 6, 7, 8, 9 or all."),
    quick: bool = QUICK,
    out: str = typer.Option(..., "--out", help="Report folder (report.html, report.md, figures/, cache/)."),
    items: str | None = typer.Option(None, "--items", help="Only these item keys, comma separated."),
    scheduler: str = typer.Option(
        "auto",
        "--scheduler",
        help="auto (serial with --quick, else local processes), serial, processes, local (Dask) or a Dask "
        "address tcp://host:port.",
    ),
    workers: int | None = typer.Option(None, "--workers", help="Worker processes (default: one per core)."),
) -> None:
    """Run the thesis studies with every model that applies and write the report (resumable: finished
    items are cached in the folder and skipped by a rerun)."""
    from ..io import current_output_set
    from ..report import CHAPTERS
    from ..report import reproduce as run_report
    from ..report.build import expected_row_times, rows_to_run
    from ._common import weighted_progress

    folder = out_folder("--out", out)
    assert folder is not None
    text = chapter.strip().lower()
    if text == "all":
        chapters = None
    else:
        try:
            chapters = [int(text)]
        except ValueError:
            chapters = [-1]
        if chapters[0] not in CHAPTERS:
            raise InputError("--chapter", chapter, f"one of {', '.join(map(str, CHAPTERS))} or all")
    if workers is not None and workers < 1:
        raise InputError("--workers", workers, "an integer >= 1")
    only = [k.strip() for k in items.split(",") if k.strip()] if items else None
    if items is not None and not only:
        raise InputError("--items", items, "one or more item keys")
    if scheduler not in ("auto", "serial", "processes", "local") and "://" not in scheduler:
        raise InputError(
            "--scheduler", scheduler, "auto, serial, processes, local or a Dask address like tcp://host:8786"
        )
    if scheduler == "auto":
        scheduler = "serial" if quick else "processes"
    todo = rows_to_run(folder, chapters=chapters, quick=quick, only=only)
    times, source = expected_row_times(todo, quick=quick, folder=folder)
    costs = {f"{key}/{model}": t for (key, model), t in zip(todo, times, strict=True)}
    parallel = 1 if scheduler == "serial" else (workers or os.cpu_count() or 1)
    with weighted_progress(
        costs, f"reproduce ({len(todo)} rows)", source=source, workers=parallel
    ) as finished:
        try:
            run = run_report(
                folder,
                chapters=chapters,
                quick=quick,
                only=only,
                scheduler=scheduler,
                workers=workers,
                on_row=lambda key, model: finished(f"{key}/{model}"),
            )
        except KeyboardInterrupt as exc:
            exc.message = f"finished rows are cached in {folder / 'cache'}; rerun the same command to resume"  # type: ignore[attr-defined]
            raise
    outs = current_output_set()
    lines = [
        f"report: {folder / 'report.html'} and {folder / 'report.md'}",
        f"{run.ran} rows run, {run.reused} reused from the cache, {run.wall_time_s:.1f} s",
    ]
    lines += [f"failed: {f}" for f in run.failures]
    message = "\n".join(lines) + "\n"
    if outs is not None:
        outs.print(message)
    else:
        typer.echo(message, nl=False)
