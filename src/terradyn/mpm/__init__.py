"""Plane-strain MPM continuum solver for dry granular media, coupled to rigid intruders and wheels.

The Dunatunga-Kamrin (2015) granular model (hypoelastic Jaumann trial stress, Drucker-Prager cone with
optional mu(I) rate dependence, stress-free below the critical density) on an explicit MPM grid
(APIC transfer, quadratic B-splines) with rigid bodies in frictional contact. Entry points:
:func:`run_intrusion`, :func:`run_wheel` and :func:`run_drag` (a buried body dragged
horizontally), :func:`run_node_footing` (a strip footing whose base is a grid condition, the
continuum without the contact), and :class:`MPMTerrain`, the stateful terrain model
(``init``/``step``) for driving a body from your own code; :class:`GranularModel` maps a material
(mu = sin(phi)). Their settings come as frozen specs shared by every case (:mod:`terradyn.mpm.specs`):
:class:`Bed`, :class:`Resolution`, :class:`Outputs`, and the run length, :class:`Stroke` (intrusions)
or :class:`Drive` (wheels).

Modelling choices to know when using it:

* Forces are quasi-static only if the speed is small: inertia ``rho v^2`` and the elastic radiation
  stress ``rho c v`` (c: P-wave speed of the softened bed) must be small against ``rho g D``.
* Bodies couple through two-field grid contact (:class:`terradyn.mpm.bodies.ContactScheme`): a
  zero-thickness plate is resolved as it is, composite and placed bodies as bare ones; a body whose
  parts span less than one cell is refused. ``contact="cover"`` selects the earlier scheme (plates
  thickened to three cells) for comparison.
* Free-slip walls that cut the failure mechanism raise intrusion forces; the default bed keeps 1.25
  times the Prandtl mechanism's extent beside and below the body (``runs.mechanism_clearance``).
* Runs below :data:`terradyn.mpm.solver.PARALLEL_MIN_PARTICLES` particles use one thread.

Submodules are imported lazily so that ``import terradyn.mpm`` does not load numba.
"""

from __future__ import annotations

from importlib import import_module
from typing import Any

__all__ = [
    "Bed",
    "BedGrid",
    "BedPacking",
    "DragResult",
    "Drive",
    "FootingBase",
    "FootingPush",
    "GranularModel",
    "IntrusionResult",
    "MPMInstabilityError",
    "MPMTerrain",
    "NodeFootingCase",
    "NodeFootingRun",
    "Outputs",
    "Resolution",
    "Stroke",
    "Wall",
    "WallKind",
    "Walls",
    "WheelResult",
    "bed_stability_ratio",
    "friction_coefficient_from_angle",
    "read_snapshot",
    "run_drag",
    "run_intrusion",
    "run_node_footing",
    "run_wheel",
]

_WHERE = {
    "BedGrid": "solver",
    "MPMInstabilityError": "solver",
    "BedPacking": "model",
    "GranularModel": "model",
    "Wall": "model",
    "WallKind": "model",
    "Walls": "model",
    "bed_stability_ratio": "model",
    "friction_coefficient_from_angle": "model",
    "MPMTerrain": "terrain",
    "Bed": "specs",
    "Drive": "specs",
    "Outputs": "specs",
    "Resolution": "specs",
    "Stroke": "specs",
    "IntrusionResult": "runs",
    "WheelResult": "wheel_runs",
    "run_intrusion": "runs",
    "run_wheel": "wheel_runs",
    "DragResult": "drag",
    "run_drag": "drag",
    "read_snapshot": "checkpoint",
    "FootingBase": "footing",
    "FootingPush": "footing",
    "NodeFootingCase": "footing",
    "NodeFootingRun": "footing",
    "run_node_footing": "footing",
}


def __getattr__(name: str) -> Any:
    if name in _WHERE:
        value = getattr(import_module(f".{_WHERE[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(__all__)
