"""Checkpoints (resume a killed run) and particle snapshots (NetCDF via xarray), written atomically.

A checkpoint is one ``.npz`` file holding the particle and body arrays, the step counter, the rows
and animation frames recorded so far, and the inputs that identify the run as JSON (``__inputs__``,
with its SHA-256 in ``__fingerprint__``): resuming with different inputs is refused with a message
naming the inputs that differ. Every file is written to a temporary name in the same directory and
moved into place with :func:`os.replace`, so a kill never leaves a half-written file behind.
"""

from __future__ import annotations

import hashlib
import json
import zipfile
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError
from ..runrecords import atomic_write, input_differences, plain, read_snapshot, write_snapshot

__all__ = [
    "CHECKPOINT_FORMAT",
    "atomic_write",
    "input_differences",
    "load_checkpoint",
    "plain",
    "read_snapshot",
    "save_checkpoint",
    "write_snapshot",
]

#: Format tag stored in every checkpoint (``__format__``).
CHECKPOINT_FORMAT = "terradyn-mpm-checkpoint-2"
#: Differences listed in a mismatch message before "and N more".
_MAX_LISTED = 4
#: Errors of reading a damaged or foreign file (never let one escape raw).
_READ_ERRORS = (zipfile.BadZipFile, ValueError, OSError, KeyError, EOFError)


def _canonical(inputs: Mapping[str, Any] | str) -> tuple[dict[str, Any], str]:
    """The inputs as loaded back from JSON, and their JSON text (sorted keys)."""
    data = {"fingerprint": inputs} if isinstance(inputs, str) else plain(inputs)
    text = json.dumps(data, sort_keys=True, allow_nan=True)
    return json.loads(text), text


def save_checkpoint(
    path: str | Path, arrays: Mapping[str, np.ndarray], inputs: Mapping[str, Any] | str
) -> Path:
    """Write ``arrays`` and the run's ``inputs`` (JSON-able, see :func:`plain`) to ``path`` (.npz)
    atomically."""
    _, text = _canonical(inputs)
    payload = {k: np.asarray(v) for k, v in arrays.items()}
    payload["__format__"] = np.array(CHECKPOINT_FORMAT)
    payload["__inputs__"] = np.array(text)
    payload["__fingerprint__"] = np.array(hashlib.sha256(text.encode()).hexdigest())

    def _write(tmp: str) -> None:
        with open(tmp, "wb") as fh:
            np.savez(fh, **payload)  # type: ignore[arg-type]

    return atomic_write(path, _write, suffix=".npz")


def _unreadable(field: str, path: Path, why: str) -> InputError:
    return InputError(
        field,
        str(path),
        "a readable terradyn checkpoint (.npz)",
        f"the file is not a readable terradyn checkpoint: {why}; remove it or give another path",
    )


def _read_error(exc: BaseException) -> str:
    if isinstance(exc, zipfile.BadZipFile | EOFError):
        return "truncated or not an .npz archive"
    if isinstance(exc, KeyError):
        return f"it lacks the entry {exc.args[0] if exc.args else '?'}"
    if isinstance(exc, OSError):
        return f"it cannot be read ({exc.strerror or type(exc).__name__})"
    return "damaged or not an .npz archive"


def load_checkpoint(
    path: str | Path,
    inputs: Mapping[str, Any] | str,
    *,
    required: Iterable[str] = (),
    field: str = "checkpoint_path",
) -> dict[str, np.ndarray]:
    """Arrays of a checkpoint written by :func:`save_checkpoint` for the same ``inputs``.

    Raises :class:`~terradyn.errors.InputError` (on ``field``) if there is no file at ``path``, if it
    is not a readable terradyn checkpoint holding every ``required`` array, or if it was written for
    other inputs (the message names them: ``cell_size: checkpoint 0.005, this run 0.004``).
    """
    p = Path(path)
    if not p.is_file():
        raise InputError(
            field,
            str(p),
            "an existing checkpoint file",
            f"no checkpoint at {p}"
            + ("; run without resume to start afresh" if field == "checkpoint_path" else ""),
        )
    try:
        with open(p, "rb") as fh:  # our handle: np.load leaks its own when the zip is damaged
            loaded = np.load(fh, allow_pickle=False)
            if not isinstance(loaded, np.lib.npyio.NpzFile):
                raise _unreadable(field, p, "a single .npy array, not an .npz archive")
            with loaded as data:
                arrays = {k: data[k] for k in data.files}
        for k, v in arrays.items():
            if not isinstance(v, np.ndarray):  # a member that is not an .npy array comes as bytes
                raise _unreadable(field, p, f"its entry {k} is not an array")
        fmt = str(arrays.pop("__format__", ""))
        text = str(arrays.pop("__inputs__", ""))
        arrays.pop("__fingerprint__", None)
        if fmt != CHECKPOINT_FORMAT or not text:
            raise _unreadable(field, p, "written by another program or an older terradyn")
        saved = json.loads(text)
        missing = [k for k in required if k not in arrays]
        if missing:
            raise _unreadable(field, p, f"it lacks the entries {', '.join(missing)}")
    except InputError:
        raise
    except _READ_ERRORS as exc:
        raise _unreadable(field, p, _read_error(exc)) from None
    current, _ = _canonical(inputs)
    diffs = input_differences(saved, current)
    if diffs:
        listed = "; ".join(diffs[:_MAX_LISTED])
        more = f" and {len(diffs) - _MAX_LISTED} more" if len(diffs) > _MAX_LISTED else ""
        raise InputError(
            field,
            str(p),
            "a checkpoint of a run with the same inputs",
            f"it differs in {listed}{more}; rerun with the checkpoint's inputs or remove the file",
        )
    return arrays
