"""Shared CLI plumbing: output formats, atomic writes, progress bars."""

from __future__ import annotations

import io
import json
import math
import os
import sys
import tempfile
from collections.abc import Callable, Iterable, Iterator, Sequence
from contextlib import contextmanager
from enum import Enum
from pathlib import Path
from typing import Any, TypeVar

from ..errors import InputError

__all__ = [
    "OutputFormat",
    "atomic_write_text",
    "emit",
    "parse_float_list",
    "progress",
    "save_figure",
]

T = TypeVar("T")


class OutputFormat(str, Enum):
    table = "table"
    json = "json"
    csv = "csv"


def _clean(value: Any) -> Any:
    if isinstance(value, float) and not math.isfinite(value):
        raise InputError("output", value, "finite numbers", "a computation produced a non-finite value")
    if hasattr(value, "item") and not isinstance(value, str | bytes):
        return _clean(value.item())
    return value


def _rows(data: dict[str, Any] | Sequence[dict[str, Any]]) -> list[dict[str, Any]]:
    rows = [data] if isinstance(data, dict) else list(data)
    return [{k: _clean(v) for k, v in row.items()} for row in rows]


def format_output(
    data: dict[str, Any] | Sequence[dict[str, Any]], fmt: OutputFormat, *, title: str = ""
) -> str:
    """Render one record (dict) or a table (list of dicts) as text."""
    rows = _rows(data)
    if fmt is OutputFormat.json:
        payload: Any = rows[0] if isinstance(data, dict) else rows
        return json.dumps(payload, indent=2) + "\n"
    if fmt is OutputFormat.csv:
        import csv

        buf = io.StringIO()
        if rows:
            writer = csv.DictWriter(buf, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(rows)
        return buf.getvalue()
    from rich.console import Console
    from rich.table import Table

    table = Table(title=title or None)
    keys = list(rows[0]) if rows else []
    for key in keys:
        table.add_column(key, justify="right")
    for row in rows:
        table.add_row(*(_fmt_cell(row[k]) for k in keys))
    buf = io.StringIO()
    Console(file=buf, width=max(100, 16 * len(keys)), force_terminal=False).print(table)
    return buf.getvalue()


def _fmt_cell(value: Any) -> str:
    from rich.markup import escape

    if isinstance(value, float):
        return f"{value:.6g}"
    return escape(str(value))


def _umask_mode() -> int:
    """Permissions a plainly created file would get (0o666 minus the umask)."""
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


def finalize_temp(tmp: str | Path, target: Path) -> None:
    """Give a finished temporary file normal permissions and move it into place atomically."""
    os.chmod(tmp, _umask_mode())
    os.replace(tmp, target)


def atomic_write_text(path: str | Path, text: str) -> Path:
    """Write ``text`` to ``path`` through a temporary file in the same folder (no partial files)."""
    p = Path(path)
    if p.parent and not p.parent.exists():
        raise InputError("--out", str(path), "a path in an existing folder")
    fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".tmp", dir=p.parent or Path("."))
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="") as fh:
            fh.write(text)
        finalize_temp(tmp, p)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return p


def emit(
    data: dict[str, Any] | Sequence[dict[str, Any]],
    fmt: OutputFormat,
    out: Path | None,
    *,
    title: str = "",
) -> None:
    """Print the result in ``fmt``; with ``out`` also write it there atomically."""
    text = format_output(data, fmt, title=title)
    if out is not None:
        file_fmt = fmt
        if fmt is OutputFormat.table:
            file_fmt = OutputFormat.json if str(out).endswith(".json") else OutputFormat.csv
        atomic_write_text(out, format_output(data, file_fmt))
    sys.stdout.write(text)


def check_figure_path(path: Path, field: str = "--plot") -> Path:
    """``path`` if it names a figure file (.png/.pdf/.svg/.jpg) in an existing folder."""
    p = Path(path)
    if p.suffix.lower() not in {".png", ".pdf", ".svg", ".jpg", ".jpeg"}:
        raise InputError(field, str(path), "a file ending in .png, .pdf, .svg or .jpg")
    if p.parent and not p.parent.exists():
        raise InputError(field, str(path), "a path in an existing folder")
    return p


def save_figure(fig: Any, path: Path, field: str = "--plot") -> Path:
    """Save a matplotlib figure atomically (format from the file extension)."""
    p = check_figure_path(path, field)
    suffix = p.suffix.lower()
    fd, tmp = tempfile.mkstemp(prefix=f".{p.stem}.", suffix=suffix, dir=p.parent or Path("."))
    os.close(fd)
    try:
        fig.savefig(tmp, dpi=130, bbox_inches="tight")
        finalize_temp(tmp, p)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    finally:
        import matplotlib.pyplot as plt

        plt.close(fig)
    return p


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
                return [start]
            return [start + (stop - start) * i / (count - 1) for i in range(count)]
        values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise InputError(
            field, text, "a number, a comma list (0.01,0.02) or a range start:stop:count"
        ) from None
    if not values or not all(math.isfinite(v) for v in values):
        raise InputError(field, text, "finite numbers")
    return values


@contextmanager
def progress(total: int, description: str) -> Iterator[Callable[[int], None]]:
    """A progress bar with ETA on a terminal, silent in pipes and CI. Yields ``advance(n)``."""
    quiet = not sys.stderr.isatty() or os.environ.get("CI")
    if quiet:

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


def iterate_with_progress(items: Iterable[T], total: int, description: str) -> Iterator[T]:
    with progress(total, description) as advance:
        for item in items:
            yield item
            advance(1)
