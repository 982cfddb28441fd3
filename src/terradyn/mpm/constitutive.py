"""Dunatunga-Kamrin granular constitutive update for plane strain (pointwise law).

One material point, one step: hypoelastic Jaumann trial stress, then the closed-form return map of
the rate-independent Drucker-Prager cone ``tau <= mu_s p`` or its mu(I)-rate-dependent extension, and
the stress-free *disconnected* state when the density is below the critical density or the trial
pressure is not positive. Plastic flow is isochoric (no pressure correction): the return is radial in
the deviatoric plane.

Stress components are stored as ``(s_xx, s_zz, s_xz, s_yy)`` [Pa], tension positive, with ``s_yy`` the
out-of-plane stress tracked for plane strain. ``L`` is the in-plane velocity gradient
``L[a, b] = d v_a / d x_b`` [1/s] with index 0 = x and 1 = z.

Symbols (continuum.md section 2): ``p = -tr(sigma)/3``, ``tau = |sigma_0| / sqrt(2)``,
``I = gdot d / sqrt(p / rho_s)``, ``mu(I) = mu_s + (mu_2 - mu_s) / (I_0 / I + 1)``.

Dilatancy (opt-in, :func:`dk_dilatant_stress_update`): the packing fraction ``phi = rho / rho_s`` is the
state variable and the critical-state dilatancy law of Roux & Radjai (1998) in the form of Pailha &
Pouliquen (2009) sets the dilatancy angle and adds it to the friction:

    tan(psi) = K (phi - phi_c),    mu = mu(I) + tan(psi),    tr D^p = tan(psi) gdot_p,

so a point denser than critical (``phi > phi_c = rho_c / rho_s``) dilates while it flows and is
stronger, a looser one compacts and is weaker, and at ``phi_c`` flow is isochoric. The plastic
volume rate is taken out of the elastic one, so under a fixed total volume a dilating point gains
pressure ``K_b dt tan(psi) gdot_p`` (``K_b`` the bulk modulus) and pushes its neighbours apart; its
volume, and so ``phi``, then changes through the motion (``V_p`` follows ``det F``). ``K = 0`` is the
isochoric model above. ``phi_c`` does not depend on ``I`` here (the quasi-static limit).

References
----------
S. Dunatunga, K. Kamrin, Continuum modelling and simulation of granular flows through their many
phases, J. Fluid Mech. 779 (2015). doi:10.1017/jfm.2015.383
P. Jop, Y. Forterre, O. Pouliquen, A constitutive law for dense granular flows, Nature 441 (2006).
S. Roux, F. Radjai, Texture-dependent rigid-plastic behavior, in Physics of Dry Granular Media,
NATO ASI Series E 350, Kluwer (1998) 229-236.
M. Pailha, O. Pouliquen, A two-phase flow description of the initiation of underwater granular
avalanches, J. Fluid Mech. 633 (2009) 115-135. doi:10.1017/S0022112009007460
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from numpy.typing import NDArray

__all__ = [
    "TAN_PSI_LIMIT",
    "dilatancy_slope",
    "dk_dilatant_stress_update",
    "dk_dilatant_stress_update_reference",
    "dk_stress_update",
    "dk_stress_update_many",
    "dk_stress_update_reference",
    "mu_of_inertial_number",
]


@njit(cache=True, fastmath=True, inline="always")
def dk_stress_update(
    sxx: float,
    szz: float,
    sxz: float,
    syy: float,
    lxx: float,
    lxz: float,
    lzx: float,
    lzz: float,
    dt: float,
    rho: float,
    shear_modulus: float,
    lame_lambda: float,
    mu_s: float,
    mu_2: float,
    inertial_number_0: float,
    grain_diameter: float,
    grain_density: float,
    critical_density: float,
) -> tuple[float, float, float, float, float]:
    """Update one point's stress over ``dt`` [s]; returns ``(s_xx, s_zz, s_xz, s_yy, gdot_p)``.

    Stresses [Pa], velocity gradient components [1/s], densities [kg/m^3], moduli [Pa], grain
    diameter [m]; ``gdot_p`` is the equivalent plastic shear rate [1/s].
    """
    g = shear_modulus
    # Jaumann (co-rotational) hypoelastic trial stress; D = sym L, W = skew L.
    dxx = lxx
    dzz = lzz
    dxz = 0.5 * (lxz + lzx)
    wxz = 0.5 * (lxz - lzx)
    trd = dxx + dzz
    txx = sxx + dt * (2.0 * g * dxx + lame_lambda * trd + 2.0 * wxz * sxz)
    tzz = szz + dt * (2.0 * g * dzz + lame_lambda * trd - 2.0 * wxz * sxz)
    txz = sxz + dt * (2.0 * g * dxz + wxz * (szz - sxx))
    tyy = syy + dt * lame_lambda * trd
    # Trial invariants.
    p = -(txx + tzz + tyy) / 3.0
    s0xx = txx + p
    s0zz = tzz + p
    s0yy = tyy + p
    tau_tr = math.sqrt(0.5 * (s0xx * s0xx + s0zz * s0zz + s0yy * s0yy + 2.0 * txz * txz))
    # Disconnected: no stress below the critical density or without compression.
    if rho < critical_density or p <= 0.0:
        return 0.0, 0.0, 0.0, 0.0, tau_tr / (g * dt)
    s0 = mu_s * p
    if tau_tr <= s0:
        return txx, tzz, txz, tyy, 0.0
    # Flowing: smaller root of tau^2 - (S2 + tau_tr + alpha) tau + (S2 tau_tr + S0 alpha) = 0.
    s2 = mu_2 * p
    alpha = g * inertial_number_0 * dt * math.sqrt(p / grain_density) / grain_diameter
    b = -(s2 + tau_tr + alpha)
    c = s2 * tau_tr + s0 * alpha
    disc = b * b - 4.0 * c
    if disc < 0.0:
        disc = 0.0
    tau = 2.0 * c / (-b + math.sqrt(disc))
    scale = tau / tau_tr
    return (
        scale * s0xx - p,
        scale * s0zz - p,
        scale * txz,
        scale * s0yy - p,
        (tau_tr - tau) / (g * dt),
    )


#: Bound on |tan(psi)| as a fraction of mu_s: keeps the friction ``mu_s + tan(psi)`` positive and the
#: return map well posed for points far from critical (|psi| <= 15.6 deg for mu_s = 0.56).
TAN_PSI_LIMIT = 0.5


@njit(cache=True, fastmath=True, inline="always")
def dilatancy_slope(
    rho: float, dilatancy: float, critical_density: float, grain_density: float, mu_s: float
) -> float:
    """``tan(psi) = K (phi - phi_c)`` [-] with ``phi = rho / rho_s``, bounded by ``TAN_PSI_LIMIT mu_s``.

    Densities [kg/m^3]; ``dilatancy`` is K [-] (Pailha & Pouliquen 2009, after Roux & Radjai 1998).
    """
    beta = dilatancy * (rho - critical_density) / grain_density
    limit = TAN_PSI_LIMIT * mu_s
    return min(limit, max(-limit, beta))


@njit(cache=True, fastmath=True)
def _dilatant_residual(gd, tau_tr, p_tr, g_dt, kb_dt, beta, mu_s, mu_2, i_0, d, rho_s):
    """``tau - mu p`` [Pa] after a plastic shear rate ``gd`` [1/s] (see :func:`dk_dilatant_stress_update`)."""
    tau = tau_tr - g_dt * gd
    p = p_tr + kb_dt * beta * gd
    if p <= 0.0:
        return tau
    inertial = gd * d / math.sqrt(p / rho_s)
    return tau - (mu_s + beta + (mu_2 - mu_s) * inertial / (i_0 + inertial)) * p


@njit(cache=True, fastmath=True)
def dk_dilatant_stress_update(
    sxx: float,
    szz: float,
    sxz: float,
    syy: float,
    lxx: float,
    lxz: float,
    lzx: float,
    lzz: float,
    dt: float,
    rho: float,
    shear_modulus: float,
    lame_lambda: float,
    mu_s: float,
    mu_2: float,
    inertial_number_0: float,
    grain_diameter: float,
    grain_density: float,
    critical_density: float,
    dilatancy: float,
    loose_density: float,
) -> tuple[float, float, float, float, float]:
    """:func:`dk_stress_update` with the dilatancy law of the module doc; same arguments and return.

    ``dilatancy`` is K [-] (> 0); ``loose_density`` [kg/m^3] (<= critical) replaces the critical
    density as the disconnection threshold: a point between the two is connected and compacts as it
    flows. Flowing points solve, for the plastic shear rate ``gdot``, ``tau = mu(I) p`` with
    ``tau = tau_tr - G dt gdot``, ``p = p_tr + K_b dt tan(psi) gdot`` and ``mu = mu(I) + tan(psi)``
    (``tan(psi)`` from the density at the start of the step); in closed form when mu_2 = mu_s, else by
    bisection. A compacting point whose pressure would reach zero first is returned stress-free.
    """
    g = shear_modulus
    dxx = lxx
    dzz = lzz
    dxz = 0.5 * (lxz + lzx)
    wxz = 0.5 * (lxz - lzx)
    trd = dxx + dzz
    txx = sxx + dt * (2.0 * g * dxx + lame_lambda * trd + 2.0 * wxz * sxz)
    tzz = szz + dt * (2.0 * g * dzz + lame_lambda * trd - 2.0 * wxz * sxz)
    txz = sxz + dt * (2.0 * g * dxz + wxz * (szz - sxx))
    tyy = syy + dt * lame_lambda * trd
    p = -(txx + tzz + tyy) / 3.0
    s0xx = txx + p
    s0zz = tzz + p
    s0yy = tyy + p
    tau_tr = math.sqrt(0.5 * (s0xx * s0xx + s0zz * s0zz + s0yy * s0yy + 2.0 * txz * txz))
    free_rate = tau_tr / (g * dt)
    if rho < loose_density or p <= 0.0:
        return 0.0, 0.0, 0.0, 0.0, free_rate
    beta = dilatancy_slope(rho, dilatancy, critical_density, grain_density, mu_s)
    mu_y = mu_s + beta
    f0 = tau_tr - mu_y * p
    if f0 <= 0.0:
        return txx, tzz, txz, tyy, 0.0
    g_dt = g * dt
    kb_dt = (lame_lambda + 2.0 * g / 3.0) * dt
    # Largest admissible rate: the deviator vanishes, or (compacting) the pressure does.
    gd_max = free_rate
    if beta < 0.0:
        gd_max = min(gd_max, p / (kb_dt * -beta))
    if mu_2 == mu_s:
        slope = g_dt + mu_y * kb_dt * beta  # -d(tau - mu_y p)/d gdot
        if slope <= 0.0 or f0 >= slope * gd_max:
            return 0.0, 0.0, 0.0, 0.0, free_rate  # compacts to zero pressure first: liquefied
        gd = f0 / slope
    else:
        args = (tau_tr, p, g_dt, kb_dt, beta, mu_s, mu_2, inertial_number_0, grain_diameter)
        if _dilatant_residual(gd_max, *args, grain_density) >= 0.0:
            return 0.0, 0.0, 0.0, 0.0, free_rate
        lo = 0.0
        hi = gd_max
        for _ in range(100):
            mid = 0.5 * (lo + hi)
            if _dilatant_residual(mid, *args, grain_density) > 0.0:
                lo = mid
            else:
                hi = mid
            if hi - lo <= 1e-14 * hi:
                break
        gd = 0.5 * (lo + hi)
    p_new = p + kb_dt * beta * gd
    tau = tau_tr - g_dt * gd
    scale = tau / tau_tr
    return scale * s0xx - p_new, scale * s0zz - p_new, scale * txz, scale * s0yy - p_new, gd


def mu_of_inertial_number(inertial_number, mu_s: float, mu_2: float, inertial_number_0: float):
    """Friction coefficient mu(I) = mu_s + (mu_2 - mu_s) I / (I_0 + I) [-] (Jop et al. 2006)."""
    i = np.asarray(inertial_number, dtype=float)
    return mu_s + (mu_2 - mu_s) * i / (inertial_number_0 + i)


@njit(cache=True, fastmath=True)
def dk_stress_update_many(
    stress: NDArray[np.float64],
    grad_v: NDArray[np.float64],
    rho: NDArray[np.float64],
    dt: float,
    shear_modulus: float,
    lame_lambda: float,
    mu_s: float,
    mu_2: float,
    inertial_number_0: float,
    grain_diameter: float,
    grain_density: float,
    critical_density: float,
) -> NDArray[np.float64]:
    """Batched :func:`dk_stress_update`: ``stress`` (N, 4) [Pa] updated in place; returns gdot_p (N,)."""
    n = stress.shape[0]
    gdot = np.empty(n)
    for k in range(n):
        out = dk_stress_update(
            stress[k, 0],
            stress[k, 1],
            stress[k, 2],
            stress[k, 3],
            grad_v[k, 0, 0],
            grad_v[k, 0, 1],
            grad_v[k, 1, 0],
            grad_v[k, 1, 1],
            dt,
            rho[k],
            shear_modulus,
            lame_lambda,
            mu_s,
            mu_2,
            inertial_number_0,
            grain_diameter,
            grain_density,
            critical_density,
        )
        stress[k, 0] = out[0]
        stress[k, 1] = out[1]
        stress[k, 2] = out[2]
        stress[k, 3] = out[3]
        gdot[k] = out[4]
    return gdot


def dk_stress_update_reference(
    stress: NDArray[np.float64],
    grad_v: NDArray[np.float64],
    rho: NDArray[np.float64],
    dt: float,
    shear_modulus: float,
    lame_lambda: float,
    mu_s: float,
    mu_2: float,
    inertial_number_0: float,
    grain_diameter: float,
    grain_density: float,
    critical_density: float,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Pure-NumPy reference of :func:`dk_stress_update_many`; returns ``(new_stress (N, 4), gdot (N,))``.

    Written with full tensors (3x3 with y out of plane) rather than components, as an independent check.
    """
    n = stress.shape[0]
    sig = np.zeros((n, 3, 3))
    sig[:, 0, 0], sig[:, 2, 2], sig[:, 1, 1] = stress[:, 0], stress[:, 1], stress[:, 3]
    sig[:, 0, 2] = sig[:, 2, 0] = stress[:, 2]
    lg = np.zeros((n, 3, 3))
    lg[:, 0, 0], lg[:, 0, 2] = grad_v[:, 0, 0], grad_v[:, 0, 1]
    lg[:, 2, 0], lg[:, 2, 2] = grad_v[:, 1, 0], grad_v[:, 1, 1]
    d = 0.5 * (lg + np.transpose(lg, (0, 2, 1)))
    w = 0.5 * (lg - np.transpose(lg, (0, 2, 1)))
    eye = np.eye(3)
    trd = np.trace(d, axis1=1, axis2=2)
    rate = 2.0 * shear_modulus * d + lame_lambda * trd[:, None, None] * eye + w @ sig - sig @ w
    trial = sig + dt * rate
    p = -np.trace(trial, axis1=1, axis2=2) / 3.0
    dev = trial + p[:, None, None] * eye
    tau_tr = np.sqrt(0.5 * np.einsum("kij,kij->k", dev, dev))
    s0, s2 = mu_s * p, mu_2 * p
    alpha = shear_modulus * inertial_number_0 * dt * np.sqrt(np.maximum(p, 0.0) / grain_density)
    alpha /= grain_diameter
    bq = s2 + tau_tr + alpha
    cq = s2 * tau_tr + s0 * alpha
    tau_flow = 0.5 * (bq - np.sqrt(np.maximum(bq * bq - 4.0 * cq, 0.0)))
    open_ = (rho < critical_density) | (p <= 0.0)
    elastic = ~open_ & (tau_tr <= s0)
    flowing = ~open_ & ~elastic
    tau = np.where(flowing, tau_flow, tau_tr)
    scale = np.divide(tau, tau_tr, out=np.ones_like(tau), where=tau_tr > 0)
    new = scale[:, None, None] * dev - p[:, None, None] * eye
    new[open_] = 0.0
    gdot = np.where(open_, tau_tr / (shear_modulus * dt), (tau_tr - tau) / (shear_modulus * dt))
    out = np.stack([new[:, 0, 0], new[:, 2, 2], new[:, 0, 2], new[:, 1, 1]], axis=1)
    return out, gdot


