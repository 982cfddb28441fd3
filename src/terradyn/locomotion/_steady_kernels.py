"""Numba kernels of the steady wheel solves: the whole root-finding loop of one operating point.

Plain functions of NumPy arrays and floats in SI. The 2D kernel takes the plane-RFT element arrays of
:mod:`terradyn.rft.kernels` (``mid``, ``nrm`` (N, 2) [m, -], ``lengths`` (N,) [m], ``coeffs`` (9,),
``scale`` [N/m^3]); the 3D kernels take the component-major facet arrays of
:mod:`terradyn.rft.kernels` (``centroids``, ``normals`` (3, F), ``areas`` (F,)).

Both solves follow :func:`terradyn.locomotion.steady.wheel_steady` and
:func:`terradyn.locomotion.steady3d.wheel_steady_3d`: a coarse scan of ``SCAN_POINTS`` axle heights
brackets the height where the period-mean vertical force equals the load, then Brent's method
(:func:`brent_step`, the same iteration as ``scipy.optimize.brentq``) refines it. The pure-Python
references are the generic paths of those two modules (any terrain model, SciPy's ``brentq``).

Status codes returned by the point kernels: :data:`OK`, :data:`OVERLOADED` (the medium cannot carry
the load with the axle at the surface), :data:`NO_CONTACT` (the load is carried with no contact),
:data:`NOT_MONOTONIC` (the vertical force is not monotonic in sinkage on the scan),
:data:`NOT_CONVERGED` (Brent did not converge in ``maxiter`` steps).
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from ..rft.kernels import (
    rft3d_alpha_kernel,
    rft3d_wrench_range_kernel,
    rft_contact_angles_kernel,
    rft_wrench_kernel,
)

__all__ = [
    "NOT_CONVERGED",
    "NOT_MONOTONIC",
    "NO_CONTACT",
    "OK",
    "OVERLOADED",
    "SCAN_POINTS",
    "brent_start",
    "brent_step",
    "rft3d_facet_order_kernel",
    "rft3d_steady_kernel",
    "rft_steady_kernel",
]

OK, OVERLOADED, NO_CONTACT, NOT_MONOTONIC, NOT_CONVERGED = 0, 1, 2, 3, 4

#: Axle heights of the coarse scan that brackets the load (both solves).
SCAN_POINTS = 17

# Brent state vector: indices.
_XPRE, _XCUR, _XBLK, _FPRE, _FCUR, _FBLK, _SPRE, _SCUR, _XTOL, _RTOL = range(10)


@nb.njit(cache=True, nogil=True)
def brent_start(
    xa: float, fa: float, xb: float, fb: float, xtol: float, rtol: float, state: np.ndarray
) -> None:
    """Fill ``state`` (10,) for Brent's method on the bracket [xa, xb] with f(xa) = fa, f(xb) = fb.

    The caller has checked that fa and fb are non-zero with opposite signs.
    """
    state[_XPRE], state[_XCUR], state[_XBLK] = xa, xb, 0.0
    state[_FPRE], state[_FCUR], state[_FBLK] = fa, fb, 0.0
    state[_SPRE], state[_SCUR] = 0.0, 0.0
    state[_XTOL], state[_RTOL] = xtol, rtol


@nb.njit(cache=True, nogil=True)
def brent_step(state: np.ndarray) -> tuple[bool, float]:
    """One step of Brent's root finder in reverse-communication form.

    Returns ``(True, root)`` when the bracket is within tolerance, else ``(False, x)``: the caller
    evaluates f(x), stores it in ``state[4]`` and calls again. Inverse quadratic (or secant)
    interpolation when it stays well inside the bracket, bisection otherwise; the tolerance is
    ``(xtol + rtol |x|) / 2``, the rule of ``scipy.optimize.brentq``.
    """
    xpre, xcur, xblk = state[_XPRE], state[_XCUR], state[_XBLK]
    fpre, fcur, fblk = state[_FPRE], state[_FCUR], state[_FBLK]
    spre, scur = state[_SPRE], state[_SCUR]
    if fpre != 0.0 and fcur != 0.0 and (fpre < 0.0) != (fcur < 0.0):
        # The root lies between the last two iterates: they become the new bracket.
        xblk, fblk = xpre, fpre
        spre = scur = xcur - xpre
    if abs(fblk) < abs(fcur):
        # Keep the best estimate in xcur.
        xpre, xcur, xblk = xcur, xblk, xcur
        fpre, fcur, fblk = fcur, fblk, fcur
    delta = 0.5 * (state[_XTOL] + state[_RTOL] * abs(xcur))
    sbis = 0.5 * (xblk - xcur)
    done = fcur == 0.0 or abs(sbis) < delta
    if not done:
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:
                stry = -fcur * (xcur - xpre) / (fcur - fpre)  # secant
            else:
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2.0 * abs(stry) < min(abs(spre), 3.0 * abs(sbis) - delta):
                spre, scur = scur, stry
            else:
                spre, scur = sbis, sbis
        else:
            spre, scur = sbis, sbis
        xpre, fpre = xcur, fcur
        if abs(scur) > delta:
            xcur += scur
        else:
            xcur += delta if sbis > 0.0 else -delta
    state[_XPRE], state[_XCUR], state[_XBLK] = xpre, xcur, xblk
    state[_FPRE], state[_FCUR], state[_FBLK] = fpre, fcur, fblk
    state[_SPRE], state[_SCUR] = spre, scur
    return done, xcur


@nb.njit(cache=True, nogil=True)
def _scan_bracket(fz: np.ndarray, load: float) -> tuple[int, int]:
    """(status, j) of the coarse scan ``fz`` (deepest first): the load lies in [fz[j], fz[j - 1])."""
    if fz[0] < load:
        return OVERLOADED, 0
    j = -1
    for i in range(fz.shape[0]):
        if fz[i] < load:
            j = i
            break
    if j < 0:
        return NO_CONTACT, 0
    return OK, j


@nb.njit(cache=True, nogil=True)
def _rft_vertical_mean(
    mid: np.ndarray, nrm: np.ndarray, lengths: np.ndarray, width: float, z: float, thetas: np.ndarray,
    vx: float, vz: float, omega: float, coeffs: np.ndarray, scale: float, surface: float,
) -> float:  # fmt: skip
    """Phase-mean vertical force [N] of a plane body with its origin at height ``z`` [m]."""
    acc = 0.0
    for k in range(thetas.shape[0]):
        _, fz, _ = rft_wrench_kernel(
            mid, nrm, lengths, width, 0.0, z, thetas[k], vx, vz, omega, coeffs, scale, surface, 0.0, z
        )
        acc += fz
    return acc / thetas.shape[0]


@nb.njit(cache=True, nogil=True)
def rft_steady_kernel(
    mid: np.ndarray,
    nrm: np.ndarray,
    lengths: np.ndarray,
    width: float,
    points: np.ndarray,
    thetas: np.ndarray,
    vx: float,
    vz: float,
    omega: float,
    coeffs: np.ndarray,
    scale: float,
    surface: float,
    load: float,
    maxiter: int,
    out: np.ndarray,
) -> int:
    """Steady point of a plane wheel in RFT; returns a status code and fills ``out`` (16,).

    ``points`` (M, 2) [m] is the body-frame outline; its lowest point at each phase ``thetas`` (P,)
    [rad] sets the sinkage and the top of the scan. The wheel moves with (vx, vz) [m/s] and spins at
    omega [rad/s]; ``load`` [N]. The scan runs from the axle at the surface up to where the deepest
    phase just touches; tolerances as
    ``brentq(xtol=1e-12 top, rtol=1e-13)``. ``out``: axle height z [m], the force carried at the
    deepest scan height [N], mean drawbar pull [N], mean drive torque [N m], drawbar pull min, max,
    drive torque min, max, vertical force min, max, sinkage mean, min, max [m], entry and exit angle
    [rad] (phase 0), and 1.0 if any element is loaded at phase 0.
    """
    p = thetas.shape[0]
    lowest = np.empty(p)
    for k in range(p):
        c, s = math.cos(thetas[k]), math.sin(thetas[k])
        low = math.inf
        for m in range(points.shape[0]):
            low = min(low, -s * points[m, 0] + c * points[m, 1])
        lowest[k] = low
    top = surface - lowest.min()
    n = SCAN_POINTS
    fz = np.empty(n)
    step = top / (n - 1)
    for i in range(n):
        h = i * step if i < n - 1 else top
        fz[i] = _rft_vertical_mean(mid, nrm, lengths, width, h, thetas, vx, vz, omega, coeffs, scale, surface)
    out[1] = fz[0]
    status, j = _scan_bracket(fz, load)
    if status != OK:
        return status
    rising = False
    crossing = False
    tol = 1e-9 * max(1.0, load)
    for i in range(j - 1, n - 1):
        rising = rising or fz[i + 1] - fz[i] > tol
    for i in range(j, n):
        crossing = crossing or fz[i] >= load
    if rising and crossing:
        return NOT_MONOTONIC
    a = (j - 1) * step
    b = j * step if j < n - 1 else top
    fa, fb = fz[j - 1] - load, fz[j] - load
    if fa == 0.0:
        z = a
    else:
        state = np.empty(10)
        brent_start(a, fa, b, fb, 1e-12 * top, 1e-13, state)
        z = b
        converged = False
        for _ in range(maxiter):
            done, z = brent_step(state)
            if done:
                converged = True
                break
            state[_FCUR] = (
                _rft_vertical_mean(mid, nrm, lengths, width, z, thetas, vx, vz, omega, coeffs, scale, surface)
                - load
            )
        if not converged:
            return NOT_CONVERGED
    out[0] = z
    sum_dp = sum_drive = sum_sink = 0.0
    dp_lo = drive_lo = fz_lo = sink_lo = math.inf
    dp_hi = drive_hi = fz_hi = sink_hi = -math.inf
    for k in range(p):
        f_x, f_z, t_y = rft_wrench_kernel(
            mid, nrm, lengths, width, 0.0, z, thetas[k], vx, vz, omega, coeffs, scale, surface, 0.0, z
        )
        drive = -t_y
        sink = max(surface - (z + lowest[k]), 0.0)
        sum_dp += f_x
        sum_drive += drive
        sum_sink += sink
        dp_lo, dp_hi = min(dp_lo, f_x), max(dp_hi, f_x)
        drive_lo, drive_hi = min(drive_lo, drive), max(drive_hi, drive)
        fz_lo, fz_hi = min(fz_lo, f_z), max(fz_hi, f_z)
        sink_lo, sink_hi = min(sink_lo, sink), max(sink_hi, sink)
    out[2], out[3] = sum_dp / p, sum_drive / p
    out[4], out[5], out[6], out[7] = dp_lo, dp_hi, drive_lo, drive_hi
    out[8], out[9] = fz_lo, fz_hi
    out[10], out[11], out[12] = sum_sink / p, sink_lo, sink_hi
    hi, lo, found = rft_contact_angles_kernel(mid, nrm, 0.0, z, thetas[0], vx, vz, omega, surface)
    out[13], out[14], out[15] = hi, lo, 1.0 if found else 0.0
    return OK


@nb.njit(cache=True, nogil=True)
def rft3d_facet_order_kernel(
    centroids: np.ndarray,
    normals: np.ndarray,
    areas: np.ndarray,
    rotations: np.ndarray,
    surface: float,
    low: float,
    high: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Facets that can touch the medium in the scan, deepest-reaching first, and prefix counts.

    For axle heights ``low + i (high - low) / (SCAN_POINTS - 1)`` [m] and the phase rotations
    ``rotations`` (P, 3, 3), a facet is counted for scan height i when its lowest centroid height over
    the phases may lie below ``surface`` [m] there (with a margin, so the set is a superset). Returns
    the reordered ``centroids``, ``normals`` (3, F') and ``areas`` (F',), and ``counts`` (SCAN_POINTS,):
    the first ``counts[i]`` facets are the ones that can be submerged at scan height i and at every
    height above it. Facets never submerged in the scan are dropped; they carry no load there.
    """
    n = SCAN_POINTS
    f = areas.shape[0]
    p = rotations.shape[0]
    step = (high - low) / (n - 1)
    step = step if step > 0.0 else 1e-300
    key = np.empty(f, dtype=np.int64)
    hist = np.zeros(n + 1, dtype=np.int64)
    for i in range(f):
        bx, by, bz = centroids[0, i], centroids[1, i], centroids[2, i]
        rz = math.inf
        for k in range(p):
            rz = min(rz, rotations[k, 2, 0] * bx + rotations[k, 2, 1] * by + rotations[k, 2, 2] * bz)
        u = (surface - rz - low) / step
        m = 0 if u <= -1e-6 else min(n, math.floor(u + 1e-6) + 1)
        key[i] = m
        hist[m] += 1
    counts = np.zeros(n, dtype=np.int64)
    acc = 0
    for m in range(n, 0, -1):
        acc += hist[m]
        counts[m - 1] = acc
    start = np.zeros(n + 1, dtype=np.int64)  # first slot of each key, deepest-reaching (key n) first
    pos = 0
    for m in range(n, 0, -1):
        start[m] = pos
        pos += hist[m]
    total = counts[0]
    c2 = np.empty((3, total))
    n2 = np.empty((3, total))
    a2 = np.empty(total)
    for i in range(f):
        m = key[i]
        if m == 0:
            continue
        s = start[m]
        start[m] += 1
        for d in range(3):
            c2[d, s] = centroids[d, i]
            n2[d, s] = normals[d, i]
        a2[s] = areas[i]
    return c2, n2, a2, counts


