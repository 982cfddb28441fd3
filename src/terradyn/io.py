"""Atomic output: one file or a set of files, checked before work starts; output formats.

Every file terradyn writes goes through a temporary file in the target's folder and is moved into
place with :func:`os.replace`, so a kill never leaves a half-written file. Inside an
:func:`output_set` block nothing is moved into place until the block ends without an error: a
command that fails half-way leaves none of its outputs behind (and overwrites nothing). Physics,
studies and the command line all write through this module.
"""

from __future__ import annotations

import contextvars
import io
import json
import math
import os
import shutil
import tempfile
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from enum import Enum
from pathlib import Path
from typing import Any

from ._interrupts import raise_if_interrupted
from .errors import InputError

__all__ = [
    "FIGURE_SUFFIXES",
    "OutputFormat",
    "OutputSet",
    "atomic_write",
    "atomic_write_text",
    "check_output_file",
    "check_output_folder",
    "current_output_set",
    "format_output",
    "output_set",
    "save_figure",
]

FIGURE_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg")


class OutputFormat(str, Enum):
    """How a result is printed or written: a readable table, JSON (SI, unit-suffixed keys) or CSV."""

    table = "table"
    json = "json"
    csv = "csv"


# --------------------------------------------------------------------------------------------- checks
def _name_max(folder: Path) -> int:
    try:
        return os.pathconf(folder, "PC_NAME_MAX")
    except (OSError, ValueError, AttributeError):  # pragma: no cover - platform without pathconf
        return 255


def _check_parent(field_name: str, text: str, p: Path) -> None:
    parent = p.parent
    outs = current_output_set()
    if outs is not None and outs.stages(parent):
        return
    # the nearest existing ancestor must be a folder (a path "under a file" is refused)
    probe = parent
    while not probe.exists() and probe != probe.parent:
        probe = probe.parent
    if probe.exists() and not probe.is_dir():
        raise InputError(field_name, text, "a path whose folders are folders", f"{probe} is a file")
    if not parent.exists():
        raise InputError(field_name, text, "a path in an existing folder", f"{parent} does not exist")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise InputError(field_name, text, "a path in a folder you can write to")


def check_output_file(
    field_name: str, path: str | Path, *, suffixes: Sequence[str] | None = None, what: str = "file"
) -> Path:
    """``path`` as a :class:`Path` if a file can be written there; else :class:`InputError` naming
    ``field_name``. Refused: an empty name, ``.``, an existing folder, a path under a file, a missing
    or read-only folder, over-long names and (with ``suffixes``) other extensions."""
    text = os.fspath(path)
    if not text.strip():
        raise InputError(field_name, text, f"a {what} path", "the name is empty")
    p = Path(text)
    limit = _name_max(Path("."))
    if any(len(os.fsencode(part)) > limit for part in p.parts):
        raise InputError(field_name, text, f"file and folder names of at most {limit} bytes")
    try:
        is_dir = p.is_dir()
    except OSError as exc:
        raise InputError(field_name, text, f"a {what} path", exc.strerror or "cannot be accessed") from None
    if text.endswith(("/", os.sep)) or p.name in ("", ".", "..") or is_dir:
        raise InputError(field_name, text, f"a {what} path, not a folder")
    if suffixes is not None and p.suffix.lower() not in suffixes:
        listed = ", ".join(suffixes[:-1]) + (" or " if len(suffixes) > 1 else "") + suffixes[-1]
        raise InputError(field_name, text, f"a {what} ending in {listed}")
    _check_parent(field_name, text, p)
    return p


def check_output_folder(field_name: str, path: str | Path) -> Path:
    """``path`` if it is an existing folder or one that can be created in an existing folder."""
    text = os.fspath(path)
    if not text.strip():
        raise InputError(field_name, text, "a folder path", "the name is empty")
    p = Path(text)
    limit = _name_max(Path("."))
    if any(len(os.fsencode(part)) > limit for part in p.parts):
        raise InputError(field_name, text, f"file and folder names of at most {limit} bytes")
    if p.exists():
        if not p.is_dir():
            raise InputError(field_name, text, "a folder path", "it names an existing file")
        if not os.access(p, os.W_OK | os.X_OK):
            raise InputError(field_name, text, "a folder you can write to")
        return p
    _check_parent(field_name, text, p.absolute())
    return p


