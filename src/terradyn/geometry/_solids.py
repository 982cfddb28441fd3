"""Intruder shapes: square, cylinder, half-cylinder, wedge and any simple polygon (also from a file)."""

from __future__ import annotations

import csv
import json
import math
from dataclasses import KW_ONLY, InitVar, dataclass
from enum import Enum
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError, check_finite, check_length
from ._basic import WheelCircular
from ._body import Body
from ._path import Arc, Line, Segment

__all__ = ["Cylinder", "FlatSide", "HalfCylinder", "Polygon", "Square", "Wedge"]


def _xy(p: NDArray[np.float64]) -> tuple[float, float]:
    return (float(p[0]), float(p[1]))


def _polygon_loop(points: NDArray[np.float64]) -> list[Segment]:
    """Closed loop of lines through ``points`` (M, 2) in order."""
    n = len(points)
    return [Line(_xy(points[i]), _xy(points[(i + 1) % n])) for i in range(n)]


def _first_crossing(p: NDArray[np.float64]) -> tuple[int, int] | None:
    """First pair (i, j), i < j, of non-neighbouring edges of the closed polygon ``p`` (N, 2) that
    cross or touch (edge k joins vertices k and k+1), else None.

    Vectorised O(N^2): bounding-box tests on blocks of rows of bounded memory, then exact orientation
    tests on the pairs whose boxes overlap.
    """
    p0, p1 = p, np.roll(p, -1, axis=0)
    n = len(p0)
    lo, hi = np.minimum(p0, p1), np.maximum(p0, p1)
    cols = np.arange(n)[None, :]
    rows_per_block = max(1, 2**18 // n)
    for first in range(0, n, rows_per_block):
        rows = np.arange(first, min(n, first + rows_per_block))
        r = rows[:, None]
        candidate = (
            (cols > r + 1)
            & ~((r == 0) & (cols == n - 1))
            & (lo[rows, None, 0] <= hi[None, :, 0])
            & (lo[None, :, 0] <= hi[rows, None, 0])
            & (lo[rows, None, 1] <= hi[None, :, 1])
            & (lo[None, :, 1] <= hi[rows, None, 1])
        )
        ii, jj = np.nonzero(candidate)
        if ii.size == 0:
            continue
        ii = ii + first
        a, b, c, d = p0[ii], p1[ii], p0[jj], p1[jj]
        side_cd = np.sign(_cross(b - a, c - a)) * np.sign(_cross(b - a, d - a))
        side_ab = np.sign(_cross(d - c, a - c)) * np.sign(_cross(d - c, b - c))
        hit = (side_cd <= 0) & (side_ab <= 0)
        if hit.any():
            k = int(np.argmax(hit))
            return int(ii[k]), int(jj[k])
    return None


def _cross(u: NDArray[np.float64], v: NDArray[np.float64]) -> NDArray[np.float64]:
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def _signed_area(p: NDArray[np.float64]) -> float:
    """Shoelace area [m^2] of the closed polygon ``p`` (M, 2): > 0 when counter-clockwise."""
    q = np.roll(p, -1, axis=0)
    return 0.5 * float(np.sum(p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]))


def _centroid(p: NDArray[np.float64]) -> NDArray[np.float64]:
    """Area centroid (x, z) [m] of the closed polygon ``p`` (M, 2)."""
    q = np.roll(p, -1, axis=0)
    w = p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]
    return np.array([np.sum((p[:, 0] + q[:, 0]) * w), np.sum((p[:, 1] + q[:, 1]) * w)]) / (3.0 * np.sum(w))


@dataclass(frozen=True)
class Square(Body):
    """Square of ``side`` [m] with axis-parallel faces, ``width`` [m]; origin at its centre."""

    side: float
    width: float

    def __post_init__(self) -> None:
        check_length("side", self.side)
        self._check_width()

    @property
    def size(self) -> float:
        return self.side

    def loops(self) -> list[list[Segment]]:
        a = 0.5 * self.side
        return [_polygon_loop(np.array([[-a, -a], [a, -a], [a, a], [-a, a]]))]


@dataclass(frozen=True)
class Cylinder(WheelCircular):
    """Circular cylinder of ``radius`` [m] and ``width`` [m] for intrusion studies; origin at its centre.

    The same shape as :class:`WheelCircular`, named for intrusion rather than rolling.
    """


class FlatSide(str, Enum):
    """Which way the flat face of a :class:`HalfCylinder` looks."""

    UP = "up"
    DOWN = "down"


