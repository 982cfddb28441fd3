"""Basic bodies: flat plate and circular wheel."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import InputError, check_length
from ._body import Body
from ._path import Arc, Line, Segment

__all__ = ["Plate", "WheelCircular"]


@dataclass(frozen=True)
class Plate(Body):
    """Flat plate of ``length`` [m] along body x, ``width`` [m] out of plane, origin at its centre.

    With ``thickness`` = 0 (default) the plate is two coincident faces (normals +z and -z); with a
    thickness it is a rectangle ``length`` x ``thickness``.
    """

    length: float
    width: float
    thickness: float = 0.0

    def __post_init__(self) -> None:
        check_length("length", self.length)
        self._check_width()
        check_length("thickness", self.thickness, allow_zero=True)
        if self.thickness >= self.length:
            raise InputError("thickness", self.thickness, f"a value below the length {self.length:g} m")

    @property
    def size(self) -> float:
        return self.length

    def loops(self) -> list[list[Segment]]:
        a, t = 0.5 * self.length, 0.5 * self.thickness
        if t == 0:
            return [[Line((-a, 0.0), (a, 0.0)), Line((a, 0.0), (-a, 0.0))]]
        return [
            [
                Line((-a, -t), (a, -t)),
                Line((a, -t), (a, t)),
                Line((a, t), (-a, t)),
                Line((-a, t), (-a, -t)),
            ]
        ]


@dataclass(frozen=True)
class WheelCircular(Body):
    """Rigid circular wheel (or cylinder) of ``radius`` [m] and ``width`` [m]; origin at the axle."""

    radius: float
    width: float

    def __post_init__(self) -> None:
        check_length("radius", self.radius)
        self._check_width()

    @property
    def size(self) -> float:
        return self.radius

    @property
    def outer_radius(self) -> float:
        return self.radius

    @property
    def default_element_size(self) -> float:
        # 360 elements around the rim.
        return 2.0 * math.pi * self.radius / 360.0

    def loops(self) -> list[list[Segment]]:
        return [[Arc((0.0, 0.0), self.radius, -math.pi / 2, 1.5 * math.pi)]]
