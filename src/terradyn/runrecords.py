"""Run records shared by the engines (the MPM and the DEM): the inputs that identify a run as JSON-able
data and what differs between two runs' inputs (checkpoints refuse a resume with other inputs), and
particle snapshots as NetCDF (through xarray, the ``fields`` extra), written atomically.
"""

from __future__ import annotations

import dataclasses
import enum
import json
import math
import os
import tempfile
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from .errors import InputError

__all__ = ["atomic_write", "input_differences", "plain", "read_snapshot", "write_snapshot"]


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
