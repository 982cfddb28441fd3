"""Numba kernels of the explicit plane-strain MPM step (APIC transfer, quadratic B-splines).

One step has the three phases of the literature (update-stress-last):

1. particle -> grid (:func:`p2g`): mass ``m_i = sum w_ip m_p``, affine momentum
   ``sum w_ip m_p (v_p + C_p (x_i - x_p))`` plus the internal-force impulse ``-dt sum V_p sigma_p grad w_ip``;
2. grid update (:func:`grid_update`, :func:`body_contact`): ``v_i = p_i / m_i + dt g``, wall conditions,
   rigid-body frictional contact (the impulse taken from the grains is the force on the body);
3. grid -> particle (:func:`g2p`): ``v_p = sum w_ip v_i``, ``C_p = 4/h^2 sum w_ip v_i (x_i - x_p)^T``,
   ``L_p = sum v_i grad w_ip^T``, ``x_p += dt v_p``, ``V_p *= exp(dt tr L_p)``, stress update.

Grid node ``(i, j)`` sits at world ``(x0 + i h, z0 + j h)``. Particle arrays: positions ``pos`` (N, 2)
[m], velocities ``vel`` (N, 2) [m/s], affine matrices ``aff`` (N, 2, 2) [1/s], stresses ``stress``
(N, 4) = (s_xx, s_zz, s_xz, s_yy) [Pa], masses ``mass`` (N,) [kg/m] and volumes ``vol`` (N,) [m^2]
per unit out-of-plane width. Wall codes: 0 free-slip (separable), 1 no-slip, 2 Coulomb friction.
"""

from __future__ import annotations

import math

import numpy as np
from numba import get_num_threads, njit, prange

from .constitutive import dk_stress_update

__all__ = [
    "advance",
    "body_contact",
    "body_project",
    "g2p",
    "grid_totals",
    "grid_update",
    "p2g",
    "polygon_sdf",
]

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


@njit(cache=True, fastmath=True, parallel=True)
def p2g(pos, vel, aff, stress, mass, vol, x0, z0, h, dt, buf):
    """Particle -> grid scatter into ``buf`` (chunks, nx, nz, 3) = (mass [kg/m], momentum [kg/s] x, z).

    The momentum includes the internal-force impulse over ``dt`` [s]. Each chunk of particles scatters
    into its own copy of the grid; :func:`grid_update` sums the copies (:func:`grid_totals` for tests).
    """
    nchunk = buf.shape[0]
    n = pos.shape[0]
    inv_h = 1.0 / h
    for c in prange(nchunk):
        bc = buf[c]
        bc[:] = 0.0
        wx = np.empty(3)
        wz = np.empty(3)
        dwx = np.empty(3)
        dwz = np.empty(3)
        start = (c * n) // nchunk
        stop = ((c + 1) * n) // nchunk
        for p in range(start, stop):
            bi, fx = _weights((pos[p, 0] - x0) * inv_h, wx, dwx, inv_h)
            bj, fz = _weights((pos[p, 1] - z0) * inv_h, wz, dwz, inv_h)
            m = mass[p]
            vdt = vol[p] * dt
            sxx = stress[p, 0]
            szz = stress[p, 1]
            sxz = stress[p, 2]
            vx = vel[p, 0]
            vz = vel[p, 1]
            c00 = aff[p, 0, 0]
            c01 = aff[p, 0, 1]
            c10 = aff[p, 1, 0]
            c11 = aff[p, 1, 1]
            for a in range(3):
                dx = (a - fx) * h
                for b in range(3):
                    dz = (b - fz) * h
                    wgt = wx[a] * wz[b]
                    gx = dwx[a] * wz[b]
                    gz = wx[a] * dwz[b]
                    wm = wgt * m
                    i = bi + a
                    j = bj + b
                    bc[i, j, 0] += wm
                    bc[i, j, 1] += wm * (vx + c00 * dx + c01 * dz) - vdt * (sxx * gx + sxz * gz)
                    bc[i, j, 2] += wm * (vz + c10 * dx + c11 * dz) - vdt * (sxz * gx + szz * gz)


def grid_totals(buf):
    """Summed chunk copies of :func:`p2g`: ``(grid_mass (nx, nz), grid_mom (nx, nz, 2))``."""
    tot = buf.sum(axis=0)
    return tot[..., 0], np.ascontiguousarray(tot[..., 1:])


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


