"""Numba kernels of the explicit plane-strain MPM step (APIC transfer, quadratic B-splines).

One step has the three phases of the literature (update-stress-last):

1. particle -> grid (:func:`p2g`): mass ``m_i = sum w_ip m_p``, affine momentum
   ``sum w_ip m_p (v_p + C_p (x_i - x_p))`` plus the internal-force impulse ``-dt sum V_p sigma_p grad w_ip``;
2. grid update (:func:`grid_update`, then the contact kernels of :mod:`terradyn.mpm._contact_kernels`):
   ``v_i = p_i / m_i + dt g``, wall conditions, rigid-body frictional contact (the impulse taken from
   the grains is the force on the body); near the body the grains keep two velocity fields, one per
   side of its surface, so a body needs no thickness;
3. grid -> particle (:func:`g2p`): ``v_p = sum w_ip v_i``, ``C_p = 4/h^2 sum w_ip v_i (x_i - x_p)^T``,
   ``L_p = sum v_i grad w_ip^T``, ``x_p += dt v_p``, ``V_p *= exp(dt tr L_p)``, stress update.

Phases 1 and 3 with their options (the force-free scatter and blend of FLIP, the patch-averaged
divergence) are :func:`step_to_grid` and :func:`step_to_particles`, shared by the two step loops: the
body's (:func:`advance`) and the footing's (:func:`terradyn.mpm._footing_kernels.advance_footing`),
each of which adds its own grid conditions after :func:`grid_update`.

Grid node ``(i, j)`` sits at world ``(x0 + i h, z0 + j h)``. Particle arrays: positions ``pos`` (N, 2)
[m], velocities ``vel`` (N, 2) [m/s], affine matrices ``aff`` (N, 2, 2) [1/s], stresses ``stress``
(N, 4) = (s_xx, s_zz, s_xz, s_yy) [Pa], masses ``mass`` (N,) [kg/m] and volumes ``vol`` (N,) [m^2]
per unit out-of-plane width. Wall codes: 0 free-slip (separable), 1 no-slip, 2 Coulomb friction.
"""

from __future__ import annotations

import math

import numpy as np
from numba import get_num_threads, njit, prange

from ._common_kernels import _MASS_EPS, _node_velocity, _weights
from ._contact_kernels import (
    _FAR,
    BAND_CELLS,
    _far_side,
    body_contact,
    body_contact_sides,
    body_nodes,
    body_particles,
    body_project,
    body_project_sides,
    p2g_sides,
    polygon_sdf,
)
from .constitutive import dk_dilatant_stress_update, dk_stress_update

