"""Wheel meshes from CAD files: units, axle axis, centring on the axle, and a plausibility check.

A CAD wheel rarely comes in terradyn's body frame (metres, origin on the axle, axle along +y). This
module maps a mesh there:

1. units: coordinates times the unit's length in metres (``units="mm"`` for most CAD exports);
2. axle: the file axis the wheel turns about (x, y or z) becomes body y by a proper rotation (the
   file's +axle becomes body +y, the wheel's left; normals stay outward);
3. center: the axle position, either given (file units) or fitted: in the plane across the axle the
   algebraic least-squares circle through the outermost vertex of each 5 deg sector (refitted three
   times about the new center; the surface centroid when it agrees within 2 % of the radius), along
   the axle the middle of the mesh's extent;
4. check: the radius must lie in [1 mm, 5 m], the width in [0.1 mm, 10 m]; a fitted axle needs an
   outline across it that is round (outer radius varying by at most 25 % with angle; else the axle
   is probably another axis); a given centre (any wheel shape, round or not) must lie within 25 % of
   the radius of the mesh's surface centroid across the axle.

The fit reports the detected radius, width, center and roundness (:class:`WheelMeshFit`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import Enum
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError
from .mesh import TriangleMesh, load_mesh

__all__ = [
    "Axle",
    "MeshUnits",
    "WheelMeshFit",
    "fit_wheel_mesh",
    "load_wheel_mesh",
    "wheel_from_mesh",
]

#: plausible wheel sizes [m]
RADIUS_RANGE = (1e-3, 5.0)
WIDTH_RANGE = (1e-4, 10.0)
#: the outermost radius over any 5 deg sector may fall this fraction below the largest (grousers up to a
#: third of the rim radius; a square is 0.29, a wheel seen across a wrong axis typically over 0.4)
ROUNDNESS_LIMIT = 0.25
#: a given center may lie this fraction of the radius from the surface centroid
CENTER_LIMIT = 0.25


class MeshUnits(str, Enum):
    """Length unit of a mesh file's coordinates."""

    m = "m"
    cm = "cm"
    mm = "mm"

    @property
    def metres(self) -> float:
        return {"m": 1.0, "cm": 1e-2, "mm": 1e-3}[self.value]


class Axle(str, Enum):
    """File axis along which the wheel's axle lies."""

    x = "x"
    y = "y"
    z = "z"


# Proper rotations taking the file axle to body +y (rows: body axes in file coordinates).
_TO_BODY = {
    Axle.y: np.eye(3),
    Axle.z: np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]]),  # file z -> y, y -> -z
    Axle.x: np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]),  # file x -> y, y -> -x
}


@dataclass(frozen=True)
class WheelMeshFit:
    """What :func:`fit_wheel_mesh` found (lengths in metres, in the file's axes).

    radius_m : outer radius about the fitted axle [m]; width_m : extent along the axle [m];
    center_m : fitted axle center (3,) [m] in file axes (scaled to metres); axle : the file axis;
    roundness : 1 - (smallest) / (largest outermost radius over 72 angular sectors about the axle)
    [-]: 0 for a round wheel, about h / (r + h) with grousers of height h, near 1 across a wrong axis;
    facet_count.
    """

    radius_m: float
    width_m: float
    center_m: tuple[float, float, float]
    axle: str
    roundness: float
    facet_count: int

    def summary(self, units: MeshUnits | str = MeshUnits.m) -> str:
        """One line: detected radius, width, axle and center in ``units``."""
        u = MeshUnits(units)
        c = ", ".join(f"{v / u.metres:.6g}" for v in self.center_m)
        return (
            f"wheel mesh: radius {self.radius_m * 1e3:.4g} mm, width {self.width_m * 1e3:.4g} mm, "
            f"axle along file {self.axle}, center ({c}) {u.value}, {self.facet_count} facets"
        )


def _circle_fit(points: NDArray[np.float64]) -> tuple[float, float, float]:
    """Algebraic (Kasa) least-squares circle through 2D points: (cx, cy, radius)."""
    a = np.column_stack((2.0 * points, np.ones(points.shape[0])))
    b = np.einsum("ij,ij->i", points, points)
    sol, *_ = np.linalg.lstsq(a, b, rcond=None)
    cx, cy, c = sol
    return float(cx), float(cy), float(math.sqrt(max(c + cx * cx + cy * cy, 0.0)))


