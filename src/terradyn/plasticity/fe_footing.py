"""A small-strain finite-element strip footing on the MPM's own cone, with the flow rule selectable.

An independent reference for the MPM strip footing (:func:`terradyn.studies.mpm_verification.strip_footing`):
the same material (the Drucker-Prager cone ``sqrt(J2) = mu p`` with the MPM's elastic moduli and unit
weight) solved by another method, with the flow rule as the only switch:

* ``flow="associated"``: normality; the collapse pressure must approach the exact value of the
  associated cone, which in plane strain is Mohr-Coulomb at
  :func:`~terradyn.plasticity.references.cone_plane_strain_friction_angle` (the method of
  characteristics, :func:`~terradyn.plasticity.moc.moc_n_gamma`). This checks the solver.
* ``flow="isochoric"``: no plastic volume change (``psi = 0``), the MPM's flow rule. In plane strain
  this cone is then Mohr-Coulomb at ``asin(mu)``; the value is the non-associated ``N_gamma`` the MPM
  should read, computed rather than estimated.

Method (the mixed-discretisation idea of explicit finite-difference codes, here as Q4 elements):
square bilinear elements on a half domain (symmetry at ``x = 0``), 2 x 2 Gauss points whose volumetric
strain rate is replaced by the element mean (B-bar, against volumetric locking), lumped masses, an
explicit update with local non-viscous damping (the unbalanced force of each node reduced by
``damping |F| sign(v)``) so the run relaxes to static equilibrium, small strain (the mesh does not move;
no embedment). The bed starts at rest under gravity with ``sigma_xx = sigma_yy = K0 sigma_zz``,
``K0 = 1 - mu`` (inside the cone), is relaxed, then the footing nodes (the surface nodes with
``x <= B/2``) move down at a constant small rate: vertical velocity only for a smooth base, both
components for a rough one. The bearing pressure is the vertical reaction of the footing nodes over
``B / 2``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numba import njit

from ..errors import InputError

__all__ = ["FEConvergence", "FEFooting", "fe_n_gamma_convergence", "fe_strip_footing"]

_G = 1.0 / math.sqrt(3.0)


@njit(cache=True, fastmath=True)
def _cone_return(sxx, szz, sxz, syy, g_mod, k_mod, mu, associated):
    """Return a trial stress (tension positive, Pa) to the cone ``sqrt(J2) <= mu p``.

    Isochoric flow scales the deviator at constant ``p``; associated flow also raises ``p`` by
    ``K mu dlambda`` (plastic dilation held by the elastic bed). Beyond the apex: zero stress."""
    p = -(sxx + szz + syy) / 3.0
    dxx = sxx + p
    dzz = szz + p
    dyy = syy + p
    tau = math.sqrt(0.5 * (dxx * dxx + dzz * dzz + dyy * dyy) + sxz * sxz)
    f = tau - mu * p
    if f <= 0.0:
        return sxx, szz, sxz, syy, 0.0
    if associated:
        lam = f / (g_mod + k_mod * mu * mu)
        tau_n = tau - g_mod * lam
        p_n = p + k_mod * mu * lam
        if tau_n <= 0.0 or p_n <= 0.0:
            return 0.0, 0.0, 0.0, 0.0, 1.0
    else:
        if p <= 0.0:
            return 0.0, 0.0, 0.0, 0.0, 1.0
        tau_n = mu * p
        p_n = p
    s = tau_n / tau
    return s * dxx - p_n, s * dzz - p_n, s * sxz, s * dyy - p_n, 1.0


@njit(cache=True, fastmath=True)
def _run(xs, zs, rho, gravity, g_mod, lam, mu, associated, k0, n_foot, rough, rate, n_settle, n_push,
         n_hold, record_every, damping):  # fmt: skip
    """Relax, then push the footing on the rectilinear mesh of node lines ``xs`` (from the symmetry
    line) and ``zs`` (up to the surface z = 0), then hold it still for ``n_hold`` steps; returns rows
    (settlement [m], pressure x B / 2 [N/m], fraction of Gauss points at yield).

    Inertia uses a density scaled per element to the smallest element's time step (the result is
    static, so only the unit weight must be real); ``dt`` is half the smallest element's P-wave transit.
    """
    k_mod = lam + 2.0 * g_mod / 3.0
    nnx = xs.shape[0]
    nnz = zs.shape[0]
    nx = nnx - 1
    nz = nnz - 1
    h_min = 1e300
    for i in range(nx):
        h_min = min(h_min, xs[i + 1] - xs[i])
    for j in range(nz):
        h_min = min(h_min, zs[j + 1] - zs[j])
    dt = 0.5 * h_min / math.sqrt((lam + 2.0 * g_mod) / rho)
    vel = np.zeros((nnx, nnz, 2))
    force = np.zeros((nnx, nnz, 2))
    inertia = np.zeros((nnx, nnz))
    weight = np.zeros((nnx, nnz))
    stress = np.zeros((nx, nz, 4, 4))
    xi_n = np.array([-1.0, 1.0, 1.0, -1.0])
    eta_n = np.array([-1.0, -1.0, 1.0, 1.0])
    di = np.array([0, 1, 1, 0])
    dj = np.array([0, 0, 1, 1])
    # reference-element gradients: d N / d xi and d N / d eta at the Gauss points
    gxi = np.empty((4, 4))
    geta = np.empty((4, 4))
    for g in range(4):
        for a in range(4):
            gxi[g, a] = 0.25 * xi_n[a] * (1.0 + eta_n[a] * eta_n[g] * _G)
            geta[g, a] = 0.25 * eta_n[a] * (1.0 + xi_n[a] * xi_n[g] * _G)
    for i in range(nx):
        for j in range(nz):
            a = xs[i + 1] - xs[i]
            b = zs[j + 1] - zs[j]
            for g in range(4):
                zg = zs[j] + 0.5 * b * (1.0 + eta_n[g] * _G)
                szz = rho * gravity * zg
                stress[i, j, g, 0] = k0 * szz
                stress[i, j, g, 1] = szz
                stress[i, j, g, 3] = k0 * szz
            scaled = rho * (h_min / min(a, b)) ** 2
            for c in range(4):
                inertia[i + di[c], j + dj[c]] += 0.25 * scaled * a * b
                weight[i + di[c], j + dj[c]] += 0.25 * rho * gravity * a * b
    n_rec = (n_push + n_hold) // record_every + 1
    out = np.zeros((n_rec, 3))
    rec = 0
    settlement = 0.0
    lxx = np.empty(4)
    lxz = np.empty(4)
    lzx = np.empty(4)
    lzz = np.empty(4)
    gx = np.empty((4, 4))
    gz = np.empty((4, 4))
    for step in range(n_settle + n_push + n_hold):
        pushing = step >= n_settle
        held = step >= n_settle + n_push
        force[:, :, :] = 0.0
        n_plastic = 0
        for i in range(nx):
            a_len = xs[i + 1] - xs[i]
            for j in range(nz):
                b_len = zs[j + 1] - zs[j]
                w = 0.25 * a_len * b_len
                div = 0.0
                for g in range(4):
                    a_xx = 0.0
                    a_xz = 0.0
                    a_zx = 0.0
                    a_zz = 0.0
                    for c in range(4):
                        dx = gxi[g, c] * 2.0 / a_len
                        dz = geta[g, c] * 2.0 / b_len
                        gx[g, c] = dx
                        gz[g, c] = dz
                        vx = vel[i + di[c], j + dj[c], 0]
                        vz = vel[i + di[c], j + dj[c], 1]
                        a_xx += vx * dx
                        a_xz += vx * dz
                        a_zx += vz * dx
                        a_zz += vz * dz
                    lxx[g] = a_xx
                    lxz[g] = a_xz
                    lzx[g] = a_zx
                    lzz[g] = a_zz
                    div += 0.25 * (a_xx + a_zz)
                for g in range(4):
                    # B-bar: the volumetric strain rate of every Gauss point is the element mean
                    shift = 0.5 * (div - (lxx[g] + lzz[g]))
                    exx = (lxx[g] + shift) * dt
                    ezz = (lzz[g] + shift) * dt
                    exz = 0.5 * (lxz[g] + lzx[g]) * dt
                    tr = exx + ezz
                    sxx = stress[i, j, g, 0] + lam * tr + 2.0 * g_mod * exx
                    szz = stress[i, j, g, 1] + lam * tr + 2.0 * g_mod * ezz
                    sxz = stress[i, j, g, 2] + 2.0 * g_mod * exz
                    syy = stress[i, j, g, 3] + lam * tr
                    sxx, szz, sxz, syy, yl = _cone_return(sxx, szz, sxz, syy, g_mod, k_mod, mu, associated)
                    n_plastic += int(yl)
                    stress[i, j, g, 0] = sxx
                    stress[i, j, g, 1] = szz
                    stress[i, j, g, 2] = sxz
                    stress[i, j, g, 3] = syy
                    # the B-bar transpose: the in-plane mean stress acts through the element-mean
                    # gradient (d N / d x averaged over the Gauss points is xi_c / a)
                    half_d = 0.5 * (sxx - szz)
                    half_m = 0.5 * (sxx + szz)
                    for c in range(4):
                        fx = gx[g, c] * half_d + 0.5 * xi_n[c] / a_len * half_m + sxz * gz[g, c]
                        fz = -gz[g, c] * half_d + 0.5 * eta_n[c] / b_len * half_m + sxz * gx[g, c]
                        force[i + di[c], j + dj[c], 0] -= w * fx
                        force[i + di[c], j + dj[c], 1] -= w * fz
        # the reaction of the footing nodes, before their velocity is imposed
        react = 0.0
        for i in range(n_foot):
            react += force[i, nz, 1] - weight[i, nz]
        for i in range(nnx):
            for j in range(nnz):
                m = inertia[i, j]
                for c in range(2):
                    f = force[i, j, c] - (weight[i, j] if c == 1 else 0.0)
                    v = vel[i, j, c]
                    if v != 0.0:
                        f -= damping * abs(f) * (1.0 if v > 0.0 else -1.0)
                    vel[i, j, c] = v + dt * f / m
        # symmetry at x = 0, rollers at the far side, a fixed floor; then the footing
        for j in range(nnz):
            vel[0, j, 0] = 0.0
            vel[nnx - 1, j, 0] = 0.0
        for i in range(nnx):
            vel[i, 0, 0] = 0.0
            vel[i, 0, 1] = 0.0
        if pushing:
            for i in range(n_foot):
                vel[i, nz, 1] = 0.0 if held else -rate
                if rough:
                    vel[i, nz, 0] = 0.0
            if not held:
                settlement += rate * dt
            k = step - n_settle
            if k % record_every == 0:
                out[rec, 0] = settlement
                out[rec, 1] = react
                out[rec, 2] = n_plastic / (4.0 * nx * nz)
                rec += 1
    return out[:rec], dt


def _graded(fine: float, extent: float, h: float, ratio: float, h_max: float) -> np.ndarray:
    """Node coordinates from 0: spacing ``h`` up to ``fine``, then growing by ``ratio`` per element
    (at most ``h_max``) until ``extent`` is reached or passed."""
    n_fine = round(fine / h)
    pts = [k * h for k in range(n_fine + 1)]
    step = h
    while pts[-1] < extent - 1e-12:
        step = min(step * ratio, h_max)
        pts.append(pts[-1] + step)
    return np.asarray(pts)


@dataclass(frozen=True)
class FEFooting:
    """Result of :func:`fe_strip_footing`.

    ``curve`` (n, 2): settlement [m] and bearing pressure [Pa]; ``N_gamma`` = 2 q / (gamma B) of the
    mean pressure over the last quarter of the push, ``N_gamma_peak`` of the largest pressure,
    ``N_gamma_spread`` the max - min of ``2 q / (gamma B)`` over that last quarter (how far the curve
    is from a plateau)."""

    friction_coefficient: float
    flow: str
    base: str
    width_m: float
    element_size_m: float
    domain_m: tuple[float, float]
    unit_weight_N_m3: float
    N_gamma: float
    N_gamma_peak: float
    N_gamma_spread: float
    curve: np.ndarray
    plastic_fraction: float
    steps: int
    elements: int
    #: 2 q / (gamma B) while held after the push (``hold_crossings``), and its last-quarter mean
    N_gamma_held: float | None = None
    held_curve: np.ndarray | None = None
    #: duration of the push [s] (the loading rate is settlement / push time)
    push_time_s: float = 0.0

    def record(self) -> dict[str, Any]:
        """JSON-ready summary (no curve)."""
        return {
            "friction_coefficient": self.friction_coefficient,
            "flow": self.flow,
            "base": self.base,
            "width_m": self.width_m,
            "element_size_m": self.element_size_m,
            "domain_half_width_m": self.domain_m[0],
            "domain_depth_m": self.domain_m[1],
            "N_gamma": self.N_gamma,
            "N_gamma_peak": self.N_gamma_peak,
            "N_gamma_spread_last_quarter": self.N_gamma_spread,
            "plastic_fraction_end": self.plastic_fraction,
            "steps": self.steps,
            "elements": self.elements,
            "push_time_s": self.push_time_s,
            **({} if self.N_gamma_held is None else {"N_gamma_held": self.N_gamma_held}),
        }


def _check_material(friction_coefficient: float, flow: str, base: str) -> float:
    """The cone's friction coefficient mu in [0.05, 5], the flow rule and the footing base, checked."""
    mu = float(friction_coefficient)
    if not (math.isfinite(mu) and 0.05 <= mu <= 5.0):
        raise InputError("friction_coefficient", friction_coefficient, "a number in [0.05, 5]")
    if flow not in ("isochoric", "associated"):
        raise InputError("flow", flow, "'isochoric' or 'associated'")
    if base not in ("smooth", "rough"):
        raise InputError("base", base, "'smooth' or 'rough'")
    return mu


