"""Numba kernels of 3D RFT (the Agarwal, Goldman & Kamrin 2023 law summed over triangle facets).

Plain functions of NumPy arrays and floats in SI. Shapes: the wrench kernels take body-frame facet
``centroids`` [m] and outward unit ``normals`` [-] (zero for zero-area facets) component-major,
shape (3, F) and C-contiguous (:attr:`TriangleMesh.kernel_arrays`; this layout lets the facet loop
vectorise, about three times faster than (F, 3)), and ``areas`` (F,) [m^2];
``coeffs`` (3, 20) the fit coefficients c_i^k [-] in the term order of
:data:`terradyn.rft.rft3d.AGARWAL2023_TERMS`; ``xi`` the media scale [N/m^3]; ``surface`` the free-surface
height [m]; ``leading`` applies the leading-edge rule (n . v > 0); ``mu_surf`` caps the tangential
traction at ``mu_surf`` times the normal traction (a negative value: no cap); ``up_tol`` is the n_z above
which a facet counts as upward-facing and is folded to its plate normal -n. The law is evaluated
without trigonometry: x1 = sin(gamma) = -v_z/|v|, x2 = cos(beta) = -p_z, x3 = p . v/|v| with p the
plate normal, and alpha = f1 p + f2 v/|v| - f3 z_hat. The NumPy reference is
:func:`terradyn.rft.rft3d.agarwal2023_alpha` and :func:`terradyn.rft.rft3d.rft3d_facet_forces`.

References
----------
S. Agarwal, D. I. Goldman, K. Kamrin, "Mechanistic framework for reduced-order models in soft
materials: application to three-dimensional granular intrusion", PNAS 120, e2214017120 (2023).
doi:10.1073/pnas.2214017120
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

__all__ = [
    "rft3d_tractions_kernel",
    "rft3d_wrench_kernel",
    "rft3d_wrench_many_kernel",
    "rft3d_wrench_parallel_kernel",
]

# Fast-math flags: reassociation (vectorised sums) and contraction (FMA), but no "arcp" (x / y turned
# into x * (1 / y), which overflows for subnormal y) and no no-NaN/no-inf assumptions.
_FAST = {"reassoc", "contract", "nsz"}

# Facets per parallel work item of rft3d_wrench_parallel_kernel.
_CHUNK = 4096


@nb.njit(cache=True, fastmath=_FAST, error_model="numpy", nogil=True, inline="always")
def _poly(
    c: np.ndarray,
    i: int,
    x1: float,
    x2: float,
    x3: float,
    t4: float,
    t5: float,
    t6: float,
    t7: float,
    t8: float,
    t9: float,
    t10: float,
    t11: float,
    t12: float,
    t13: float,
    t14: float,
    t15: float,
    t16: float,
    t17: float,
    t18: float,
    t19: float,
) -> float:
    """sum_k c[i, k] T_k: the 20-term cubic of fit ``i`` (terms T_4.. precomputed)."""
    return (
        c[i, 0]
        + c[i, 1] * x1
        + c[i, 2] * x2
        + c[i, 3] * x3
        + c[i, 4] * t4
        + c[i, 5] * t5
        + c[i, 6] * t6
        + c[i, 7] * t7
        + c[i, 8] * t8
        + c[i, 9] * t9
        + c[i, 10] * t10
        + c[i, 11] * t11
        + c[i, 12] * t12
        + c[i, 13] * t13
        + c[i, 14] * t14
        + c[i, 15] * t15
        + c[i, 16] * t16
        + c[i, 17] * t17
        + c[i, 18] * t18
        + c[i, 19] * t19
    )


@nb.njit(cache=True, fastmath=_FAST, error_model="numpy", nogil=True, inline="always")
def rft3d_alpha_kernel(
    nx: float,
    ny: float,
    nz: float,
    vx: float,
    vy: float,
    vz: float,
    coeffs: np.ndarray,
    leading: bool,
    mu_surf: float,
    up_tol: float,
) -> tuple[float, float, float]:
    """Generic alpha [-] of one facet (world frame); zero if it is at rest, degenerate or trailing.

    Branch-free (selects only) so that the facet loops vectorise.
    """
    # Scale by the largest component first, so that tiny or huge speeds normalise exactly.
    vmax = max(abs(vx), abs(vy), abs(vz))
    moving = vmax > 0.0
    vref = vmax if moving else 1.0
    wx, wy, wz = vx / vref, vy / vref, vz / vref  # division, not a reciprocal: 1/vmax may overflow
    inv = 1.0 / math.sqrt(wx * wx + wy * wy + wz * wz + (0.0 if moving else 1.0))
    ux, uy, uz = wx * inv, wy * inv, wz * inv
    nv = nx * ux + ny * uy + nz * uz
    n2 = nx * nx + ny * ny + nz * nz
    carries = moving & (n2 > 0.25) & ((nv > 0.0) | (not leading))
    on = 1.0 if carries else 0.0
    s = -1.0 if nz > up_tol else 1.0
    px, py, pz = s * nx, s * ny, min(s * nz, 0.0)  # |n_z| <= up_tol: exactly vertical plate
    x1 = -uz
    x2 = -pz
    x3 = px * ux + py * uy + pz * uz
    x11, x22, x33 = x1 * x1, x2 * x2, x3 * x3
    t4, t5, t6 = x11, x22, x33
    t7, t8, t9 = x1 * x2, x2 * x3, x3 * x1
    t10, t11, t12 = x11 * x1, x22 * x2, x33 * x3
    t13, t14, t15 = x1 * x22, x2 * x11, x2 * x33
    t16, t17, t18 = x3 * x22, x3 * x11, x1 * x33
    t19 = x1 * x2 * x3
    f1 = _poly(
        coeffs, 0, x1, x2, x3, t4, t5, t6, t7, t8, t9, t10, t11, t12, t13, t14, t15, t16, t17, t18, t19
    )
    f2 = _poly(
        coeffs, 1, x1, x2, x3, t4, t5, t6, t7, t8, t9, t10, t11, t12, t13, t14, t15, t16, t17, t18, t19
    )
    f3 = _poly(
        coeffs, 2, x1, x2, x3, t4, t5, t6, t7, t8, t9, t10, t11, t12, t13, t14, t15, t16, t17, t18, t19
    )
    ax = f1 * px + f2 * ux
    ay = f1 * py + f2 * uy
    az = f1 * pz + f2 * uz - f3
    if mu_surf >= 0.0:
        an = ax * nx + ay * ny + az * nz
        tx, ty, tz = ax - an * nx, ay - an * ny, az - an * nz
        tmag = math.sqrt(tx * tx + ty * ty + tz * tz)
        limit = mu_surf * abs(an)
        k = limit / (tmag if tmag > limit else 1.0) if tmag > limit else 1.0
        ax, ay, az = an * nx + k * tx, an * ny + k * ty, an * nz + k * tz
    return ax * on, ay * on, az * on


@nb.njit(cache=True, fastmath=_FAST, error_model="numpy", nogil=True)
def rft3d_wrench_range_kernel(
    centroids: np.ndarray,
    normals: np.ndarray,
    areas: np.ndarray,
    rot: np.ndarray,
    pos: np.ndarray,
    lin: np.ndarray,
    ang: np.ndarray,
    coeffs: np.ndarray,
    xi: float,
    surface: float,
    leading: bool,
    mu_surf: float,
    up_tol: float,
    about: np.ndarray,
    start: int,
    stop: int,
) -> tuple[float, float, float, float, float, float]:
    """Force [N] and moment [N m] about ``about`` of the facets start..stop-1 (body-frame inputs)."""
    r00, r01, r02 = rot[0, 0], rot[0, 1], rot[0, 2]
    r10, r11, r12 = rot[1, 0], rot[1, 1], rot[1, 2]
    r20, r21, r22 = rot[2, 0], rot[2, 1], rot[2, 2]
    wx, wy, wz = ang[0], ang[1], ang[2]
    ox, oy, oz = pos[0] - about[0], pos[1] - about[1], pos[2] - about[2]
    fx = fy = fz = mx = my = mz = 0.0
    for i in range(start, stop):
        bx, by, bz = centroids[0, i], centroids[1, i], centroids[2, i]
        rz = r20 * bx + r21 * by + r22 * bz
        depth = surface - (pos[2] + rz)
        depth = depth if depth > 0.0 else 0.0
        rx = r00 * bx + r01 * by + r02 * bz
        ry = r10 * bx + r11 * by + r12 * bz
        cx, cy, cz = normals[0, i], normals[1, i], normals[2, i]
        nx = r00 * cx + r01 * cy + r02 * cz
        ny = r10 * cx + r11 * cy + r12 * cz
        nz = r20 * cx + r21 * cy + r22 * cz
        vx = lin[0] + wy * rz - wz * ry
        vy = lin[1] + wz * rx - wx * rz
        vz = lin[2] + wx * ry - wy * rx
        ax, ay, az = rft3d_alpha_kernel(nx, ny, nz, vx, vy, vz, coeffs, leading, mu_surf, up_tol)
        w = xi * depth * areas[i]
        gx, gy, gz = ax * w, ay * w, az * w
        fx += gx
        fy += gy
        fz += gz
        lx, ly, lz = ox + rx, oy + ry, oz + rz
        mx += ly * gz - lz * gy
        my += lz * gx - lx * gz
        mz += lx * gy - ly * gx
    return fx, fy, fz, mx, my, mz


@nb.njit(cache=True, error_model="numpy", nogil=True)
def rft3d_wrench_kernel(
    centroids: np.ndarray,
    normals: np.ndarray,
    areas: np.ndarray,
    rot: np.ndarray,
    pos: np.ndarray,
    lin: np.ndarray,
    ang: np.ndarray,
    coeffs: np.ndarray,
    xi: float,
    surface: float,
    leading: bool,
    mu_surf: float,
    up_tol: float,
    about: np.ndarray,
) -> np.ndarray:
    """Soil wrench (6,) = (F [N], M [N m] about ``about`` (3,) [m]) on a rigid body, one thread.

    The body-frame mesh is placed by ``rot`` (3, 3) and ``pos`` (3,) [m] and moves with the origin
    velocity ``lin`` (3,) [m/s] and angular velocity ``ang`` (3,) [rad/s], both in the world frame.
    """
    out = np.empty(6)
    res = rft3d_wrench_range_kernel(
        centroids, normals, areas, rot, pos, lin, ang, coeffs, xi, surface, leading, mu_surf, up_tol,
        about, 0, areas.shape[0],
    )  # fmt: skip
    for k in range(6):
        out[k] = res[k]
    return out


@nb.njit(cache=True, error_model="numpy", nogil=True, parallel=True)
def rft3d_wrench_parallel_kernel(
    centroids: np.ndarray,
    normals: np.ndarray,
    areas: np.ndarray,
    rot: np.ndarray,
    pos: np.ndarray,
    lin: np.ndarray,
    ang: np.ndarray,
    coeffs: np.ndarray,
    xi: float,
    surface: float,
    leading: bool,
    mu_surf: float,
    up_tol: float,
    about: np.ndarray,
) -> np.ndarray:
    """:func:`rft3d_wrench_kernel` split over threads in chunks of facets (large meshes)."""
    n = areas.shape[0]
    chunks = (n + _CHUNK - 1) // _CHUNK
    partial = np.zeros((chunks, 6))
    for c in nb.prange(chunks):
        res = rft3d_wrench_range_kernel(
            centroids, normals, areas, rot, pos, lin, ang, coeffs, xi, surface, leading, mu_surf,
            up_tol, about, c * _CHUNK, min(n, (c + 1) * _CHUNK),
        )  # fmt: skip
        for k in range(6):
            partial[c, k] = res[k]
    out = np.zeros(6)
    for c in range(chunks):
        for k in range(6):
            out[k] += partial[c, k]
    return out


@nb.njit(cache=True, error_model="numpy", nogil=True, parallel=True)
def rft3d_wrench_many_kernel(
    centroids: np.ndarray,
    normals: np.ndarray,
    areas: np.ndarray,
    rots: np.ndarray,
    positions: np.ndarray,
    lins: np.ndarray,
    angs: np.ndarray,
    coeffs: np.ndarray,
    xi: float,
    surface: float,
    leading: bool,
    mu_surf: float,
    up_tol: float,
    abouts: np.ndarray,
) -> np.ndarray:
    """Wrenches (M, 6) for M states: ``rots`` (M, 3, 3), ``positions``, ``lins``, ``angs``, ``abouts``
    (M, 3). Parallel over states."""
    m = rots.shape[0]
    out = np.empty((m, 6))
    for j in nb.prange(m):
        res = rft3d_wrench_range_kernel(
            centroids, normals, areas, rots[j], positions[j], lins[j], angs[j], coeffs, xi, surface,
            leading, mu_surf, up_tol, abouts[j], 0, areas.shape[0],
        )  # fmt: skip
        for k in range(6):
            out[j, k] = res[k]
    return out


@nb.njit(cache=True, error_model="numpy", nogil=True, parallel=True)
def rft3d_tractions_kernel(
    centroids: np.ndarray,
    normals: np.ndarray,
    velocities: np.ndarray,
    coeffs: np.ndarray,
    xi: float,
    surface: float,
    leading: bool,
    mu_surf: float,
    up_tol: float,
) -> np.ndarray:
    """Tractions (F, 3) [Pa] on facets at world ``centroids`` (F, 3) [m] with world ``normals`` (F, 3)
    and ``velocities`` (F, 3) [m/s]: ``xi * alpha * depth`` below the surface, else 0. Parallel."""
    n = centroids.shape[0]
    out = np.zeros((n, 3))
    for i in nb.prange(n):
        depth = surface - centroids[i, 2]
        if depth <= 0.0:
            continue
        ax, ay, az = rft3d_alpha_kernel(
            normals[i, 0], normals[i, 1], normals[i, 2], velocities[i, 0], velocities[i, 1],
            velocities[i, 2], coeffs, leading, mu_surf, up_tol,
        )  # fmt: skip
        w = xi * depth
        out[i, 0] = ax * w
        out[i, 1] = ay * w
        out[i, 2] = az * w
    return out