def _outline(
    pts: NDArray[np.float64], cx: float, cy: float, bins: int = 72
) -> tuple[NDArray[np.float64], float]:
    """The outermost point of each of ``bins`` angular sectors about (cx, cy) that holds a vertex, and
    the roundness 1 - (smallest sector radius) / (largest) over those [-] (1 if fewer than 8)."""
    d = pts - np.array([cx, cy])
    rho = np.hypot(d[:, 0], d[:, 1])
    sector = ((np.arctan2(d[:, 1], d[:, 0]) + math.pi) / (2.0 * math.pi) * bins).astype(np.int64) % bins
    order = np.lexsort((rho, sector))
    last = np.nonzero(np.diff(np.append(sector[order], bins)))[0]
    best = order[last]
    if best.size < 8:  # too few sectors hold a vertex to tell
        return pts[best], 1.0
    r = rho[best]
    return pts[best], float(1.0 - r.min() / max(r.max(), 1e-300))


def _axle(axle: Axle | str) -> Axle:
    try:
        return Axle(axle.strip().lower() if isinstance(axle, str) else axle)
    except ValueError:
        raise InputError("axle", axle, "one of x, y, z (the file axis the wheel turns about)") from None


def _units(units: MeshUnits | str) -> MeshUnits:
    try:
        return MeshUnits(units.strip().lower() if isinstance(units, str) else units)
    except ValueError:
        raise InputError("mesh_units", units, "one of m, cm, mm (the file's length unit)") from None


def fit_wheel_mesh(mesh: TriangleMesh, *, axle: Axle | str = Axle.y) -> WheelMeshFit:
    """Fit the axle of a wheel mesh (coordinates in metres) turning about the file ``axle``.

    The center across the axle is the least-squares circle through the outermost vertex of each 5 deg
    sector (so hubs and spokes do not bias it), replaced by the area-weighted surface centroid when
    that lies within 2 % of the radius of it (exact for any k-fold symmetric wheel); along the axle
    it is the middle of the mesh's extent. No plausibility check (see :func:`wheel_from_mesh`).
    """
    if not isinstance(mesh, TriangleMesh):
        raise InputError("mesh", type(mesh).__name__, "a terradyn.geometry3d.TriangleMesh")
    a = _axle(axle)
    k = "xyz".index(a.value)
    plane = [i for i in range(3) if i != k]
    v = mesh.vertices
    pts = v[:, plane]
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    cx, cy = 0.5 * (lo + hi)
    roundness = 1.0
    for _ in range(3):
        outer, roundness = _outline(pts, cx, cy)
        if outer.shape[0] < 3:
            break
        cx, cy, _ = _circle_fit(outer)
    outer, roundness = _outline(pts, cx, cy)
    radius = float(np.hypot(pts[:, 0] - cx, pts[:, 1] - cy).max())
    # The surface centroid lies exactly on the axle of any wheel with a k-fold symmetry (k >= 2), where
    # the sector fit is only close (odd lug counts); take it when it agrees with the fit.
    area = mesh.areas.sum()
    if area > 0.0:
        g = (mesh.centroids[:, plane] * mesh.areas[:, None]).sum(axis=0) / area
        if math.hypot(g[0] - cx, g[1] - cy) < 0.02 * radius:
            cx, cy = float(g[0]), float(g[1])
            outer, roundness = _outline(pts, cx, cy)
            radius = float(np.hypot(pts[:, 0] - cx, pts[:, 1] - cy).max())
    center = np.zeros(3)
    center[plane[0]], center[plane[1]] = cx, cy
    center[k] = 0.5 * (v[:, k].min() + v[:, k].max())
    width = float(v[:, k].max() - v[:, k].min())
    return WheelMeshFit(
        radius_m=radius, width_m=width, center_m=(float(center[0]), float(center[1]), float(center[2])),
        axle=a.value, roundness=roundness, facet_count=mesh.facet_count,
    )  # fmt: skip


