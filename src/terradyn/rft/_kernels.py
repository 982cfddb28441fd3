"""Numba kernels of plane RFT (Li et al. 2013 law summed over surface elements).

Plain functions of NumPy arrays and floats in SI. Shapes: ``mid``, ``nrm`` (N, 2) body-frame element
midpoints [m] and outward unit normals [-]; ``lengths`` (N,) [m]; ``coeffs`` (9,) Li coefficients in
the order A00, A10, B01, B11, Bm11, C01, C11, Cm11, D10 [-]; ``scale`` [N/m^3]. Poses are
(x [m], z [m], theta [rad] about +y), twists (vx [m/s], vz [m/s], omega [rad/s] about +y). The NumPy
reference is :func:`terradyn.rft.forces.rft_element_forces`.

Leading-edge rule: an element below the surface carries the share
``clip(1/2 + n . v / (2 |v| LEADING_BAND), 0, 1)`` of its load (:data:`terradyn.rft.li2013.LEADING_BAND`
= 1e-3: the sharp rule n . v > 0 outside a band of 0.057 deg about faces parallel to their motion, which
carry half), so the force is continuous in the direction of motion.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from .li2013 import LEADING_BAND, MIN_SPEED

__all__ = ["rft_wrench_kernel", "rft_wrench_many_kernel", "rft_wrench_phases_kernel"]

_HALF_INV_BAND = 0.5 / LEADING_BAND
# n . v <= _SKIP * max(|v_x|, |v_z|) implies n . v / |v| < -LEADING_BAND (share 0), as |v| <= sqrt(2) max.
_SKIP = -1.5 * LEADING_BAND


@nb.njit(cache=True, fastmath=True, nogil=True, inline="always")
def li2013_alpha_unit(coeffs: np.ndarray, nx: float, nz: float, cg: float, sg: float) -> tuple[float, float]:
    """(alpha_x, alpha_z) of the Li et al. (2013) fit for unit scale, from the outward normal (nx, nz)
    and the direction of motion (cos gamma, sin gamma) = (cg, sg); no trigonometry:
    cos 2 beta = nz^2 - nx^2, sin 2 beta = -2 nx nz."""
    c2b = nz * nz - nx * nx
    s2b = -2.0 * nx * nz
    az = (
        coeffs[0]
        + coeffs[1] * c2b
        + coeffs[2] * sg
        + coeffs[3] * (s2b * cg + c2b * sg)
        + coeffs[4] * (c2b * sg - s2b * cg)
    )
    ax = (
        coeffs[5] * cg
        + coeffs[6] * (c2b * cg - s2b * sg)
        + coeffs[7] * (c2b * cg + s2b * sg)
        + coeffs[8] * s2b
    )
    return ax, az


@nb.njit(cache=True, fastmath=True, nogil=True)
def rft_wrench_kernel(
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
) -> tuple[float, float, float]:
    """Soil wrench (F_x [N], F_z [N], torque about +y [N m] about (about_x, about_z)) on a body.

    Only elements below ``surface`` [m] whose outward normal has a positive component along their
    velocity (leading elements) carry the traction ``share * scale * (-alpha_x, alpha_z) * depth``,
    ``share = clip(1/2 + n . v / (2 |v| LEADING_BAND), 0, 1)`` (module notes).
    """
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
        # Speeds below MIN_SPEED count as rest (the direction of motion is undefined there).
        big = max(abs(ex), abs(ez))
        if big < MIN_SPEED or nx * ex + nz * ez <= _SKIP * big:  # trailing beyond the band
            continue
        ux, uz = ex / big, ez / big
        inv = 1.0 / math.sqrt(ux * ux + uz * uz)
        cg = ux * inv
        sg = -uz * inv
        share = min(1.0, 0.5 + (nx * cg - nz * sg) * _HALF_INV_BAND)
        if share <= 0.0:
            continue
        ax, az = li2013_alpha_unit(coeffs, nx, nz, cg, sg)
        w = scale * depth * lengths[i] * width * share
        f_x = -ax * w
        f_z = az * w
        fx += f_x
        fz += f_z
        ty += (z + rz - about_z) * f_x - (x + rx - about_x) * f_z
    return fx, fz, ty


@nb.njit(cache=True, parallel=True, nogil=True)
def rft_wrench_many_kernel(
    mid: np.ndarray,
    nrm: np.ndarray,
    lengths: np.ndarray,
    width: float,
    poses: np.ndarray,
    twists: np.ndarray,
    coeffs: np.ndarray,
    scale: float,
    surface: float,
    about: np.ndarray,
) -> np.ndarray:
    """Wrenches (M, 3) for M poses (M, 3) and twists (M, 3); torque about ``about`` (M, 2) [m]."""
    m = poses.shape[0]
    out = np.empty((m, 3))
    for k in nb.prange(m):
        fx, fz, ty = rft_wrench_kernel(
            mid,
            nrm,
            lengths,
            width,
            poses[k, 0],
            poses[k, 1],
            poses[k, 2],
            twists[k, 0],
            twists[k, 1],
            twists[k, 2],
            coeffs,
            scale,
            surface,
            about[k, 0],
            about[k, 1],
        )
        out[k, 0] = fx
        out[k, 1] = fz
        out[k, 2] = ty
    return out


@nb.njit(cache=True, nogil=True)
def rft_wrench_phases_kernel(
    mid: np.ndarray,
    nrm: np.ndarray,
    lengths: np.ndarray,
    width: float,
    x: float,
    z: float,
    thetas: np.ndarray,
    vx: float,
    vz: float,
    omega: float,
    coeffs: np.ndarray,
    scale: float,
    surface: float,
) -> np.ndarray:
    """Wrenches (P, 3) of one body at P rotation phases ``thetas`` [rad]; torque about the origin."""
    out = np.empty((thetas.shape[0], 3))
    for k in range(thetas.shape[0]):
        fx, fz, ty = rft_wrench_kernel(
            mid, nrm, lengths, width, x, z, thetas[k], vx, vz, omega, coeffs, scale, surface, x, z
        )
        out[k, 0] = fx
        out[k, 1] = fz
        out[k, 2] = ty
    return out


@nb.njit(cache=True, nogil=True)
def rft_vertical_mean_kernel(
    mid: np.ndarray,
    nrm: np.ndarray,
    lengths: np.ndarray,
    width: float,
    heights: np.ndarray,
    thetas: np.ndarray,
    vx: float,
    vz: float,
    omega: float,
    coeffs: np.ndarray,
    scale: float,
    surface: float,
) -> np.ndarray:
    """Vertical force [N] averaged over the phases ``thetas`` at each body height (H,) [m]."""
    out = np.empty(heights.shape[0])
    for j in range(heights.shape[0]):
        acc = 0.0
        for k in range(thetas.shape[0]):
            _, fz, _ = rft_wrench_kernel(
                mid,
                nrm,
                lengths,
                width,
                0.0,
                heights[j],
                thetas[k],
                vx,
                vz,
                omega,
                coeffs,
                scale,
                surface,
                0.0,
                heights[j],
            )
            acc += fz
        out[j] = acc / thetas.shape[0]
    return out


@nb.njit(cache=True, nogil=True)
def rft_contact_angles_kernel(
    mid: np.ndarray,
    nrm: np.ndarray,
    x: float,
    z: float,
    theta: float,
    vx: float,
    vz: float,
    omega: float,
    surface: float,
) -> tuple[float, float, bool]:
    """Largest and smallest angle [rad] from the downward vertical (+ towards +x) of loaded elements."""
    c = math.cos(theta)
    s = math.sin(theta)
    hi = -1e300
    lo = 1e300
    found = False
    for i in range(mid.shape[0]):
        rx = c * mid[i, 0] + s * mid[i, 1]
        rz = -s * mid[i, 0] + c * mid[i, 1]
        if surface - (z + rz) <= 0.0:
            continue
        nx = c * nrm[i, 0] + s * nrm[i, 1]
        nz = -s * nrm[i, 0] + c * nrm[i, 1]
        ex = vx + omega * rz
        ez = vz - omega * rx
        big = max(abs(ex), abs(ez))
        if big < MIN_SPEED:
            continue
        ux, uz = ex / big, ez / big
        if (nx * ux + nz * uz) <= -LEADING_BAND * math.sqrt(ux * ux + uz * uz):
            continue  # leading-edge share 0
        a = math.atan2(rx, -rz)
        hi = max(hi, a)
        lo = min(lo, a)
        found = True
    return hi, lo, found