# ------------------------------------------------------------------------------------------- output set
@dataclass
class OutputSet:
    """Files staged as temporaries and moved into place together by :meth:`commit`.

    Folders that do not exist yet are staged as hidden temporary folders beside them and renamed into
    place. :meth:`discard` removes every temporary; nothing the user named is touched before commit.
    """

    _files: list[tuple[Path, Path]] = field(default_factory=list)
    _folders: dict[Path, Path] = field(default_factory=dict)
    _stdout: list[str] = field(default_factory=list)
    committed: bool = False

    def _stage_dir(self, folder: Path) -> Path:
        folder = Path(folder)
        if folder in self._folders:
            return self._folders[folder]
        if folder.exists() or str(folder) in ("", "."):
            return folder
        parent = self._stage_dir(folder.parent)
        tmp = Path(tempfile.mkdtemp(prefix=f".{folder.name}.", suffix=".tmp", dir=parent))
        self._folders[folder] = tmp
        return tmp

    def staged_path(self, target: str | Path, *, suffix: str = ".tmp") -> Path:
        """A fresh temporary file that :meth:`commit` will move to ``target``."""
        target = Path(target)
        where = self._stage_dir(target.parent)
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=suffix, dir=where)
        os.close(fd)
        self._files.append((Path(tmp), target))
        return Path(tmp)

    def stages(self, folder: str | Path) -> bool:
        """Whether ``folder`` (not existing yet) is created by this set at commit."""
        return Path(folder) in self._folders

    def folder(self, target: str | Path) -> Path:
        """Register an output folder (created at commit if it does not exist)."""
        return self._stage_dir(Path(target))

    def print(self, text: str) -> None:
        """Text for standard output, printed at commit (after the files are in place)."""
        self._stdout.append(text)

    def _staged(self, target: Path) -> Path:
        """Where ``target`` lies before commit: under the staged copy of its nearest missing folder."""
        for ancestor in target.parents:
            if ancestor in self._folders:
                return self._folders[ancestor] / target.relative_to(ancestor)
        return target

    def commit(self) -> None:
        """Move every staged file and folder into place, then print the staged standard output."""
        import sys

        mode = _umask_mode()
        for tmp, target in self._files:
            os.chmod(tmp, mode)
            os.replace(tmp, self._staged(target))
        for folder in sorted(self._folders, key=lambda f: -len(f.parts)):
            tmp_dir = self._folders.pop(folder)
            os.chmod(tmp_dir, 0o777 & ~_umask())
            os.replace(tmp_dir, self._staged(folder))
        self._files.clear()
        self.committed = True
        texts, self._stdout = self._stdout, []
        for text in texts:
            sys.stdout.write(text)
        sys.stdout.flush()

    def discard(self) -> None:
        """Remove every temporary file and staged folder."""
        for tmp, _ in self._files:
            tmp.unlink(missing_ok=True)
        for tmp_dir in self._folders.values():
            shutil.rmtree(tmp_dir, ignore_errors=True)
        self._files.clear()
        self._folders.clear()
        self._stdout.clear()


_CURRENT: contextvars.ContextVar[OutputSet | None] = contextvars.ContextVar("terradyn_outputs", default=None)


def current_output_set() -> OutputSet | None:
    """The :class:`OutputSet` of the enclosing :func:`output_set` block, if any."""
    return _CURRENT.get()


@contextmanager
def output_set() -> Iterator[OutputSet]:
    """Stage every file written by this module inside the block; commit them together at its end.

    On any exception (including ``KeyboardInterrupt``) the temporaries are removed and nothing the
    user named is created or overwritten. A nested block joins the enclosing set."""
    outer = current_output_set()
    if outer is not None:
        yield outer
        return
    outs = OutputSet()
    token = _CURRENT.set(outs)
    try:
        yield outs
    except BaseException:
        outs.discard()
        raise
    finally:
        _CURRENT.reset(token)
    try:
        raise_if_interrupted()  # an interrupt swallowed inside the block still leaves no files
        outs.commit()
    except BaseException:
        outs.discard()
        raise


# ------------------------------------------------------------------------------------------- writing
def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _umask_mode() -> int:
    """Permissions a plainly created file would get (0o666 minus the umask)."""
    return 0o666 & ~_umask()


def finalize_temp(tmp: str | Path, target: Path) -> None:
    """Give a finished temporary file normal permissions and move it into place atomically."""
    os.chmod(tmp, _umask_mode())
    os.replace(tmp, target)