@njit(cache=True, fastmath=True, parallel=True)
def grid_update(buf, grid_mass, grid_vel, dt, gravity, damping, pad, wall_kind, wall_mu):
    """Sum the :func:`p2g` copies into ``grid_mass`` (nx, nz) [kg/m] and set grid velocities
    ``grid_vel`` (nx, nz, 2) [m/s] from momentum, gravity [m/s^2] and walls.

    ``damping`` [1/s] scales velocities by ``max(0, 1 - damping dt)`` (bed settling only). Walls sit on
    node ``pad`` (left, bottom) and ``nx - 1 - pad`` (right); ``wall_kind``/``wall_mu`` are (3,) arrays
    for (left, right, bottom). The top is open.
    """
    nchunk = buf.shape[0]
    nx = grid_mass.shape[0]
    nz = grid_mass.shape[1]
    keep = max(0.0, 1.0 - damping * dt)
    for i in prange(nx):
        for j in range(nz):
            m = 0.0
            px = 0.0
            pz = 0.0
            for c in range(nchunk):
                m += buf[c, i, j, 0]
                px += buf[c, i, j, 1]
                pz += buf[c, i, j, 2]
            grid_mass[i, j] = m
            if m <= _MASS_EPS:
                grid_vel[i, j, 0] = 0.0
                grid_vel[i, j, 1] = 0.0
                continue
            vx = (px / m) * keep
            vz = (pz / m - dt * gravity) * keep
            if i <= pad:
                vx, vz = _wall(vx, vz, 1.0, 0.0, wall_kind[0], wall_mu[0])
            if i >= nx - 1 - pad:
                vx, vz = _wall(vx, vz, -1.0, 0.0, wall_kind[1], wall_mu[1])
            if j <= pad:
                vx, vz = _wall(vx, vz, 0.0, 1.0, wall_kind[2], wall_mu[2])
            grid_vel[i, j, 0] = vx
            grid_vel[i, j, 1] = vz


@njit(cache=True, fastmath=True)
def polygon_sdf(px, pz, seg):
    """Signed distance [m] of body-frame point (px, pz) to closed polygons ``seg`` (S, 4) = (x1, z1, x2, z2).

    Negative inside (even-odd rule over all loops). Returns ``(phi, nx, nz)`` with ``n`` the unit
    outward normal of the body at the nearest boundary point.
    """
    best = 1e300
    bx = 0.0
    bz = 0.0
    inside = False
    for s in range(seg.shape[0]):
        x1 = seg[s, 0]
        z1 = seg[s, 1]
        x2 = seg[s, 2]
        z2 = seg[s, 3]
        ex = x2 - x1
        ez = z2 - z1
        ll = ex * ex + ez * ez
        t = 0.0
        if ll > 0.0:
            t = ((px - x1) * ex + (pz - z1) * ez) / ll
            t = min(1.0, max(0.0, t))
        qx = x1 + t * ex - px
        qz = z1 + t * ez - pz
        d2 = qx * qx + qz * qz
        if d2 < best:
            best = d2
            bx = qx
            bz = qz
        if (z1 > pz) != (z2 > pz):
            xc = x1 + (pz - z1) * ex / ez
            if px < xc:
                inside = not inside
    d = math.sqrt(best)
    if d < 1e-300:
        return 0.0, 0.0, 1.0
    if inside:
        return -d, bx / d, bz / d
    return d, -bx / d, -bz / d


@njit(cache=True, fastmath=True)
def body_contact(grid_mass, grid_vel, x0, z0, h, dt, seg, pose, twist, reach, mu):
    """Frictional rigid-body contact on grid nodes inside the body; returns the force on the body.

    Nodes within ``reach`` [m] of the body origin with signed distance < 0 have their velocity relative
    to the body point projected (no approach along the outward normal, Coulomb friction ``mu``,
    separation free). Returns ``(f_x, f_z, torque_y)`` [N/m, N m/m] on the body about its origin:
    ``-sum m_i dv_i / dt``.
    """
    nx = grid_mass.shape[0]
    nz = grid_mass.shape[1]
    xb = pose[0]
    zb = pose[1]
    cth = math.cos(pose[2])
    sth = math.sin(pose[2])
    i_lo = max(0, int((xb - reach - x0) / h))
    i_hi = min(nx - 1, int((xb + reach - x0) / h) + 1)
    j_lo = max(0, int((zb - reach - z0) / h))
    j_hi = min(nz - 1, int((zb + reach - z0) / h) + 1)
    fx = 0.0
    fz = 0.0
    ty = 0.0
    for i in range(i_lo, i_hi + 1):
        for j in range(j_lo, j_hi + 1):
            m = grid_mass[i, j]
            if m <= _MASS_EPS:
                continue
            rx = x0 + i * h - xb
            rz = z0 + j * h - zb
            # world -> body frame: p = R^T r with R = [[c, s], [-s, c]]
            phi, nbx, nbz = polygon_sdf(cth * rx - sth * rz, sth * rx + cth * rz, seg)
            if phi >= 0.0:
                continue
            nwx = cth * nbx + sth * nbz
            nwz = -sth * nbx + cth * nbz
            ubx = twist[0] + twist[2] * rz
            ubz = twist[1] - twist[2] * rx
            vx = grid_vel[i, j, 0]
            vz = grid_vel[i, j, 1]
            ux, uz = _coulomb(vx - ubx, vz - ubz, nwx, nwz, mu)
            nvx = ubx + ux
            nvz = ubz + uz
            jx = -m * (nvx - vx) / dt
            jz = -m * (nvz - vz) / dt
            grid_vel[i, j, 0] = nvx
            grid_vel[i, j, 1] = nvz
            fx += jx
            fz += jz
            ty += rz * jx - rx * jz
    return fx, fz, ty