def _check_mesh(
    elements_per_half_width: int,
    domain_widths: tuple[float, float],
    fine_widths: tuple[float, float],
    growth: float,
) -> tuple[float, float, float, float]:
    """The mesh inputs checked: (domain half-width, domain depth, fine half-width, fine depth) [B]."""
    if not (isinstance(elements_per_half_width, int) and 2 <= elements_per_half_width <= 400):
        raise InputError("elements_per_half_width", elements_per_half_width, "an integer in [2, 400]")
    half_l, depth = (float(v) for v in domain_widths)
    fine_x, fine_z = (float(v) for v in fine_widths)
    if not (0.5 <= fine_x <= half_l and 0.0 < fine_z <= depth):
        raise InputError(
            "fine_widths", fine_widths, "(half-width in [0.5, domain half-width], depth in (0, domain depth])"
        )
    if not (1.0 <= growth <= 1.5):
        raise InputError("growth", growth, "a ratio in [1, 1.5]")
    return half_l, depth, fine_x, fine_z


def _check_loading(
    settlement_ratio: float,
    poisson_ratio: float,
    youngs_modulus: float,
    density: float,
    gravity: float,
    crossings: float,
    hold_crossings: float,
    damping: float,
) -> None:
    """One :class:`InputError` line for the first bad elastic, weight, push or hold input."""
    if not (0.0 < settlement_ratio <= 0.2):
        raise InputError("settlement_ratio", settlement_ratio, "a number in (0, 0.2]")
    if not (0.0 <= poisson_ratio < 0.5):
        raise InputError("poisson_ratio", poisson_ratio, "a number in [0, 0.5)")
    for name, value in (("youngs_modulus", youngs_modulus), ("density", density), ("gravity", gravity),
                        ("crossings", crossings)):  # fmt: skip
        if not (math.isfinite(value) and value > 0.0):
            raise InputError(name, value, "a positive number")
    if not (math.isfinite(hold_crossings) and 0.0 <= hold_crossings <= 1e4):
        raise InputError("hold_crossings", hold_crossings, "a number in [0, 1e4]")
    if not (0.0 <= damping < 1.0):
        raise InputError("damping", damping, "a number in [0, 1)")