@nb.njit(cache=True, nogil=True)
def _rft3d_phase_wrench(
    centroids: np.ndarray, normals: np.ndarray, areas: np.ndarray, rot: np.ndarray, height: float,
    lin: np.ndarray, ang: np.ndarray, coeffs: np.ndarray, xi: float, surface: float, leading: bool,
    mu_surf: float, up_tol: float, count: int,
) -> tuple[float, float, float, float, float, float]:  # fmt: skip
    """Wrench of the first ``count`` facets with the axle at (0, 0, height), moments about the axle."""
    pos = np.zeros(3)
    pos[2] = height
    return rft3d_wrench_range_kernel(
        centroids, normals, areas, rot, pos, lin, ang, coeffs, xi, surface, leading, mu_surf, up_tol,
        pos, 0, count,
    )  # fmt: skip


@nb.njit(cache=True, nogil=True)
def _rft3d_vertical_mean(
    centroids: np.ndarray, normals: np.ndarray, areas: np.ndarray, rotations: np.ndarray,
    height: float, lin: np.ndarray, ang: np.ndarray, coeffs: np.ndarray, xi: float, surface: float,
    leading: bool, mu_surf: float, up_tol: float, count: int,
) -> float:  # fmt: skip
    acc = 0.0
    for k in range(rotations.shape[0]):
        acc += _rft3d_phase_wrench(
            centroids, normals, areas, rotations[k], height, lin, ang, coeffs, xi, surface, leading,
            mu_surf, up_tol, count,
        )[2]  # fmt: skip
    return acc / rotations.shape[0]