__all__ = [
    "BAND_CELLS",
    "CONTACT_COVER",
    "CONTACT_SIDES",
    "CONTACT_SIDES_GAP",
    "advance",
    "body_contact",
    "body_contact_sides",
    "body_nodes",
    "body_particles",
    "body_project",
    "body_project_sides",
    "chunk_sum",
    "flip_scratch",
    "g2p",
    "grid_totals",
    "grid_update",
    "make_buffer",
    "make_scratch",
    "p2g",
    "p2g_sides",
    "patch_divergence",
    "patch_scratch",
    "polygon_sdf",
    "step_to_grid",
    "step_to_particles",
]


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
            vx, vz = _node_velocity(m, px, pz, dt, gravity, keep, i, j, nx, pad, wall_kind, wall_mu)
            grid_vel[i, j, 0] = vx
            grid_vel[i, j, 1] = vz


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
    grid_vel_m,
    geo,
    node,
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
    dilatancy=0.0,
    loose_density=0.0,
    div_bar=None,
):
    """Grid -> particle: velocities, affine matrices, positions, volumes and stresses (in place).

    A particle near the body (``geo[p]`` has a normal, see :func:`body_particles`) reads, at a band
    node whose normal ``node[i, j, :2]`` points against its own (the far side of a thin body), the
    far-side field ``grid_vel_m``; every other particle-node pair reads ``grid_vel``. ``bounds`` (4,) =
    (x_min, x_max, z_min, z_max) [m] clamps positions inside the walls; ``gdot`` (N,) receives the
    plastic shear rate [1/s]. Material parameters as in :func:`~terradyn.mpm.constitutive.dk_stress_update`;
    ``dilatancy`` K [-] > 0 selects :func:`~terradyn.mpm.constitutive.dk_dilatant_stress_update` with
    ``loose_density`` [kg/m^3] (the density of a point is its mass over its volume). A ``div_bar``
    (N,) [1/s] replaces each point's velocity divergence by the patch average of
    :func:`patch_divergence` (the isotropic part of its velocity gradient is shifted, its deviatoric
    part kept), in the volume and the stress update alike.
    """
    n = pos.shape[0]
    inv_h = 1.0 / h
    dscale = 4.0 * inv_h * inv_h
    if div_bar is None:
        bar = np.empty(0)
    else:
        bar = div_bar
    averaged = bar.shape[0] == n and n > 0
    for p in prange(n):
        wx = np.empty(3)
        wz = np.empty(3)
        dwx = np.empty(3)
        dwz = np.empty(3)
        bi, fx = _weights((pos[p, 0] - x0) * inv_h, wx, dwx, inv_h)
        bj, fz = _weights((pos[p, 1] - z0) * inv_h, wz, dwz, inv_h)
        npx = geo[p, 0]
        npz = geo[p, 1]
        near = npx != 0.0 or npz != 0.0
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
                i = bi + a
                j = bj + b
                if near and _far_side(npx, npz, node, i, j):
                    ux = grid_vel_m[i, j, 0]
                    uz = grid_vel_m[i, j, 1]
                else:
                    ux = grid_vel[i, j, 0]
                    uz = grid_vel[i, j, 1]
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
        if averaged:
            shift = 0.5 * (bar[p] - (lxx + lzz))
            lxx += shift
            lzz += shift
        v = vol[p] * math.exp(dt * (lxx + lzz))
        vol[p] = v
        if dilatancy > 0.0:
            out = dk_dilatant_stress_update(
                stress[p, 0], stress[p, 1], stress[p, 2], stress[p, 3], lxx, lxz, lzx, lzz, dt,
                mass[p] / v, shear_modulus, lame_lambda, mu_s, mu_2, inertial_number_0,
                grain_diameter, grain_density, critical_density, dilatancy, loose_density,
            )  # fmt: skip
        else:
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


@njit(cache=True, inline="always")
def _side_key(npx, npz):
    """Which side of a body a particle with outward normal (npx, npz) lies on, for
    :func:`patch_divergence`: 1 / 2 above / below where the normal is mostly vertical, 3 / 4 to +x / -x
    where it is mostly horizontal. Mirroring x (or z) maps each key to one key, so a mirrored case
    groups its particles as the original does. A normal at 45 deg to rounding (a grain on the
    diagonal of a corner, common when corners and grains sit on the grid's lattice) is vertical."""
    if abs(npz) >= abs(npx) - 1e-9:
        return 1 if npz > 0.0 else 2
    return 3 if npx > 0.0 else 4