def fe_strip_footing(
    friction_coefficient: float,
    *,
    flow: str = "isochoric",
    base: str = "smooth",
    width: float = 0.04,
    elements_per_half_width: int = 20,
    domain_widths: tuple[float, float] = (6.0, 3.0),
    fine_widths: tuple[float, float] = (1.5, 1.0),
    growth: float = 1.1,
    youngs_modulus: float = 5.0e6,
    poisson_ratio: float = 0.33,
    density: float = 1591.2,
    gravity: float = 9.81,
    settlement_ratio: float = 0.02,
    crossings: float = 200.0,
    damping: float = 0.8,
    hold_crossings: float = 0.0,
) -> FEFooting:
    """Collapse pressure of a rigid strip footing of ``width`` B [m] on the cone ``sqrt(J2) = mu p``.

    ``friction_coefficient`` mu [-] (the MPM's ``mu_s``; ``sin(phi)`` for Mohr-Coulomb ``phi`` with
    isochoric flow), ``flow`` ``"isochoric"`` or ``"associated"``, ``base`` ``"smooth"`` or
    ``"rough"``. Mesh: square elements of h = B / (2 ``elements_per_half_width``) over
    ``fine_widths`` = (half-width, depth) [B] next to the footing, growing by ``growth`` per element
    (up to B / 4) to the half domain ``domain_widths`` [B]. Elasticity ``youngs_modulus`` [Pa],
    ``poisson_ratio``; unit weight ``density`` [kg/m^3] x ``gravity`` [m/s^2]. The footing is pushed
    to ``settlement_ratio`` x B over ``crossings`` times the steps a wave needs to cross the mesh
    (2 per element along x plus z), after 20 crossings of relaxation under gravity; then held still
    for ``hold_crossings`` crossings (``N_gamma_held``: the mean over the hold's last quarter).
    """
    mu = _check_material(friction_coefficient, flow, base)
    half_l, depth, fine_x, fine_z = _check_mesh(elements_per_half_width, domain_widths, fine_widths, growth)
    _check_loading(
        settlement_ratio, poisson_ratio, youngs_modulus, density, gravity, crossings, hold_crossings, damping
    )
    h = 0.5 * width / elements_per_half_width
    xs = _graded(fine_x * width, half_l * width, h, growth, 0.25 * width)
    zs = -_graded(fine_z * width, depth * width, h, growth, 0.25 * width)[::-1]
    g_mod = youngs_modulus / (2.0 * (1.0 + poisson_ratio))
    lam = youngs_modulus * poisson_ratio / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio))
    n_cross = 2 * (len(xs) + len(zs))
    n_push = int(crossings * n_cross)
    n_settle = 20 * n_cross
    n_hold = int(hold_crossings * n_cross)
    dt = 0.5 * h / math.sqrt((lam + 2.0 * g_mod) / density)
    rate = settlement_ratio * width / (n_push * dt)
    n_foot = elements_per_half_width + 1
    record_every = max(1, n_push // 400)
    rows, dt_run = _run(xs, zs, density, gravity, g_mod, lam, mu, flow == "associated", 1.0 - mu, n_foot,
                        base == "rough", rate, n_settle, n_push, n_hold, record_every, damping)  # fmt: skip
    if abs(dt_run - dt) > 1e-9 * dt:  # the run's step is the smallest element's, which is h
        raise RuntimeError("fe_strip_footing: time step mismatch")
    gamma = density * gravity
    n_push_rows = -(-n_push // record_every)  # rows recorded while pushing; the rest are the hold
    q_all = rows[:, 1] / (0.5 * width)
    held = 2.0 * q_all[n_push_rows:] / (gamma * width)
    rows, q = rows[:n_push_rows], q_all[:n_push_rows]
    n = 2.0 * q / (gamma * width)
    tail = n[int(0.75 * len(n)) :]
    return FEFooting(
        friction_coefficient=mu,
        flow=flow,
        base=base,
        width_m=width,
        element_size_m=h,
        domain_m=(float(xs[-1]), float(-zs[0])),
        unit_weight_N_m3=gamma,
        N_gamma=float(np.mean(tail)),
        N_gamma_peak=float(np.max(n)),
        N_gamma_spread=float(np.max(tail) - np.min(tail)),
        curve=np.column_stack([rows[:, 0], q]),
        plastic_fraction=float(rows[-1, 2]),
        steps=n_settle + n_push + n_hold,
        N_gamma_held=float(np.mean(held[int(0.75 * len(held)) :])) if len(held) else None,
        held_curve=held,
        push_time_s=n_push * dt,
        elements=(len(xs) - 1) * (len(zs) - 1),
    )


@dataclass(frozen=True)
class FEConvergence:
    """:func:`fe_strip_footing` at several meshes with the Richardson estimate of ``N_gamma``."""

    runs: tuple[FEFooting, ...]
    elements_per_half_width: tuple[int, ...]
    estimate: Any  # terradyn.numerics.RichardsonEstimate
    wall_s: tuple[float, ...]

    def record(self) -> dict[str, Any]:
        """JSON-ready: the runs (mesh, N_gamma, spread, wall time) and the estimate."""
        first = self.runs[0]
        return {
            "friction_coefficient": first.friction_coefficient,
            "flow": first.flow,
            "base": first.base,
            "runs": [
                {"elements_per_half_width": n, **r.record(), "wall_s": w}
                for n, r, w in zip(self.elements_per_half_width, self.runs, self.wall_s, strict=True)
            ],
            **self.estimate.record("N_gamma"),
        }


def fe_n_gamma_convergence(
    friction_coefficient: float,
    *,
    flow: str = "isochoric",
    base: str = "smooth",
    elements: tuple[int, ...] = (5, 10, 20),
    progress: Callable[[float, float], None] | None = None,
    **kwargs: Any,
) -> FEConvergence:
    """:func:`fe_strip_footing` at each of ``elements`` (elements per footing half-width, three or more)
    and the Richardson estimate (:func:`terradyn.numerics.richardson`) of ``N_gamma`` from
    the three finest. ``progress(done, total)`` after each mesh, with work counted as elements x
    steps (the cost of a mesh grows about as the cube of its refinement)."""
    import time

    from ..numerics import richardson

    meshes = tuple(elements)
    if (len(meshes) < 3 or len(set(meshes)) != len(meshes)
            or not all(isinstance(n, int) and 2 <= n <= 400 for n in meshes)):  # fmt: skip
        # checked before the first mesh runs, so a bad last mesh does not waste the others
        raise InputError("elements", list(meshes), "three or more distinct integers in [2, 400]")
    cost = [float(n) ** 3 for n in meshes]
    total = sum(cost)
    done = 0.0
    runs = []
    walls = []
    for n, c in zip(meshes, cost, strict=True):
        t0 = time.perf_counter()
        runs.append(fe_strip_footing(friction_coefficient, flow=flow, base=base, elements_per_half_width=n,
                                     **kwargs))  # fmt: skip
        walls.append(time.perf_counter() - t0)
        done += c
        if progress is not None:
            progress(done, total)
    est = richardson([r.element_size_m for r in runs], [r.N_gamma for r in runs])
    return FEConvergence(tuple(runs), meshes, est, tuple(walls))
