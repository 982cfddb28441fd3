"""Numba primitives shared by the MPM step kernels: B-spline weights, Coulomb/wall velocity rules."""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__: list[str] = []

_MASS_EPS = 1e-14


@njit(cache=True, fastmath=True, inline="always")
def _weights(xi: float, w: np.ndarray, dw: np.ndarray, inv_h: float) -> tuple[int, float]:
    """Quadratic B-spline weights of the 3 nodes from ``base``; returns (base, fractional offset)."""
    base = int(xi - 0.5)
    f = xi - base
    a = 1.5 - f
    b = f - 1.0
    c = f - 0.5
    w[0] = 0.5 * a * a
    w[1] = 0.75 - b * b
    w[2] = 0.5 * c * c
    dw[0] = -a * inv_h
    dw[1] = -2.0 * b * inv_h
    dw[2] = c * inv_h
    return base, f


@njit(cache=True, fastmath=True, inline="always")
def _coulomb(vx, vz, nx, nz, mu):
    """Remove an approaching normal velocity (v.n < 0) and apply Coulomb friction to the tangential part."""
    vn = vx * nx + vz * nz
    if vn >= 0.0:
        return vx, vz
    tx = vx - vn * nx
    tz = vz - vn * nz
    vt = math.sqrt(tx * tx + tz * tz)
    if mu < 0.0 or vt <= -mu * vn:  # mu < 0 means no-slip
        return 0.0, 0.0
    f = 1.0 + mu * vn / vt
    return tx * f, tz * f


@njit(cache=True, fastmath=True, inline="always")
def _wall(vx, vz, nx, nz, kind, mu):
    if kind == 1:
        return 0.0, 0.0
    if kind == 2:
        return _coulomb(vx, vz, nx, nz, mu)
    vn = vx * nx + vz * nz
    if vn < 0.0:
        return vx - vn * nx, vz - vn * nz
    return vx, vz


@njit(cache=True, fastmath=True, inline="always")
def _node_velocity(m, px, pz, dt, gravity, keep, i, j, nx, pad, wall_kind, wall_mu):
    """Velocity [m/s] of a grid field of mass ``m`` and momentum ``(px, pz)`` at node (i, j) after
    gravity, damping (``keep``) and the walls."""
    vx = (px / m) * keep
    vz = (pz / m - dt * gravity) * keep
    if i <= pad:
        vx, vz = _wall(vx, vz, 1.0, 0.0, wall_kind[0], wall_mu[0])
    if i >= nx - 1 - pad:
        vx, vz = _wall(vx, vz, -1.0, 0.0, wall_kind[1], wall_mu[1])
    if j <= pad:
        vx, vz = _wall(vx, vz, 0.0, 1.0, wall_kind[2], wall_mu[2])
    return vx, vz
