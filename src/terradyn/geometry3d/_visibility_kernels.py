"""Numba kernel of :func:`terradyn.geometry3d.visibility.visible_facets` (rays walked over voxels)."""

from __future__ import annotations

import math

import numba
import numpy as np

#: barycentric slack: a ray through a shared edge (or vertex) counts as crossing, whatever the round-off
EDGE_SLACK = 1e-9
_EDGE = EDGE_SLACK


@numba.njit(cache=True, inline="always")
def _hits(
    ox: float, oy: float, oz: float, dx: float, dy: float, dz: float, vertices: np.ndarray, face: np.ndarray
) -> bool:
    """Moller-Trumbore: does the ray o + t d (t > 0) cross the triangle ``face``, edges included?"""
    a, b, c = face[0], face[1], face[2]
    x0, y0, z0 = vertices[a, 0], vertices[a, 1], vertices[a, 2]
    e1x, e1y, e1z = vertices[b, 0] - x0, vertices[b, 1] - y0, vertices[b, 2] - z0
    e2x, e2y, e2z = vertices[c, 0] - x0, vertices[c, 1] - y0, vertices[c, 2] - z0
    px, py, pz = dy * e2z - dz * e2y, dz * e2x - dx * e2z, dx * e2y - dy * e2x
    det = e1x * px + e1y * py + e1z * pz
    if det == 0.0:
        return False
    inv = 1.0 / det
    sx, sy, sz = ox - x0, oy - y0, oz - z0
    u = (sx * px + sy * py + sz * pz) * inv
    if u < -_EDGE or u > 1.0 + _EDGE:
        return False
    qx, qy, qz = sy * e1z - sz * e1y, sz * e1x - sx * e1z, sx * e1y - sy * e1x
    w = (dx * qx + dy * qy + dz * qz) * inv
    if w < -_EDGE or u + w > 1.0 + _EDGE:
        return False
    return (e2x * qx + e2y * qy + e2z * qz) * inv > 0.0


