"""Plane bodies and their discretisation into :class:`SurfaceElements`.

Every body is an immutable description in its own frame (origin = reference point; wheels: the axle)
with an out-of-plane ``width`` [m]; :meth:`Body.discretize` returns the elements a force law sums over.
Shapes: :class:`Plate`, :class:`WheelCircular`, :class:`WheelGrousered`, :class:`WheelFlapped`,
:class:`CLeg`, :class:`Wedge`, :class:`Square`, :class:`Cylinder`, :class:`HalfCylinder`,
:class:`Polygon`; :meth:`Body.placed` and :class:`Composite` move and combine them.
"""

from ._basic import Plate, WheelCircular
from ._body import Body
from ._composite import Composite, Placed
from ._elements import SurfaceElements
from ._path import Arc, Line
from ._solids import Cylinder, FlatSide, HalfCylinder, Polygon, Square, Wedge
from ._wheels import CLeg, WheelFlapped, WheelGrousered

__all__ = [
    "Arc",
    "Body",
    "CLeg",
    "Composite",
    "Cylinder",
    "FlatSide",
    "HalfCylinder",
    "Line",
    "Placed",
    "Plate",
    "Polygon",
    "Square",
    "SurfaceElements",
    "Wedge",
    "WheelCircular",
    "WheelFlapped",
    "WheelGrousered",
]
