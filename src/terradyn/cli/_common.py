"""Shared CLI plumbing: printing results, number lists, progress bars (files go through terradyn.io)."""

from __future__ import annotations

import math
import os
import sys
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from ..errors import InputError
from ..io import (
    OutputFormat,
    atomic_write,
    atomic_write_text,
    current_output_set,
    format_output,
    save_figure,
)

__all__ = [
    "OutputFormat",
    "atomic_write",
    "atomic_write_text",
    "emit",
    "format_output",
    "parse_float_list",
    "progress",
    "save_figure",
]


def emit(
    data: dict[str, Any] | Sequence[dict[str, Any]],
    fmt: OutputFormat,
    out: Path | None,
    *,
    title: str = "",
    table: str | None = None,
) -> None:
    """Print the result in ``fmt``; with ``out`` also write it there (JSON for .json, else CSV).
    ``table`` replaces the printed text in table format (e.g. a record with nested rows printed as
    two tables); the file still holds ``data``.

    Inside a command both go through the command's output set: printed and written only when the
    whole command has succeeded."""
    text = table if table is not None and fmt is OutputFormat.table else format_output(data, fmt, title=title)
    if out is not None:
        file_fmt = fmt
        if fmt is OutputFormat.table:
            file_fmt = OutputFormat.json if str(out).endswith(".json") else OutputFormat.csv
        atomic_write_text(out, format_output(data, file_fmt), field_name="--out")
    outs = current_output_set()
    if outs is not None:
        outs.print(text)
    else:
        sys.stdout.write(text)


def parse_float_list(field: str, text: str) -> list[float]:
    """Parse ``"0.01"``, ``"0.01,0.02"`` or a range ``"0.01:0.05:5"`` (start:stop:count)."""
    text = text.strip()
    try:
        if ":" in text:
            parts = text.split(":")
            if len(parts) != 3:
                raise ValueError
            start, stop, count = float(parts[0]), float(parts[1]), int(parts[2])
            if count < 1 or count > 100000:
                raise ValueError
            if count == 1:
                values = [start]
            else:
                values = [start + (stop - start) * i / (count - 1) for i in range(count)]
        else:
            values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise InputError(
            field, text, "a number, a comma list (0.01,0.02) or a range start:stop:count (count 1-100000)"
        ) from None
    if not values or not all(math.isfinite(v) for v in values):
        raise InputError(field, text, "finite numbers")
    return values


def _quiet() -> bool:
    return not sys.stderr.isatty() or bool(os.environ.get("CI"))


def _clock(seconds: float) -> str:
    s = round(seconds)
    return f"{s // 3600}:{s // 60 % 60:02d}:{s % 60:02d}"


@contextmanager
def progress(total: int, description: str) -> Iterator[Callable[[int], None]]:
    """A progress bar with ETA on a terminal, silent in pipes and CI. Yields ``advance(n)``.

    (Work of hours whose pieces differ in cost, often run with stderr sent to a file, uses
    :func:`weighted_progress`, which writes one line per finished piece there.)"""
    if _quiet():

        def _silent(n: int = 1) -> None:
            return None

        yield _silent
        return
    from rich.progress import (
        BarColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    with Progress(
        TextColumn("{task.description}"),
        BarColumn(),
        TextColumn("{task.completed}/{task.total}"),
        TimeElapsedColumn(),
        TimeRemainingColumn(),
        transient=True,
    ) as bar:
        task = bar.add_task(description, total=total)

        def _advance(n: int = 1) -> None:
            bar.advance(task, n)

        yield _advance


@contextmanager
def weighted_progress(
    costs: dict[str, float], description: str, *, source: str = "", workers: int = 1
) -> Iterator[Callable[[str], None]]:
    """Progress of named pieces of work whose costs differ (``costs``: name -> expected seconds on one
    core). Yields ``finished(name)``. The ETA is the expected cost of what is left, scaled by the pace
    so far (elapsed / expected cost of what finished), so one long piece does not read as one row in
    thirty. On a terminal a bar; in a pipe or CI one line at the start (the expected total, at
    ``workers`` in parallel, and where the costs come from) and one line per finished piece."""
    import time

    total = sum(costs.values())
    n = len(costs)
    if _quiet():
        start = time.perf_counter()
        done: list[str] = []
        if n:
            sys.stderr.write(
                f"{description}: expected {_clock(total / max(1, min(workers, n)))}"
                + (f" (row times: {source})" if source else "")
                + "\n"
            )
            sys.stderr.flush()

        def _line(name: str) -> None:
            done.append(name)
            spent = time.perf_counter() - start
            finished = sum(costs.get(d, 0.0) for d in done)
            left = total - finished
            pace = spent / finished if finished > 0 else 1.0 / max(1, min(workers, n))
            sys.stderr.write(
                f"{description}: {len(done)}/{n} done ({name}), elapsed {_clock(spent)}, "
                f"ETA {_clock(left * pace)}\n"
            )
            sys.stderr.flush()

        yield _line
        return
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn, TimeRemainingColumn

    with Progress(
        TextColumn("{task.description}"),
        BarColumn(),
        TextColumn("{task.fields[rows]}/" + str(n)),
        TimeElapsedColumn(),
        TimeRemainingColumn(),
        transient=True,
    ) as bar:
        task = bar.add_task(description, total=max(total, 1e-9), rows=0)
        count = [0]

        def _advance(name: str) -> None:
            count[0] += 1
            bar.update(task, advance=costs.get(name, 0.0), rows=count[0])

        yield _advance


@contextmanager
def fraction_progress(label: str, unit: str = "") -> Iterator[Callable[[float, float], None]]:
    """A progress bar driven by ``update(value, fraction_done)`` (e.g. simulated time), with ETA."""
    if _quiet():
        yield lambda value, fraction: None
        return
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn, TimeRemainingColumn

    with Progress(
        TextColumn(label),
        BarColumn(),
        TextColumn("{task.fields[value]:.4g}" + (f" {unit}" if unit else "")),
        TimeElapsedColumn(),
        TimeRemainingColumn(),
        transient=True,
    ) as bar:
        task = bar.add_task(label, total=1.0, value=0.0)

        def update(value: float, fraction: float) -> None:
            bar.update(task, completed=min(1.0, max(0.0, fraction)), value=value)

        yield update


@contextmanager
def spinner(label: str) -> Iterator[None]:
    """An elapsed-time indicator for work without a known total (silent in pipes and CI)."""
    if _quiet():
        yield
        return
    from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

    with Progress(SpinnerColumn(), TextColumn(label), TimeElapsedColumn(), transient=True) as bar:
        bar.add_task(label, total=None)
        yield
