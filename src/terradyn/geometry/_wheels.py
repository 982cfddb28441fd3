"""Rotating locomotors: grousered wheel, flapped wheel and C-shaped leg (origin at the axle/hip)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from numbers import Integral

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError, check_finite, check_length
from ._body import Body
from ._elements import SurfaceElements
from ._path import Arc, Line, Segment
from ._solids import _xy

__all__ = ["CLeg", "WheelFlapped", "WheelGrousered"]

_BOTTOM = -0.5 * math.pi  # angle (from +x towards +z) of the first lug/flap at theta = 0


def _check_count(field: str, value: object, minimum: int = 1) -> int:
    """``value`` as an int >= ``minimum`` (integral floats such as 15.0 are accepted)."""
    integral = isinstance(value, Integral) and not isinstance(value, bool)
    if not (integral or (isinstance(value, float) and value.is_integer())):
        raise InputError(field, value, f"an integer >= {minimum}")
    count = int(value)  # type: ignore[call-overload]
    if count < minimum:
        raise InputError(field, value, f"an integer >= {minimum}")
    return count


def _point(radius: float, angle: float) -> tuple[float, float]:
    return (radius * math.cos(angle), radius * math.sin(angle))


@dataclass(frozen=True)
class WheelGrousered(Body):
    """Rigid wheel with rectangular lugs (grousers); origin at the axle.

    The rim (hub) has ``radius`` [m]. ``grouser_count`` equally spaced lugs stand radially on it, each
    ``grouser_height`` [m] tall (rim to the flat outer face, measured on the lug centreline) and
    ``grouser_thickness`` [m] thick tangentially. At theta = 0 the first lug is centred at the bottom
    (pointing along -z); the others follow counter-clockwise in view every 2 pi / ``grouser_count``.
    The boundary is one counter-clockwise loop: for each lug a side face, the flat outer face and the
    other side face, then the rim arc to the next lug.
    """

    radius: float
    width: float
    grouser_count: int
    grouser_height: float
    grouser_thickness: float

    def __post_init__(self) -> None:
        check_length("radius", self.radius)
        self._check_width()
        object.__setattr__(self, "grouser_count", _check_count("grouser_count", self.grouser_count))
        check_length("grouser_height", self.grouser_height)
        check_length("grouser_thickness", self.grouser_thickness)
        limit = 2.0 * self.radius * math.sin(min(math.pi / self.grouser_count, 0.5 * math.pi))
        if not self.grouser_thickness < limit:
            raise InputError(
                "grouser_thickness",
                self.grouser_thickness,
                f"a thickness below {limit:.6g} m",
                f"{self.grouser_count} lugs this thick would overlap on a rim of radius "
                f"{self.radius:g} m; use fewer or thinner lugs",
            )

    @property
    def outer_radius(self) -> float:
        """Nominal radius [m] used for slip: ``radius + grouser_height``."""
        return self.radius + self.grouser_height

    @property
    def size(self) -> float:
        return self.outer_radius

    @property
    def default_element_size(self) -> float:
        # 360 elements around the outer circle, at least 4 along each lug side.
        return min(2.0 * math.pi * self.outer_radius / 360.0, self.grouser_height / 4.0)

    def _lug_angles(self) -> NDArray[np.float64]:
        return _BOTTOM + 2.0 * math.pi * np.arange(self.grouser_count) / self.grouser_count

    def _pieces(self) -> list[tuple[list[Line], Arc]]:
        """For each lug: its three faces (side, outer, side) and the rim arc that follows it."""
        r, h, n = self.radius, self.grouser_height, self.grouser_count
        half = 0.5 * self.grouser_thickness
        delta = math.asin(half / r)  # angular half-width of a lug at the rim
        foot = r * math.cos(delta)  # radial coordinate where a lug side meets the rim
        pieces = []
        for a in self._lug_angles():
            er, et = np.array([math.cos(a), math.sin(a)]), np.array([-math.sin(a), math.cos(a)])
            p0, p1 = foot * er - half * et, (r + h) * er - half * et
            p2, p3 = (r + h) * er + half * et, foot * er + half * et
            faces = [Line(_xy(p0), _xy(p1)), Line(_xy(p1), _xy(p2)), Line(_xy(p2), _xy(p3))]
            rim = Arc((0.0, 0.0), r, float(a) + delta, float(a) + 2.0 * math.pi / n - delta)
            pieces.append((faces, rim))
        return pieces

    def loops(self) -> list[list[Segment]]:
        loop: list[Segment] = []
        for faces, rim in self._pieces():
            loop.extend(faces)
            loop.append(rim)
        return [loop]

    def discretize_counts(self, rim_elements: int, face_elements: int) -> SurfaceElements:
        """Elements with exactly ``rim_elements`` on each rim arc and ``face_elements`` on each lug face.

        The element count is ``grouser_count * (rim_elements + 3 * face_elements)``; 15 lugs with 14
        and 8 give the published 570-element wheel.
        """
        rim_n = _check_count("rim_elements", rim_elements)
        face_n = _check_count("face_elements", face_elements)
        parts: list[tuple[NDArray[np.float64], ...]] = []
        for faces, rim in self._pieces():
            parts.extend(face.elements(face.length / face_n) for face in faces)
            parts.append(rim.elements(rim.length / rim_n))
        mid, nrm, lng = (np.concatenate([p[k] for p in parts]) for k in range(3))
        return SurfaceElements(mid, nrm, lng, self.width)


@dataclass(frozen=True)
class WheelFlapped(Body):
    """Circular hub with straight flaps; origin at the axle.

    The hub has ``hub_radius`` [m]; ``flap_count`` flaps of ``flap_length`` [m] (from the hub surface
    along the flap centreline) are rooted on it, equally spaced, the first at the bottom at theta = 0.
    ``flap_angle`` [rad] in (-pi/2, pi/2) is the angle between a flap and the radial direction at its
    root: 0 (default) is radial, a positive angle turns the flap counter-clockwise in view, against
    the clockwise spin of forward rolling, so the tip trails the root (at the bottom flap, a positive
    angle puts the tip ahead, +x, of the root). With ``flap_thickness`` = 0 (default) a flap is a
    zero-thickness out-and-back spike of the single loop around the hub (both faces); with a thickness
    [m] it is a rectangle about the centreline whose sides end on the hub and whose tip face is flat.
    ``outer_radius`` is the largest distance of a tip (corner) from the axle.
    """

    hub_radius: float
    width: float
    flap_count: int
    flap_length: float
    flap_angle: float = 0.0
    flap_thickness: float = 0.0

    def __post_init__(self) -> None:
        check_length("hub_radius", self.hub_radius)
        self._check_width()
        object.__setattr__(self, "flap_count", _check_count("flap_count", self.flap_count))
        check_length("flap_length", self.flap_length)
        angle = check_finite("flap_angle", self.flap_angle)
        if not abs(angle) < 0.5 * math.pi:
            raise InputError("flap_angle", self.flap_angle, "an angle in (-pi/2, pi/2) rad from radial")
        check_length("flap_thickness", self.flap_thickness, allow_zero=True)
        # Identical straight flaps at one angle never cross away from the hub (their centrelines are
        # all tangent to the circle of radius hub_radius * |sin(flap_angle)|, each turned from the
        # previous by the spacing); so flaps intersect only where their roots overlap on the hub.
        flaps = self._flaps()  # raises if a thick flap does not sit on the hub
        spread = flaps[0][1] - flaps[0][0]  # hub angle covered by a flap root
        if not 0.0 <= spread < 2.0 * math.pi / self.flap_count:
            raise InputError(
                "flap_thickness",
                self.flap_thickness,
                "a thickness at which neighbouring flaps do not touch on the hub",
                "use thinner or fewer flaps",
            )

    def _flaps(self) -> list[tuple[float, float, NDArray[np.float64]]]:
        """Per flap, in loop order: the hub angles [rad] where its first and second side meet the hub,
        and its points (4, 2): hub foot, tip corner, tip corner, hub foot (thin: root, tip, tip, root).
        """
        r, length, psi = self.hub_radius, self.flap_length, float(self.flap_angle)
        half = 0.5 * self.flap_thickness
        flaps = []
        for k in range(self.flap_count):
            a = _BOTTOM + 2.0 * math.pi * k / self.flap_count
            d = np.array([math.cos(a + psi), math.sin(a + psi)])  # flap direction
            nd = np.array([-d[1], d[0]])  # d turned counter-clockwise
            root = r * np.array([math.cos(a), math.sin(a)])
            pts, rel = [], []
            for sign in (-1.0, 1.0):
                c = root + sign * half * nd
                cd = float(c @ d)
                disc = cd * cd - (float(c @ c) - r * r)
                if half == 0:
                    s = 0.0  # the root itself
                elif disc > 0:
                    s = -cd + math.sqrt(disc)  # where the side line leaves the hub circle
                else:
                    s = math.nan
                if not s < length:  # NaN too: the side misses the hub or is not outside it
                    raise InputError(
                        "flap_thickness",
                        self.flap_thickness,
                        "a thickness at which both flap sides start on the hub and end past it",
                        "use thinner or longer flaps",
                    )
                foot = c + s * d
                pts.append((foot, c + length * d))
                rel.append(math.remainder(math.atan2(foot[1], foot[0]) - a, 2.0 * math.pi))
            points = np.array([pts[0][0], pts[0][1], pts[1][1], pts[1][0]])
            flaps.append((a + rel[0], a + rel[1], points))
        return flaps

    @property
    def outer_radius(self) -> float:
        """Largest distance [m] of a flap tip (tip corner, if thick) from the axle."""
        return float(max(np.max(np.hypot(*f[2][1:3].T)) for f in self._flaps()))

    @property
    def size(self) -> float:
        return self.outer_radius

    @property
    def default_element_size(self) -> float:
        # 360 elements around the outer circle, at least 20 along a flap.
        return min(2.0 * math.pi * self.outer_radius / 360.0, self.flap_length / 20.0)

    def loops(self) -> list[list[Segment]]:
        flaps = self._flaps()
        loop: list[Segment] = []
        for k, (_, leave, pts) in enumerate(flaps):
            p = [_xy(q) for q in pts]
            if self.flap_thickness == 0:
                loop += [Line(p[0], p[1]), Line(p[1], p[0])]
            else:
                loop += [Line(p[0], p[1]), Line(p[1], p[2]), Line(p[2], p[3])]
            arrive = flaps[k + 1][0] if k + 1 < len(flaps) else flaps[0][0] + 2.0 * math.pi
            loop.append(Arc((0.0, 0.0), self.hub_radius, leave, arrive))
        return [loop]


@dataclass(frozen=True)
class CLeg(Body):
    """C-shaped leg (Li et al. 2013): a circular arc of centreline ``radius`` [m]; origin at the hip.

    The hip (rotation axis) is one end of the centreline. At theta = 0 the arc hangs below the hip and
    bulges forward: its centre is at (0, -radius), the centreline runs clockwise in view from the hip
    through (radius, -radius) over an angle ``sweep`` [rad] in (0, 2 pi) (pi: the far end is at
    (0, -2 radius)). ``thickness`` [m] is radial, centred on the centreline; the loop is outer arc, end
    cap, inner arc, end cap. With ``thickness`` = 0 (default) the leg is a zero-thickness arc with both
    faces.
    """

    radius: float
    width: float
    thickness: float = 0.0
    sweep: float = math.pi

    def __post_init__(self) -> None:
        check_length("radius", self.radius)
        self._check_width()
        check_length("thickness", self.thickness, allow_zero=True)
        if not self.thickness < 2.0 * self.radius:
            raise InputError(
                "thickness", self.thickness, f"a thickness below 2 * radius = {2 * self.radius:g} m"
            )
        sweep = check_finite("sweep", self.sweep)
        if not 0.0 < sweep < 2.0 * math.pi:
            raise InputError("sweep", self.sweep, "an angle in (0, 2 pi) rad")

    @property
    def size(self) -> float:
        return 2.0 * self.radius

    def loops(self) -> list[list[Segment]]:
        c = (0.0, -self.radius)
        top, end = 0.5 * math.pi, 0.5 * math.pi - float(self.sweep)  # hip end and far end
        if self.thickness == 0:
            return [[Arc(c, self.radius, end, top), Arc(c, self.radius, top, end)]]
        ro, ri = self.radius + 0.5 * self.thickness, self.radius - 0.5 * self.thickness

        def at(radius: float, angle: float) -> tuple[float, float]:
            x, z = _point(radius, angle)
            return (c[0] + x, c[1] + z)

        return [
            [
                Arc(c, ro, end, top),
                Line(at(ro, top), at(ri, top)),
                Arc(c, ri, top, end),
                Line(at(ri, end), at(ro, end)),
            ]
        ]
