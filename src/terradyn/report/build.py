"""Run the rows of the chosen chapters (cached, resumable, parallel) and write the report.

A *unit* is one (item, model) row. Each finished unit is cached as JSON in ``DIR/cache/`` (figures as
base64 PNG), written atomically the moment it finishes, so an interrupted run keeps what it finished
and the next run with the same ``--quick`` setting skips it. Units run through
:func:`terradyn.parallel.map_items` (serial, local processes or Dask); the HTML and Markdown report are
written together at the end through the enclosing :func:`terradyn.io.output_set`.
"""

from __future__ import annotations

import base64
import functools
import hashlib
import io
import json
import os
import platform
import tempfile
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError
from .registry import CHAPTERS, ITEMS, ThesisItem, row_for, rows_of

__all__ = [
    "ReportRun",
    "cache_path",
    "code_fingerprint",
    "expected_row_times",
    "measured_row_times",
    "package_versions",
    "reproduce",
    "rows_to_run",
    "run_unit",
    "units_for",
]

CACHE_FOLDER = "cache"
#: shipped wall times of the rows (seconds, one core), for the ETA only: not part of the code fingerprint
ROW_TIMES_FILE = "row_times.json"


@dataclass
class ReportRun:
    """What :func:`reproduce` did: items shown, unit results (by (key, model)), files written."""

    items: list[ThesisItem]
    results: dict[tuple[str, str], dict[str, Any]]
    ran: int
    reused: int
    wall_time_s: float
    files: list[Path] = field(default_factory=list)

    @property
    def failures(self) -> list[str]:
        return [f"{k}/{m}: {r['error']}" for (k, m), r in self.results.items() if r.get("status") == "failed"]


def package_versions() -> dict[str, str]:
    """Versions of terradyn, Python and the numerical packages the report depends on."""
    import importlib.metadata as md

    from .._version import __version__

    out = {"terradyn": __version__, "python": platform.python_version()}
    for name in ("numpy", "scipy", "numba", "matplotlib", "pandas"):
        try:
            out[name] = md.version(name)
        except md.PackageNotFoundError:
            out[name] = "not installed"
    return out


def select_items(chapters: Sequence[int] | None, only: Sequence[str] | None = None) -> list[ThesisItem]:
    """Registry items of ``chapters`` (all when None), restricted to the keys ``only`` if given."""
    chosen = list(CHAPTERS) if chapters is None else list(chapters)
    for c in chosen:
        if c not in CHAPTERS:
            raise InputError("chapter", c, f"one of {list(CHAPTERS)} or all")
    items = [it for it in ITEMS if it.chapter in chosen]
    if only:
        known = {it.key for it in items}
        for key in only:
            if key not in known:
                raise InputError("items", key, f"an item of the chosen chapters: {sorted(known)}")
        items = [it for it in items if it.key in set(only)]
    return items


def units_for(items: Sequence[ThesisItem]) -> list[tuple[str, str]]:
    """The (item, model) rows that compute something (pending rows and shared rows excluded)."""
    return [
        (it.key, model) for it in items for model, spec in rows_of(it) if spec and not spec.startswith("=")
    ]


def cache_path(folder: Path, key: str, model: str, quick: bool) -> Path:
    """Where the result of one unit is cached."""
    return folder / CACHE_FOLDER / f"{key}__{model}__{'quick' if quick else 'full'}.json"