@njit(cache=True, fastmath=True, parallel=True)
def patch_divergence(pos, vol, geo, node, grid_vel, grid_vel_m, x0, z0, h, patch, keys, div_bar):
    """Patch-averaged velocity divergence of every particle into ``div_bar`` (N,) [1/s].

    A patch is the node-centred cell of the particle's nearest grid node; where that node is in the
    body's band (``node``) and the particle has a body normal (``geo[p]``), the particles of a patch
    are further split by the side of the body their normal points to (:func:`_side_key`), so the two
    grain fields of a thin body are not mixed. Within a patch the divergence
    ``tr L_p`` (read from the grid as in :func:`g2p`) is averaged with the particle volumes as
    weights. This is the B-bar idea for material points (Coombs et al. 2018, Comput. Methods Appl.
    Mech. Engrg. 333, 1-21, doi:10.1016/j.cma.2018.01.010): one volumetric rate per patch instead of
    one per point, which frees isochoric plastic flow from volumetric locking. ``patch`` (nx, nz, 5,
    2) and ``keys`` (N, 3) int64 are scratch.
    """
    n = pos.shape[0]
    inv_h = 1.0 / h
    patch[:] = 0.0
    for p in prange(n):
        wx = np.empty(3)
        wz = np.empty(3)
        dwx = np.empty(3)
        dwz = np.empty(3)
        bi, _ = _weights((pos[p, 0] - x0) * inv_h, wx, dwx, inv_h)
        bj, _ = _weights((pos[p, 1] - z0) * inv_h, wz, dwz, inv_h)
        npx = geo[p, 0]
        npz = geo[p, 1]
        near = npx != 0.0 or npz != 0.0
        div = 0.0
        for a in range(3):
            for b in range(3):
                i = bi + a
                j = bj + b
                if near and _far_side(npx, npz, node, i, j):
                    div += grid_vel_m[i, j, 0] * dwx[a] * wz[b] + grid_vel_m[i, j, 1] * wx[a] * dwz[b]
                else:
                    div += grid_vel[i, j, 0] * dwx[a] * wz[b] + grid_vel[i, j, 1] * wx[a] * dwz[b]
        div_bar[p] = div
        ki = bi + 1  # the nearest node (the B-spline offset of node bi + 1 is below half a cell)
        kj = bj + 1
        keys[p, 0] = ki
        keys[p, 1] = kj
        # split by side only in the body's band, where the two grain fields differ
        keys[p, 2] = _side_key(npx, npz) if near and node[ki, kj, 2] < 0.5 * _FAR else 0
    for p in range(n):
        cell = patch[keys[p, 0], keys[p, 1], keys[p, 2]]
        cell[0] += vol[p] * div_bar[p]
        cell[1] += vol[p]
    for p in prange(n):
        cell = patch[keys[p, 0], keys[p, 1], keys[p, 2]]
        div_bar[p] = cell[0] / cell[1]


#: Contact schemes of :func:`advance`: the grid nodes inside a (thickened) outline take the body
#: velocity, plus a particle projection (legacy); or the two-field scheme of :func:`body_contact_sides`.
CONTACT_COVER = 0
CONTACT_SIDES = 1
#: two-field contact decided by the grains' gap to the body (:func:`p2g_sides`, ``gap_check``)
CONTACT_SIDES_GAP = 2


@njit(cache=True)
def flip_scratch(use, pos, buf, grid_mass):
    """Scratch of the FLIP blend (empty when ``use`` is false): the points' old velocities and
    positions (N, 2), a zero stress (N, 4), a :func:`p2g` buffer like ``buf`` and the grid change
    (nx, nz, 3): the velocity change and a two-field flag (see :func:`mark_two_fields`)."""
    n = pos.shape[0] if use else 0
    return (
        np.empty((n, 2)),
        np.empty((n, 2)),
        np.zeros((n, 4)),
        np.empty(buf.shape if use else (0, 0, 0, 3)),
        np.zeros((grid_mass.shape[0] if use else 0, grid_mass.shape[1], 3)),
    )


@njit(cache=True, fastmath=True)
def chunk_sum(buf, i, j):
    """``(mass, p_x, p_z)`` at node (i, j) summed over the chunk copies of a :func:`p2g` buffer."""
    m = 0.0
    px = 0.0
    pz = 0.0
    for c in range(buf.shape[0]):
        m += buf[c, i, j, 0]
        px += buf[c, i, j, 1]
        pz += buf[c, i, j, 2]
    return m, px, pz


@njit(cache=True, fastmath=True, parallel=True)
def grid_change(buf_old, grid_mass, grid_vel, grid_dv):
    """``grid_dv`` (nx, nz, 3): the step's grid velocity change [m/s], ``grid_vel`` less the
    force-free velocity of ``buf_old`` (a :func:`p2g` scatter with zero stress), zero at nodes
    without mass; the two-field flag (third entry) is cleared."""
    nx = grid_mass.shape[0]
    nz = grid_mass.shape[1]
    for i in prange(nx):
        for j in range(nz):
            m, px, pz = chunk_sum(buf_old, i, j)
            grid_dv[i, j, 2] = 0.0
            if m <= _MASS_EPS or grid_mass[i, j] <= _MASS_EPS:
                grid_dv[i, j, 0] = 0.0
                grid_dv[i, j, 1] = 0.0
            else:
                grid_dv[i, j, 0] = grid_vel[i, j, 0] - px / m
                grid_dv[i, j, 1] = grid_vel[i, j, 1] - pz / m


