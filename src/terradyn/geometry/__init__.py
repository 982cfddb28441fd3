"""Plane bodies and their discretisation into :class:`SurfaceElements`.

Every body is an immutable description in its own frame (origin = reference point; wheels: the axle)
with an out-of-plane ``width`` [m]; :meth:`Body.discretize` returns the elements a force law sums over.
"""

from ._basic import Plate, WheelCircular
from ._body import Body
from ._elements import SurfaceElements
from ._path import Arc, Line

__all__ = [
    "Arc",
    "Body",
    "Line",
    "Plate",
    "SurfaceElements",
    "WheelCircular",
]
