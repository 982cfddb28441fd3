"""Rigid intruders in a DEM bed: terradyn bodies as clumps of wall spheres moved at a prescribed velocity.

A body's outline (:meth:`terradyn.geometry.Body.outline`, the same outline MPM resolves) is sampled
every quarter grain diameter and extruded, in rows 0.35 grain apart, across the bed (slab: its
whole periodic thickness; 3d: the body's width) with spheres of half a grain diameter, so close
that no grain passes between them.
Body spheres do not interact with each other (``neigh_modify exclude``); LAMMPS's ``fix move`` moves
them rigidly. The force on the body is the sum of the contact forces on its spheres; the torque about
the body's reference point adds the spheres' own contact torques. The DEM body is therefore the outline
thickened by a quarter grain diameter on each side (a zero-thickness plate is half a grain thick).
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from ..errors import InputError
from ..geometry import Body

__all__ = ["WALL_DIAMETER_FRACTION", "body_points", "body_spheres"]

#: diameter of a body sphere as a fraction of the mean grain diameter
WALL_DIAMETER_FRACTION = 0.5
#: spacing of body spheres as a fraction of their diameter
WALL_SPACING_FRACTION = 0.5


def body_points(body: Body, spacing: float) -> np.ndarray:
    """Points (M, 2) [m] along the outline of ``body`` in its frame, at most ``spacing`` apart,
    duplicates (the two faces of a zero-thickness plate) merged."""
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
    body: Body, grain_diameter: float, pose: tuple[float, float, float], surface: float,
    y_range: tuple[float, float], *, periodic: bool,
) -> tuple[np.ndarray, float]:  # fmt: skip
    """Centres (K, 3) [m] of the body spheres in the LAMMPS box at ``pose`` (x, z, theta) in terradyn's
    frame (free surface at z = 0, box surface at ``surface``), and the sphere diameter [m]."""
    d_w = WALL_DIAMETER_FRACTION * grain_diameter
    h = WALL_SPACING_FRACTION * d_w
    p = body_points(body, h)
    x, z, theta = pose
    c, s = math.cos(theta), math.sin(theta)
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


def rotated_extent(body: Body, theta: float) -> tuple[float, float, float, float]:
    """(x_min, x_max, z_min, z_max) [m] of the body's outline rotated by ``theta`` about its origin."""
    p = body_points(body, body.size / 50.0)
    c, s = math.cos(theta), math.sin(theta)
    x = c * p[:, 0] + s * p[:, 1]
    z = -s * p[:, 0] + c * p[:, 1]
    return float(x.min()), float(x.max()), float(z.min()), float(z.max())