@nb.njit(cache=True, nogil=True, parallel=True)
def _rft3d_scan(
    centroids: np.ndarray, normals: np.ndarray, areas: np.ndarray, counts: np.ndarray,
    rotations: np.ndarray, lin: np.ndarray, ang: np.ndarray, coeffs: np.ndarray, xi: float,
    surface: float, leading: bool, mu_surf: float, up_tol: float, low: float, high: float,
    min_parallel: int,
) -> np.ndarray:  # fmt: skip
    """Phase-mean vertical force [N] at the SCAN_POINTS scan heights; parallel over (height, phase)
    when the facet evaluations reach ``min_parallel``, one thread otherwise."""
    n = SCAN_POINTS
    p = rotations.shape[0]
    step = (high - low) / (n - 1)
    work = 0
    for i in range(n):
        work += counts[i] * p
    fz = np.zeros((n, p))
    if work >= min_parallel:
        # Uneven items (deep heights hold more facets): callers hand them out one at a time
        # (numba.parallel_chunksize(1)), so that a thread without a core delays only its own item.
        for item in nb.prange(n * p):
            i, k = item // p, item % p
            h = low + i * step if i < n - 1 else high
            fz[i, k] = _rft3d_phase_wrench(
                centroids, normals, areas, rotations[k], h, lin, ang, coeffs, xi, surface, leading,
                mu_surf, up_tol, counts[i],
            )[2]  # fmt: skip
    else:
        for item in range(n * p):
            i, k = item // p, item % p
            h = low + i * step if i < n - 1 else high
            fz[i, k] = _rft3d_phase_wrench(
                centroids, normals, areas, rotations[k], h, lin, ang, coeffs, xi, surface, leading,
                mu_surf, up_tol, counts[i],
            )[2]  # fmt: skip
    out = np.empty(n)
    for i in range(n):
        acc = 0.0
        for k in range(p):
            acc += fz[i, k]
        out[i] = acc / p
    return out


