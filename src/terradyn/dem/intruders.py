"""Rigid intruders in a DEM bed: terradyn bodies as clumps of wall spheres moved at a prescribed velocity.

A body's outline (:meth:`terradyn.geometry.Body.outline`, the same outline MPM resolves) is sampled
every quarter grain diameter and extruded, in rows 0.35 grain apart, across the bed (slab: its
whole periodic thickness; 3d: the body's width) with spheres of half a grain diameter, so close
that no grain passes between them.
Body spheres do not interact with each other (``neigh_modify exclude``); LAMMPS's ``fix move`` moves
them rigidly. The force on the body is the sum of the contact forces on its spheres; the torque about
the body's reference point adds the spheres' own contact torques. The DEM body is therefore the outline
thickened by a quarter grain diameter on each side (a zero-thickness plate is half a grain thick).

A 3D body (:class:`MeshIntruder`, a :class:`terradyn.geometry3d.TriangleMesh`) for a ``3d`` bed is
its surface sampled instead, on a lattice in every facet at the same spacing, with the same spheres;
its reference point is the centre of its bounding box.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..errors import InputError
from ..geometry import Body

if TYPE_CHECKING:
    from ..geometry3d import TriangleMesh

__all__ = ["WALL_DIAMETER_FRACTION", "MeshIntruder", "body_points", "body_spheres"]

#: diameter of a body sphere as a fraction of the mean grain diameter
WALL_DIAMETER_FRACTION = 0.5
#: spacing of body spheres as a fraction of their diameter
WALL_SPACING_FRACTION = 0.5


def _hull(points: np.ndarray) -> np.ndarray:
    """Convex hull (counter-clockwise, first point not repeated) of 2D points (Andrew's monotone chain)."""
    pts = sorted(set(map(tuple, np.round(points, 12).tolist())))
    if len(pts) < 3:
        return np.asarray(pts, dtype=float)

    def half(seq: list[tuple[float, float]]) -> list[tuple[float, float]]:
        out: list[tuple[float, float]] = []
        for q in seq:
            while len(out) >= 2:
                (ax, az), (bx, bz) = out[-2], out[-1]
                if (bx - ax) * (q[1] - az) - (bz - az) * (q[0] - ax) > 0:
                    break
                out.pop()
            out.append(q)
        return out

    lower, upper = half(pts), half(pts[::-1])
    return np.asarray(lower[:-1] + upper[:-1], dtype=float)


@dataclass(frozen=True, eq=False)
class MeshIntruder:
    """A 3D rigid body for a ``3d`` DEM bed: ``mesh`` in the body frame (x forward, y across, z up)
    with the centre of its bounding box at the origin, the reference point (:meth:`from_mesh` moves a
    mesh there). ``angle`` rotates it about +y as it does a plane body."""

    mesh: TriangleMesh

    @classmethod
    def from_mesh(cls, mesh: TriangleMesh) -> MeshIntruder:
        from ..geometry3d import TriangleMesh

        if not isinstance(mesh, TriangleMesh):
            raise InputError("body", type(mesh).__name__, "a terradyn.geometry3d.TriangleMesh")
        lo, hi = mesh.bounds
        if np.count_nonzero(hi - lo > 0) < 2:
            raise InputError(
                "mesh", (hi - lo).tolist(), "a body with a positive extent along two axes or three [m]"
            )
        return cls(mesh.translated(-0.5 * (lo + hi)))

    @property
    def width(self) -> float:
        """Extent across the bed (along y) [m]."""
        lo, hi = self.mesh.bounds
        return float(hi[1] - lo[1])

    @property
    def size(self) -> float:
        """Largest extent in the x-z plane [m]."""
        lo, hi = self.mesh.bounds
        return float(max(hi[0] - lo[0], hi[2] - lo[2]))

    @property
    def outer_radius(self) -> float:
        """Largest distance [m] of a vertex from the y axis through the reference point (a wheel's
        nominal radius when the mesh is a wheel centred on its axle)."""
        v = self.mesh.vertices
        return float(np.hypot(v[:, 0], v[:, 2]).max())

    def describe(self) -> dict[str, object]:
        """What identifies the body (checkpoint inputs): counts, bounds and a digest of the arrays."""
        import hashlib

        digest = hashlib.sha256(self.mesh.vertices.tobytes() + self.mesh.faces.tobytes()).hexdigest()
        lo, hi = self.mesh.bounds
        return {"mesh_sha256": digest[:16], "facets": int(self.mesh.facet_count),
                "bounds_m": [lo.tolist(), hi.tolist()]}  # fmt: skip

    def outline(self, spacing: float | None = None) -> list[np.ndarray]:
        """The silhouette in the x-z plane (the convex hull of the vertices), for plots and extents."""
        return [_hull(self.mesh.vertices[:, [0, 2]])]

    def surface_points(self, spacing: float) -> np.ndarray:
        """Points (K, 3) [m] on every facet, on a lattice at most ``spacing`` apart (edges included),
        thinned to one point per cube of half ``spacing`` (neighbouring facets share their edge
        points, and the slivers of a fan-triangulated disc would otherwise crowd its centre), so every
        point of the surface is within 1.5 ``spacing`` of a sample."""
        tri = self.mesh.vertices[self.mesh.faces]
        longest = np.linalg.norm(tri[:, [1, 2, 0]] - tri, axis=2).max(axis=1)
        pts = []
        for (a, b, c), edge in zip(tri, longest, strict=True):
            n = max(1, math.ceil(float(edge) / spacing))
            i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
            keep = (i + j) <= n
            u, v = i[keep][:, None] / n, j[keep][:, None] / n
            pts.append(a + u * (b - a) + v * (c - a))
        allp = np.vstack(pts)
        key = np.floor(allp / (0.5 * spacing)).astype(np.int64)
        _, first = np.unique(key, axis=0, return_index=True)
        return allp[np.sort(first)]


def body_points(body: Body | MeshIntruder, spacing: float) -> np.ndarray:
    """Points (M, 2) [m] along the outline of ``body`` in its frame, at most ``spacing`` apart,
    duplicates (the two faces of a zero-thickness plate) merged; a mesh's vertices in the x-z plane."""
    if isinstance(body, MeshIntruder):
        return np.asarray(body.mesh.vertices[:, [0, 2]], dtype=float)
    if not isinstance(body, Body):
        raise InputError("body", body, "a terradyn.geometry Body (Plate, Wedge, Cylinder, ...)")
    pts = []
    for poly in body.outline(min(spacing, body.size)):
        p = np.asarray(poly, dtype=float)
        if len(p) > 1 and not np.allclose(p[0], p[-1]):
            p = np.vstack([p, p[:1]])
        for a, b in itertools.pairwise(p):
            n = max(1, math.ceil(float(np.hypot(*(b - a))) / spacing))
            t = np.arange(n)[:, None] / n
            pts.append(a + t * (b - a))
    allp = np.vstack(pts)
    key = np.round(allp / (1e-3 * spacing)).astype(np.int64)
    _, first = np.unique(key, axis=0, return_index=True)
    return allp[np.sort(first)]


def body_spheres(
    body: Body | MeshIntruder, grain_diameter: float, pose: tuple[float, float, float], surface: float,
    y_range: tuple[float, float], *, periodic: bool,
) -> tuple[np.ndarray, float]:  # fmt: skip
    """Centres (K, 3) [m] of the body spheres in the LAMMPS box at ``pose`` (x, z, theta) in terradyn's
    frame (free surface at z = 0, box surface at ``surface``), and the sphere diameter [m]."""
    d_w = WALL_DIAMETER_FRACTION * grain_diameter
    h = WALL_SPACING_FRACTION * d_w
    x, z, theta = pose
    c, s = math.cos(theta), math.sin(theta)
    if isinstance(body, MeshIntruder):
        if periodic:
            raise InputError("bed", "slab", "a 3d bed for a 3D (mesh) body")
        q = body.surface_points(h)
        mid = 0.5 * (y_range[0] + y_range[1])
        wx = x + c * q[:, 0] + s * q[:, 2]
        wz = surface + z - s * q[:, 0] + c * q[:, 2]
        return np.column_stack((wx, mid + q[:, 1], wz)), d_w
    p = body_points(body, h)
    wx = x + c * p[:, 0] + s * p[:, 1]
    wz = surface + z - s * p[:, 0] + c * p[:, 1]
    y0, y1 = y_range
    ny = max(1, math.ceil((y1 - y0) / (0.7 * d_w)))  # overlapping across, gaps far below a grain
    if periodic:
        ys = y0 + (np.arange(ny) + 0.5) * (y1 - y0) / ny
    else:
        ys = np.linspace(y0, y1, ny + 1)
    xx = np.repeat(wx, len(ys))
    zz = np.repeat(wz, len(ys))
    yy = np.tile(ys, len(wx))
    return np.column_stack((xx, yy, zz)), d_w


def rotated_extent(body: Body | MeshIntruder, theta: float) -> tuple[float, float, float, float]:
    """(x_min, x_max, z_min, z_max) [m] of the body's outline rotated by ``theta`` about its origin."""
    p = body_points(body, body.size / 50.0)
    c, s = math.cos(theta), math.sin(theta)
    x = c * p[:, 0] + s * p[:, 1]
    z = -s * p[:, 0] + c * p[:, 1]
    return float(x.min()), float(x.max()), float(z.min()), float(z.max())