def wheel_from_mesh(
    mesh: TriangleMesh,
    *,
    units: MeshUnits | str = MeshUnits.m,
    axle: Axle | str = Axle.y,
    center: ArrayLike | None = None,
    check: bool = True,
) -> tuple[TriangleMesh, WheelMeshFit]:
    """The wheel in terradyn's body frame (metres, origin on the axle, axle along +y) and its fit.

    Parameters
    ----------
    mesh : TriangleMesh
        The wheel in file coordinates (in ``units``).
    units : "m", "cm" or "mm"
        Length unit of the coordinates.
    axle : "x", "y" or "z"
        File axis the wheel turns about; the file's +axle becomes body +y.
    center : (3,) array, optional
        Axle center in file coordinates and ``units``; default fitted (:func:`fit_wheel_mesh`).
    check : bool
        Refuse an implausible wheel (module notes); the error names ``mesh_units``, ``axle`` or
        ``center`` as the likely culprit.

    Returns
    -------
    (TriangleMesh, WheelMeshFit)
        The placed mesh, and the fit (in metres, file axes).
    """
    u, a = _units(units), _axle(axle)
    scaled = mesh.scaled(u.metres) if u is not MeshUnits.m else mesh
    fit = fit_wheel_mesh(scaled, axle=a)
    if center is None:
        c = np.asarray(fit.center_m)
    else:
        c = np.asarray(center, dtype=np.float64) * u.metres
        if c.shape != (3,) or not np.all(np.isfinite(c)):
            raise InputError("center", center, "three finite coordinates X,Y,Z in the mesh's units")
    if check:
        _check_plausible(fit, u, a, None if center is None else c, center, scaled)
    rot = _TO_BODY[a]
    placed = TriangleMesh((scaled.vertices - c) @ rot.T, scaled.faces)
    return placed, fit


def _check_plausible(
    fit: WheelMeshFit,
    units: MeshUnits,
    axle: Axle,
    center: NDArray[np.float64] | None,
    given: object,
    mesh: TriangleMesh,
) -> None:
    r, w = fit.radius_m, fit.width_m
    lo, hi = RADIUS_RANGE
    if not lo <= r <= hi:
        other = "mm" if r > hi else "m"
        raise InputError(
            "mesh_units", units.value,
            f"units giving a wheel radius in [{lo * 1e3:g} mm, {hi:g} m] (it would be {r:.4g} m)",
            f"is the file in {other}? (radius from the outermost vertices about the {axle.value} axis)",
        )  # fmt: skip
    if not WIDTH_RANGE[0] <= w <= WIDTH_RANGE[1]:
        raise InputError(
            "axle", axle.value, f"the axis along which the wheel is {WIDTH_RANGE[0] * 1e3:g} mm to "
            f"{WIDTH_RANGE[1]:g} m wide (it is {w:.4g} m along {axle.value})",
        )  # fmt: skip
    k = "xyz".index(axle.value)
    if center is None:
        if fit.roundness > ROUNDNESS_LIMIT:
            raise InputError(
                "axle", axle.value,
                f"the axis the wheel turns about (across {axle.value} its outline is not round: the "
                f"outer radius varies by {fit.roundness:.0%} with angle, at most {ROUNDNESS_LIMIT:.0%})",
                "give the axle axis with --axle x|y|z; a wheel that is not round needs --center too",
            )  # fmt: skip
        return
    # A given axle: it must pass near the surface centroid (every wheel turning about its axle has it
    # there, round or not); the fitted radius is about the given axle here.
    plane = [i for i in range(3) if i != k]
    area = float(mesh.areas.sum())
    g = (mesh.centroids * mesh.areas[:, None]).sum(axis=0) / max(area, 1e-300)
    rho = np.hypot(
        mesh.vertices[:, plane[0]] - center[plane[0]], mesh.vertices[:, plane[1]] - center[plane[1]]
    )
    radius = float(rho.max())
    dist = float(np.hypot(g[plane[0]] - center[plane[0]], g[plane[1]] - center[plane[1]]))
    if not RADIUS_RANGE[0] <= radius <= RADIUS_RANGE[1] or dist > CENTER_LIMIT * radius:
        cg = ", ".join(f"{v / units.metres:.6g}" for v in g)
        raise InputError(
            "center", given,
            f"an axle within {CENTER_LIMIT:.0%} of the wheel's radius from its surface centroid "
            f"({cg}) {units.value}; it is {dist / max(radius, 1e-300):.2f} radii away",
            "omit it to centre on the fitted axle",
        )  # fmt: skip


def load_wheel_mesh(
    path: str | Path,
    *,
    units: MeshUnits | str = MeshUnits.m,
    axle: Axle | str = Axle.y,
    center: ArrayLike | None = None,
    allow_open: bool = False,
    check: bool = True,
) -> tuple[TriangleMesh, WheelMeshFit]:
    """:func:`load_mesh` then :func:`wheel_from_mesh`: a CAD wheel file in terradyn's body frame."""
    return wheel_from_mesh(
        load_mesh(path, allow_open=allow_open), units=units, axle=axle, center=center, check=check
    )