def atomic_write(
    path: str | Path, write: Callable[[str], Any], *, suffix: str = ".tmp", field_name: str = "path"
) -> Path:
    """Call ``write(tmp_path)``, then move the file to ``path`` atomically (or stage it in the current
    :func:`output_set`); returns ``path``."""
    p = Path(path)
    outs = current_output_set()
    if outs is not None:
        tmp = outs.staged_path(p, suffix=suffix)
        write(str(tmp))
        return p
    parent = p.parent
    if not parent.exists():
        raise InputError(field_name, str(path), "a path in an existing folder", f"{parent} does not exist")
    fd, tmp_name = tempfile.mkstemp(prefix=f".{p.name}.", suffix=suffix, dir=parent)
    os.close(fd)
    try:
        write(tmp_name)
        finalize_temp(tmp_name, p)
    except BaseException:
        Path(tmp_name).unlink(missing_ok=True)
        raise
    return p


def atomic_write_text(path: str | Path, text: str, *, field_name: str = "path") -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically; see :func:`atomic_write`."""

    def _write(tmp: str) -> None:
        with open(tmp, "w", encoding="utf-8", newline="") as fh:
            fh.write(text)

    return atomic_write(path, _write, field_name=field_name)


def save_figure(fig: Any, path: str | Path, field_name: str = "--plot") -> Path:
    """Save a matplotlib figure atomically (format from the extension) and close it."""
    p = check_output_file(field_name, path, suffixes=FIGURE_SUFFIXES, what="figure file")
    try:
        atomic_write(p, lambda tmp: fig.savefig(tmp, dpi=130, bbox_inches="tight"), suffix=p.suffix.lower())
    finally:
        import matplotlib.pyplot as plt

        plt.close(fig)
    return p


# ------------------------------------------------------------------------------------------- formats
def _clean(value: Any) -> Any:
    if hasattr(value, "item") and not isinstance(value, str | bytes):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        raise InputError("output", value, "finite numbers", "a computation produced a non-finite value")
    if isinstance(value, Path):
        return str(value)
    return value


def _rows(data: dict[str, Any] | Sequence[dict[str, Any]]) -> list[dict[str, Any]]:
    rows = [data] if isinstance(data, dict) else list(data)
    return [{k: _clean(v) for k, v in row.items()} for row in rows]


def format_output(
    data: dict[str, Any] | Sequence[dict[str, Any]], fmt: OutputFormat, *, title: str = ""
) -> str:
    """Render one record (dict) or a table (list of dicts) as text.

    A table with many columns is printed as one block per row (``key  value`` lines) so that no
    header is ever cut."""
    rows = _rows(data)
    if fmt is OutputFormat.json:
        payload: Any = rows[0] if isinstance(data, dict) else rows
        return json.dumps(payload, indent=2) + "\n"
    if fmt is OutputFormat.csv:
        import csv

        buf = io.StringIO()
        if rows:
            keys: list[str] = []
            for r in rows:
                keys += [k for k in r if k not in keys]
            writer = csv.DictWriter(buf, fieldnames=keys, restval="")
            writer.writeheader()
            writer.writerows(rows)
        return buf.getvalue()
    return _format_table(rows, title)


def _cell(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:.6g}"
    if value is None:
        return "-"
    return str(value)


def _table_width() -> int:
    """Columns a table may use: the terminal's width, unlimited when the output is not a terminal."""
    import shutil
    import sys

    if not sys.stdout.isatty():
        return 10**6
    return shutil.get_terminal_size((120, 24)).columns


def _format_table(rows: list[dict[str, Any]], title: str) -> str:
    """Plain-text table, no cell or header ever cut; a single record, or a table wider than the
    terminal, prints as ``key  value`` lines."""
    keys: list[str] = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    cells = [[_cell(r.get(k)) for k in keys] for r in rows]
    widths = [max([len(k)] + [len(c[i]) for c in cells]) for i, k in enumerate(keys)]
    lines = [title] if title else []
    if len(rows) == 1 or sum(widths) + 2 * len(widths) > _table_width():
        kw = max((len(k) for k in keys), default=0)
        for n, (r, c) in enumerate(zip(rows, cells, strict=True)):
            if len(rows) > 1:
                lines.append(f"[{n + 1}]")
            lines += [f"  {k.ljust(kw)}  {v}" for k, v in zip(keys, c, strict=True) if r.get(k) is not None]
        return "\n".join(lines) + "\n"
    numeric = [
        all(isinstance(r.get(k), int | float) and not isinstance(r.get(k), bool) for r in rows) for k in keys
    ]

    def line(values: list[str]) -> str:
        parts = [v.rjust(w) if num else v.ljust(w) for v, w, num in zip(values, widths, numeric, strict=True)]
        return "  ".join(parts).rstrip()

    lines.append(line(keys))
    lines.append("  ".join("-" * w for w in widths))
    lines += [line(c) for c in cells]
    return "\n".join(lines) + "\n"
