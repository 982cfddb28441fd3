"""Numba loop of the MPM strip footing with its base as a grid boundary condition (no contact body).

Launched by :func:`terradyn.mpm.footing.run_node_footing`. The step is the MPM step of
:func:`terradyn.mpm._kernels.advance` without a body: the same shared phases
(:func:`~terradyn.mpm._kernels.step_to_grid`, :func:`~terradyn.mpm._kernels.grid_update`,
:func:`~terradyn.mpm._kernels.step_to_particles`), with the footing's own grid conditions after the
grid update: the floor of a grid that follows the footing, the local damping if asked for, a
symmetry plane at the left wall (``v_x = 0`` on both sides), if asked for, and the footing nodes,
which take the footing's velocity. Conventions (units, shapes, grid origin) as in
:mod:`terradyn.mpm._kernels`.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ._common_kernels import _MASS_EPS
from ._kernels import (
    chunk_sum,
    flip_scratch,
    grid_update,
    patch_scratch,
    step_to_grid,
    step_to_particles,
)

__all__ = ["advance_footing", "footing_nodes", "local_damp"]


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
    (:func:`local_damp`) at the free nodes; 0 leaves the step unchanged. ``scratch_grid`` and
    ``geo`` as ``scratch_grid`` and ``scratch_particles`` of :func:`~terradyn.mpm._kernels.advance`
    (:func:`~terradyn.mpm._kernels.make_scratch`; no band, zero normals).
    """
    grid_vel_m = scratch_grid[:, :, 0:2]
    node = scratch_grid[:, :, 2:5]
    side = scratch_grid[:, :, 5:16]
    no_box = (0, -1, 0, -1)  # no body: no two-field nodes
    patches = patch_scratch(averaged, pos, grid_mass)
    keep_old = flip > 0.0 or local_damping > 0.0
    old = flip_scratch(keep_old, pos, buf, grid_mass)
    buf_old = old[3]
    s = settled
    for k in range(n_steps):
        step = step0 + k
        zg = z0 - s if follow else z0
        ramp = 1.0
        if step < ramp_steps:
            ramp = 0.5 * (1.0 - np.cos(np.pi * (step + 0.5) / ramp_steps))
        vz_foot = -speed * ramp
        # 1. particle -> grid
        step_to_grid(pos, vel, aff, stress, mass, vol, x0, zg, h, dt, buf, old, keep_old)
        # 2. grid update: momentum, gravity, walls; the floor, damping, symmetry plane and footing nodes
        grid_update(buf, grid_mass, grid_vel, dt, gravity, damping, pad, wall_kind, wall_mu)
        j_floor = following_floor(grid_vel, zg, floor_z, h, pad) if follow else pad
        if local_damping > 0.0:
            local_damp(buf_old, grid_mass, grid_vel, local_damping, pad, j_floor, foot_i, foot_j)
        if symmetric:
            grid_vel[: pad + 1, :, 0] = 0.0
        fx, fz = footing_nodes(grid_mass, grid_vel, foot_i, foot_j, rough, vz_foot, dt)
        # 3. grid -> particle, stress update
        step_to_particles(pos, vel, aff, stress, mass, vol, gdot, grid_mass, grid_vel, grid_vel_m, geo, node,
                          side, no_box, x0, zg, h, dt, bounds, material, averaged, patches, flip,
                          old)  # fmt: skip
        forces[k, 0] = fx
        forces[k, 1] = fz
        forces[k, 2] = vz_foot
        s -= vz_foot * dt


@njit(cache=True)
def following_floor(grid_vel, z0, floor_z, h, pad):
    """The floor of a grid that follows the footing (origin ``z0`` [m] this step): the node line
    nearest the world floor ``floor_z`` [m] and those below it down to the wall line ``pad`` lose
    any downward velocity. The floor stays within h/2 of ``floor_z`` (rounding down instead let it
    sink with the grid by up to a cell, and the bed with it: 40-70 um in 0.1 s of hold at B/40,
    docs/mpm.md). Returns the floor's node line."""
    j_floor = int(np.floor((floor_z - z0) / h + 0.5))
    for i in range(grid_vel.shape[0]):
        for j in range(pad + 1, j_floor + 1):
            if grid_vel[i, j, 1] < 0.0:
                grid_vel[i, j, 1] = 0.0
    return j_floor


@njit(cache=True)
def footing_nodes(grid_mass, grid_vel, foot_i, foot_j, rough, vz_foot, dt):
    """The footing's grid condition, in place: the nodes ``foot_i[0] <= i <= foot_i[1]``,
    ``foot_j[0] <= j <= foot_j[1]`` holding mass take the vertical velocity ``vz_foot`` [m/s] (and
    ``v_x = 0`` if ``rough``). Returns the force of the grains on the footing (F_x, F_z) [N/m]: the
    impulse the condition takes from the grid over ``dt`` [s]."""
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
    return fx, fz


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
