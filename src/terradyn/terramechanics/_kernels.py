"""Numba kernels of the Wong-Reece wheel integrals, with their NumPy references.

Plain SI floats and arrays, no checks; the public layer is :mod:`terradyn.terramechanics.wong_reece`.
"""

from __future__ import annotations

import math
from functools import cache

import numba as nb
import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


# --------------------------------------------------------------------------------------------------
# Kernel: plain SI floats and arrays, no checks.
# --------------------------------------------------------------------------------------------------


@cache
def _gauss_legendre(node_count: int) -> tuple[FloatArray, FloatArray]:
    """Gauss-Legendre nodes mapped to [0, 1] and their weights (summing to 1)."""
    x, w = np.polynomial.legendre.leggauss(node_count)
    return 0.5 * (x + 1.0), 0.5 * w


_BISECTIONS = 64


def _breakpoints_reference(
    entry_angle: FloatArray, exit_angle: float, slip: float, theta_m_ratio: float
) -> FloatArray:
    """Sorted segment ends (M, 4): theta_2, theta_m, the sign change of j (or theta_m again), theta_1.

    j(theta) / r = (theta_1 - theta) - q (sin theta_1 - sin theta), q = 1 - s, vanishes at theta_1. For
    s >= 0 it has no other zero on the contact (sin is 1-Lipschitz). For s < 0 its sign just behind
    theta_1 is that of 1 - q cos theta_1; if j(theta_2) has the other sign, bisection finds where j
    changes sign, and the quadrature splits there (tau changes sign over a shear displacement ~ K).
    """
    t1 = np.asarray(entry_angle, dtype=np.float64)
    t2 = np.full_like(t1, exit_angle)
    tm = theta_m_ratio * t1
    q = 1.0 - slip
    zero = tm.copy()
    if slip < 0.0:
        right = np.where(1.0 - q * np.cos(t1) > 0.0, 1.0, -1.0)
        left = np.sign((t1 - t2) - q * (np.sin(t1) - np.sin(t2)))
        found = left * right < 0.0
        lo, hi = t2.copy(), t1.copy()
        for _ in range(_BISECTIONS):
            mid = 0.5 * (lo + hi)
            g = np.sign((t1 - mid) - q * (np.sin(t1) - np.sin(mid)))
            same = g == left
            lo = np.where(same, mid, lo)
            hi = np.where(same, hi, mid)
        zero = np.where(found, 0.5 * (lo + hi), tm)
    return np.sort(np.stack((t2, tm, zero, t1), axis=1), axis=1)


def _wong_reece_integrals_reference(
    entry_angle: FloatArray,
    exit_angle: float,
    radius: float,
    width: float,
    modulus: float,
    n: float,
    cohesion: float,
    tan_phi: float,
    shear_modulus: float,
    slip: float,
    theta_m_ratio: float,
    node_count: int,
) -> FloatArray:
    """Wong-Reece integrals at each entry angle (M,) [rad] -> (5, M): W, DP, T, thrust, resistance.

    NumPy reference of :func:`_wong_reece_integrals_kernel`. ``modulus`` is k = k_c / b + k_phi
    [N/m^(n+2)], ``theta_m_ratio`` is c1 + c2 s; forces in [N], the (motor) drive torque in [N m].
    Three Gauss-Legendre segments per entry angle, split at theta_m and where j changes sign.
    """
    u, w = _gauss_legendre(node_count)
    t1 = np.asarray(entry_angle, dtype=np.float64).reshape(-1)
    ends = _breakpoints_reference(t1, exit_angle, slip, theta_m_ratio)
    a, b = ends[:, :-1, None], ends[:, 1:, None]  # (M, 3, 1)
    theta = (a + u * (b - a)).reshape(t1.size, -1)  # (M, 3N)
    weights = (w * (b - a)).reshape(t1.size, -1)
    t1c = t1[:, None]
    tm = theta_m_ratio * t1c
    span = np.where(tm > exit_angle, tm - exit_angle, 1.0)
    mapped = t1c - (theta - exit_angle) * (t1c - tm) / span
    stress_angle = np.where(theta >= tm, theta, mapped)
    cos_t, sin_t = np.cos(theta), np.sin(theta)
    sigma = modulus * np.power(np.maximum(radius * (np.cos(stress_angle) - np.cos(t1c)), 0.0), n)
    j = radius * ((t1c - theta) - (1.0 - slip) * (np.sin(t1c) - sin_t))
    tau = np.sign(j) * (cohesion + sigma * tan_phi) * -np.expm1(-np.abs(j) / shear_modulus)
    rb = radius * width
    thrust = rb * np.sum(weights * tau * cos_t, axis=1)
    resistance = rb * np.sum(weights * sigma * sin_t, axis=1)
    out = np.empty((5, t1.size))
    out[0] = rb * np.sum(weights * (sigma * cos_t + tau * sin_t), axis=1)
    out[1] = thrust - resistance
    out[2] = radius * rb * np.sum(weights * tau, axis=1)
    out[3] = thrust
    out[4] = resistance
    return out


