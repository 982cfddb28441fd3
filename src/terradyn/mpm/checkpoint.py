"""Checkpoints (resume a killed run) and particle snapshots (NetCDF via xarray), written atomically.

A checkpoint is one ``.npz`` file holding the particle and body arrays, the step counter, the rows
and animation frames recorded so far, and the inputs that identify the run as JSON (``__inputs__``,
with its SHA-256 in ``__fingerprint__``): resuming with different inputs is refused with a message
naming the inputs that differ. Every file is written to a temporary name in the same directory and
moved into place with :func:`os.replace`, so a kill never leaves a half-written file behind.
"""

from __future__ import annotations

import dataclasses
import enum
import hashlib
import json
import math
import os
import tempfile
import zipfile
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError

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


def atomic_write(path: str | Path, write: Any, *, suffix: str = ".tmp") -> Path:
    """Call ``write(tmp_path)`` then move the file to ``path`` atomically; returns ``path``."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=suffix, dir=p.parent)
    os.close(fd)
    try:
        write(tmp)
        os.replace(tmp, p)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return p


def plain(value: Any) -> Any:
    """``value`` as JSON-able data: dataclasses become dicts (with their ``type``), enums their value,
    NumPy scalars and arrays Python numbers and lists, paths strings, tuples lists. A dataclass field
    with ``metadata={"omit_default": True}`` is left out while it holds its default (an option added
    later then leaves the fingerprints of earlier runs unchanged)."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        out: dict[str, Any] = {"type": type(value).__name__}
        for f in dataclasses.fields(value):
            item = getattr(value, f.name)
            if f.metadata.get("omit_default") and item == f.default:
                continue
            out[f.name] = plain(item)
        return out
    if isinstance(value, enum.Enum):
        return plain(value.value)
    if isinstance(value, bool | np.bool_):
        return bool(value)
    if isinstance(value, int | np.integer):
        return int(value)
    if isinstance(value, float | np.floating):
        return float(value)
    if isinstance(value, str | Path):
        return str(value)
    if value is None:
        return None
    if isinstance(value, np.ndarray):
        return plain(value.tolist())
    if isinstance(value, Mapping):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, Iterable):
        return [plain(v) for v in value]
    return repr(value)


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


def _flat(data: Any, prefix: str, out: dict[str, Any]) -> None:
    if isinstance(data, dict):
        for k, v in data.items():
            _flat(v, f"{prefix}.{k}" if prefix else str(k), out)
    else:
        out[prefix] = data


def _show(value: Any, digits: int = 12) -> str:
    if isinstance(value, float):
        return f"{value:.{digits}g}" if math.isfinite(value) else str(value)
    text = "none" if value is None else str(value) if isinstance(value, str) else json.dumps(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _same(x: Any, y: Any) -> bool:
    """Equal inputs; 1 and 1.0 are the same number, True and 1 are not."""
    if isinstance(x, bool) or isinstance(y, bool):
        return type(x) is type(y) and x == y
    if isinstance(x, int | float) and isinstance(y, int | float):
        return bool(x == y)
    return type(x) is type(y) and bool(x == y)


def input_differences(saved: Mapping[str, Any], current: Mapping[str, Any]) -> list[str]:
    """``"name: checkpoint A, this run B"`` for every input that differs (nested names joined by
    dots). Inputs under ``derived`` (quantities computed from the others) are listed only when no
    named input differs; a different ``run`` (another kind of run) is the only difference listed."""
    a: dict[str, Any] = {}
    b: dict[str, Any] = {}
    _flat(dict(saved), "", a)
    _flat(dict(current), "", b)
    out = []
    for key in [*a, *(k for k in b if k not in a)]:
        if key in a and key in b and _same(a[key], b[key]):
            continue
        left = _show(a[key]) if key in a else "absent"
        right = _show(b[key]) if key in b else "absent"
        if left == right:  # differ past 12 digits
            left, right = _show(a[key], 17), _show(b[key], 17)
        out.append(f"{key}: checkpoint {left}, this run {right}")
    kind = [d for d in out if d.startswith("run:")]  # another kind of run: nothing else matters
    named = [d for d in out if not d.startswith("derived.")]
    return kind or named or out


def write_snapshot(
    path: str | Path,
    fields: dict[str, np.ndarray],
    attrs: dict[str, Any],
    *,
    units: Mapping[str, str] | None = None,
) -> Path:
    """Write particle ``fields`` (each (N,)) as NetCDF with xarray (lazy import): HDF5-based NetCDF4 via
    h5netcdf when h5py is available, else NetCDF3 via scipy. ``units`` names the units of fields
    beyond the MPM ones (or overrides them); every variable carries its ``units`` attribute."""
    try:
        import xarray as xr
    except ImportError:  # pragma: no cover - optional extra
        raise InputError(
            "snapshot_path", str(path), "xarray and h5netcdf installed", "pip install terradyn[fields]"
        ) from None
    unit_of = {
        "x": "m",
        "z": "m",
        "vx": "m/s",
        "vz": "m/s",
        "stress_xx": "Pa",
        "stress_zz": "Pa",
        "stress_xz": "Pa",
        "stress_yy": "Pa",
        "pressure": "Pa",
        "density": "kg/m^3",
        "plastic_shear_rate": "1/s",
        **(units or {}),
    }
    ds = xr.Dataset(
        {k: ("particle", np.asarray(v), {"units": unit_of.get(k, "")}) for k, v in fields.items()},
        attrs={
            k: (float(v) if isinstance(v, int | float | np.floating) else str(v)) for k, v in attrs.items()
        },
    )

    engine = _engine()

    def _write(tmp: str) -> None:
        ds.to_netcdf(tmp, engine=engine)  # type: ignore[call-overload]

    return atomic_write(path, _write, suffix=".nc")


def _engine() -> str:
    """NetCDF4/HDF5 through h5netcdf when h5py is installed, else NetCDF3 through scipy."""
    import importlib.util

    return "h5netcdf" if importlib.util.find_spec("h5py") is not None else "scipy"


def read_snapshot(path: str | Path) -> Any:
    """Open a snapshot written by :func:`write_snapshot` as an ``xarray.Dataset`` (loaded in memory)."""
    import xarray as xr

    with xr.open_dataset(path) as ds:
        return ds.load()
