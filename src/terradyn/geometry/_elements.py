"""Discretised body surfaces: the input of every surface force law."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError, check_length

__all__ = ["SurfaceElements"]


@dataclass(frozen=True, eq=False)
class SurfaceElements:
    """Straight surface elements of a plane body, in the body frame.

    Attributes
    ----------
    midpoints : ndarray, shape (N, 2)
        Element midpoints (x, z) [m] relative to the body origin.
    normals : ndarray, shape (N, 2)
        Outward unit normals (n_x, n_z) [-].
    lengths : ndarray, shape (N,)
        Element lengths in the plane [m].
    width : float
        Out-of-plane width of the body [m]; element area = length * width.
    part : ndarray of int, shape (N,)
        Index of the body part each element belongs to (composites, faces); 0 for simple bodies.
    """

    midpoints: NDArray[np.float64]
    normals: NDArray[np.float64]
    lengths: NDArray[np.float64]
    width: float
    part: NDArray[np.int64] | None = None

    def __post_init__(self) -> None:
        mid = np.ascontiguousarray(self.midpoints, dtype=np.float64)
        nrm = np.ascontiguousarray(self.normals, dtype=np.float64)
        lng = np.ascontiguousarray(self.lengths, dtype=np.float64)
        if mid.ndim != 2 or mid.shape[1] != 2:
            raise InputError("elements.midpoints", mid.shape, "an array of shape (N, 2)")
        n = mid.shape[0]
        if nrm.shape != (n, 2):
            raise InputError("elements.normals", nrm.shape, f"an array of shape ({n}, 2)")
        if lng.shape != (n,):
            raise InputError("elements.lengths", lng.shape, f"an array of shape ({n},)")
        if not (np.all(np.isfinite(mid)) and np.all(np.isfinite(nrm)) and np.all(np.isfinite(lng))):
            raise InputError("elements", "non-finite values", "finite midpoints, normals and lengths")
        if n and np.any(lng <= 0):
            raise InputError("elements.lengths", float(lng.min()), "lengths > 0")
        if n and np.max(np.abs(np.hypot(nrm[:, 0], nrm[:, 1]) - 1.0)) > 1e-9:
            raise InputError("elements.normals", "non-unit vectors", "unit outward normals")
        check_length("width", self.width)
        part = (
            np.zeros(n, dtype=np.int64)
            if self.part is None
            else np.ascontiguousarray(self.part, dtype=np.int64)
        )
        if part.shape != (n,):
            raise InputError("elements.part", part.shape, f"an array of shape ({n},)")
        for arr in (mid, nrm, lng, part):
            arr.setflags(write=False)
        object.__setattr__(self, "midpoints", mid)
        object.__setattr__(self, "normals", nrm)
        object.__setattr__(self, "lengths", lng)
        object.__setattr__(self, "width", float(self.width))
        object.__setattr__(self, "part", part)

    @property
    def element_count(self) -> int:
        return int(self.lengths.shape[0])

    @property
    def areas(self) -> NDArray[np.float64]:
        """Element areas [m^2] (length * width)."""
        return self.lengths * self.width

    @property
    def perimeter(self) -> float:
        """Total element length [m]."""
        return float(self.lengths.sum())

    def with_width(self, width: float) -> SurfaceElements:
        """The same elements with another out-of-plane width [m]."""
        return SurfaceElements(self.midpoints, self.normals, self.lengths, width, self.part)

    def shifted(self, dx: float, dz: float) -> SurfaceElements:
        """Elements moved by (dx, dz) [m] in the body frame (the origin stays put)."""
        return SurfaceElements(
            self.midpoints + np.array([dx, dz]), self.normals, self.lengths, self.width, self.part
        )

    def rotated(self, theta: float) -> SurfaceElements:
        """Elements rotated by ``theta`` [rad] about +y around the body origin (clockwise in view)."""
        c, s = np.cos(theta), np.sin(theta)
        rot = np.array([[c, s], [-s, c]])
        return SurfaceElements(
            self.midpoints @ rot.T, self.normals @ rot.T, self.lengths, self.width, self.part
        )

    @staticmethod
    def concatenate(items: list[SurfaceElements]) -> SurfaceElements:
        """Join element sets of the same width; parts are renumbered to stay distinct."""
        if not items:
            raise InputError("elements", "[]", "at least one element set")
        widths = {round(e.width, 12) for e in items}
        if len(widths) != 1:
            raise InputError("width", sorted(widths), "the same width for every part of a composite")
        parts, offset = [], 0
        for e in items:
            assert e.part is not None
            parts.append(e.part + offset)
            offset += int(e.part.max()) + 1 if e.element_count else 1
        return SurfaceElements(
            np.concatenate([e.midpoints for e in items]),
            np.concatenate([e.normals for e in items]),
            np.concatenate([e.lengths for e in items]),
            items[0].width,
            np.concatenate(parts),
        )