@nb.njit(cache=True, nogil=True)
def rft3d_steady_kernel(
    centroids: np.ndarray,
    normals: np.ndarray,
    areas: np.ndarray,
    counts: np.ndarray,
    rotations: np.ndarray,
    lowest: np.ndarray,
    lin: np.ndarray,
    ang: np.ndarray,
    coeffs: np.ndarray,
    xi: float,
    surface: float,
    leading: bool,
    mu_surf: float,
    up_tol: float,
    low: float,
    high: float,
    load: float,
    maxiter: int,
    min_parallel: int,
    out: np.ndarray,
) -> int:
    """Steady point of a 3D wheel in 3D RFT; returns a status code and fills ``out`` (30,).

    Facet arrays and ``counts`` from :func:`rft3d_facet_order_kernel`; ``rotations`` (P, 3, 3) and
    ``lowest`` (P,) [m] (lowest body-frame z at each phase); axle velocity ``lin`` (3,) [m/s], spin
    ``ang`` (3,) [rad/s]; the scan covers axle heights [low, high] [m]; tolerances as
    ``brentq(xtol=1e-13 span, rtol=1e-14)``. ``out``: z [m]; the force carried at ``low`` [N]; means
    of F_x, F_y, F_z [N], M_x, drive torque -M_y, M_z [N m]; min, max of F_x, F_y, drive torque, F_z;
    sinkage mean, min, max [m]; contact x min, x max, y min, y max [m], entry, exit [rad] (phase 0).
    """
    n = SCAN_POINTS
    fz = _rft3d_scan(
        centroids, normals, areas, counts, rotations, lin, ang, coeffs, xi, surface, leading, mu_surf,
        up_tol, low, high, min_parallel,
    )  # fmt: skip
    out[1] = fz[0]
    status, j = _scan_bracket(fz, load)
    if status != OK:
        return status
    for i in range(j, n):
        if fz[i] >= load:
            return NOT_MONOTONIC
    step = (high - low) / (n - 1)
    a = low + (j - 1) * step
    b = low + j * step if j < n - 1 else high
    count = counts[j - 1]
    fa, fb = fz[j - 1] - load, fz[j] - load
    if fa == 0.0:
        z = a
    else:
        state = np.empty(10)
        span = max(high - low, 1e-12)
        brent_start(a, fa, b, fb, 1e-13 * span, 1e-14, state)
        z = b
        converged = False
        for _ in range(maxiter):
            done, z = brent_step(state)
            if done:
                converged = True
                break
            fz_z = _rft3d_vertical_mean(
                centroids, normals, areas, rotations, z, lin, ang, coeffs, xi, surface, leading, mu_surf,
                up_tol, count,
            )  # fmt: skip
            state[_FCUR] = fz_z - load
        if not converged:
            return NOT_CONVERGED
    out[0] = z
    p = rotations.shape[0]
    sums = np.zeros(6)
    lo = np.full(4, math.inf)
    hi = np.full(4, -math.inf)
    sink_sum, sink_lo, sink_hi = 0.0, math.inf, -math.inf
    for k in range(p):
        w = _rft3d_phase_wrench(
            centroids, normals, areas, rotations[k], z, lin, ang, coeffs, xi, surface, leading, mu_surf,
            up_tol, count,
        )  # fmt: skip
        vals = (w[0], w[1], -w[4], w[2])
        for m in range(6):
            sums[m] += -w[m] if m == 4 else w[m]
        for m in range(4):
            lo[m] = min(lo[m], vals[m])
            hi[m] = max(hi[m], vals[m])
        sink = max(surface - (z + lowest[k]), 0.0)  # a phase clear of the surface sinks 0
        sink_sum += sink
        sink_lo, sink_hi = min(sink_lo, sink), max(sink_hi, sink)
    for m in range(6):
        out[2 + m] = sums[m] / p
    for m in range(4):
        out[8 + 2 * m] = lo[m]
        out[9 + 2 * m] = hi[m]
    out[16], out[17], out[18] = sink_sum / p, sink_lo, sink_hi
    _contact_patch(centroids, normals, areas, rotations[0], z, lin, ang, coeffs, surface, leading, mu_surf,
                   up_tol, count, out[19:25])  # fmt: skip
    return OK


