"""Steady wheel states for any twist: load control (root-find the axle height) and sinkage control.

The library's steady solvers (:func:`terradyn.locomotion.wheel_steady`, ``wheel_steady_3d``) take the
slip ``s = 1 - V/(omega r)`` and need omega > 0; a rig also runs locked wheels (omega = 0), skids
beyond ``V = 2 omega r`` and slip angles of 90 deg. These solvers take the twist itself (axle velocity
and spin) and a function giving the period-averaged wrench at axle heights, so they serve every terrain
model, 2D and 3D. Quasi-static models depend only on the direction of the velocities, not their size.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from ..errors import SolverError

__all__ = ["solve_load", "state_at_height"]

#: mean wrench at axle heights: heights (H,) [m] -> (H, K) with the vertical force in column ``vertical``
WrenchFunction = Callable[[NDArray[np.float64]], NDArray[np.float64]]

_SCAN = 17


def solve_load(
    mean_wrench: WrenchFunction, vertical: int, load: float, low: float, high: float, what: str
) -> float:
    """Axle height [m] in [low, high] at which the period-mean vertical force equals ``load`` [N].

    ``low`` puts the axle at the surface (deepest accepted state), at ``high`` the wheel just touches.
    Raises SolverError when the medium cannot carry the load or the force is not monotonic in height.
    """
    grid = np.linspace(low, high, _SCAN)
    fz = mean_wrench(grid)[:, vertical]
    if fz[0] < load:
        raise SolverError(
            f"{what}: the medium carries at most {fz[0]:.4g} N before the axle reaches the surface, "
            f"less than the load {load:.4g} N"
        )
    below = np.nonzero(fz < load)[0]
    if below.size == 0:
        raise SolverError(f"{what}: the wheel carries the load with no contact; check its geometry")
    j = int(below[0])
    if np.any(fz[j:] >= load):
        raise SolverError(f"{what}: vertical force is not monotonic in sinkage; no unique sinkage")
    from scipy.optimize import brentq

    def residual(z: float) -> float:
        return float(mean_wrench(np.array([z]))[0, vertical]) - load

    span = max(high - low, 1e-12)
    return float(brentq(residual, grid[j - 1], grid[j], xtol=1e-12 * span, rtol=1e-13, maxiter=200))


def state_at_height(
    phase_wrench: Callable[[float], NDArray[np.float64]],
    lowest: NDArray[np.float64],
    height: float,
    surface: float,
) -> tuple[NDArray[np.float64], float]:
    """(mean wrench over the phases, mean sinkage [m]) at one axle height; ``phase_wrench(z)`` gives
    (P, K) and ``lowest`` (P,) the lowest body-frame z of each phase relative to the axle [m]."""
    w = phase_wrench(height)
    sink = np.maximum(surface - (height + lowest), 0.0)
    return w.mean(axis=0), float(sink.mean())