def _reference_stress_after(rate, trial, n_dev, beta, dt, g, kb):
    """Stress (3, 3) [Pa] after the plastic rate ``D^p = rate (n_dev + tan(psi) 1 / 3)`` [1/s]."""
    eye = np.eye(3)
    d_p = rate * (n_dev + beta * eye / 3.0)
    tr = np.trace(d_p)
    return trial - dt * (2.0 * g * (d_p - tr * eye / 3.0) + kb * tr * eye)


def _reference_residual(rate, trial, n_dev, beta, dt, g, kb, mu_s, mu_2, i_0, d, rho_s):
    """``tau - (mu(I) + tan(psi)) p`` [Pa] after the plastic rate ``rate`` [1/s]."""
    new = _reference_stress_after(rate, trial, n_dev, beta, dt, g, kb)
    p = -np.trace(new) / 3.0
    s0 = new + p * np.eye(3)
    tau = math.sqrt(0.5 * float(np.sum(s0 * s0)))
    if p <= 0.0:
        return tau
    inertial = rate * d / math.sqrt(p / rho_s)
    return tau - (mu_s + beta + (mu_2 - mu_s) * inertial / (i_0 + inertial)) * p


def dk_dilatant_stress_update_reference(
    stress: NDArray[np.float64],
    grad_v: NDArray[np.float64],
    rho: NDArray[np.float64],
    dt: float,
    shear_modulus: float,
    lame_lambda: float,
    mu_s: float,
    mu_2: float,
    inertial_number_0: float,
    grain_diameter: float,
    grain_density: float,
    critical_density: float,
    dilatancy: float,
    loose_density: float,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Pure-Python reference of :func:`dk_dilatant_stress_update` for N points (arguments as in
    :func:`dk_stress_update_reference`); returns ``(new_stress (N, 4), gdot (N,))``.

    Independent of the kernel: full 3x3 tensors, the flow rule written as a plastic strain rate
    ``D^p = gdot (sigma_0 / (2 tau) + tan(psi) 1 / 3)`` taken out of the elastic rate, and the
    consistency condition solved by Brent's method in every case.
    """
    from scipy.optimize import brentq

    g, lam = shear_modulus, lame_lambda
    kb = lam + 2.0 * g / 3.0
    eye = np.eye(3)
    out = np.zeros((len(stress), 4))
    rates = np.zeros(len(stress))
    for k in range(len(stress)):
        s = stress[k]
        sig = np.array([[s[0], 0.0, s[2]], [0.0, s[3], 0.0], [s[2], 0.0, s[1]]])
        lg = np.zeros((3, 3))
        lg[0, 0], lg[0, 2] = grad_v[k, 0, 0], grad_v[k, 0, 1]
        lg[2, 0], lg[2, 2] = grad_v[k, 1, 0], grad_v[k, 1, 1]
        d = 0.5 * (lg + lg.T)
        w = 0.5 * (lg - lg.T)
        trial = sig + dt * (2.0 * g * d + lam * np.trace(d) * eye + w @ sig - sig @ w)
        p_tr = -np.trace(trial) / 3.0
        dev = trial + p_tr * eye
        tau_tr = math.sqrt(0.5 * float(np.sum(dev * dev)))
        if rho[k] < loose_density or p_tr <= 0.0:
            rates[k] = tau_tr / (g * dt)
            continue
        beta = dilatancy * (rho[k] - critical_density) / grain_density
        beta = float(np.clip(beta, -TAN_PSI_LIMIT * mu_s, TAN_PSI_LIMIT * mu_s))
        if tau_tr <= (mu_s + beta) * p_tr:
            out[k] = trial[0, 0], trial[2, 2], trial[0, 2], trial[1, 1]
            continue
        n_dev = dev / (2.0 * tau_tr)
        flow = (trial, n_dev, beta, dt, g, kb)
        material = (mu_s, mu_2, inertial_number_0, grain_diameter, grain_density)
        hi = tau_tr / (g * dt)
        if beta < 0.0:
            hi = min(hi, p_tr / (kb * dt * -beta))
        if _reference_residual(hi, *flow, *material) >= 0.0:
            rates[k] = tau_tr / (g * dt)  # liquefied: stress-free
            continue
        rate = brentq(_reference_residual, 0.0, hi, args=(*flow, *material), xtol=1e-14 * hi, rtol=1e-14,
                      maxiter=500)  # fmt: skip
        new = _reference_stress_after(rate, *flow)
        out[k] = new[0, 0], new[2, 2], new[0, 2], new[1, 1]
        rates[k] = rate
    return out, rates