@dataclass(frozen=True)
class HalfCylinder(Body):
    """Half of a circular cylinder of ``radius`` [m], ``width`` [m]; origin at the centre of the flat face.

    ``flat_side="up"`` (default): flat face on top (normal +z), round side below (body z in [-r, 0]);
    ``"down"``: flat face at the bottom (normal -z), round side above.
    """

    radius: float
    width: float
    flat_side: FlatSide | str = FlatSide.UP

    def __post_init__(self) -> None:
        check_length("radius", self.radius)
        self._check_width()
        try:
            side = FlatSide(self.flat_side)
        except ValueError:
            raise InputError("flat_side", self.flat_side, "'up' or 'down'") from None
        object.__setattr__(self, "flat_side", side)

    @property
    def size(self) -> float:
        return self.radius

    def loops(self) -> list[list[Segment]]:
        r = self.radius
        if self.flat_side is FlatSide.UP:
            return [[Arc((0.0, 0.0), r, math.pi, 2.0 * math.pi), Line((r, 0.0), (-r, 0.0))]]
        return [[Arc((0.0, 0.0), r, 0.0, math.pi), Line((-r, 0.0), (r, 0.0))]]


@dataclass(frozen=True)
class Wedge(Body):
    """Triangle with a horizontal top ``base`` [m], tip ``height`` [m] below it, ``width`` [m].

    Origin at the tip (the lowest point), so the intrusion depth of the origin is the depth of the tip.
    The base runs from x = -base/2 - tip_offset to x = base/2 - tip_offset at z = height: the tip lies
    ``tip_offset`` [m] to the right (+x) of the base centre. Symmetric when ``tip_offset`` = 0; any
    finite offset is allowed (beyond base/2 both faces lean the same way).
    """

    base: float
    height: float
    width: float
    tip_offset: float = 0.0

    def __post_init__(self) -> None:
        check_length("base", self.base)
        check_length("height", self.height)
        self._check_width()
        check_finite("tip_offset", self.tip_offset)

    @classmethod
    def from_angles(
        cls,
        tip_angle: float,
        width: float,
        *,
        height: float | None = None,
        base: float | None = None,
    ) -> Wedge:
        """Symmetric wedge of total ``tip_angle`` [rad] in (0, pi) and either ``height`` or ``base`` [m]."""
        angle = check_finite("tip_angle", tip_angle)
        if not 0.0 < angle < math.pi:
            raise InputError("tip_angle", tip_angle, "an angle in (0, pi) rad")
        if (height is None) == (base is None):
            raise InputError(
                "height/base", (height, base), "exactly one of height and base", "give the other"
            )
        t = math.tan(0.5 * angle)
        if height is not None:
            h = check_length("height", height)
            return cls(2.0 * h * t, h, width)
        b = check_length("base", base)  # type: ignore[arg-type]
        return cls(b, 0.5 * b / t, width)

    @property
    def vertices(self) -> NDArray[np.float64]:
        """Tip, right and left base corners (3, 2) [m], counter-clockwise."""
        a, o, h = 0.5 * self.base, self.tip_offset, self.height
        return np.array([[0.0, 0.0], [a - o, h], [-a - o, h]])

    @property
    def projected_width(self) -> float:
        """Horizontal extent of the wedge [m]."""
        x = self.vertices[:, 0]
        return float(x.max() - x.min())

    @property
    def size(self) -> float:
        return max(self.projected_width, self.height)

    def loops(self) -> list[list[Segment]]:
        return [_polygon_loop(self.vertices)]


@dataclass(frozen=True)
class Polygon(Body):
    """Any simple polygon of vertices ``points`` (N, 2) (x, z) [m] in the body frame, ``width`` [m].

    The vertices are stored counter-clockwise as a tuple of (x, z) pairs (order reversed if given
    clockwise); repeated consecutive points and a closing point equal to the first are dropped. The
    origin is the one of the given coordinates, or the area centroid with ``center=True``.
    """

    points: ArrayLike
    width: float
    _: KW_ONLY
    center: InitVar[bool] = False

    def __post_init__(self, center: bool) -> None:
        self._check_width()
        p = _simple_polygon(self.points)
        if center:
            p = p - _centroid(p)
        object.__setattr__(self, "points", tuple((float(x), float(z)) for x, z in p))

    @classmethod
    def from_file(cls, path: str | Path, width: float, *, center: bool = False) -> Polygon:
        """Polygon from a CSV file (two columns x, z [m], optional header) or a JSON file.

        JSON holds ``{"points": [[x, z], ...]}`` or the bare list. Any problem (missing file, a value
        that is not a number, a polygon that is not simple) raises :class:`InputError` naming the file.
        """
        points = _read_points(Path(path))
        try:
            return cls(points, width, center=center)
        except InputError as exc:
            hint = f"in {path}" + (f"; {exc.hint}" if exc.hint else "")
            raise InputError(exc.field, exc.value, exc.allowed, hint) from None

    @property
    def vertices(self) -> NDArray[np.float64]:
        """Vertices (N, 2) [m], counter-clockwise."""
        return np.array(self.points, dtype=np.float64)

    @property
    def area(self) -> float:
        """Enclosed area [m^2]."""
        return _signed_area(self.vertices)

    @property
    def size(self) -> float:
        v = self.vertices
        return float(np.max(v.max(axis=0) - v.min(axis=0)))

    def loops(self) -> list[list[Segment]]:
        return [_polygon_loop(self.vertices)]


