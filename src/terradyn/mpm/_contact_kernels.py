"""Numba kernels of rigid-body contact on the MPM grid (signed distances, two-field contact).

Launched by :func:`terradyn.mpm._kernels.advance`; conventions (grid origin, units, shapes) as in
:mod:`terradyn.mpm._kernels`. Two schemes: the legacy "cover" contact (:func:`body_contact`,
:func:`body_project`) and the two-field contact (:func:`body_particles`, :func:`body_nodes`,
:func:`p2g_sides`, :func:`body_contact_sides`, :func:`body_project_sides`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from ._common_kernels import _MASS_EPS, _coulomb, _node_velocity, _weights

__all__ = [
    "BAND_CELLS",
    "body_contact",
    "body_contact_sides",
    "body_nodes",
    "body_particles",
    "body_project",
    "body_project_sides",
    "p2g_sides",
    "polygon_sdf",
]


@njit(cache=True, fastmath=True)
def polygon_sdf(px, pz, seg):
    """Signed distance [m] of body-frame point (px, pz) to closed polygons ``seg`` (S, 4) = (x1, z1, x2, z2).

    Negative inside (even-odd rule over all loops). Returns ``(phi, nx, nz)`` with ``n`` the unit
    outward normal of the body at the nearest boundary point.
    """
    phi, nx, nz, _ = _polygon_sdf_from(px, pz, seg, 0)
    return phi, nx, nz


@njit(cache=True, fastmath=True, inline="always")
def _segment_offset(px, pz, x1, z1, x2, z2):
    """Vector (qx, qz) [m] from (px, pz) to the nearest point of segment (x1, z1)-(x2, z2)."""
    ex = x2 - x1
    ez = z2 - z1
    ll = ex * ex + ez * ez
    t = 0.0
    if ll > 0.0:
        t = ((px - x1) * ex + (pz - z1) * ez) / ll
        t = min(1.0, max(0.0, t))
    return x1 + t * ex - px, z1 + t * ez - pz


#: A point closer to the outline than this fraction of its nearest segment's length is on it
#: (rounding of grid and particle coordinates is ~1e-16 of them; real gaps are far larger).
_ON_OUTLINE = 1e-9


@njit(cache=True, fastmath=True)
def _inside(px, pz, seg):
    """Even-odd test of body-frame point (px, pz) against the closed polygons ``seg``."""
    inside = False
    for s in range(seg.shape[0]):
        z1 = seg[s, 1]
        z2 = seg[s, 3]
        if (z1 > pz) != (z2 > pz):
            x1 = seg[s, 0]
            xc = x1 + (pz - z1) * (seg[s, 2] - x1) / (z2 - z1)
            if px < xc:
                inside = not inside
    return inside


@njit(cache=True, fastmath=True)
def _outline_normal(px, pz, seg, tol):
    """Unit outward normal at a point (px, pz) on the outline: the sum of the outward normals of
    the segments within ``tol`` [m] of it (two at a vertex), each oriented by probing which side of
    the segment is outside. ``(0, 1)`` where they cancel (the two coincident faces of a
    zero-thickness plate)."""
    sx = 0.0
    sz = 0.0
    for s in range(seg.shape[0]):
        x1 = seg[s, 0]
        z1 = seg[s, 1]
        qx, qz = _segment_offset(px, pz, x1, z1, seg[s, 2], seg[s, 3])
        if qx * qx + qz * qz > tol * tol:
            continue
        ex = seg[s, 2] - x1
        ez = seg[s, 3] - z1
        ll = math.sqrt(ex * ex + ez * ez)
        if ll <= 0.0:
            continue
        nx = ez / ll
        nz = -ex / ll
        probe = 1e3 * tol
        if _inside(px + probe * nx, pz + probe * nz, seg):
            nx = -nx
            nz = -nz
        sx += nx
        sz += nz
    ns = math.sqrt(sx * sx + sz * sz)
    if ns < 1e-6:
        return 0.0, 1.0
    return sx / ns, sz / ns


@njit(cache=True, fastmath=True)
def _polygon_sdf_from(px, pz, seg, first):
    """:func:`polygon_sdf` that tries segment ``first`` (say the nearest one of a neighbouring point)
    before the others, so that most segments are passed over by a bounding-box test; returns
    ``(phi, nx, nz, index of the nearest segment)``. Equal to :func:`polygon_sdf` to rounding (only
    which of two equally near segments is kept can differ)."""
    x1 = seg[first, 0]
    z1 = seg[first, 1]
    x2 = seg[first, 2]
    z2 = seg[first, 3]
    bx, bz = _segment_offset(px, pz, x1, z1, x2, z2)
    best = bx * bx + bz * bz
    nearest = first
    inside = False
    for s in range(seg.shape[0]):
        x1 = seg[s, 0]
        z1 = seg[s, 1]
        x2 = seg[s, 2]
        z2 = seg[s, 3]
        if s != first:
            # distance to the segment's bounding box: a lower bound of the distance to the segment
            ox = max(min(x1, x2) - px, px - max(x1, x2), 0.0)
            oz = max(min(z1, z2) - pz, pz - max(z1, z2), 0.0)
            if ox * ox + oz * oz < best:
                qx, qz = _segment_offset(px, pz, x1, z1, x2, z2)
                d2 = qx * qx + qz * qz
                if d2 < best:
                    best = d2
                    bx = qx
                    bz = qz
                    nearest = s
        if (z1 > pz) != (z2 > pz):
            xc = x1 + (pz - z1) * (x2 - x1) / (z2 - z1)
            if px < xc:
                inside = not inside
    d = math.sqrt(best)
    ex = seg[nearest, 2] - seg[nearest, 0]
    ez = seg[nearest, 3] - seg[nearest, 1]
    tol = _ON_OUTLINE * math.sqrt(ex * ex + ez * ez)
    if d <= tol:
        # on the outline to rounding: the offset's direction is rounding noise, so take the
        # outline's own normal (phi = 0), which a mirrored point gets mirrored
        nx, nz = _outline_normal(px, pz, seg, tol)
        return 0.0, nx, nz, nearest
    nx = bx / d if inside else -bx / d
    nz = bz / d if inside else -bz / d
    x1 = seg[nearest, 0]
    z1 = seg[nearest, 1]
    t = ((px - x1) * ex + (pz - z1) * ez) / (ex * ex + ez * ez)
    if 0.0 < t < 1.0:
        # nearest point inside the segment: the normal is the segment's own, exactly (the offset's
        # direction carries rounding of the coordinates over d, large close to the surface)
        ll = math.sqrt(ex * ex + ez * ez)
        if nx * ez - nz * ex >= 0.0:
            nx = ez / ll
            nz = -ex / ll
        else:
            nx = -ez / ll
            nz = ex / ll
    return (-d if inside else d), nx, nz, nearest


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


# --- Two-sided (multi-velocity-field) rigid-body contact ------------------------------------------
#
# Near the body every grid node of a band (signed distance below BAND_CELLS cells) keeps two grain
# fields: the near-side field (particles whose body normal n_p agrees with the node's own normal n_i,
# n_p . n_i >= 0) and the far-side field (n_p . n_i < 0: grains across a body thinner than the
# B-spline stencil). Each field carries the sums M = sum w m, N = sum w m n_p and
# G = sum w m ((x_i - x_p) . n_p + phi_p): G / M is the mean height of the node above the field's
# particles' nearest surface points. A field is in contact where G <= 0 (the node lies on the body
# side of that field's surface): its velocity relative to the rigid body loses any approach along
# n = N / |N| and gets Coulomb friction. Far from the body there is one field and no contact.

#: Signed distance [cells] below which a grid node carries two grain fields near the body.
BAND_CELLS = 2.0
_FAR = 1e300


@njit(cache=True, fastmath=True, inline="always")
def _far_side(npx, npz, node, i, j):
    """True if a particle of body normal (npx, npz) is in the far-side field of band node (i, j)."""
    # a normal perpendicular to the node's (dot product zero to rounding) stays on the near side
    return node[i, j, 2] < 0.5 * _FAR and npx * node[i, j, 0] + npz * node[i, j, 1] < -1e-9


#: Particles per block of :func:`body_particles` (each block lists its near particles in place).
_PARTICLE_BLOCK = 4096


@njit(cache=True, fastmath=True, parallel=True)
def body_particles(pos, seg, pose, reach, geo, near):
    """Body normal and signed distance of the particles within ``reach`` [m] of the body origin.

    ``geo`` (N, 3) receives (n_x, n_z, phi): the world unit outward normal of the body at the
    particle's nearest boundary point and the signed distance phi [m] (< 0 inside a closed outline);
    zeros for particles further away (rows already zero are not written again). ``near`` (N,)
    receives the indices of the near particles in ascending order; returns their count. Blocks of
    particles run in parallel, each listing its near particles in its own part of ``near``; the lists
    are then joined in block order.
    """
    n = pos.shape[0]
    xb = pose[0]
    zb = pose[1]
    cth = math.cos(pose[2])
    sth = math.sin(pose[2])
    r2 = reach * reach
    nblock = (n + _PARTICLE_BLOCK - 1) // _PARTICLE_BLOCK
    counts = np.zeros(max(1, nblock), dtype=np.int64)
    for c in prange(nblock):
        start = c * _PARTICLE_BLOCK
        k = start
        hint = 0  # nearest segment of the previous near particle of the block
        for p in range(start, min(n, start + _PARTICLE_BLOCK)):
            rx = pos[p, 0] - xb
            rz = pos[p, 1] - zb
            if rx * rx + rz * rz > r2:
                if geo[p, 0] != 0.0 or geo[p, 1] != 0.0 or geo[p, 2] != 0.0:
                    geo[p, 0] = 0.0
                    geo[p, 1] = 0.0
                    geo[p, 2] = 0.0
                continue
            phi, nbx, nbz, hint = _polygon_sdf_from(cth * rx - sth * rz, sth * rx + cth * rz, seg, hint)
            geo[p, 0] = cth * nbx + sth * nbz
            geo[p, 1] = -sth * nbx + cth * nbz
            geo[p, 2] = phi
            near[k] = p
            k += 1
        counts[c] = k - start
    k = 0
    for c in range(nblock):
        start = c * _PARTICLE_BLOCK
        for q in range(counts[c]):  # k <= start: moving down in ascending order is safe
            near[k + q] = near[start + q]
        k += counts[c]
    return k


@njit(cache=True, fastmath=True, parallel=True)
def body_nodes(x0, z0, h, seg, pose, reach, band, node, old_box):
    """Band nodes of the body: ``node`` (nx, nz, 3) = (n_x, n_z, phi) [-, -, m].

    Nodes within ``reach`` [m] of the body origin whose signed distance phi is below ``band`` [m]
    get their world outward normal and phi; every other node gets phi = ``_FAR`` (no band), given
    that only nodes of ``old_box`` (the previous call's box) had a band. Returns the node box
    ``(i_lo, i_hi, j_lo, j_hi)`` searched. Rows of nodes run in parallel.
    """
    nx = node.shape[0]
    nz = node.shape[1]
    xb = pose[0]
    zb = pose[1]
    cth = math.cos(pose[2])
    sth = math.sin(pose[2])
    i_lo = max(0, int((xb - reach - x0) / h))
    i_hi = min(nx - 1, int((xb + reach - x0) / h) + 1)
    j_lo = max(0, int((zb - reach - z0) / h))
    j_hi = min(nz - 1, int((zb + reach - z0) / h) + 1)
    # every node of the old box or the new one is visited by exactly one (i, j) iteration
    u_lo = min(i_lo, old_box[0]) if old_box[1] >= old_box[0] else i_lo
    u_hi = max(i_hi, old_box[1])
    v_lo = min(j_lo, old_box[2]) if old_box[3] >= old_box[2] else j_lo
    v_hi = max(j_hi, old_box[3])
    for i in prange(u_lo, u_hi + 1):
        hint = 0  # nearest segment of the previous node of the row
        for j in range(v_lo, v_hi + 1):
            if i_lo <= i <= i_hi and j_lo <= j <= j_hi:
                rx = x0 + i * h - xb
                rz = z0 + j * h - zb
                phi, nbx, nbz, hint = _polygon_sdf_from(cth * rx - sth * rz, sth * rx + cth * rz, seg, hint)
                node[i, j, 2] = _FAR
                if phi < band * (1.0 - 1e-9):  # a node at the band's edge to rounding is out
                    node[i, j, 0] = cth * nbx + sth * nbz
                    node[i, j, 1] = -sth * nbx + cth * nbz
                    node[i, j, 2] = phi
            elif old_box[0] <= i <= old_box[1] and old_box[2] <= j <= old_box[3]:
                node[i, j, 2] = _FAR
    return i_lo, i_hi, j_lo, j_hi


@njit(cache=True, fastmath=True)
def p2g_sides(
    pos, vel, aff, stress, mass, vol, geo, near, n_near, node, box, x0, z0, h, dt, side, gap_check=False
):
    """Particle -> grid scatter of the two grain fields on band nodes (after :func:`p2g`).

    ``side`` (nx, nz, 9) is zeroed on the node ``box`` of :func:`body_nodes` (which holds every band
    node), then receives on band nodes: the far-side field's mass [kg/m] and
    momentum (x, z) [kg/s] as :func:`p2g` computes them (internal-force impulse included), then for the
    near-side and the far-side field in turn ``sum w m n_p`` (x, z) [kg/m] and the gap sum
    ``sum w m ((x_i - x_p) . n_p + phi_p)`` [kg] (its ratio to the field's mass is the node's height above
    the body surface). With ``gap_check`` (and ``side`` (nx, nz, 11)) slots 9 and 10 receive, for the
    near and the far field, the smallest gap ``phi_p - sqrt(V_p) / 2`` [m] between one of its grains
    (reaching half its side beyond its centre) and the body (``_FAR`` where the field has no grain).
    Only the ``n_near`` particles ``near`` (from :func:`body_particles`, whose ``geo`` they use)
    contribute.
    """
    side[box[0] : box[1] + 1, box[2] : box[3] + 1, :9] = 0.0
    if gap_check:
        side[box[0] : box[1] + 1, box[2] : box[3] + 1, 9:11] = _FAR
    inv_h = 1.0 / h
    wx = np.empty(3)
    wz = np.empty(3)
    dwx = np.empty(3)
    dwz = np.empty(3)
    for k in range(n_near):
        p = near[k]
        bi, fx = _weights((pos[p, 0] - x0) * inv_h, wx, dwx, inv_h)
        bj, fz = _weights((pos[p, 1] - z0) * inv_h, wz, dwz, inv_h)
        m = mass[p]
        vdt = vol[p] * dt
        npx = geo[p, 0]
        npz = geo[p, 1]
        phi = geo[p, 2]
        for a in range(3):
            dx = (a - fx) * h
            for b in range(3):
                i = bi + a
                j = bj + b
                if node[i, j, 2] >= 0.5 * _FAR:
                    continue
                dz = (b - fz) * h
                wm = wx[a] * wz[b] * m
                o = 3
                if _far_side(npx, npz, node, i, j):
                    gx = dwx[a] * wz[b]
                    gz = wx[a] * dwz[b]
                    vx = vel[p, 0] + aff[p, 0, 0] * dx + aff[p, 0, 1] * dz
                    vz = vel[p, 1] + aff[p, 1, 0] * dx + aff[p, 1, 1] * dz
                    side[i, j, 0] += wm
                    side[i, j, 1] += wm * vx - vdt * (stress[p, 0] * gx + stress[p, 2] * gz)
                    side[i, j, 2] += wm * vz - vdt * (stress[p, 2] * gx + stress[p, 1] * gz)
                    o = 6
                side[i, j, o] += wm * npx
                side[i, j, o + 1] += wm * npz
                side[i, j, o + 2] += wm * (dx * npx + dz * npz + phi)
                if gap_check:
                    g = 9 if o == 3 else 10
                    side[i, j, g] = min(side[i, j, g], phi - 0.5 * math.sqrt(vol[p]))


#: Relative rounding of a field's gap sum (kg m), per kg of field mass and metre of cell size.
_GAP_TOL = 1e-9


@njit(cache=True, fastmath=True, inline="always")
def _in_contact(gap_sum, nearest, mass, h, gap_check):
    """Whether a grain field of ``mass`` is in contact with the body at a band node.

    Node test: its gap sum is at most zero, to a rounding tolerance (a node exactly on a face aligned
    with a grid line has a gap sum of zero to rounding, whose sign must not decide the contact nor
    differ between mirror images). Gap check: the node lies within half a cell of the surface or
    behind it and the field's nearest grain reaches the body (``nearest`` <= 0)."""
    tol = _GAP_TOL * h * mass
    if gap_check:
        return nearest <= 0.0 and gap_sum <= 0.5 * h * mass + tol
    return gap_sum <= tol


@njit(cache=True, fastmath=True, inline="always")
def _contact_field(vx, vz, sx, sz, touching, ubx, ubz, mu):
    """New velocity of one grain field: body contact (normal ``(sx, sz)`` normalised, Coulomb
    friction ``mu``) if ``touching`` (:func:`_in_contact`), else unchanged."""
    if not touching:
        return vx, vz
    ns = math.sqrt(sx * sx + sz * sz)
    if ns <= 0.0:
        return vx, vz
    ux, uz = _coulomb(vx - ubx, vz - ubz, sx / ns, sz / ns, mu)
    return ubx + ux, ubz + uz


@njit(cache=True, fastmath=True)
def body_contact_sides(
    buf,
    grid_mass,
    grid_vel,
    grid_vel_m,
    side,
    node,
    box,
    x0,
    z0,
    h,
    dt,
    gravity,
    damping,
    pad,
    wall_kind,
    wall_mu,
    pose,
    twist,
    mu,
    gap_check=False,
):
    """Two-field frictional contact on the band nodes; returns the force on the body.

    On each band node of ``box`` (i_lo, i_hi, j_lo, j_hi) the near-side field (total of ``buf`` minus
    the far-side field of ``side``) and the far-side field get their own velocity (gravity, damping
    [1/s] and walls as :func:`grid_update`), then contact against the rigid body velocity at the node
    (``pose``, ``twist``) with Coulomb coefficient ``mu``. The near-side velocity goes to ``grid_vel``,
    the far-side one to ``grid_vel_m`` (nx, nz, 2) [m/s]. Returns ``(f_x, f_z, torque_y)``
    [N/m, N m/m] on the body about its origin: ``-sum_fields m_f dv_f / dt``.

    A field is in contact where the node lies behind the body surface (its gap sum at most zero, to
    rounding); with ``gap_check`` where the node lies within half a cell of the surface or behind it
    and one of the field's grains reaches the body (``side`` slots 9 / 10 at most zero).
    """
    nchunk = buf.shape[0]
    nx = grid_mass.shape[0]
    keep = max(0.0, 1.0 - damping * dt)
    xb = pose[0]
    zb = pose[1]
    fx = 0.0
    fz = 0.0
    ty = 0.0
    for i in range(box[0], box[1] + 1):
        for j in range(box[2], box[3] + 1):
            m = grid_mass[i, j]
            if node[i, j, 2] >= 0.5 * _FAR or m <= _MASS_EPS:
                continue
            px = 0.0
            pz = 0.0
            for c in range(nchunk):
                px += buf[c, i, j, 1]
                pz += buf[c, i, j, 2]
            rx = x0 + i * h - xb
            rz = z0 + j * h - zb
            ubx = twist[0] + twist[2] * rz
            ubz = twist[1] - twist[2] * rx
            m_far = side[i, j, 0]
            m_near = m - m_far
            jx = 0.0
            jz = 0.0
            near_in = _in_contact(side[i, j, 5], side[i, j, 9] if gap_check else 0.0, m_near, h, gap_check)
            far_in = _in_contact(side[i, j, 8], side[i, j, 10] if gap_check else 0.0, m_far, h, gap_check)
            if m_near > 1e-9 * m:
                vx, vz = _node_velocity(
                    m_near, px - side[i, j, 1], pz - side[i, j, 2], dt, gravity, keep, i, j, nx, pad,
                    wall_kind, wall_mu,
                )  # fmt: skip
                nvx, nvz = _contact_field(vx, vz, side[i, j, 3], side[i, j, 4], near_in, ubx, ubz, mu)
                grid_vel[i, j, 0] = nvx
                grid_vel[i, j, 1] = nvz
                jx -= m_near * (nvx - vx) / dt
                jz -= m_near * (nvz - vz) / dt
            if m_far > 1e-9 * m:
                vx, vz = _node_velocity(
                    m_far, side[i, j, 1], side[i, j, 2], dt, gravity, keep, i, j, nx, pad, wall_kind, wall_mu
                )
                nvx, nvz = _contact_field(vx, vz, side[i, j, 6], side[i, j, 7], far_in, ubx, ubz, mu)
                grid_vel_m[i, j, 0] = nvx
                grid_vel_m[i, j, 1] = nvz
                jx -= m_far * (nvx - vx) / dt
                jz -= m_far * (nvz - vz) / dt
            else:
                grid_vel_m[i, j, 0] = grid_vel[i, j, 0]
                grid_vel_m[i, j, 1] = grid_vel[i, j, 1]
            if m_near <= 1e-9 * m:
                grid_vel[i, j, 0] = grid_vel_m[i, j, 0]
                grid_vel[i, j, 1] = grid_vel_m[i, j, 1]
            fx += jx
            fz += jz
            ty += rz * jx - rx * jz
    return fx, fz, ty


@njit(cache=True, fastmath=True, parallel=True)
def body_project_sides(pos, vel, mass, geo, near, n_near, dt, seg, pose_old, pose, twist, mu, eps):
    """Keep particles on their side of the body surface, for thin and thick bodies alike.

    A near particle (from :func:`body_particles`, outside the body at the start of the step) whose
    path over the step relative to the body (old pose ``pose_old`` to ``pose``, start point
    ``pos - dt vel``) crosses a boundary segment goes back to the first crossing point, ``eps`` [m] off
    the surface on the side it came from. One that ends inside a closed outline moves out along the
    outward normal. Its velocity relative to the body then loses any approach along that normal
    (Coulomb friction ``mu``). Returns the reaction on the body, ``-sum m_p dv_p / dt``
    (f_x, f_z, torque_y) [N/m, N m/m]. The near particles run in parallel; their impulses are summed
    afterwards in particle order, so the result does not depend on the thread count.
    """
    c0 = math.cos(pose_old[2])
    s0 = math.sin(pose_old[2])
    c1 = math.cos(pose[2])
    s1 = math.sin(pose[2])
    imp = np.zeros((n_near, 3))
    for k in prange(n_near):
        p = near[k]
        phi0 = geo[p, 2]
        rx = pos[p, 0] - pose[0]
        rz = pos[p, 1] - pose[1]
        ex = c1 * rx - s1 * rz
        ez = s1 * rx + c1 * rz
        qx = pos[p, 0] - dt * vel[p, 0] - pose_old[0]
        qz = pos[p, 1] - dt * vel[p, 1] - pose_old[1]
        ox = c0 * qx - s0 * qz
        oz = s0 * qx + c0 * qz
        mx = ex - ox
        mz = ez - oz
        travel = math.sqrt(mx * mx + mz * mz)
        if phi0 > travel + eps:
            continue  # too far from the surface to reach it this step
        hit = False
        best = 2.0
        cx = 0.0
        cz = 0.0
        nbx = 0.0
        nbz = 0.0
        if phi0 >= 0.0:
            for s in range(seg.shape[0]):
                ax = seg[s, 0]
                az = seg[s, 1]
                dx = seg[s, 2] - ax
                dz = seg[s, 3] - az
                den = mx * dz - mz * dx
                if den == 0.0:
                    continue
                wx = ax - ox
                wz = az - oz
                t = (wx * dz - wz * dx) / den
                u = (wx * mz - wz * mx) / den
                if 0.0 <= t <= 1.0 and 0.0 <= u <= 1.0 and t < best:
                    best = t
                    cx = ax + u * dx
                    cz = az + u * dz
                    ll = math.sqrt(dx * dx + dz * dz)
                    nbx = dz / ll
                    nbz = -dx / ll
                    if (ox - cx) * nbx + (oz - cz) * nbz < 0.0:
                        nbx = -nbx
                        nbz = -nbz
                    hit = True
        if hit:
            ex = cx + eps * nbx
            ez = cz + eps * nbz
        else:
            phi, sx, sz = polygon_sdf(ex, ez, seg)
            if phi >= 0.0:
                continue
            ex -= (phi - eps) * sx
            ez -= (phi - eps) * sz
            nbx = sx
            nbz = sz
        # back to the world
        rx = c1 * ex + s1 * ez
        rz = -s1 * ex + c1 * ez
        pos[p, 0] = pose[0] + rx
        pos[p, 1] = pose[1] + rz
        nwx = c1 * nbx + s1 * nbz
        nwz = -s1 * nbx + c1 * nbz
        ubx = twist[0] + twist[2] * rz
        ubz = twist[1] - twist[2] * rx
        ux, uz = _coulomb(vel[p, 0] - ubx, vel[p, 1] - ubz, nwx, nwz, mu)
        dvx = ubx + ux - vel[p, 0]
        dvz = ubz + uz - vel[p, 1]
        vel[p, 0] += dvx
        vel[p, 1] += dvz
        jx = -mass[p] * dvx / dt
        jz = -mass[p] * dvz / dt
        imp[k, 0] = jx
        imp[k, 1] = jz
        imp[k, 2] = rz * jx - rx * jz
    fx = 0.0
    fz = 0.0
    ty = 0.0
    for k in range(n_near):
        fx += imp[k, 0]
        fz += imp[k, 1]
        ty += imp[k, 2]
    return fx, fz, ty
