"""Placement of a run's moving window (see :class:`~terradyn.mpm.solver.Runner`): where the window's grid
lies in the bed, and how far ahead of a moving body grains are heaped (the bow wave it must clear)."""

from __future__ import annotations

import math

import numpy as np

__all__ = ["heap_toe", "window_cells"]


def heap_toe(pos: np.ndarray, vx: float, x_body: float) -> float | None:
    """x [m] of the farthest grain above the free surface (z > 0) ahead of ``x_body`` in the direction
    of ``vx`` (grain positions ``pos`` (n, 2)), or None (``vx`` is 0, or nothing is heaped ahead)."""
    if vx == 0.0:
        return None
    x, z = pos[:, 0], pos[:, 1]
    ahead = (z > 0.0) & ((x - x_body) * vx > 0.0)
    if not np.any(ahead):
        return None
    return float(np.max(x[ahead]) if vx > 0.0 else np.min(x[ahead]))


def window_cells(
    x_left: float, width: float, h: float, window: float, x_body: float, toe: float | None, clearance: float
) -> tuple[int, int]:
    """First and last cell index (left, right) of a window of ``window`` [m] centred on ``x_body`` to the
    nearest cell inside the bed [x_left, x_left + width], its leading edge moved on to keep
    ``clearance`` [m] beyond the heap's ``toe`` (ahead of the body on the toe's side)."""
    cells = math.ceil(window / h - 1e-9)
    first = round(x_left / h)
    end = first + round(width / h)
    left = min(max(round(x_body / h - 0.5 * cells), first), end - cells)
    right = left + cells
    if toe is not None and clearance > 0.0:
        if toe > x_body:
            right = max(right, min(end, math.ceil((toe + clearance) / h - 1e-9)))
        else:
            left = min(left, max(first, math.floor((toe - clearance) / h + 1e-9)))
    return left, right