@nb.njit(cache=True, nogil=True)
def _contact_patch(
    centroids: np.ndarray, normals: np.ndarray, areas: np.ndarray, rot: np.ndarray, height: float,
    lin: np.ndarray, ang: np.ndarray, coeffs: np.ndarray, surface: float, leading: bool,
    mu_surf: float, up_tol: float, count: int, out: np.ndarray,
) -> None:  # fmt: skip
    """x min, x max, y min, y max [m] (relative to the axle) and entry, exit angles [rad] of the loaded
    facets among the first ``count`` at one phase; zeros when none is loaded."""
    x0 = y0 = exit_ = math.inf
    x1 = y1 = entry = -math.inf
    found = False
    wx, wy, wz = ang[0], ang[1], ang[2]
    for i in range(count):
        bx, by, bz = centroids[0, i], centroids[1, i], centroids[2, i]
        rx = rot[0, 0] * bx + rot[0, 1] * by + rot[0, 2] * bz
        ry = rot[1, 0] * bx + rot[1, 1] * by + rot[1, 2] * bz
        rz = rot[2, 0] * bx + rot[2, 1] * by + rot[2, 2] * bz
        if surface - (rz + height) <= 0.0 or not areas[i] > 0.0:
            continue
        cx, cy, cz = normals[0, i], normals[1, i], normals[2, i]
        nx = rot[0, 0] * cx + rot[0, 1] * cy + rot[0, 2] * cz
        ny = rot[1, 0] * cx + rot[1, 1] * cy + rot[1, 2] * cz
        nz = rot[2, 0] * cx + rot[2, 1] * cy + rot[2, 2] * cz
        vx = lin[0] + wy * rz - wz * ry
        vy = lin[1] + wz * rx - wx * rz
        vz = lin[2] + wx * ry - wy * rx
        ax, ay, az = rft3d_alpha_kernel(nx, ny, nz, vx, vy, vz, coeffs, leading, mu_surf, up_tol)
        if ax == 0.0 and ay == 0.0 and az == 0.0:
            continue
        found = True
        x0, x1 = min(x0, rx), max(x1, rx)
        y0, y1 = min(y0, ry), max(y1, ry)
        angle = math.atan2(rx, -rz)
        entry, exit_ = max(entry, angle), min(exit_, angle)
    if not found:
        out[:] = 0.0
        return
    out[0], out[1], out[2], out[3], out[4], out[5] = x0, x1, y0, y1, entry, exit_
