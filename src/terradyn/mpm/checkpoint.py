"""Checkpoints (resume a killed run) and particle snapshots (NetCDF via xarray), written atomically.

A checkpoint is one ``.npz`` file holding the particle and body arrays, the step counter and the rows
recorded so far, plus a fingerprint of the run's inputs: resuming with different inputs is refused.
Every file is written to a temporary name in the same directory and moved into place with
:func:`os.replace`, so a kill never leaves a half-written file behind.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError

__all__ = ["atomic_write", "load_checkpoint", "read_snapshot", "save_checkpoint", "write_snapshot"]


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


def save_checkpoint(path: str | Path, arrays: dict[str, np.ndarray], fingerprint: str) -> Path:
    """Write ``arrays`` and the run ``fingerprint`` to ``path`` (.npz) atomically."""
    payload = {k: np.asarray(v) for k, v in arrays.items()}
    payload["__fingerprint__"] = np.array(fingerprint)

    def _write(tmp: str) -> None:
        with open(tmp, "wb") as fh:
            np.savez(fh, **payload)  # type: ignore[arg-type]

    return atomic_write(path, _write, suffix=".npz")


def load_checkpoint(path: str | Path, fingerprint: str) -> dict[str, np.ndarray]:
    """Arrays of a checkpoint written by :func:`save_checkpoint` for the same inputs."""
    p = Path(path)
    with np.load(p, allow_pickle=False) as data:
        saved = str(data["__fingerprint__"])
        if saved != fingerprint:
            raise InputError(
                "checkpoint_path",
                str(p),
                "a checkpoint written by a run with the same inputs",
                "delete it or pass resume=False to start afresh",
            )
        return {k: data[k].copy() for k in data.files if k != "__fingerprint__"}


def write_snapshot(path: str | Path, fields: dict[str, np.ndarray], attrs: dict[str, Any]) -> Path:
    """Write particle ``fields`` (each (N,)) as NetCDF with xarray (lazy import): HDF5-based NetCDF4 via
    h5netcdf when h5py is available, else NetCDF3 via scipy."""
    try:
        import xarray as xr
    except ImportError:  # pragma: no cover - optional extra
        raise InputError(
            "snapshot_path", str(path), "xarray and h5netcdf installed", "pip install terradyn[fields]"
        ) from None
    units = {
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
    }
    ds = xr.Dataset(
        {k: ("particle", np.asarray(v), {"units": units.get(k, "")}) for k, v in fields.items()},
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
