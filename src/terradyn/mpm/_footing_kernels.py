"""Numba loop of the MPM strip footing with its base as a grid boundary condition (no contact body).

Used by :func:`terradyn.studies.mpm_footing_nodes.node_strip_footing`. The step is the MPM step of
:func:`terradyn.mpm._kernels.advance` without a body (p2g, grid update with the walls, optional
patch-averaged divergence, g2p); after the grid update the footing nodes take the footing's velocity
and a symmetry plane at the left wall, if asked for, takes ``v_x = 0`` on both sides. Conventions
(units, shapes, grid origin) as in :mod:`terradyn.mpm._kernels`.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ._common_kernels import _MASS_EPS
from ._kernels import (
    chunk_sum,
    flip_blend,
    flip_scratch,
    g2p,
    grid_change,
    grid_update,
    p2g,
    patch_divergence,
)

__all__: list[str] = []


@njit(cache=True)
def advance_footing(
    n_steps,
    step0,
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
    foot_i,
    foot_j,
    rough,
    symmetric,
    speed,
    ramp_steps,
    settled,
    follow,
    floor_z,
    scratch_grid,
    geo,
    averaged,
    forces,
    flip=0.0,
    local_damping=0.0,
):
    """Run ``n_steps`` steps (global step numbers ``step0 + k``).

    Footing: the nodes ``foot_i[0] <= i <= foot_i[1]``, ``foot_j[0] <= j <= foot_j[1]`` holding mass
    move down at ``speed`` [m/s] times a half-cosine ramp over the first ``ramp_steps`` steps
    (``speed`` 0: they are held still); a ``rough`` base also holds ``v_x = 0`` there, a smooth one
    leaves ``v_x`` free. ``symmetric``: the nodes ``i <= pad`` (the left wall and outside it) take
    ``v_x = 0``. ``forces`` (n_steps, 3) receives (F_x, F_z, footing velocity) per step: the force of
    the grains on the footing [N/m] (the impulse the condition takes from the grid over ``dt``) and
    the prescribed velocity [m/s] (negative: down). ``settled`` [m] is the footing's settlement at
    the first step. ``follow``: the grid moves down with the footing (node (i, j) at
    ``(x0 + i h, z0 - s + j h)`` with s the settlement), so the footing nodes stay on its base
    however far it goes; the floor is then the node line nearest ``floor_z`` [m] (world) and the nodes
    below it, which get the free-slip floor condition (no downward velocity), as the nodes
    ``j <= pad`` of a still grid. ``flip`` in [0, 1] blends the particle velocity update: ``flip``
    x (the particle's old velocity plus the interpolated grid velocity change) + (1 - ``flip``) x
    the interpolated grid velocity (0: the APIC update of the solver; positions and affine matrices
    always from the new grid velocity). Used to measure the transfer's numerical dissipation.
    ``local_damping`` alpha in [0, 1): the local damping of quasi-static explicit codes
    (:func:`local_damp`) at the free nodes; 0 leaves the step unchanged.
    """
    g_mod = material[0]
    lam = material[1]
    dilatancy = material[8] if material.shape[0] > 8 else 0.0
    loose_density = material[9] if material.shape[0] > 9 else material[7]
    grid_vel_m = scratch_grid[:, :, 0:2]
    node = scratch_grid[:, :, 2:5]
    n_patch = grid_mass.shape[0] if averaged else 0
    patch = np.zeros((n_patch, grid_mass.shape[1] if averaged else 0, 5, 2))
    div_bar = np.empty(pos.shape[0] if averaged else 0)
    keys = np.empty((pos.shape[0] if averaged else 0, 3), dtype=np.int64)
    s = settled
    use_flip = flip > 0.0
    use_old = use_flip or local_damping > 0.0
    vel_old, pos_old, zero_stress, buf_old, grid_dv = flip_scratch(use_old, pos, buf, grid_mass)
    for k in range(n_steps):
        step = step0 + k
        zg = z0 - s if follow else z0
        ramp = 1.0
        if step < ramp_steps:
            ramp = 0.5 * (1.0 - np.cos(np.pi * (step + 0.5) / ramp_steps))
        vz_foot = -speed * ramp
        if use_old:
            # the grid velocity before this step's forces: momentum / mass of a force-free scatter
            p2g(pos, vel, aff, zero_stress, mass, vol, x0, zg, h, dt, buf_old)
            vel_old[:] = vel
            pos_old[:] = pos
        p2g(pos, vel, aff, stress, mass, vol, x0, zg, h, dt, buf)
        grid_update(buf, grid_mass, grid_vel, dt, gravity, damping, pad, wall_kind, wall_mu)
        j_floor = pad
        if follow:
            # the node line nearest the world floor and those below it: the floor stays within h/2
            # of floor_z (rounding down instead let it sink with the grid by up to a cell, and the bed
            # with it: 40-70 um in 0.1 s of hold at B/40, docs/mpm.md)
            j_floor = int(np.floor((floor_z - zg) / h + 0.5))
            for i in range(grid_mass.shape[0]):
                for j in range(pad + 1, j_floor + 1):
                    if grid_vel[i, j, 1] < 0.0:
                        grid_vel[i, j, 1] = 0.0
        if local_damping > 0.0:
            local_damp(buf_old, grid_mass, grid_vel, local_damping, pad, j_floor, foot_i, foot_j)
        if symmetric:
            for i in range(pad + 1):
                for j in range(grid_mass.shape[1]):
                    grid_vel[i, j, 0] = 0.0
        fx = 0.0
        fz = 0.0
        for i in range(foot_i[0], foot_i[1] + 1):
            for j in range(foot_j[0], foot_j[1] + 1):
                m = grid_mass[i, j]
                if m <= _MASS_EPS:
                    continue
                if rough:
                    fx -= m * (0.0 - grid_vel[i, j, 0]) / dt
                    grid_vel[i, j, 0] = 0.0
                fz -= m * (vz_foot - grid_vel[i, j, 1]) / dt
                grid_vel[i, j, 1] = vz_foot
        if averaged:
            patch_divergence(pos, vol, geo, node, grid_vel, grid_vel_m, x0, zg, h, patch, keys, div_bar)
        if use_flip:
            grid_change(buf_old, grid_mass, grid_vel, grid_dv)
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
            zg,
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
            dilatancy,
            loose_density,
            div_bar,
        )
        if use_flip:
            flip_blend(pos_old, vel_old, vel, grid_dv, x0, zg, h, flip)
        forces[k, 0] = fx
        forces[k, 1] = fz
        forces[k, 2] = vz_foot
        s -= vz_foot * dt


@njit(cache=True)
def local_damp(buf_old, grid_mass, grid_vel, alpha, pad, j_floor, foot_i, foot_j):
    """Local (non-viscous) damping of the free grid nodes, in place: each velocity component's
    change over the step, ``dv`` (the unbalanced force x dt / m, gravity included), loses
    ``alpha |dv|`` against the sign of the node's velocity before the step (the force-free scatter
    ``buf_old``), as in the dynamic-relaxation codes used for collapse loads. It removes kinetic
    energy where the motion reverses and would vanish in a steady flow without unbalanced force; in
    MPM the step-to-step changes are largely noise that grows with the flow's speed, so it acts as a
    drag that grows with the loading speed (docs/mpm.md, "The creep is not ringing"). Wall, floor
    (``j <= j_floor``) and footing nodes are left to their conditions, so the footing reads the
    grains' unbalanced force."""
    nx = grid_mass.shape[0]
    nz = grid_mass.shape[1]
    for i in range(pad + 1, nx - 1 - pad):
        for j in range(max(pad, j_floor) + 1, nz):
            if grid_mass[i, j] <= _MASS_EPS:
                continue
            if foot_i[0] <= i <= foot_i[1] and foot_j[0] <= j <= foot_j[1]:
                continue
            m, px, pz = chunk_sum(buf_old, i, j)
            if m <= _MASS_EPS:
                continue
            for a, p_a in ((0, px), (1, pz)):
                v0 = p_a / m
                grid_vel[i, j, a] -= alpha * abs(grid_vel[i, j, a] - v0) * np.sign(v0)
