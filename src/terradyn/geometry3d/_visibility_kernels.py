"""Numba kernel of :func:`terradyn.geometry3d.visibility.visible_facets` (ray casting on a 2D grid)."""

from __future__ import annotations

import math

import numba
import numpy as np

from .visibility import _EDGE


@numba.njit(cache=True)
def _basis(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors orthogonal to the unit vector d and to each other."""
    a = np.array([1.0, 0.0, 0.0]) if abs(d[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    e1 = a - (a[0] * d[0] + a[1] * d[1] + a[2] * d[2]) * d
    e1 /= math.sqrt(e1[0] ** 2 + e1[1] ** 2 + e1[2] ** 2)
    e2 = np.array([d[1] * e1[2] - d[2] * e1[1], d[2] * e1[0] - d[0] * e1[2], d[0] * e1[1] - d[1] * e1[0]])
    return e1, e2


@numba.njit(cache=True)
def _hits(o: np.ndarray, d: np.ndarray, v0: np.ndarray, v1: np.ndarray, v2: np.ndarray, tmin: float) -> bool:
    """Moller-Trumbore: does the ray o + t d (t > tmin) cross the triangle (v0, v1, v2), edges included?"""
    e1 = v1 - v0
    e2 = v2 - v0
    p = np.array([d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2], d[0] * e2[1] - d[1] * e2[0]])
    det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2]
    if det == 0.0:
        return False
    inv = 1.0 / det
    s = o - v0
    u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) * inv
    if u < -_EDGE or u > 1.0 + _EDGE:
        return False
    q = np.array([s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]])
    w = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) * inv
    if w < -_EDGE or u + w > 1.0 + _EDGE:
        return False
    t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * inv
    return t > tmin


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
    is blocked by any other facet it crosses. Per direction the facets are binned by their projection
    on the plane across d (a uniform grid of about F cells), so each ray tests only its cell.
    """
    nf = faces.shape[0]
    out = np.zeros(nf, dtype=np.bool_)
    cells = max(1, int(math.sqrt(nf)))
    for k in range(directions.shape[0]):
        d = directions[k]
        e1, e2 = _basis(d)
        nv = vertices.shape[0]
        pu = np.empty(nv)
        pw = np.empty(nv)
        for j in range(nv):
            x, y, z = vertices[j, 0], vertices[j, 1], vertices[j, 2]
            pu[j] = x * e1[0] + y * e1[1] + z * e1[2]
            pw[j] = x * e2[0] + y * e2[1] + z * e2[2]
        u0, u1, w0, w1 = pu.min(), pu.max(), pw.min(), pw.max()
        hu = max((u1 - u0) / cells, 1e-300)
        hw = max((w1 - w0) / cells, 1e-300)
        lo_u = np.empty(nf, dtype=np.int64)
        hi_u = np.empty(nf, dtype=np.int64)
        lo_w = np.empty(nf, dtype=np.int64)
        hi_w = np.empty(nf, dtype=np.int64)
        count = np.zeros(cells * cells + 1, dtype=np.int64)
        for j in range(nf):
            a, b, c = faces[j, 0], faces[j, 1], faces[j, 2]
            lo_u[j] = min(cells - 1, int((min(pu[a], pu[b], pu[c]) - u0) / hu))
            hi_u[j] = min(cells - 1, int((max(pu[a], pu[b], pu[c]) - u0) / hu))
            lo_w[j] = min(cells - 1, int((min(pw[a], pw[b], pw[c]) - w0) / hw))
            hi_w[j] = min(cells - 1, int((max(pw[a], pw[b], pw[c]) - w0) / hw))
            for iu in range(lo_u[j], hi_u[j] + 1):
                for iw in range(lo_w[j], hi_w[j] + 1):
                    count[iu * cells + iw + 1] += 1
        start = np.cumsum(count)
        fill = start[:-1].copy()
        members = np.empty(start[-1], dtype=np.int64)
        for j in range(nf):
            for iu in range(lo_u[j], hi_u[j] + 1):
                for iw in range(lo_w[j], hi_w[j] + 1):
                    cell = iu * cells + iw
                    members[fill[cell]] = j
                    fill[cell] += 1
        for i in range(nf):
            if out[i]:
                continue
            n = normals[i]
            if n[0] * d[0] + n[1] * d[1] + n[2] * d[2] <= facing:
                continue
            o = centroids[i] + offset * n
            ou = o[0] * e1[0] + o[1] * e1[1] + o[2] * e1[2]
            ow = o[0] * e2[0] + o[1] * e2[1] + o[2] * e2[2]
            iu = min(cells - 1, max(0, int((ou - u0) / hu)))
            iw = min(cells - 1, max(0, int((ow - w0) / hw)))
            cell = iu * cells + iw
            blocked = False
            for m in range(start[cell], start[cell + 1]):
                j = members[m]
                if j == i:
                    continue
                if _hits(o, d, vertices[faces[j, 0]], vertices[faces[j, 1]], vertices[faces[j, 2]], 0.0):
                    blocked = True
                    break
            if not blocked:
                out[i] = True
    return out