def _simple_polygon(points: Any) -> NDArray[np.float64]:
    """Validated vertices (N, 2): finite, distinct, counter-clockwise, non-zero area, simple."""
    allowed = "an (N, 2) array of finite vertices (x, z) [m]"
    try:
        p = np.array(points, dtype=np.float64)
    except (TypeError, ValueError):
        raise InputError("points", _short(points), allowed) from None
    if p.ndim != 2 or p.shape[1] != 2:
        raise InputError("points", f"array of shape {p.shape}", allowed)
    if not np.all(np.isfinite(p)):
        bad = int(np.nonzero(~np.all(np.isfinite(p), axis=1))[0][0])
        raise InputError("points", f"vertex {bad} = {p[bad].tolist()}", allowed)
    scale = float(np.max(np.ptp(p, axis=0))) if len(p) else 0.0
    if len(p) > 1:  # drop repeated points, then closing points equal to the first
        keep = np.ones(len(p), dtype=bool)
        keep[1:] = np.hypot(*np.diff(p, axis=0).T) > 1e-12 * scale
        p = p[keep]
        while len(p) > 1 and math.hypot(*(p[-1] - p[0])) <= 1e-12 * scale:
            p = p[:-1]
    if len(p) < 3:
        raise InputError("points", f"{len(p)} distinct vertices", "at least 3 distinct vertices")
    crossing = _first_crossing(p)
    if crossing is not None:
        i, j = crossing
        raise InputError(
            "points",
            f"edge {i} crosses edge {j} (edge k joins vertices k and k+1)",
            "a simple polygon (no self-intersection)",
        )
    area = _signed_area(p)
    if abs(area) <= 1e-12 * scale**2:
        raise InputError("points", f"area {area:.3g} m^2", "a polygon enclosing a non-zero area")
    if area < 0:
        p = p[::-1].copy()
    return p


def _short(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _read_points(path: Path) -> list[list[float]]:
    """Vertex rows from a CSV or JSON file; every problem is an InputError naming the path."""
    allowed = "a CSV (x,z rows [m], optional header) or JSON points file"
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError("path", str(path), allowed, "file not found") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError("path", str(path), allowed, f"cannot read it: {exc}") from None
    stripped = text.lstrip()
    if path.suffix.lower() == ".json" or stripped.startswith(("{", "[")):
        return _json_points(path, text, allowed)
    return _csv_points(path, text, allowed)


def _json_points(path: Path, text: str, allowed: str) -> list[list[float]]:
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError("path", str(path), allowed, f"invalid JSON: {exc}") from None
    if isinstance(data, dict):
        if "points" not in data:
            raise InputError("path", str(path), allowed, 'JSON object without a "points" key')
        data = data["points"]
    if not isinstance(data, list):
        raise InputError("path", str(path), allowed, "the points are not a list of [x, z] pairs")
    rows = []
    for k, row in enumerate(data):
        if not (isinstance(row, list | tuple) and len(row) == 2):
            raise InputError("path", str(path), allowed, f"points[{k}] = {_short(row)} is not [x, z]")
        values = []
        for value in row:
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise InputError("path", str(path), allowed, f"points[{k}]: {_short(value)} is not a number")
            values.append(float(value))
        rows.append(values)
    return rows


def _csv_points(path: Path, text: str, allowed: str) -> list[list[float]]:
    rows: list[list[float]] = []
    lines = enumerate(text.splitlines(), start=1)
    body = [(n, line) for n, line in lines if line.strip() and not line.lstrip().startswith("#")]
    for k, (n, line) in enumerate(body):
        cells = next(csv.reader([line])) if "," in line else line.split()
        cells = [c.strip() for c in cells]
        if len(cells) != 2:
            raise InputError(
                "path", str(path), allowed, f"line {n} has {len(cells)} columns, expected 2 (x, z)"
            )
        try:
            rows.append([float(c) for c in cells])
        except ValueError:
            if k == 0:
                continue  # a header
            bad = next(c for c in cells if not _is_number(c))
            raise InputError("path", str(path), allowed, f"line {n}: {bad!r} is not a number") from None
    if not rows:
        raise InputError("path", str(path), allowed, "no vertex rows found")
    return rows


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True