@njit(cache=True, fastmath=True)
def body_project(pos, vel, mass, dt, seg, pose, twist, reach, mu):
    """Push particles that ended a step inside the body back to its surface (no leaking through).

    A particle with signed distance ``phi < 0`` moves ``-phi`` along the outward normal; its velocity
    relative to the body point loses any approaching normal part (Coulomb friction ``mu`` on the
    tangential part). Returns the reaction on the body from these velocity changes,
    ``(f_x, f_z, torque_y)`` = ``-sum m_p dv_p / dt`` [N/m, N m/m].
    """
    n = pos.shape[0]
    xb = pose[0]
    zb = pose[1]
    cth = math.cos(pose[2])
    sth = math.sin(pose[2])
    r2 = reach * reach
    fx = 0.0
    fz = 0.0
    ty = 0.0
    for p in range(n):
        rx = pos[p, 0] - xb
        rz = pos[p, 1] - zb
        if rx * rx + rz * rz > r2:
            continue
        phi, nbx, nbz = polygon_sdf(cth * rx - sth * rz, sth * rx + cth * rz, seg)
        if phi >= 0.0:
            continue
        nwx = cth * nbx + sth * nbz
        nwz = -sth * nbx + cth * nbz
        pos[p, 0] -= phi * nwx
        pos[p, 1] -= phi * nwz
        rx = pos[p, 0] - xb
        rz = pos[p, 1] - zb
        ubx = twist[0] + twist[2] * rz
        ubz = twist[1] - twist[2] * rx
        ux, uz = _coulomb(vel[p, 0] - ubx, vel[p, 1] - ubz, nwx, nwz, mu)
        dvx = ubx + ux - vel[p, 0]
        dvz = ubz + uz - vel[p, 1]
        vel[p, 0] += dvx
        vel[p, 1] += dvz
        jx = -mass[p] * dvx / dt
        jz = -mass[p] * dvz / dt
        fx += jx
        fz += jz
        ty += rz * jx - rx * jz
    return fx, fz, ty


@njit(cache=True, fastmath=True, parallel=True)
def g2p(
    pos,
    vel,
    aff,
    stress,
    mass,
    vol,
    gdot,
    grid_vel,
    x0,
    z0,
    h,
    dt,
    bounds,
    shear_modulus,
    lame_lambda,
    mu_s,
    mu_2,
    inertial_number_0,
    grain_diameter,
    grain_density,
    critical_density,
):
    """Grid -> particle: velocities, affine matrices, positions, volumes and stresses (in place).

    ``bounds`` (4,) = (x_min, x_max, z_min, z_max) [m] clamps positions inside the walls; ``gdot`` (N,)
    receives the plastic shear rate [1/s]. Material parameters as in
    :func:`~terradyn.mpm.constitutive.dk_stress_update`.
    """
    n = pos.shape[0]
    inv_h = 1.0 / h
    dscale = 4.0 * inv_h * inv_h
    for p in prange(n):
        wx = np.empty(3)
        wz = np.empty(3)
        dwx = np.empty(3)
        dwz = np.empty(3)
        bi, fx = _weights((pos[p, 0] - x0) * inv_h, wx, dwx, inv_h)
        bj, fz = _weights((pos[p, 1] - z0) * inv_h, wz, dwz, inv_h)
        vx = 0.0
        vz = 0.0
        b00 = 0.0
        b01 = 0.0
        b10 = 0.0
        b11 = 0.0
        lxx = 0.0
        lxz = 0.0
        lzx = 0.0
        lzz = 0.0
        for a in range(3):
            dx = (a - fx) * h
            for b in range(3):
                dz = (b - fz) * h
                wgt = wx[a] * wz[b]
                gx = dwx[a] * wz[b]
                gz = wx[a] * dwz[b]
                ux = grid_vel[bi + a, bj + b, 0]
                uz = grid_vel[bi + a, bj + b, 1]
                vx += wgt * ux
                vz += wgt * uz
                b00 += wgt * ux * dx
                b01 += wgt * ux * dz
                b10 += wgt * uz * dx
                b11 += wgt * uz * dz
                lxx += ux * gx
                lxz += ux * gz
                lzx += uz * gx
                lzz += uz * gz
        vel[p, 0] = vx
        vel[p, 1] = vz
        aff[p, 0, 0] = dscale * b00
        aff[p, 0, 1] = dscale * b01
        aff[p, 1, 0] = dscale * b10
        aff[p, 1, 1] = dscale * b11
        pos[p, 0] = min(bounds[1], max(bounds[0], pos[p, 0] + dt * vx))
        pos[p, 1] = min(bounds[3], max(bounds[2], pos[p, 1] + dt * vz))
        v = vol[p] * math.exp(dt * (lxx + lzz))
        vol[p] = v
        out = dk_stress_update(
            stress[p, 0],
            stress[p, 1],
            stress[p, 2],
            stress[p, 3],
            lxx,
            lxz,
            lzx,
            lzz,
            dt,
            mass[p] / v,
            shear_modulus,
            lame_lambda,
            mu_s,
            mu_2,
            inertial_number_0,
            grain_diameter,
            grain_density,
            critical_density,
        )
        stress[p, 0] = out[0]
        stress[p, 1] = out[1]
        stress[p, 2] = out[2]
        stress[p, 3] = out[3]
        gdot[p] = out[4]


