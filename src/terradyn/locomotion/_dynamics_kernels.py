"""Numba kernels of plane rigid-body time integration through (dynamic) RFT.

The whole time loop runs compiled: :func:`integrate_wheel_kernel` advances a body in the plane
(x, z, theta) with backward Euler on the velocities and positions and returns sampled time series.

Scheme (one step of size h, unknown end-of-step velocity u' = (vx', vz'[, omega'])):

    M (u' - u) / h = F(q + h u', u') + G,      q' = q + h u',

with M = diag(m, m[, I]), F the soil wrench (DRFT kernel; RFT when lam_rho = drop = 0) evaluated at the
end of the step, G = (-drawbar_load, -m g[, drive_torque]). With a prescribed spin omega(t) the wheel
angle follows theta' = theta + h (omega + omega') / 2 and only (vx', vz') are unknown. The implicit
equations are solved by Newton's method with a finite-difference Jacobian of the soil force (reused
across steps while the iteration converges in at most three updates, refreshed otherwise) and a
backtracking line search; a step whose iteration fails is retried as 2, 4, ... 2**max_halvings
substeps. The soil force is the DRFT kernel with its time-stepping smoothing (``P_BAND`` > 0: smoothed
leading-edge switch and structural split, see :func:`terradyn.rft.kernels.drft_wrench_kernel`),
so the implicit equations have a root; the body-frame element angles it needs are computed once.

A body without spin at rest is a set-valued (plastic) contact problem: RFT gives no force at zero
velocity but resists any motion into the medium. When the spin is zero and the force needed to stop the
body within the step does not exceed the resistance the medium offers to motion in the opposite
direction (RFT force for motion along the push direction, projected on it), the body sticks: u' = 0.

Kernel inputs are SI floats and arrays; ``params`` is a float64 array with the layout of the ``P_*``
index constants below.

Numba caches each function by its own source file: after editing ``rft/_kernels_drft.py``, delete this
module's cache (``locomotion/__pycache__/_dynamics_kernels.*.nbi/.nbc``) or the integrator keeps the old
force law.

References
----------
S. Agarwal, A. Karsai, D. I. Goldman, K. Kamrin, Sci. Adv. 7, eabe0631 (2021),
doi:10.1126/sciadv.abe0631 (implicit RFT integration of wheel momentum balance).
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from ..rft.kernels import body_angles_kernel, drft_wrench_kernel, drft_wrench_smooth_kernel

__all__ = ["N_COLUMNS", "N_PARAMS", "N_STATS", "integrate_wheel_kernel", "omega_profile"]

# params layout
P_WIDTH = 0  # out-of-plane width [m]
P_SCALE = 1  # RFT scale [N/m^3]
P_SURFACE = 2  # free-surface height [m]
P_LAM_RHO = 3  # lambda * rho of DRFT [kg/m^3] (0: RFT)
P_DROP_COEFF = 4  # structural correction delta_h / omega^2 = r^2 / g [m s^2] (0: off)
P_MASS = 5  # m [kg]
P_INERTIA = 6  # I about the axle [kg m^2]
P_GRAVITY = 7  # g [m/s^2]
P_DRAWBAR = 8  # rearward horizontal load on the axle [N]
P_MODE = 9  # 0: prescribed omega(t); 1: prescribed drive torque
P_OMEGA0 = 10  # spin before step_time / start of the ramp [rad/s]
P_OMEGA1 = 11  # target spin [rad/s]
P_RAMP = 12  # ramp rate [rad/s^2] (<= 0: step)
P_STEP_TIME = 13  # time of the step / start of the ramp [s]
P_TORQUE = 14  # prescribed drive torque [N m] (mode 1)
P_RADIUS = 15  # nominal radius for slip [m]
P_RTOL = 16  # Newton tolerance on the force residual, relative to m g [-]
P_MAX_ITER = 17  # Newton iterations per attempt
P_MAX_HALVINGS = 18  # substep refinements of a failing step
P_BAND = 19  # smoothing band of the leading-edge switch [-] (0: sharp)
N_PARAMS = 20

# output columns
C_T, C_X, C_Z, C_THETA, C_VX, C_VZ, C_OMEGA = 0, 1, 2, 3, 4, 5, 6
C_FX, C_FZ, C_TORQUE, C_SLIP, C_SINKAGE, C_POWER, C_SOIL_TORQUE, C_WORK = 7, 8, 9, 10, 11, 12, 13, 14
N_COLUMNS = 15

# stats layout: force evaluations, Jacobians, steps, substeps, stuck steps, failed steps,
# largest residual / (m g) of a step accepted on a force discontinuity, such steps
N_STATS = 8


@nb.njit(cache=True, nogil=True)
def omega_profile(t: float, params: np.ndarray) -> float:
    """Prescribed spin [rad/s] at time ``t`` [s]: step or ramp from OMEGA0 to OMEGA1 at STEP_TIME."""
    w0 = params[P_OMEGA0]
    w1 = params[P_OMEGA1]
    if t < params[P_STEP_TIME]:
        return w0
    rate = params[P_RAMP]
    if rate <= 0.0:
        return w1
    w = w0 + math.copysign(rate, w1 - w0) * (t - params[P_STEP_TIME])
    if (w1 >= w0 and w > w1) or (w1 < w0 and w < w1):
        return w1
    return w


@nb.njit(cache=True, nogil=True)
def _soil(geo, coeffs, params, x, z, th, vx, vz, w):
    """Soil wrench (F_x, F_z [N], torque about the axle [N m]) at a state.

    ``geo`` = (midpoints (N, 2), normals (N, 2), lengths (N,), body angles (N,), angular sizes (N,)).
    """
    mid, nrm, lengths, ang, size = geo
    drop = params[P_DROP_COEFF] * w * w
    if drop > 0.0 and params[P_BAND] > 0.0:
        return drft_wrench_smooth_kernel(
            mid,
            nrm,
            lengths,
            ang,
            size,
            params[P_WIDTH],
            x,
            z,
            th,
            vx,
            vz,
            w,
            coeffs,
            params[P_SCALE],
            params[P_SURFACE],
            x,
            z,
            params[P_LAM_RHO],
            drop,
            params[P_BAND],
        )
    return drft_wrench_kernel(
        mid,
        nrm,
        lengths,
        params[P_WIDTH],
        x,
        z,
        th,
        vx,
        vz,
        w,
        coeffs,
        params[P_SCALE],
        params[P_SURFACE],
        x,
        z,
        params[P_LAM_RHO],
        drop,
        params[P_BAND],
    )


@nb.njit(cache=True, nogil=True)
def _residual(geo, coeffs, params, q, u, up, h, th_next, dim, res, frc):
    """Residual M (u' - u) / h - F(q + h u', u') - G (force units; torque row divided by r)."""
    m = params[P_MASS]
    x = q[0] + h * up[0]
    z = q[1] + h * up[1]
    if dim == 3:
        th = q[2] + h * up[2]
        w = up[2]
    else:
        th = th_next
        w = up[2]
    fx, fz, ty = _soil(geo, coeffs, params, x, z, th, up[0], up[1], w)
    frc[0] = fx
    frc[1] = fz
    frc[2] = ty
    res[0] = m * (up[0] - u[0]) / h - fx + params[P_DRAWBAR]
    res[1] = m * (up[1] - u[1]) / h - fz + m * params[P_GRAVITY]
    if dim == 3:
        res[2] = (params[P_INERTIA] * (up[2] - u[2]) / h - ty - params[P_TORQUE]) / params[P_RADIUS]
    else:
        res[2] = 0.0


@nb.njit(cache=True, nogil=True)
def _norm(res, dim):
    r = 0.0
    for i in range(dim):
        r = max(r, abs(res[i]))
    return r


@nb.njit(cache=True, nogil=True)
def _solve(a, b, dim, out):
    """Solve the dim x dim system a out = b by Gaussian elimination with partial pivoting."""
    m = np.empty((3, 4))
    for i in range(dim):
        for j in range(dim):
            m[i, j] = a[i, j]
        m[i, 3] = b[i]
    for k in range(dim):
        p = k
        for i in range(k + 1, dim):
            if abs(m[i, k]) > abs(m[p, k]):
                p = i
        if m[p, k] == 0.0:
            return False
        if p != k:
            for j in range(4):
                m[k, j], m[p, j] = m[p, j], m[k, j]
        for i in range(k + 1, dim):
            f = m[i, k] / m[k, k]
            for j in range(k, 4):
                m[i, j] -= f * m[k, j]
    for i in range(dim - 1, -1, -1):
        s = m[i, 3]
        for j in range(i + 1, dim):
            s -= m[i, j] * out[j]
        out[i] = s / m[i, i]
    return True


@nb.njit(cache=True, nogil=True)
def _jacobian(geo, coeffs, params, q, u, up, h, th_next, dim, res, jac, stats):
    """Finite-difference Jacobian d(residual)/du' at ``up`` (``res`` is the residual there)."""
    tmp = np.empty(3)
    frc = np.empty(3)
    pert = up.copy()
    vscale = 1e-3 * math.sqrt(params[P_GRAVITY] * params[P_RADIUS])
    for j in range(dim):
        eps = 1e-6 * (abs(up[j]) + vscale) if j < 2 else 1e-6 * (abs(up[j]) + vscale / params[P_RADIUS])
        pert[j] = up[j] + eps
        _residual(geo, coeffs, params, q, u, pert, h, th_next, dim, tmp, frc)
        stats[0] += 1.0
        for i in range(dim):
            jac[i, j] = (tmp[i] - res[i]) / eps
        pert[j] = up[j]
    stats[1] += 1.0


@nb.njit(cache=True, nogil=True)
def _try_stick(geo, coeffs, params, q, u, h, frc):
    """Stick test for a body without spin: True (and the holding force in ``frc``) if it stays put."""
    m = params[P_MASS]
    fx = -m * u[0] / h + params[P_DRAWBAR]
    fz = -m * u[1] / h + m * params[P_GRAVITY]
    f = math.sqrt(fx * fx + fz * fz)
    if f == 0.0:
        frc[0] = 0.0
        frc[1] = 0.0
        frc[2] = 0.0
        return True
    probe = 1e-3 * math.sqrt(params[P_GRAVITY] * params[P_RADIUS])
    dx = -fx / f * probe
    dz = -fz / f * probe
    rx, rz, _ = _soil(geo, coeffs, params, q[0], q[1], q[2], dx, dz, 0.0)
    if (rx * fx + rz * fz) / f >= f:
        frc[0] = fx
        frc[1] = fz
        frc[2] = 0.0
        return True
    return False


@nb.njit(cache=True, nogil=True)
def _newton(geo, coeffs, params, q, u, up, h, th_next, dim, jac, jac_ok, frc, stats):
    """Solve the backward-Euler equations for ``up`` in place. Returns (converged, jacobian_ok).

    Converged when the force residual is below ``RTOL * m g``, or when the iterate stops moving
    (``|du| <= 1e-3 RTOL * sqrt(g r)``) or cannot be improved with a fresh Jacobian: the root then sits on a
    discontinuity of the discretised force law (an element switching between leading and trailing, or
    crossing the split of the structural correction) and the iterate is the closest point to it. Such
    steps are counted in ``stats[7]``.
    """
    mg = params[P_MASS] * params[P_GRAVITY]
    tol = params[P_RTOL] * mg
    vtol = 1e-3 * params[P_RTOL] * math.sqrt(params[P_GRAVITY] * params[P_RADIUS])
    res = np.empty(3)
    trial = np.empty(3)
    rtrial = np.empty(3)
    ftrial = np.empty(3)
    du = np.zeros(3)
    _residual(geo, coeffs, params, q, u, up, h, th_next, dim, res, frc)
    stats[0] += 1.0
    rn = _norm(res, dim)
    fresh = False
    for it in range(int(params[P_MAX_ITER])):
        if rn <= tol:
            # slow convergence with an old Jacobian: refresh it for the next step
            return True, jac_ok and it < 3
        if not jac_ok:
            _jacobian(geo, coeffs, params, q, u, up, h, th_next, dim, res, jac, stats)
            jac_ok = True
            fresh = True
        for i in range(dim):
            res[i] = -res[i]
        ok = _solve(jac, res, dim, du)
        for i in range(dim):
            res[i] = -res[i]
        if not ok:
            if fresh:
                return False, False
            jac_ok = False
            continue
        step = 1.0
        improved = False
        rt = rn
        for _ls in range(10):
            for i in range(3):
                trial[i] = up[i]
            for i in range(dim):
                trial[i] = up[i] + step * du[i]
            _residual(geo, coeffs, params, q, u, trial, h, th_next, dim, rtrial, ftrial)
            stats[0] += 1.0
            rt = _norm(rtrial, dim)
            if rt < rn:
                improved = True
                break
            step *= 0.5
        if not improved:
            if not fresh:
                jac_ok = False  # stale Jacobian: refresh and retry from the same point
                continue
            stats[6] = max(stats[6], rn / mg)
            stats[7] += 1.0
            return True, jac_ok
        moved = 0.0
        for i in range(dim):
            moved = max(moved, abs(step * du[i]) * (params[P_RADIUS] if i == 2 else 1.0))
        for i in range(3):
            up[i] = trial[i]
            res[i] = rtrial[i]
            frc[i] = ftrial[i]
        rn = rt
        fresh = False
        if rn > tol and moved <= vtol:
            stats[6] = max(stats[6], rn / mg)
            stats[7] += 1.0
            return True, jac_ok
    return rn <= tol, False


@nb.njit(cache=True, nogil=True)
def _step(geo, coeffs, params, t, state, acc, h, jac, jac_ok, frc, stats, out_state):
    """One backward-Euler step of size h from ``state`` (x, z, theta, vx, vz, omega).

    Writes the end state in ``out_state`` and the end soil wrench in ``frc``; returns
    (converged, jac_ok, stuck).
    """
    dim = 3 if params[P_MODE] == 1.0 else 2
    q = state[0:3]
    u = state[3:6]
    up = np.empty(3)
    th_next = 0.0
    if dim == 2:
        w_next = omega_profile(t + h, params)
        th_next = q[2] + 0.5 * h * (u[2] + w_next)
        up[2] = w_next
        if w_next == 0.0 and u[2] == 0.0 and _try_stick(geo, coeffs, params, q, u, h, frc):
            stats[4] += 1.0
            out_state[0] = q[0]
            out_state[1] = q[1]
            out_state[2] = q[2]
            out_state[3] = 0.0
            out_state[4] = 0.0
            out_state[5] = 0.0
            return True, jac_ok, True
    else:
        up[2] = u[2] + h * acc[2]
    up[0] = u[0] + h * acc[0]
    up[1] = u[1] + h * acc[1]
    ok, jac_ok = _newton(geo, coeffs, params, q, u, up, h, th_next, dim, jac, jac_ok, frc, stats)
    out_state[0] = q[0] + h * up[0]
    out_state[1] = q[1] + h * up[1]
    out_state[2] = q[2] + h * up[2] if dim == 3 else th_next
    out_state[3] = up[0]
    out_state[4] = up[1]
    out_state[5] = up[2]
    return ok, jac_ok, False


@nb.njit(cache=True, nogil=True)
def _sinkage(outline, z, th, surface):
    c = math.cos(th)
    s = math.sin(th)
    low = math.inf
    for i in range(outline.shape[0]):
        low = min(low, z - s * outline[i, 0] + c * outline[i, 1])
    return surface - low


@nb.njit(cache=True, nogil=True)
def integrate_wheel_kernel(
    mid: np.ndarray,
    nrm: np.ndarray,
    lengths: np.ndarray,
    coeffs: np.ndarray,
    outline: np.ndarray,
    params: np.ndarray,
    state0: np.ndarray,
    dt: float,
    n_steps: int,
    output_every: int,
) -> tuple[np.ndarray, np.ndarray]:
    """Integrate a body for ``n_steps`` steps of ``dt`` [s]; sample every ``output_every`` steps.

    Parameters
    ----------
    mid, nrm : (N, 2) body-frame element midpoints [m] and outward normals [-]
    lengths : (N,) element lengths [m]
    coeffs : (9,) Li coefficients [-] (kernel order)
    outline : (P, 2) body-frame boundary points [m] for the sinkage
    params : (N_PARAMS,) float64, layout of the ``P_*`` constants
    state0 : (6,) initial x, z [m], theta [rad], vx, vz [m/s], omega [rad/s]

    Returns
    -------
    out : (n_steps // output_every + 1, N_COLUMNS) sampled series (``C_*`` columns), row 0 = start
    stats : (N_STATS,) force evaluations, Jacobians, steps, substeps, stuck steps, failed steps,
        largest residual / (m g) accepted on a force discontinuity, steps accepted on one
    """
    ang, size = body_angles_kernel(mid, lengths)
    geo = (mid, nrm, lengths, ang, size)
    n_out = n_steps // output_every + 1
    out = np.zeros((n_out, N_COLUMNS))
    stats = np.zeros(N_STATS)
    state = state0.copy()
    trial = np.empty(6)
    start = np.empty(6)
    frc = np.zeros(3)
    acc = np.zeros(3)
    acc[1] = -params[P_GRAVITY]
    jac = np.zeros((3, 3))
    jac_ok = False
    inertia = params[P_INERTIA]
    surface = params[P_SURFACE]
    radius = params[P_RADIUS]
    work = 0.0
    max_halvings = int(params[P_MAX_HALVINGS])
    torque_drive = 0.0
    if params[P_MODE] == 1.0:
        torque_drive = params[P_TORQUE]
    fx0, fz0, ty0 = _soil(geo, coeffs, params, state[0], state[1], state[2], state[3], state[4], state[5])
    _record(out, 0, 0.0, state, fx0, fz0, ty0, torque_drive, work, radius, outline, surface)
    t = 0.0
    k = 0
    for n in range(n_steps):
        for i in range(6):
            start[i] = state[i]
        level = 0
        while True:
            nsub = 1 << level
            h = dt / nsub
            ok_all = True
            for i in range(6):
                state[i] = start[i]
            wsum = 0.0
            tsub = t
            for _sub in range(nsub):
                ok, jac_ok, _stuck = _step(
                    geo, coeffs, params, tsub, state, acc, h, jac, jac_ok, frc, stats, trial
                )
                if not ok:
                    ok_all = False
                    if level < max_halvings:
                        break
                    stats[5] += 1.0
                # work of the soil wrench over the substep (backward-Euler consistent)
                wsum += frc[0] * (trial[0] - state[0]) + frc[1] * (trial[1] - state[1])
                wsum += frc[2] * (trial[2] - state[2])
                acc[0] = (trial[3] - state[3]) / h
                acc[1] = (trial[4] - state[4]) / h
                acc[2] = (trial[5] - state[5]) / h
                for i in range(6):
                    state[i] = trial[i]
                tsub += h
            if ok_all or level >= max_halvings:
                break
            level += 1
            jac_ok = False
        stats[2] += 1.0
        stats[3] += (1 << level) - 1
        work += wsum
        t = (n + 1) * dt
        if params[P_MODE] == 1.0:
            torque_drive = params[P_TORQUE]
        else:
            torque_drive = inertia * acc[2] - frc[2]
        if (n + 1) % output_every == 0:
            k += 1
            _record(out, k, t, state, frc[0], frc[1], frc[2], torque_drive, work, radius, outline, surface)
    return out, stats


@nb.njit(cache=True, nogil=True)
def _record(out, k, t, state, fx, fz, ty, torque_drive, work, radius, outline, surface):
    out[k, C_T] = t
    for i in range(6):
        out[k, C_X + i] = state[i]
    out[k, C_FX] = fx
    out[k, C_FZ] = fz
    out[k, C_TORQUE] = torque_drive
    wr = state[5] * radius
    out[k, C_SLIP] = 1.0 - state[3] / wr if abs(wr) > 1e-12 else 0.0
    out[k, C_SINKAGE] = _sinkage(outline, state[1], state[2], surface)
    out[k, C_POWER] = torque_drive * state[5]
    out[k, C_SOIL_TORQUE] = ty
    out[k, C_WORK] = work
