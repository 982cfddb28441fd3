"""Which facets of a mesh can be reached from outside: visibility along a set of directions.

A facet can touch the medium only if the medium can get to it. :func:`visible_facets` keeps a facet
when, for at least one direction d of a given set with n . d > 0 (the facet faces d), the ray from
its centroid along d leaves the body without crossing another facet. Faces enclosed by the body (a
hub inside a closed tyre, the inner surface of a hollow rim) see out along no direction and are
dropped; every facet of a convex body that faces some direction of the set is kept. The directions
are the caller's (for a wheel: the directions of motion and penetration it meets over a turn,
:func:`terradyn.locomotion.steady3d.wheel_contact_mesh`); no facet is dropped by a rule about its
position.

The compiled kernel bins the facets once on a voxel grid and walks each ray through the voxels it
crosses; :func:`_visible_facets_reference` is the brute-force NumPy version the tests compare with.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError
from ._visibility_kernels import EDGE_SLACK as _EDGE
from .mesh import TriangleMesh

__all__ = ["visible_facets"]


def _directions(directions: ArrayLike) -> NDArray[np.float64]:
    d = np.asarray(directions, dtype=np.float64)
    if d.ndim == 1:
        d = d[None, :]
    if d.ndim != 2 or d.shape[1] != 3 or d.shape[0] == 0 or not np.all(np.isfinite(d)):
        raise InputError("directions", d.shape, "an array (D, 3) of finite, non-zero directions")
    norm = np.linalg.norm(d, axis=1)
    if not np.all(norm > 0.0):
        raise InputError("directions", "a zero vector", "non-zero directions")
    return np.ascontiguousarray(d / norm[:, None])


def _offset(mesh: TriangleMesh) -> float:
    span = float(np.ptp(mesh.vertices, axis=0).max())
    return 1e-7 * max(span, 1e-300)


def visible_facets(mesh: TriangleMesh, directions: ArrayLike, *, facing: float = 1e-9) -> NDArray[np.bool_]:
    """Mask (F,) of the facets that see out of ``mesh`` along at least one of ``directions`` (D, 3).

    A facet is tested along d only when n . d > ``facing`` [-]; zero-area facets are never visible.
    """
    if not isinstance(mesh, TriangleMesh):
        raise InputError("mesh", type(mesh).__name__, "a terradyn.geometry3d.TriangleMesh")
    from ._visibility_kernels import visible_facets_kernel

    d = _directions(directions)
    out = visible_facets_kernel(
        mesh.vertices, mesh.faces, mesh.centroids, mesh.normals, d, _offset(mesh), float(facing)
    )
    return np.asarray(out & (mesh.areas > 0.0))


def _visible_facets_reference(
    mesh: TriangleMesh, directions: ArrayLike, *, facing: float = 1e-9
) -> NDArray[np.bool_]:
    """:func:`visible_facets` by testing every ray against every facet (NumPy; small meshes only)."""
    d = _directions(directions)
    tri = mesh.vertices[mesh.faces]
    v0, e1, e2 = tri[:, 0], tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    out = np.zeros(mesh.facet_count, dtype=bool)
    origins = mesh.centroids + _offset(mesh) * mesh.normals
    for k in range(d.shape[0]):
        ray = d[k]
        p = np.cross(ray, e2)
        det = np.einsum("ij,ij->i", e1, p)
        ok = det != 0.0
        inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
        for i in np.nonzero((mesh.normals @ ray > facing) & ~out)[0]:
            s = origins[i] - v0
            u = np.einsum("ij,ij->i", s, p) * inv
            q = np.cross(s, e1)
            w = (q @ ray) * inv
            t = np.einsum("ij,ij->i", e2, q) * inv
            e = _EDGE
            hit = ok & (u >= -e) & (u <= 1.0 + e) & (w >= -e) & (u + w <= 1.0 + e) & (t > 0.0)
            hit[i] = False
            out[i] = not np.any(hit)
    return out & (mesh.areas > 0.0)
