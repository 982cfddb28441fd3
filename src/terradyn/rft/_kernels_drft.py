"""Numba kernels of plane dynamic RFT (DRFT; Agarwal, Karsai, Goldman & Kamrin 2021).

Plain functions of NumPy arrays and floats in SI, same layout as :mod:`terradyn.rft._kernels`:
``mid``, ``nrm`` (N, 2) body-frame element midpoints [m] and outward unit normals [-]; ``lengths``
(N,) [m]; ``width`` [m]; ``coeffs`` (9,) Li coefficients in the order A00, A10, B01, B11, Bm11, C01,
C11, Cm11, D10 [-]; ``scale`` [N/m^3]; pose (x [m], z [m], theta [rad] about +y); twist (vx [m/s],
vz [m/s], omega [rad/s] about +y).

DRFT traction on a leading element (n . v > 0) below its effective free surface::

    t = alpha(beta, gamma) * depth_eff - n * lam_rho * v_n**2

``lam_rho`` = lambda * rho [kg/m^3] and ``v_n = n . v`` [m/s]. ``drop`` [m] is the structural
correction: elements in the rear half of the loaded contact arc (seen from the body origin, split at
the mid-angle of the arc) see the free surface lowered by ``drop``. The loaded arc is that of plain RFT
(leading elements below the undisturbed ``surface``). With ``lam_rho = 0`` and ``drop = 0`` the kernel
performs the arithmetic of :func:`terradyn.rft._kernels.rft_wrench_kernel`, leading-edge share
included (:data:`terradyn.rft.li2013.LEADING_BAND`).

The NumPy reference is :func:`terradyn.rft.drft.drft_element_forces`.

References
----------
S. Agarwal, A. Karsai, D. I. Goldman, K. Kamrin, "Surprising simplicity in the modeling of dynamic
granular intrusion", Sci. Adv. 7, eabe0631 (2021). doi:10.1126/sciadv.abe0631
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from ._kernels import _HALF_INV_BAND, _SKIP, li2013_alpha_unit
from .li2013 import MIN_SPEED

__all__ = [
    "SPLIT_TIE",
    "body_angles_kernel",
    "drft_wrench_kernel",
    "drft_wrench_smooth_kernel",
    "pseudo_angle",
]

# An element exactly at the mid-angle of the contact arc (common: uniformly spaced elements) belongs to
# the front half; this margin [rad, or pseudo-angle units] keeps rounding from deciding.
SPLIT_TIE = 1e-9


@nb.njit(cache=True, fastmath=True, nogil=True)
def pseudo_angle(a: float, b: float) -> float:
    """A trig-free number in [-2, 2] increasing with ``atan2(a, b)`` over (-pi, pi] ("diamond angle")."""
    d = abs(a) + abs(b)
    if d == 0.0:
        return 0.0
    if b >= 0.0:
        return a / d
    if a >= 0.0:
        return 2.0 - a / d
    return -2.0 - a / d


@nb.njit(cache=True, fastmath=True, nogil=True, inline="always")
def _leading_fraction(nx, nz, vn, ex, ez, band):
    """Share [0, 1] of an element's force under the leading-edge rule (``band`` 0) or its odd smoothing.

    ``band`` 0: the rule of plane RFT, ``clip(1/2 + n . v / (2 |v| LEADING_BAND), 0, 1)``, with the
    arithmetic of :func:`terradyn.rft._kernels.rft_wrench_kernel`.
    """
    if band <= 0.0:
        big = max(abs(ex), abs(ez))
        if big < MIN_SPEED or vn <= _SKIP * big:
            return 0.0
        ux, uz = ex / big, ez / big
        inv = 1.0 / math.sqrt(ux * ux + uz * uz)
        return min(1.0, max(0.0, 0.5 + (nx * (ux * inv) - nz * (-uz * inv)) * _HALF_INV_BAND))
    edge2 = band * band * (ex * ex + ez * ez)
    if vn * vn >= edge2:
        return 1.0 if vn > 0.0 else 0.0
    return 0.5 + 0.5 * vn / math.sqrt(edge2)


@nb.njit(cache=True, fastmath=True, nogil=True, inline="always")
def _element_force(coeffs, nx, nz, ex, ez, vn, depth, length, width, scale, lam_rho):
    """(F_x, F_z) [N] of one active element (the arithmetic of the RFT kernel, plus inertia)."""
    # Speeds below MIN_SPEED count as rest (as in the RFT kernel): no direction, no load.
    big = max(abs(ex), abs(ez))
    if big < MIN_SPEED:
        return 0.0, 0.0
    ux, uz = ex / big, ez / big
    inv = 1.0 / math.sqrt(ux * ux + uz * uz)
    cg = ux * inv
    sg = -uz * inv
    ax, az = li2013_alpha_unit(coeffs, nx, nz, cg, sg)
    w = scale * depth * length * width
    f_x = -ax * w
    f_z = az * w
    if lam_rho > 0.0 and vn > 0.0:
        p = lam_rho * vn * vn * length * width
        f_x -= nx * p
        f_z -= nz * p
    return f_x, f_z


@nb.njit(cache=True, fastmath=True, nogil=True)
def drft_wrench_kernel(
    mid: np.ndarray,
    nrm: np.ndarray,
    lengths: np.ndarray,
    width: float,
    x: float,
    z: float,
    theta: float,
    vx: float,
    vz: float,
    omega: float,
    coeffs: np.ndarray,
    scale: float,
    surface: float,
    about_x: float,
    about_z: float,
    lam_rho: float,
    drop: float,
    band: float,
) -> tuple[float, float, float]:
    """Soil wrench (F_x [N], F_z [N], torque about +y [N m] about (about_x, about_z)) of DRFT.

    ``lam_rho`` [kg/m^3] scales the inertial term; ``drop`` [m] >= 0 lowers the free surface for the
    rear half of the loaded contact arc (0: no structural correction). ``band`` [-] >= 0 smooths the
    model for implicit time stepping (0: the rules of quasi-static RFT, exactly):

    * leading edge: with ``band`` 0 the rule of :func:`terradyn.rft._kernels.rft_wrench_kernel`
      (share ``clip(1/2 + n . v / (2 |v| LEADING_BAND), 0, 1)``); otherwise an element with
      ``n . v / |v|`` in [-band, band] carries the fraction ``1/2 + n . v / (2 band |v|)`` of its force
      (odd about the switch: sums over many elements change at second order in ``band``);
    * structural correction: each loaded element extends the contact arc by its angular size
      ``l / |r|`` times ``min(1, depth / (l |n_x|))`` (its share of its own vertical extent), so the
      arc ends move continuously as elements enter, and elements within half their angular size of
      the mid-angle see a surface lowered by the matching fraction of ``drop``.
    """
    if drop > 0.0 and band > 0.0:
        ang, size = body_angles_kernel(mid, lengths)
        return drft_wrench_smooth_kernel(
            mid,
            nrm,
            lengths,
            ang,
            size,
            width,
            x,
            z,
            theta,
            vx,
            vz,
            omega,
            coeffs,
            scale,
            surface,
            about_x,
            about_z,
            lam_rho,
            drop,
            band,
        )
    if drop > 0.0:
        return _drft_wrench_split(
            mid,
            nrm,
            lengths,
            width,
            x,
            z,
            theta,
            vx,
            vz,
            omega,
            coeffs,
            scale,
            surface,
            about_x,
            about_z,
            lam_rho,
            drop,
            band,
        )
    c = math.cos(theta)
    s = math.sin(theta)
    fx = 0.0
    fz = 0.0
    ty = 0.0
    for i in range(lengths.shape[0]):
        rx = c * mid[i, 0] + s * mid[i, 1]
        rz = -s * mid[i, 0] + c * mid[i, 1]
        depth = surface - (z + rz)
        if depth <= 0.0:
            continue
        ex = vx + omega * rz
        ez = vz - omega * rx
        nx = c * nrm[i, 0] + s * nrm[i, 1]
        nz = -s * nrm[i, 0] + c * nrm[i, 1]
        vn = nx * ex + nz * ez
        lead = _leading_fraction(nx, nz, vn, ex, ez, band)
        if lead <= 0.0:
            continue
        f_x, f_z = _element_force(coeffs, nx, nz, ex, ez, vn, depth, lengths[i], width, scale, lam_rho)
        if lead < 1.0:
            f_x *= lead
            f_z *= lead
        fx += f_x
        fz += f_z
        ty += (z + rz - about_z) * f_x - (x + rx - about_x) * f_z
    return fx, fz, ty


@nb.njit(cache=True, fastmath=True, nogil=True)
def _drft_wrench_split(
    mid,
    nrm,
    lengths,
    width,
    x,
    z,
    theta,
    vx,
    vz,
    omega,
    coeffs,
    scale,
    surface,
    about_x,
    about_z,
    lam_rho,
    drop,
    band,
):
    """:func:`drft_wrench_kernel` with the structural correction (``drop`` > 0).

    Pass 1 collects the loaded elements (leading, below the undisturbed surface) and the ends of their
    arc; pass 2 sums over them with the rear half of the arc seen below ``surface - drop``.
    """
    n = lengths.shape[0]
    keep = np.empty(n, dtype=np.int64)
    angle = np.empty(n)
    c = math.cos(theta)
    s = math.sin(theta)
    lo = 10.0  # pseudo-angles lie in [-2, 2]; finite sentinels (fastmath assumes no infinities)
    hi = -10.0
    lo_x = lo_z = hi_x = hi_z = 0.0
    count = 0
    for i in range(n):
        rx = c * mid[i, 0] + s * mid[i, 1]
        rz = -s * mid[i, 0] + c * mid[i, 1]
        depth = surface - (z + rz)
        if depth <= 0.0:
            continue
        ex = vx + omega * rz
        ez = vz - omega * rx
        nx = c * nrm[i, 0] + s * nrm[i, 1]
        nz = -s * nrm[i, 0] + c * nrm[i, 1]
        vn = nx * ex + nz * ez
        if _leading_fraction(nx, nz, vn, ex, ez, band) <= 0.0:
            continue
        p = pseudo_angle(rx, -rz)
        if p < lo:
            lo, lo_x, lo_z = p, rx, rz
        if p > hi:
            hi, hi_x, hi_z = p, rx, rz
        keep[count] = i
        angle[count] = p
        count += 1
    fx = 0.0
    fz = 0.0
    ty = 0.0
    if count == 0:
        return fx, fz, ty
    phi = 0.5 * (math.atan2(lo_x, -lo_z) + math.atan2(hi_x, -hi_z))
    split = pseudo_angle(math.sin(phi), math.cos(phi)) - SPLIT_TIE
    for j in range(count):
        i = keep[j]
        rx = c * mid[i, 0] + s * mid[i, 1]
        rz = -s * mid[i, 0] + c * mid[i, 1]
        ex = vx + omega * rz
        ez = vz - omega * rx
        nx = c * nrm[i, 0] + s * nrm[i, 1]
        nz = -s * nrm[i, 0] + c * nrm[i, 1]
        vn = nx * ex + nz * ez
        depth = surface - (z + rz)
        if angle[j] < split:
            depth -= drop
            if depth <= 0.0:
                continue
        f_x, f_z = _element_force(coeffs, nx, nz, ex, ez, vn, depth, lengths[i], width, scale, lam_rho)
        lead = _leading_fraction(nx, nz, vn, ex, ez, band)
        if lead < 1.0:
            f_x *= lead
            f_z *= lead
        fx += f_x
        fz += f_z
        ty += (z + rz - about_z) * f_x - (x + rx - about_x) * f_z
    return fx, fz, ty


@nb.njit(cache=True, fastmath=True, nogil=True)
def body_angles_kernel(mid: np.ndarray, lengths: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Body-frame angles ``atan2(p_x, -p_z)`` [rad] of the midpoints and angular sizes ``l / |p|`` [rad].

    At a rotation theta the world angle (from the downward vertical, + front) is ``angle - theta``.
    """
    n = lengths.shape[0]
    ang = np.empty(n)
    size = np.empty(n)
    for i in range(n):
        ang[i] = math.atan2(mid[i, 0], -mid[i, 1])
        rad = math.sqrt(mid[i, 0] * mid[i, 0] + mid[i, 1] * mid[i, 1])
        size[i] = lengths[i] / rad if rad > 0.0 else 0.0
    return ang, size


