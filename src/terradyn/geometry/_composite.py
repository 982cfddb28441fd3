"""Bodies moved by a rigid transform, and bodies made of several parts."""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

from ..errors import InputError, check_finite
from ._body import Body, _discretize_cached
from ._elements import SurfaceElements
from ._path import Arc, Line, Segment

__all__ = ["Composite", "Placed"]


@dataclass(frozen=True)
class Placed(Body):
    """``body`` rotated by ``theta`` [rad] about +y (clockwise in view), then moved by (x, z) [m].

    A body point p maps to R p + (x, z) with R = [[cos, sin], [-sin, cos]]; the origin of a Placed body
    is the origin of the frame it is placed in (for a part of a :class:`Composite`, the composite's).
    Its width is the width of ``body``.
    """

    body: Body
    x: float = 0.0
    z: float = 0.0
    theta: float = 0.0

    def __post_init__(self) -> None:
        if not isinstance(self.body, Body):
            raise InputError("body", type(self.body).__name__, "a terradyn Body")
        for name in ("x", "z", "theta"):
            object.__setattr__(self, name, check_finite(name, getattr(self, name)))

    @property
    def width(self) -> float:  # type: ignore[override]
        return self.body.width

    @property
    def size(self) -> float:
        return self.body.size

    @property
    def default_element_size(self) -> float:
        return self.body.default_element_size

    def placed(self, x: float = 0.0, z: float = 0.0, theta: float = 0.0) -> Placed:
        """This placement followed by another one: still a single :class:`Placed` of the same body."""
        c, s = math.cos(theta), math.sin(theta)
        return Placed(
            self.body, c * self.x + s * self.z + x, -s * self.x + c * self.z + z, self.theta + theta
        )

    def loops(self) -> list[list[Segment]]:
        return [[self._move(seg) for seg in loop] for loop in self.body.loops()]

    def _elements(self, size: float) -> SurfaceElements:
        # The body's own elements (its own rule and part numbers), moved.
        return _discretize_cached(self.body, size).rotated(self.theta).shifted(self.x, self.z)

    def _point(self, p: tuple[float, float]) -> tuple[float, float]:
        c, s = math.cos(self.theta), math.sin(self.theta)
        return (c * p[0] + s * p[1] + self.x, -s * p[0] + c * p[1] + self.z)

    def _move(self, seg: Segment) -> Segment:
        if isinstance(seg, Line):
            return Line(self._point(seg.start), self._point(seg.end))
        # A clockwise rotation by theta lowers every polar angle (from +x towards +z) by theta.
        return Arc(self._point(seg.center), seg.radius, seg.start - self.theta, seg.end - self.theta)


@dataclass(frozen=True)
class Composite(Body):
    """A body made of several ``parts`` sharing one frame (origin = the composite's reference point).

    Each part is a :class:`Body`, usually a :class:`Placed` one (``body.placed(x, z, theta)``); all parts
    have the same width. Discretisation concatenates the parts' elements, each part keeping distinct
    ``part`` numbers. The parts may overlap: every part keeps its whole surface.
    """

    parts: tuple[Body, ...]

    def __init__(self, parts: Iterable[Body]) -> None:
        try:
            items = tuple(parts)
        except TypeError:
            raise InputError("parts", type(parts).__name__, "a sequence of terradyn bodies") from None
        object.__setattr__(self, "parts", items)
        self.__post_init__()

    def __post_init__(self) -> None:
        if not self.parts:
            raise InputError("parts", "()", "at least one body")
        for k, part in enumerate(self.parts):
            if not isinstance(part, Body):
                raise InputError(f"parts[{k}]", type(part).__name__, "a terradyn Body")
        first = self.parts[0].width
        for k, part in enumerate(self.parts[1:], start=1):
            if not math.isclose(part.width, first, rel_tol=1e-12):
                raise InputError(
                    f"parts[{k}].width",
                    part.width,
                    f"the width of parts[0], {first:g} m",
                    "every part of a composite has the same width",
                )

    @property
    def width(self) -> float:  # type: ignore[override]
        return self.parts[0].width

    @property
    def size(self) -> float:
        """Largest part size [m]."""
        return max(p.size for p in self.parts)

    @property
    def default_element_size(self) -> float:
        """Smallest default element size of the parts [m]."""
        return min(p.default_element_size for p in self.parts)

    def loops(self) -> list[list[Segment]]:
        return [loop for part in self.parts for loop in part.loops()]

    def _elements(self, size: float) -> SurfaceElements:
        return SurfaceElements.concatenate([_discretize_cached(p, size) for p in self.parts])