@nb.njit(cache=True, nogil=True)
def _shear_zero_kernel(t1: float, t2: float, q: float, fallback: float) -> float:
    """Angle in (theta_2, theta_1) where j changes sign (s < 0), else ``fallback``."""
    if q <= 1.0:
        return fallback
    right = 1.0 if 1.0 - q * math.cos(t1) > 0.0 else -1.0
    g2 = (t1 - t2) - q * (math.sin(t1) - math.sin(t2))
    left = 1.0 if g2 > 0.0 else (-1.0 if g2 < 0.0 else 0.0)
    if left * right >= 0.0:
        return fallback
    lo, hi = t2, t1
    for _ in range(_BISECTIONS):
        mid = 0.5 * (lo + hi)
        g = (t1 - mid) - q * (math.sin(t1) - math.sin(mid))
        sg = 1.0 if g > 0.0 else (-1.0 if g < 0.0 else 0.0)
        if sg == left:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


@nb.njit(cache=True, nogil=True)
def _wong_reece_integrals_kernel(
    entry_angle: FloatArray,
    exit_angle: float,
    radius: float,
    width: float,
    modulus: float,
    n: float,
    cohesion: float,
    tan_phi: float,
    shear_modulus: float,
    slip: float,
    theta_m_ratio: float,
    u: FloatArray,
    w: FloatArray,
) -> FloatArray:
    """Numba kernel of :func:`_wong_reece_integrals_reference` (same arguments; ``u``, ``w`` are the
    Gauss-Legendre nodes on [0, 1] and their weights)."""
    m = entry_angle.shape[0]
    out = np.zeros((5, m))
    q = 1.0 - slip
    rb = radius * width
    ends = np.empty(4)
    for i in range(m):
        t1 = entry_angle[i]
        tm = theta_m_ratio * t1
        cos1, sin1 = math.cos(t1), math.sin(t1)
        ends[0] = exit_angle
        ends[1] = tm
        ends[2] = _shear_zero_kernel(t1, exit_angle, q, tm)
        ends[3] = t1
        ends.sort()
        span = tm - exit_angle
        vertical = 0.0
        thrust = 0.0
        resistance = 0.0
        torque = 0.0
        for seg in range(3):
            a = ends[seg]
            length = ends[seg + 1] - a
            if length <= 0.0:
                continue
            for k in range(u.shape[0]):
                th = a + u[k] * length
                wt = w[k] * length
                if th >= tm:
                    sa = th
                else:
                    sa = t1 - (th - exit_angle) * (t1 - tm) / span
                base = radius * (math.cos(sa) - cos1)
                sigma = modulus * base**n if base > 0.0 else 0.0
                j = radius * ((t1 - th) - q * (sin1 - math.sin(th)))
                if j > 0.0:
                    tau = (cohesion + sigma * tan_phi) * -math.expm1(-j / shear_modulus)
                elif j < 0.0:
                    tau = -(cohesion + sigma * tan_phi) * -math.expm1(j / shear_modulus)
                else:
                    tau = 0.0
                ct, st = math.cos(th), math.sin(th)
                vertical += wt * (sigma * ct + tau * st)
                thrust += wt * tau * ct
                resistance += wt * sigma * st
                torque += wt * tau
        out[0, i] = rb * vertical
        out[1, i] = rb * (thrust - resistance)
        out[2, i] = radius * rb * torque
        out[3, i] = rb * thrust
        out[4, i] = rb * resistance
    return out


def _wong_reece_integrals_many(
    entry_angle: FloatArray,
    exit_angle: float,
    radius: float,
    width: float,
    modulus: float,
    n: float,
    cohesion: float,
    tan_phi: float,
    shear_modulus: float,
    slip: float,
    theta_m_ratio: float,
    node_count: int,
) -> FloatArray:
    """Compiled Wong-Reece integrals (5, M) at entry angles (M,); see the NumPy reference."""
    u, w = _gauss_legendre(node_count)
    angles = np.ascontiguousarray(entry_angle, dtype=np.float64).reshape(-1)
    f = float
    return _wong_reece_integrals_kernel(
        angles,
        f(exit_angle),
        f(radius),
        f(width),
        f(modulus),
        f(n),
        f(cohesion),
        f(tan_phi),
        f(shear_modulus),
        f(slip),
        f(theta_m_ratio),
        u,
        w,
    )


# --------------------------------------------------------------------------------------------------
# Results
# --------------------------------------------------------------------------------------------------