@nb.njit(cache=True, fastmath=True, nogil=True)
def drft_wrench_smooth_kernel(
    mid: np.ndarray,
    nrm: np.ndarray,
    lengths: np.ndarray,
    ang: np.ndarray,
    size: np.ndarray,
    width: float,
    x: float,
    z: float,
    theta: float,
    vx: float,
    vz: float,
    omega: float,
    coeffs: np.ndarray,
    scale: float,
    surface: float,
    about_x: float,
    about_z: float,
    lam_rho: float,
    drop: float,
    band: float,
) -> tuple[float, float, float]:
    """:func:`drft_wrench_kernel` with ``drop`` > 0 and ``band`` > 0, given :func:`body_angles_kernel`.

    ``ang``, ``size`` (N,) [rad] are the body-frame element angles and angular sizes (precomputed once
    per body by the time integrator).
    """
    n = lengths.shape[0]
    keep = np.empty(n, dtype=np.int64)
    angle = np.empty(n)
    c = math.cos(theta)
    s = math.sin(theta)
    lo = 10.0  # angles lie in [-pi, pi]; finite sentinels (fastmath assumes no infinities)
    hi = -10.0
    count = 0
    for i in range(n):
        rx = c * mid[i, 0] + s * mid[i, 1]
        rz = -s * mid[i, 0] + c * mid[i, 1]
        depth = surface - (z + rz)
        if depth <= 0.0:
            continue
        ex = vx + omega * rz
        ez = vz - omega * rx
        nx = c * nrm[i, 0] + s * nrm[i, 1]
        nz = -s * nrm[i, 0] + c * nrm[i, 1]
        lead = _leading_fraction(nx, nz, nx * ex + nz * ez, ex, ez, band)
        if lead <= 0.0:
            continue
        phi = ang[i] - theta
        phi -= 2.0 * math.pi * math.floor((phi + math.pi) / (2.0 * math.pi))  # to [-pi, pi)
        dphi = size[i]
        extent = lengths[i] * abs(nx)
        inside = lead * (min(1.0, depth / extent) if extent > 0.0 else 1.0)
        lo = min(lo, phi + dphi * (1.0 - inside))
        hi = max(hi, phi - dphi * (1.0 - inside))
        keep[count] = i
        angle[count] = phi
        count += 1
    fx = 0.0
    fz = 0.0
    ty = 0.0
    if count == 0:
        return fx, fz, ty
    split = 0.5 * (lo + hi)
    for j in range(count):
        i = keep[j]
        rx = c * mid[i, 0] + s * mid[i, 1]
        rz = -s * mid[i, 0] + c * mid[i, 1]
        ex = vx + omega * rz
        ez = vz - omega * rx
        nx = c * nrm[i, 0] + s * nrm[i, 1]
        nz = -s * nrm[i, 0] + c * nrm[i, 1]
        vn = nx * ex + nz * ez
        depth = surface - (z + rz)
        if size[i] > 0.0:
            rear = min(1.0, max(0.0, 0.5 - (angle[j] - split) / size[i]))
        else:
            rear = 1.0 if angle[j] < split else 0.0
        depth -= drop * rear
        if depth <= 0.0:
            continue
        f_x, f_z = _element_force(coeffs, nx, nz, ex, ez, vn, depth, lengths[i], width, scale, lam_rho)
        lead = _leading_fraction(nx, nz, vn, ex, ez, band)
        if lead < 1.0:
            f_x *= lead
            f_z *= lead
        fx += f_x
        fz += f_z
        ty += (z + rz - about_z) * f_x - (x + rx - about_x) * f_z
    return fx, fz, ty