@numba.njit(cache=True)
def _voxel_bins(
    vertices: np.ndarray, faces: np.ndarray, lo: np.ndarray, h: float, n: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """CSR lists (start (N + 1,), members) of the facets whose bounding box touches each voxel."""
    nf = faces.shape[0]
    box = np.empty((nf, 6), dtype=np.int64)
    count = np.zeros(n[0] * n[1] * n[2] + 1, dtype=np.int64)
    for j in range(nf):
        for ax in range(3):
            a = vertices[faces[j, 0], ax]
            b = vertices[faces[j, 1], ax]
            c = vertices[faces[j, 2], ax]
            box[j, ax] = min(n[ax] - 1, max(0, int((min(a, b, c) - lo[ax]) / h)))
            box[j, 3 + ax] = min(n[ax] - 1, max(0, int((max(a, b, c) - lo[ax]) / h)))
        for x in range(box[j, 0], box[j, 3] + 1):
            for y in range(box[j, 1], box[j, 4] + 1):
                for z in range(box[j, 2], box[j, 5] + 1):
                    count[(x * n[1] + y) * n[2] + z + 1] += 1
    start = np.cumsum(count)
    fill = start[:-1].copy()
    members = np.empty(start[-1], dtype=np.int64)
    for j in range(nf):
        for x in range(box[j, 0], box[j, 3] + 1):
            for y in range(box[j, 1], box[j, 4] + 1):
                for z in range(box[j, 2], box[j, 5] + 1):
                    v = (x * n[1] + y) * n[2] + z
                    members[fill[v]] = j
                    fill[v] += 1
    return start, members


@numba.njit(cache=True)
def visible_facets_kernel(
    vertices: np.ndarray,
    faces: np.ndarray,
    centroids: np.ndarray,
    normals: np.ndarray,
    directions: np.ndarray,
    offset: float,
    facing: float,
) -> np.ndarray:
    """Facets (F,) whose centroid sees out of the mesh along at least one of ``directions`` (D, 3).

    vertices (V, 3) [m]; faces (F, 3); centroids, normals (F, 3); directions unit (D, 3). A facet is
    tested along d only when n . d > ``facing``; the ray starts ``offset`` [m] off the facet along n and
    is blocked by any other facet it crosses. The facets are binned once on a uniform voxel grid (about
    2 F voxels) and each ray walks the voxels it crosses (Amanatides and Woo 1987), testing only their
    facets; a direction no untested facet faces is skipped.
    """
    nf = faces.shape[0]
    out = np.zeros(nf, dtype=np.bool_)
    lo = np.empty(3)
    ext = np.empty(3)
    for ax in range(3):
        lo[ax] = vertices[:, ax].min()
        ext[ax] = vertices[:, ax].max() - lo[ax]
    span = max(ext.max(), 1e-300)
    for ax in range(3):
        ext[ax] = max(ext[ax], 1e-3 * span)
        lo[ax] -= 1e-6 * span
        ext[ax] += 2e-6 * span
    h = (ext[0] * ext[1] * ext[2] / (2.0 * nf)) ** (1.0 / 3.0)
    h = max(h, span / 512.0)
    n = np.empty(3, dtype=np.int64)
    for ax in range(3):
        n[ax] = max(1, math.ceil(ext[ax] / h))
    start, members = _voxel_bins(vertices, faces, lo, h, n)
    blocker = np.full(nf, -1, dtype=np.int64)  # the facet that last blocked each ray: tried first
    for k in range(directions.shape[0]):
        dx, dy, dz = directions[k, 0], directions[k, 1], directions[k, 2]
        for i in range(nf):
            if out[i] or normals[i, 0] * dx + normals[i, 1] * dy + normals[i, 2] * dz <= facing:
                continue
            ox = centroids[i, 0] + offset * normals[i, 0]
            oy = centroids[i, 1] + offset * normals[i, 1]
            oz = centroids[i, 2] + offset * normals[i, 2]
            last = blocker[i]
            if last >= 0 and _hits(ox, oy, oz, dx, dy, dz, vertices, faces[last]):
                continue  # nearby directions are usually blocked by the same facet
            blocked = _march(ox, oy, oz, dx, dy, dz, i, vertices, faces, lo, h, n, start, members, blocker)
            if not blocked:
                out[i] = True
    return out


@numba.njit(cache=True)
def _march(
    ox: float,
    oy: float,
    oz: float,
    dx: float,
    dy: float,
    dz: float,
    i: int,
    vertices: np.ndarray,
    faces: np.ndarray,
    lo: np.ndarray,
    h: float,
    n: np.ndarray,
    start: np.ndarray,
    members: np.ndarray,
    blocker: np.ndarray,
) -> bool:
    """Walk the voxels the ray from facet i crosses; True (and the blocker recorded) at the first hit."""
    o = (ox, oy, oz)
    d = (dx, dy, dz)
    cell = np.empty(3, dtype=np.int64)
    step = np.empty(3, dtype=np.int64)
    t_next = np.empty(3)
    t_delta = np.empty(3)
    for ax in range(3):
        c = math.floor((o[ax] - lo[ax]) / h)
        cell[ax] = min(n[ax] - 1, max(0, c))
        if d[ax] > 0.0:
            step[ax] = 1
            t_next[ax] = (lo[ax] + (cell[ax] + 1) * h - o[ax]) / d[ax]
            t_delta[ax] = h / d[ax]
        elif d[ax] < 0.0:
            step[ax] = -1
            t_next[ax] = (lo[ax] + cell[ax] * h - o[ax]) / d[ax]
            t_delta[ax] = -h / d[ax]
        else:
            step[ax] = 0
            t_next[ax] = np.inf
            t_delta[ax] = np.inf
    while True:
        v = (cell[0] * n[1] + cell[1]) * n[2] + cell[2]
        for m in range(start[v], start[v + 1]):
            j = members[m]
            if j != i and _hits(ox, oy, oz, dx, dy, dz, vertices, faces[j]):
                blocker[i] = j
                return True
        ax = 0
        if t_next[1] < t_next[ax]:
            ax = 1
        if t_next[2] < t_next[ax]:
            ax = 2
        cell[ax] += step[ax]
        if cell[ax] < 0 or cell[ax] >= n[ax]:
            return False
        t_next[ax] += t_delta[ax]