@njit(cache=True)
def mark_two_fields(node, side, box, grid_dv):
    """Flag (``grid_dv[i, j, 2]`` = 1) the band nodes of ``box`` where a far-side grain field has
    mass (``side[i, j, 0]``, :func:`p2g_sides`): there ``grid_vel`` is one field's velocity, not the
    whole grid velocity the force-free scatter is, so the change formed there is not a field's."""
    for i in range(box[0], box[1] + 1):
        for j in range(box[2], box[3] + 1):
            if node[i, j, 2] < 0.5 * _FAR and side[i, j, 0] > _MASS_EPS:
                grid_dv[i, j, 2] = 1.0


@njit(cache=True, fastmath=True, parallel=True)
def flip_blend(pos_old, vel_old, vel, grid_dv, x0, z0, h, flip):
    """Blend the APIC velocity ``vel`` (the interpolated new grid velocity, in place) of each point
    with FLIP's, its old velocity plus the interpolated grid change (weights at the positions before
    the step): ``flip`` x FLIP + (1 - ``flip``) x APIC. APIC drops the non-affine part of the grid
    velocity around a point every step, a numerical viscosity of order h^2 / dt; FLIP keeps it
    (docs/mpm.md, "What the rate error is"). A point whose stencil has a node flagged two-field
    (:func:`mark_two_fields`: the far side of a thin body) keeps APIC: the change of its own field
    is not formed there. Elsewhere, next to a body too, the change includes the contact impulse."""
    inv_h = 1.0 / h
    for p in prange(pos_old.shape[0]):
        wx = np.empty(3)
        wz = np.empty(3)
        dwx = np.empty(3)
        dwz = np.empty(3)
        bi, _ = _weights((pos_old[p, 0] - x0) * inv_h, wx, dwx, inv_h)
        bj, _ = _weights((pos_old[p, 1] - z0) * inv_h, wz, dwz, inv_h)
        dvx = 0.0
        dvz = 0.0
        mixed = False
        for a in range(3):
            for b in range(3):
                wgt = wx[a] * wz[b]
                dvx += wgt * grid_dv[bi + a, bj + b, 0]
                dvz += wgt * grid_dv[bi + a, bj + b, 1]
                if grid_dv[bi + a, bj + b, 2] != 0.0:
                    mixed = True
        if mixed:
            continue
        vel[p, 0] = flip * (vel_old[p, 0] + dvx) + (1.0 - flip) * vel[p, 0]
        vel[p, 1] = flip * (vel_old[p, 1] + dvz) + (1.0 - flip) * vel[p, 1]


@njit(cache=True)
def patch_scratch(averaged, pos, grid_mass):
    """Scratch of the patch-averaged divergence (empty when ``averaged`` is false): the patch sums
    (nx, nz, 5, 2), the points' patch keys (N, 3) int64 and their divergence (N,) (see
    :func:`patch_divergence`)."""
    n = pos.shape[0] if averaged else 0
    return (
        np.zeros((grid_mass.shape[0] if averaged else 0, grid_mass.shape[1] if averaged else 0, 5, 2)),
        np.empty((n, 3), dtype=np.int64),
        np.empty(n),
    )


@njit(cache=True)
def step_to_grid(pos, vel, aff, stress, mass, vol, x0, z0, h, dt, buf, old, keep_old):
    """Phase 1 of a step, particle -> grid: :func:`p2g` into ``buf``. With ``keep_old`` it first
    keeps what the FLIP blend and the local damping read: a force-free scatter (the grid velocity
    before this step's forces) into ``old``'s buffer and the points' velocities and positions
    (``old`` from :func:`flip_scratch`)."""
    vel_old, pos_old, zero_stress, buf_old, _ = old
    if keep_old:
        p2g(pos, vel, aff, zero_stress, mass, vol, x0, z0, h, dt, buf_old)
        vel_old[:] = vel
        pos_old[:] = pos
    p2g(pos, vel, aff, stress, mass, vol, x0, z0, h, dt, buf)


