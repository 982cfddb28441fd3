"""The :class:`Body` base: an immutable plane shape with an out-of-plane width."""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from functools import lru_cache
from numbers import Real
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError, check_length
from ._elements import SurfaceElements
from ._path import Segment, discretize_loops, loop_polygon

if TYPE_CHECKING:
    from ._composite import Placed

__all__ = ["Body"]


class Body(ABC):
    """A rigid plane body in its own frame (origin = its reference point), with a width [m].

    Subclasses are frozen dataclasses. They describe their boundary as closed counter-clockwise loops of
    lines and arcs (:meth:`loops`); discretisation, outlines and extents follow from that.
    """

    width: float

    @abstractmethod
    def loops(self) -> list[list[Segment]]:
        """Closed boundary loops, counter-clockwise in the x-z view, in the body frame [m]."""

    @property
    @abstractmethod
    def size(self) -> float:
        """A characteristic length [m] (wheel: outer radius; plate: length)."""

    @property
    def default_element_size(self) -> float:
        """Element size [m] used when none is given: ``size / 100``."""
        return self.size / 100.0

    def discretize(self, element_size: float | None = None) -> SurfaceElements:
        """Surface elements no longer than ``element_size`` [m] (default :attr:`default_element_size`)."""
        size = self.default_element_size if element_size is None else element_size
        if not (isinstance(size, Real) and not isinstance(size, bool) and math.isfinite(size) and size > 0):
            raise InputError("element_size", element_size, "a length > 0 [m]")
        if size > self.size:
            raise InputError(
                "element_size", element_size, f"at most the body size {self.size:g} m", "refine it"
            )
        return _discretize_cached(self, float(size))

    def _elements(self, size: float) -> SurfaceElements:
        """Elements at most ``size`` [m] long, uncached (bodies with their own rule override this)."""
        mid, nrm, lng, part = discretize_loops(self.loops(), size)
        return SurfaceElements(mid, nrm, lng, self.width, part)

    def placed(self, x: float = 0.0, z: float = 0.0, theta: float = 0.0) -> Placed:
        """This body rotated by ``theta`` [rad] about +y (clockwise in view), then moved by (x, z) [m].

        The result is a :class:`Placed` body (for example a part of a :class:`Composite`).
        """
        from ._composite import Placed

        return Placed(self, x, z, theta)

    def outline(self, element_size: float | None = None) -> list[NDArray[np.float64]]:
        """Closed polygons (M, 2) [m] of the boundary in the body frame, for plots and inside tests."""
        size = self.default_element_size if element_size is None else element_size
        return [loop_polygon(loop, size) for loop in self.loops()]

    @property
    def bounding_radius(self) -> float:
        """Largest distance [m] of the boundary from the body origin."""
        return float(max(np.max(np.hypot(p[:, 0], p[:, 1])) for p in self.outline()))

    def _check_width(self) -> None:
        check_length("width", self.width)


@lru_cache(maxsize=256)
def _discretize_cached(body: Body, size: float) -> SurfaceElements:
    return body._elements(size)