@njit(cache=True)
def advance(
    n_steps,
    pos,
    vel,
    aff,
    stress,
    mass,
    vol,
    gdot,
    buf,
    grid_mass,
    grid_vel,
    x0,
    z0,
    h,
    dt,
    gravity,
    damping,
    pad,
    wall_kind,
    wall_mu,
    bounds,
    material,
    has_body,
    seg,
    pose,
    twist,
    body_mass,
    body_inertia,
    free,
    load,
    reach,
    body_mu,
    forces,
):
    """Run ``n_steps`` MPM steps of ``dt`` [s] with one rigid body, all compiled.

    ``material`` (8,) = (G, lambda, mu_s, mu_2, I_0, d, rho_s, rho_c) in SI. Body: ``seg`` outline
    segments in its frame, ``pose`` (3,) = (x, z, theta) and ``twist`` (3,) = (vx, vz, omega) updated
    in place; ``free`` (3,) flags x/z translation and the spin as free (else prescribed by ``twist``),
    with mass ``body_mass`` [kg/m], moment of inertia ``body_inertia`` [kg m^2/m] and external load
    ``load`` (3,) = force [N/m] (gravity included by the caller) and torque about +y [N m/m].
    ``forces`` (n_steps, 3) receives the grain force and torque on the body each step [N/m, N m/m].
    """
    g_mod = material[0]
    lam = material[1]
    for step in range(n_steps):
        p2g(pos, vel, aff, stress, mass, vol, x0, z0, h, dt, buf)
        grid_update(buf, grid_mass, grid_vel, dt, gravity, damping, pad, wall_kind, wall_mu)
        fx = 0.0
        fz = 0.0
        ty = 0.0
        if has_body:
            fx, fz, ty = body_contact(grid_mass, grid_vel, x0, z0, h, dt, seg, pose, twist, reach, body_mu)
            if free[0]:
                twist[0] += dt * (fx + load[0]) / body_mass
            if free[1]:
                twist[1] += dt * (fz + load[1]) / body_mass
            if free[2]:
                twist[2] += dt * (ty + load[2]) / body_inertia
            pose[0] += dt * twist[0]
            pose[1] += dt * twist[1]
            pose[2] += dt * twist[2]
        g2p(
            pos,
            vel,
            aff,
            stress,
            mass,
            vol,
            gdot,
            grid_vel,
            x0,
            z0,
            h,
            dt,
            bounds,
            g_mod,
            lam,
            material[2],
            material[3],
            material[4],
            material[5],
            material[6],
            material[7],
        )
        if has_body:
            px, pz, pt = body_project(pos, vel, mass, dt, seg, pose, twist, reach, body_mu)
            if free[0]:
                twist[0] += dt * px / body_mass
            if free[1]:
                twist[1] += dt * pz / body_mass
            if free[2]:
                twist[2] += dt * pt / body_inertia
            fx += px
            fz += pz
            ty += pt
        forces[step, 0] = fx
        forces[step, 1] = fz
        forces[step, 2] = ty


def make_buffer(nx: int, nz: int, n_particles: int) -> np.ndarray:
    """Scratch array for :func:`p2g`: one grid copy per worker thread (fewer for tiny problems)."""
    chunks = max(1, min(get_num_threads(), n_particles // 256 or 1))
    return np.zeros((chunks, nx, nz, 3))
