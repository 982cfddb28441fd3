"""Closed triangle meshes of simple bodies, built with NumPy only.

Every primitive is centred on its body origin (wheels: the axle) and returns a :class:`TriangleMesh`
with outward normals. Every flat quadrilateral cell is split into four triangles about its centre, and
all stations are placed symmetrically, so a primitive that is symmetric about a coordinate plane is
meshed exactly symmetric about it (mirror tests then hold to round-off).

Axes follow DESIGN.md: x forward, z up, y to the left; wheels spin about +y.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError, check_length, check_positive
from .mesh import TriangleMesh

__all__ = [
    "box",
    "cone",
    "plate",
    "sphere",
    "wheel_cylinder",
    "wheel_grousered",
]


def _count(field: str, value: int, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < minimum:
        raise InputError(field, value, f"an integer >= {minimum}")
    return int(value)


def _stations(n: int) -> NDArray[np.float64]:
    """n + 1 stations in [-1, 1], exactly antisymmetric and with exact end points."""
    k = np.arange(n + 1, dtype=np.float64)
    return (2.0 * k - n) / n


def _circle(n: int, start: float = 0.0) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """cos and sin of n angles ``start + 2 pi k / n``, exactly mirror-symmetric for start = 0."""
    k = np.arange(n)
    if start != 0.0:
        a = start + 2.0 * np.pi * k / n
        return np.cos(a), np.sin(a)
    m = np.minimum(k, n - k)
    a = 2.0 * np.pi * m / n
    c = np.where(4 * m == n, 0.0, np.cos(a))
    s = np.where(2 * m == n, 0.0, np.sin(a))
    return c, np.where(k <= n - k, 1.0, -1.0) * s


class _Builder:
    """Collects vertices and triangles; quads are split into four triangles about their centre."""

    def __init__(self) -> None:
        self.vertices: list[NDArray[np.float64]] = []
        self.faces: list[NDArray[np.int64]] = []
        self.count = 0

    def add_vertices(self, pts: NDArray[np.float64]) -> NDArray[np.int64]:
        pts = np.asarray(pts, dtype=np.float64)
        n = int(np.prod(pts.shape[:-1]))
        idx = self.count + np.arange(n, dtype=np.int64).reshape(pts.shape[:-1])
        self.vertices.append(pts.reshape(-1, 3))
        self.count += n
        return idx

    def grid(self, pts: NDArray[np.float64], *, closed: bool = False) -> None:
        """Quads of a (M + 1, N + 1, 3) point grid (closed: wrap along the second axis), 4 triangles each.

        Orientation: the quad (i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1) is counter-clockwise.
        """
        idx = self.add_vertices(pts)
        if closed:
            idx = np.concatenate((idx, idx[:, :1]), axis=1)
            pts = np.concatenate((pts, pts[:, :1]), axis=1)
        a, b = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel()
        c, d = idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
        # Diagonal pairs first: the sum is then exactly mirror-symmetric.
        centre = 0.25 * ((pts[:-1, :-1] + pts[1:, 1:]) + (pts[1:, :-1] + pts[:-1, 1:])).reshape(-1, 3)
        m = self.add_vertices(centre)
        for p, q in ((a, b), (b, c), (c, d), (d, a)):
            self.faces.append(np.column_stack((p, q, m)))

    def fan(self, apex: NDArray[np.float64], ring: NDArray[np.float64]) -> None:
        """Triangles (apex, ring[k], ring[k + 1]) around a closed ring of points (N, 3)."""
        i = self.add_vertices(apex[None, :])[0]
        r = self.add_vertices(ring)
        self.faces.append(np.column_stack((np.full(r.shape[0], i), r, np.roll(r, -1))))

    def mesh(self) -> TriangleMesh:
        """The welded, outward-oriented mesh."""
        vertices = np.vstack(self.vertices)
        faces = np.vstack(self.faces)
        unique, inverse = np.unique(vertices, axis=0, return_inverse=True)
        faces = inverse.reshape(-1)[faces]
        mesh = TriangleMesh(unique, faces)
        if mesh.volume < 0:
            mesh = TriangleMesh(unique, faces[:, ::-1])
        return mesh


def _disc(builder: _Builder, outline: NDArray[np.float64], centre: NDArray[np.float64], rings: int) -> None:
    """Fill a star-shaped closed outline (N, 3) about ``centre`` with ``rings`` scaled copies of it.

    The facets turn counter-clockwise with the outline (normal by the right-hand rule).
    """
    s = np.arange(1, rings + 1, dtype=np.float64) / rings
    pts = centre + s[:, None, None] * (outline - centre)[None, :, :]
    builder.fan(centre, pts[0])
    if rings > 1:
        builder.grid(pts, closed=True)


def _extrude(outline_xz: NDArray[np.float64], width: float, axial: int, rings: int) -> TriangleMesh:
    """Closed prism along y (from -width/2 to width/2) of a star-shaped (about the origin) x-z outline."""
    y = 0.5 * width * _stations(axial)
    n = outline_xz.shape[0]
    pts = np.empty((axial + 1, n, 3))
    pts[:, :, 0] = outline_xz[None, :, 0]
    pts[:, :, 1] = y[:, None]
    pts[:, :, 2] = outline_xz[None, :, 1]
    b = _Builder()
    b.grid(pts, closed=True)
    # The outline turns clockwise seen from +y: as is it faces -y, reversed it faces +y.
    _disc(b, pts[0], np.array([0.0, y[0], 0.0]), rings)
    _disc(b, pts[axial, ::-1], np.array([0.0, y[axial], 0.0]), rings)
    return b.mesh()


def _resolution(length: float, facet_size: float | None, default: int) -> int:
    if facet_size is None:
        return default
    return max(1, math.ceil(length / check_positive("facet_size", facet_size) - 1e-9))


def plate(length: float, width: float, *, facet_size: float | None = None) -> TriangleMesh:
    """A zero-thickness rectangular plate in the body x-y plane, centred on the origin.

    ``length`` [m] along x, ``width`` [m] along y. The plate is two-sided: two sheets of facets share
    the vertices, one with normals -z and one with +z, so whichever face leads carries the load under
    the leading-edge rule (turn that rule off and a plate counts twice). ``facet_size`` [m] sets the
    quad size (default: 8 quads along the longer side).
    """
    check_length("length", length)
    check_length("width", width)
    size = facet_size if facet_size is not None else max(length, width) / 8.0
    nx, ny = _resolution(length, size, 1), _resolution(width, size, 1)
    x = 0.5 * length * _stations(nx)
    y = 0.5 * width * _stations(ny)
    gx, gy = np.meshgrid(x, y, indexing="ij")
    pts = np.stack((gx, gy, np.zeros_like(gx)), axis=-1)
    b = _Builder()
    b.grid(pts)  # normals +z
    b.grid(pts[:, ::-1])  # normals -z
    vertices = np.vstack(b.vertices)
    unique, inverse = np.unique(vertices, axis=0, return_inverse=True)
    return TriangleMesh(unique, inverse.reshape(-1)[np.vstack(b.faces)])


def box(length: float, width: float, height: float, *, facet_size: float | None = None) -> TriangleMesh:
    """A closed box, ``length`` [m] along x, ``width`` [m] along y, ``height`` [m] along z, centred.

    ``facet_size`` [m] sets the quad size (default: 4 quads along the longest side).
    """
    dims = np.array(
        [check_length(n, v) for n, v in (("length", length), ("width", width), ("height", height))]
    )
    size = facet_size if facet_size is not None else float(dims.max()) / 4.0
    res = [_resolution(float(d), size, 1) for d in dims]
    b = _Builder()
    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3
        su = 0.5 * dims[u] * _stations(res[u])
        sv = 0.5 * dims[v] * _stations(res[v])
        gu, gv = np.meshgrid(su, sv, indexing="ij")
        for sign in (-1.0, 1.0):
            pts = np.empty((*gu.shape, 3))
            pts[..., axis] = sign * 0.5 * dims[axis]
            pts[..., u] = gu
            pts[..., v] = gv
            b.grid(pts if sign > 0 else pts[:, ::-1])
    return b.mesh()


def wheel_cylinder(
    radius: float,
    width: float,
    *,
    circumferential_resolution: int = 180,
    axial_resolution: int = 8,
    radial_resolution: int | None = None,
) -> TriangleMesh:
    """A closed cylindrical wheel with its axle along y, centred on the origin.

    Parameters
    ----------
    radius, width : float
        Rim radius [m] and width along y [m].
    circumferential_resolution : int
        Quads around the rim (each split into four triangles).
    axial_resolution : int
        Quads across the width.
    radial_resolution : int, optional
        Rings on each side wall (default: about as fine as the rim spacing, at most 8).
    """
    return wheel_grousered(
        radius,
        width,
        grouser_count=0,
        grouser_height=0.0,
        grouser_thickness=0.0,
        circumferential_resolution=circumferential_resolution,
        axial_resolution=axial_resolution,
        radial_resolution=radial_resolution,
    )


def _lug_outline(
    radius: float, height: float, thickness: float, centre: float, side_points: int, tip_points: int
) -> NDArray[np.float64]:
    """Outline points (angle-increasing) of one lug centred at x-z angle ``centre`` [rad]."""
    half = 0.5 * thickness
    base = math.sqrt(radius * radius - half * half)
    r = np.linspace(base, radius + height, side_points + 1)
    side_a = np.column_stack((r, np.full_like(r, -half)))  # lug frame: (along lug, across lug)
    across = half * _stations(tip_points)[1:-1]
    tip = np.column_stack((np.full(across.shape, radius + height), across))
    side_b = np.column_stack((r[::-1], np.full_like(r, half)))
    local = np.vstack((side_a, tip, side_b))
    c, s = math.cos(centre), math.sin(centre)
    return np.column_stack((c * local[:, 0] - s * local[:, 1], s * local[:, 0] + c * local[:, 1]))


def wheel_grousered(
    radius: float,
    width: float,
    *,
    grouser_count: int,
    grouser_height: float,
    grouser_thickness: float,
    circumferential_resolution: int = 180,
    axial_resolution: int = 8,
    radial_resolution: int | None = None,
) -> TriangleMesh:
    """A closed wheel with rectangular lugs across its full width; axle along y, centred on the origin.

    As the plane :class:`~terradyn.geometry.WheelGrousered`: ``grouser_count`` lugs, each
    ``grouser_height`` [m] tall from the rim (``radius`` [m]) to the flat outer face on its centreline
    and ``grouser_thickness`` [m] thick; the first lug points along -z, the others follow every
    2 pi / ``grouser_count`` counter-clockwise in the x-z view (x to the right, z up).
    ``grouser_count = 0`` gives a plain cylinder.
    Resolutions as :func:`wheel_cylinder` (the rim arc between lugs takes its share of
    ``circumferential_resolution``; each lug side and face gets the same spacing).
    """
    check_length("radius", radius)
    check_length("width", width)
    count = _count("grouser_count", grouser_count, 0)
    n_circ = _count("circumferential_resolution", circumferential_resolution, 8)
    axial = _count("axial_resolution", axial_resolution, 1)
    spacing = 2.0 * math.pi * radius / n_circ
    rings = (
        min(8, max(1, round(radius / spacing)))
        if radial_resolution is None
        else _count("radial_resolution", radial_resolution, 1)
    )
    if count == 0:
        c, s = _circle(n_circ)
        # Angle measured from -z towards +x in the x-z plane.
        return _extrude(np.column_stack((radius * s, -radius * c)), width, axial, rings)
    check_length("grouser_height", grouser_height)
    check_length("grouser_thickness", grouser_thickness)
    limit = 2.0 * radius * math.sin(min(math.pi / count, 0.5 * math.pi))
    if not grouser_thickness < limit:
        raise InputError(
            "grouser_thickness", grouser_thickness, f"a thickness below {limit:.6g} m", "lugs would overlap"
        )
    side_points = max(1, math.ceil(grouser_height / spacing))
    tip_points = max(1, math.ceil(grouser_thickness / spacing))
    half_angle = math.asin(0.5 * grouser_thickness / radius)
    pitch = 2.0 * math.pi / count
    arc_points = max(1, round((pitch - 2.0 * half_angle) * radius / spacing))
    parts = []
    for k in range(count):
        centre = -0.5 * math.pi + k * pitch  # x-z angle measured from +x towards +z
        parts.append(_lug_outline(radius, grouser_height, grouser_thickness, centre, side_points, tip_points))
        arc = centre + half_angle + (pitch - 2.0 * half_angle) * np.arange(1, arc_points) / arc_points
        parts.append(radius * np.column_stack((np.cos(arc), np.sin(arc))))
    return _extrude(np.vstack(parts), width, axial, rings)


def sphere(radius: float, *, subdivisions: int = 3) -> TriangleMesh:
    """A closed icosphere of ``radius`` [m] centred on the origin: 20 * 4**subdivisions facets.

    Mirror-symmetric about the three coordinate planes.
    """
    check_length("radius", radius)
    level = _count("subdivisions", subdivisions, 0)
    if level > 8:
        raise InputError("subdivisions", subdivisions, "an integer in [0, 8]", "8 gives 1.3 million facets")
    phi = 0.5 * (1.0 + math.sqrt(5.0))
    v = np.array(
        [[-1, phi, 0], [1, phi, 0], [-1, -phi, 0], [1, -phi, 0], [0, -1, phi], [0, 1, phi],
         [0, -1, -phi], [0, 1, -phi], [phi, 0, -1], [phi, 0, 1], [-phi, 0, -1], [-phi, 0, 1]],
        dtype=np.float64,
    )  # fmt: skip
    f = np.array(
        [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
         [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5],
         [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]],
        dtype=np.int64,
    )  # fmt: skip
    v /= np.linalg.norm(v, axis=1)[:, None]
    for _ in range(level):
        nv = v.shape[0]
        e = f[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 3, 2)
        keys = np.minimum(e[..., 0], e[..., 1]) * nv + np.maximum(e[..., 0], e[..., 1])
        uniq, inverse = np.unique(keys.reshape(-1), return_inverse=True)
        mid = v[uniq // nv] + v[uniq % nv]
        v = np.vstack((v, mid / np.linalg.norm(mid, axis=1)[:, None]))
        m = nv + inverse.reshape(-1, 3)
        f = np.vstack(
            (
                np.column_stack((f[:, 0], m[:, 0], m[:, 2])),
                np.column_stack((f[:, 1], m[:, 1], m[:, 0])),
                np.column_stack((f[:, 2], m[:, 2], m[:, 1])),
                m,
            )
        )
    mesh = TriangleMesh(radius * v, f)
    return mesh if mesh.volume > 0 else TriangleMesh(radius * v, f[:, ::-1])


def cone(
    radius: float,
    height: float,
    *,
    circumferential_resolution: int = 64,
    axial_resolution: int = 8,
    radial_resolution: int | None = None,
) -> TriangleMesh:
    """A closed cone with its apex at the origin pointing down (-z) and its base disc at z = ``height``.

    ``radius`` [m] of the base, ``height`` [m] apex to base. Resolutions: quads around, rings along the
    slant, rings on the base (default as fine as the slant).
    """
    check_length("radius", radius)
    check_length("height", height)
    n = _count("circumferential_resolution", circumferential_resolution, 3)
    axial = _count("axial_resolution", axial_resolution, 1)
    rings = axial if radial_resolution is None else _count("radial_resolution", radial_resolution, 1)
    c, s = _circle(n)
    t = np.arange(1, axial + 1, dtype=np.float64) / axial
    side = np.stack(
        (radius * t[:, None] * c, radius * t[:, None] * s, height * t[:, None] + 0.0 * c), axis=-1
    )
    b = _Builder()
    # Counter-clockwise seen from +z the rings face inward on the slant, so the slant uses them reversed.
    b.fan(np.zeros(3), side[0, ::-1])
    if axial > 1:
        b.grid(side[:, ::-1], closed=True)
    _disc(b, side[-1], np.array([0.0, 0.0, height]), rings)
    return b.mesh()