@njit(cache=True)
def step_to_particles(
    pos,
    vel,
    aff,
    stress,
    mass,
    vol,
    gdot,
    grid_mass,
    grid_vel,
    grid_vel_m,
    geo,
    node,
    side,
    box,
    x0,
    z0,
    h,
    dt,
    bounds,
    material,
    averaged,
    patches,
    flip,
    old,
):
    """Phase 3 of a step, grid -> particle, once the grid velocities hold every condition: the
    patch-averaged divergence if ``averaged`` (:func:`patch_divergence`, scratch ``patches`` from
    :func:`patch_scratch`), then :func:`g2p` and, for ``flip`` > 0, the FLIP blend
    (:func:`grid_change` against the force-free scatter in ``old``, the two-field nodes of the body's
    node ``box`` flagged by :func:`mark_two_fields`, then :func:`flip_blend`). ``material`` as in
    :func:`advance`; ``geo``, ``node``, ``side`` and ``grid_vel_m`` are the two-field contact's
    (zero normals and an empty ``box`` (0, -1, 0, -1) without a body)."""
    patch, keys, div_bar = patches
    vel_old, pos_old, _, buf_old, grid_dv = old
    if averaged:
        patch_divergence(pos, vol, geo, node, grid_vel, grid_vel_m, x0, z0, h, patch, keys, div_bar)
    if flip > 0.0:
        grid_change(buf_old, grid_mass, grid_vel, grid_dv)
        mark_two_fields(node, side, box, grid_dv)
    g2p(
        pos,
        vel,
        aff,
        stress,
        mass,
        vol,
        gdot,
        grid_vel,
        grid_vel_m,
        geo,
        node,
        x0,
        z0,
        h,
        dt,
        bounds,
        material[0],
        material[1],
        material[2],
        material[3],
        material[4],
        material[5],
        material[6],
        material[7],
        material[8] if material.shape[0] > 8 else 0.0,
        material[9] if material.shape[0] > 9 else material[7],
        div_bar,
    )
    if flip > 0.0:
        flip_blend(pos_old, vel_old, vel, grid_dv, x0, z0, h, flip)


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
    contact,
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
    scratch_grid,
    scratch_particles,
    near,
    averaged=False,
    flip=0.0,
):
    """Run ``n_steps`` MPM steps of ``dt`` [s] with one rigid body, all compiled.

    ``material`` (8,) = (G, lambda, mu_s, mu_2, I_0, d, rho_s, rho_c) in SI, or (10,) with the
    dilatancy K and the loose density appended (:meth:`GranularModel.as_kernel_array`).
    Body: ``seg`` outline
    segments in its frame, ``pose`` (3,) = (x, z, theta) and ``twist`` (3,) = (vx, vz, omega) updated
    in place; ``free`` (3,) flags x/z translation and the spin as free (else prescribed by ``twist``),
    with mass ``body_mass`` [kg/m], moment of inertia ``body_inertia`` [kg m^2/m] and external load
    ``load`` (3,) = force [N/m] (gravity included by the caller) and torque about +y [N m/m].
    ``contact`` is :data:`CONTACT_SIDES` (two grain fields near the body, thin bodies allowed),
    :data:`CONTACT_SIDES_GAP` (the same, contact decided by the grains' gap) or
    :data:`CONTACT_COVER`; ``reach`` [m] bounds the nodes searched around the body origin.
    ``forces`` (n_steps, 3) receives the grain force and torque on the body each step [N/m, N m/m].
    Scratch: ``scratch_grid`` (nx, nz, 16) (far-side velocity, band-node geometry, two-field sums),
    ``scratch_particles`` (N, 3) and ``near`` (N,) int64 (see :func:`body_particles`).
    ``averaged`` selects the patch-averaged velocity divergence (:func:`patch_divergence`).
    ``flip`` in [0, 1] blends the velocity update towards FLIP (:func:`flip_blend`), except for the
    points next to a thin body's far-side grain field; 0 (default) is APIC alone.

    The step's shared phases are :func:`step_to_grid`, :func:`grid_update` and
    :func:`step_to_particles` (the footing loop of :mod:`terradyn.mpm._footing_kernels` runs the same
    three); what is the body's own comes between them.
    """
    sides = has_body and (contact == CONTACT_SIDES or contact == CONTACT_SIDES_GAP)
    gap_check = contact == CONTACT_SIDES_GAP
    grid_vel_m = scratch_grid[:, :, 0:2]
    node = scratch_grid[:, :, 2:5]
    side = scratch_grid[:, :, 5:16]
    geo = scratch_particles
    pose_old = np.empty(3)
    band = BAND_CELLS * h
    eps = 1e-4 * h
    n_near = 0
    box = (0, -1, 0, -1)
    node[:, :, 2] = _FAR  # no band yet (and no stale two-field state for g2p)
    patches = patch_scratch(averaged, pos, grid_mass)
    if not sides:
        geo[:] = 0.0
    use_flip = flip > 0.0
    old = flip_scratch(use_flip, pos, buf, grid_mass)
    for step in range(n_steps):
        # 1. particle -> grid (and, near the body, the two grain fields)
        if sides:
            n_near = body_particles(pos, seg, pose, reach + 2.5 * h, geo, near)
            box = body_nodes(x0, z0, h, seg, pose, reach, band, node, box)
        step_to_grid(pos, vel, aff, stress, mass, vol, x0, z0, h, dt, buf, old, use_flip)
        if sides:
            p2g_sides(
                pos, vel, aff, stress, mass, vol, geo, near, n_near, node, box, x0, z0, h, dt, side, gap_check
            )
        # 2. grid update: momentum, gravity, walls, body contact; the body moves
        grid_update(buf, grid_mass, grid_vel, dt, gravity, damping, pad, wall_kind, wall_mu)
        fx = 0.0
        fz = 0.0
        ty = 0.0
        if has_body:
            if sides:
                fx, fz, ty = body_contact_sides(
                    buf, grid_mass, grid_vel, grid_vel_m, side, node, box, x0, z0, h, dt, gravity,
                    damping, pad, wall_kind, wall_mu, pose, twist, body_mu, gap_check,
                )  # fmt: skip
            else:
                fx, fz, ty = body_contact(
                    grid_mass, grid_vel, x0, z0, h, dt, seg, pose, twist, reach, body_mu
                )
            pose_old[:] = pose
            if free[0]:
                twist[0] += dt * (fx + load[0]) / body_mass
            if free[1]:
                twist[1] += dt * (fz + load[1]) / body_mass
            if free[2]:
                twist[2] += dt * (ty + load[2]) / body_inertia
            pose[0] += dt * twist[0]
            pose[1] += dt * twist[1]
            pose[2] += dt * twist[2]
        # 3. grid -> particle, stress update; particles kept out of the body
        step_to_particles(pos, vel, aff, stress, mass, vol, gdot, grid_mass, grid_vel, grid_vel_m, geo, node,
                          side, box, x0, z0, h, dt, bounds, material, averaged, patches, flip,
                          old)  # fmt: skip
        if has_body:
            if sides:
                px, pz, pt = body_project_sides(
                    pos, vel, mass, geo, near, n_near, dt, seg, pose_old, pose, twist, body_mu, eps
                )
            else:
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


def make_scratch(nx: int, nz: int, n_particles: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Scratch arrays of the two-field contact for :func:`advance`: grid (nx, nz, 16), particles
    (N, 3) and the near-particle index list (N,)."""
    grid = np.zeros((nx, nz, 16))
    grid[:, :, 4] = _FAR
    return grid, np.zeros((n_particles, 3)), np.zeros(n_particles, dtype=np.int64)
