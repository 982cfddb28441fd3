"""Closed boundaries made of straight and circular segments, and their discretisation.

A boundary loop is traversed counter-clockwise in the x-z view (x right, z up), so the outward normal of
a segment with unit tangent (t_x, t_z) is (t_z, -t_x). A zero-thickness plate is the degenerate loop
that runs along the plate and back, which gives both faces.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError

__all__ = ["Arc", "Line", "Segment", "discretize_loops", "loop_polygon"]


@dataclass(frozen=True, slots=True)
class Line:
    """Straight segment from ``start`` to ``end`` (x, z) [m]."""

    start: tuple[float, float]
    end: tuple[float, float]

    @property
    def length(self) -> float:
        return math.hypot(self.end[0] - self.start[0], self.end[1] - self.start[1])

    def elements(self, size: float) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        length = self.length
        n = max(1, math.ceil(length / size - 1e-9))
        t = (np.arange(n) + 0.5) / n
        p0, p1 = np.asarray(self.start), np.asarray(self.end)
        mid = p0 + t[:, None] * (p1 - p0)
        tx, tz = (p1 - p0) / length
        nrm = np.tile([tz, -tx], (n, 1))
        return mid, nrm, np.full(n, length / n)

    def points(self, size: float) -> NDArray[np.float64]:
        return np.asarray([self.start])


@dataclass(frozen=True, slots=True)
class Arc:
    """Circular arc of ``radius`` [m] about ``center`` from angle ``start`` to ``end`` [rad].

    Angles are measured from +x towards +z (counter-clockwise in view). ``end > start`` runs
    counter-clockwise (convex side out: normal points away from the centre); ``end < start`` runs
    clockwise (concave: normal points to the centre).
    """

    center: tuple[float, float]
    radius: float
    start: float
    end: float

    @property
    def length(self) -> float:
        return self.radius * abs(self.end - self.start)

    def elements(self, size: float) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        n = max(1, math.ceil(self.length / size - 1e-9))
        phi = self.start + (np.arange(n) + 0.5) / n * (self.end - self.start)
        radial = np.column_stack((np.cos(phi), np.sin(phi)))
        mid = np.asarray(self.center) + self.radius * radial
        sign = 1.0 if self.end > self.start else -1.0
        return mid, sign * radial, np.full(n, self.length / n)

    def points(self, size: float) -> NDArray[np.float64]:
        n = max(1, math.ceil(self.length / size - 1e-9))
        phi = self.start + np.arange(n) / n * (self.end - self.start)
        return np.asarray(self.center) + self.radius * np.column_stack((np.cos(phi), np.sin(phi)))


Segment = Line | Arc


def discretize_loops(
    loops: list[list[Segment]], size: float
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.int64]]:
    """Elements (midpoints, normals, lengths, loop index) of closed loops, each at most ``size`` long."""
    if not (size > 0 and math.isfinite(size)):
        raise InputError("element_size", size, "a length > 0 [m]")
    mids, nrms, lens, parts = [], [], [], []
    for k, loop in enumerate(loops):
        for seg in loop:
            if seg.length <= 0:
                continue
            m, n, ln = seg.elements(size)
            mids.append(m)
            nrms.append(n)
            lens.append(ln)
            parts.append(np.full(len(ln), k, dtype=np.int64))
    return np.concatenate(mids), np.concatenate(nrms), np.concatenate(lens), np.concatenate(parts)


def loop_polygon(loop: list[Segment], size: float) -> NDArray[np.float64]:
    """Vertices (M, 2) [m] of a closed loop, arcs sampled every ``size`` (for plots and inside tests)."""
    return np.concatenate([seg.points(size) for seg in loop if seg.length > 0])