def _json_safe(value: Any) -> Any:
    if isinstance(value, dict):
        return {str(k): _json_safe(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_json_safe(v) for v in value]
    if isinstance(value, np.ndarray):
        return _json_safe(value.tolist())
    if isinstance(value, np.generic):
        return _json_safe(value.item())
    if isinstance(value, float) and not np.isfinite(value):
        return None
    if value is None or isinstance(value, bool | int | float | str):
        return value
    return str(value)


def _png(fig: Any) -> str:
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    try:
        fig.savefig(buf, format="png", dpi=110, bbox_inches="tight")
    finally:
        plt.close(fig)
    return base64.b64encode(buf.getvalue()).decode("ascii")


def _write_cache(path: Path, data: dict[str, Any]) -> None:
    """Atomic write that does not wait for the report's output set: a cache entry must survive an
    interrupt of the run that made it."""
    from ..io import finalize_temp

    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            json.dump(data, fh)
        finalize_temp(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def run_unit(task: tuple[str, str, bool, str]) -> dict[str, Any]:
    """Run one (item, model) row and cache it; ``task`` = (key, model, quick, report folder)."""
    import matplotlib

    matplotlib.use("Agg")
    from .._version import __version__
    from ..errors import TerradynError

    key, model, quick, folder = task
    t0 = time.perf_counter()
    try:
        out = row_for(key, model)(quick)
    except TerradynError as exc:  # a model that cannot run this item: reported, not cached
        return {
            "key": key,
            "model": model,
            "status": "failed",
            "error": " ".join(str(exc).split()),
            "wall_time_s": time.perf_counter() - t0,
        }
    wall = time.perf_counter() - t0
    data = {
        "key": key,
        "model": model,
        "quick": quick,
        "status": "ran",
        "terradyn": __version__,
        "code": code_fingerprint(),
        "wall_time_s": wall,
        "figures": {name: _png(fig) for name, fig in out.figures.items()},
        "settings": _json_safe(out.settings),
        "metrics": _json_safe(out.metrics),
        "findings": [{"text": f.text, "verdict": f.verdict} for f in out.findings],
        "tables": _json_safe(out.tables),
    }
    _write_cache(cache_path(Path(folder), key, model, quick), data)
    return data


def _cached(folder: Path, key: str, model: str, quick: bool) -> dict[str, Any] | None:
    from .._version import __version__

    path = cache_path(folder, key, model, quick)
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("terradyn") != __version__ or data.get("status") != "ran":
        return None
    if data.get("code") != code_fingerprint():  # the package changed since the row ran
        return None
    return data


@functools.cache
def code_fingerprint() -> str:
    """SHA-256 of terradyn's own source and data files (paths and contents): a cached row is reused
    only by the code that computed it, version bump or not."""
    root = Path(__file__).resolve().parent.parent
    digest = hashlib.sha256()
    for path in sorted(root.rglob("*")):
        if path.name == ROW_TIMES_FILE:  # ETA weights: updating them must not invalidate caches
            continue
        if path.suffix in (".py", ".toml", ".csv", ".json") and "__pycache__" not in path.parts:
            digest.update(str(path.relative_to(root)).encode())
            digest.update(path.read_bytes())
    return digest.hexdigest()


def measured_row_times(folder: str | Path, quick: bool) -> dict[str, float]:
    """Wall times [s] of the rows cached in the report folder ``folder`` (``"key/model"`` -> s) for the
    quick or the full form, whatever code computed them (a stale entry still says what the row costs)."""
    out: dict[str, float] = {}
    mode = "quick" if quick else "full"
    for path in sorted((Path(folder) / CACHE_FOLDER).glob(f"*__{mode}.json")):
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
            wall = float(data["wall_time_s"])
        except (OSError, ValueError, KeyError, TypeError):
            continue
        if data.get("status") == "ran" and np.isfinite(wall) and wall >= 0:
            out[f"{data.get('key')}/{data.get('model')}"] = wall
    return out


@functools.cache
def _shipped_row_times() -> dict[str, Any]:
    path = Path(__file__).with_name(ROW_TIMES_FILE)
    return dict(json.loads(path.read_text(encoding="utf-8")))


def expected_row_times(
    units: Sequence[tuple[str, str]], *, quick: bool, folder: str | Path | None = None
) -> tuple[list[float], str]:
    """Expected wall time [s, one core] of each (key, model) row, and where the figures come from.

    In order of preference: the row's own earlier run in ``folder`` (a stale cache entry of the same
    mode), the times shipped in ``row_times.json`` (measured on a two-core machine, see its
    ``measured`` field), the median of the known rows of the same model, the median of all known
    rows. Used to weight the ETA of ``terradyn reproduce``: its rows differ in cost by 1e5."""
    mode = "quick" if quick else "full"
    shipped = _shipped_row_times()
    known: dict[str, float] = {k: float(v) for k, v in shipped[mode].items()}
    local = measured_row_times(folder, quick) if folder is not None else {}
    known.update(local)
    by_model: dict[str, list[float]] = {}
    for name, wall in known.items():
        by_model.setdefault(name.rsplit("/", 1)[-1], []).append(wall)
    every = [w for walls in by_model.values() for w in walls]
    fallback = float(np.median(every)) if every else 1.0
    times = []
    counts = {"local": 0, "shipped": 0, "guessed": 0}
    for key, model in units:
        name = f"{key}/{model}"
        if name in known:
            times.append(known[name])
            counts["local" if name in local else "shipped"] += 1
        else:
            walls = by_model.get(model)
            times.append(float(np.median(walls)) if walls else fallback)
            counts["guessed"] += 1
    source = (
        f"{counts['local']} from this folder's earlier runs, {counts['shipped']} measured on "
        f"{shipped['measured']}, {counts['guessed']} guessed from rows of the same model"
    )
    return times, source


def rows_to_run(
    out: str | Path,
    *,
    chapters: Sequence[int] | None = None,
    quick: bool = False,
    only: Sequence[str] | None = None,
) -> list[tuple[str, str]]:
    """The (item, model) rows a :func:`reproduce` call would compute (those not cached yet)."""
    folder = Path(out)
    return [u for u in units_for(select_items(chapters, only)) if _cached(folder, *u, quick) is None]


def reproduce(
    out: str | Path,
    *,
    chapters: Sequence[int] | None = None,
    quick: bool = False,
    only: Sequence[str] | None = None,
    scheduler: str = "serial",
    workers: int | None = None,
    on_done: Callable[[int], None] | None = None,
    on_row: Callable[[str, str], None] | None = None,
) -> ReportRun:
    """Run the rows of the chosen chapters (reusing cached ones) and write ``report.html`` and
    ``report.md`` (with ``figures/``) into the folder ``out``.

    Parameters
    ----------
    out : report folder (created if missing; its ``cache/`` keeps finished rows for a rerun)
    chapters : thesis chapters (default all of 3, 4, 6, 7, 8, 9)
    quick : reduced grids (minutes on two cores); cached separately from full runs
    only : item keys to run (default every item of the chapters)
    scheduler, workers : as :func:`terradyn.parallel.map_items`
    on_done : progress callback, called with the number of rows just finished
    on_row : progress callback, called with (key, model) of each row as it finishes
    """
    from ..io import check_output_folder
    from ..parallel import map_items
    from .render import write_report

    folder = check_output_folder("out", out)
    items = select_items(chapters, only)
    t0 = time.perf_counter()
    folder.mkdir(parents=True, exist_ok=True)
    results: dict[tuple[str, str], dict[str, Any]] = {}
    todo = []
    for key, model in units_for(items):
        hit = _cached(folder, key, model, quick)
        if hit is None:
            todo.append((key, model, quick, str(folder)))
        else:
            results[(key, model)] = hit
    reused = len(results)
    if todo:
        n = 1 if scheduler == "serial" else (workers or max(1, min(len(todo), os.cpu_count() or 1)))
        row_done = None
        if on_row is not None:
            report_row = on_row

            def row_done(index: int) -> None:
                report_row(todo[index][0], todo[index][1])

        done = map_items(
            run_unit,
            todo,
            scheduler=scheduler if n > 1 else "serial",
            workers=workers,
            on_done=on_done,
            on_item=row_done,
        )
        for r in done:
            results[(r["key"], r["model"])] = r
    run = ReportRun(items, results, len(todo), reused, time.perf_counter() - t0)
    run.files = write_report(folder, run, quick=quick, versions=package_versions(), scheduler=scheduler)
    return run
