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

References
----------
S. Dunatunga, K. Kamrin, Continuum modelling and simulation of granular flows through their many
phases, J. Fluid Mech. 779 (2015). doi:10.1017/jfm.2015.383
P. Jop, Y. Forterre, O. Pouliquen, A constitutive law for dense granular flows, Nature 441 (2006).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from numpy.typing import NDArray

__all__ = [
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
