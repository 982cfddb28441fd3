"""Pure-NumPy references of the MPM kernels (tests compare the numba versions against these).

Same arguments and conventions as :mod:`terradyn.mpm._kernels`; written with whole-array operations
(``np.add.at`` scatters) rather than loops.
"""

from __future__ import annotations

import numpy as np

from .constitutive import dk_stress_update_reference

__all__ = [
    "body_contact_sides_reference",
    "g2p_reference",
    "grid_update_reference",
    "p2g_reference",
    "p2g_sides_reference",
    "polygon_sdf_normals_reference",
    "polygon_sdf_reference",
]


def _stencil(pos, x0, z0, h):
    """Node indices (N, 3, 3, 2), weights (N, 3, 3), gradients and offsets x_i - x_p (N, 3, 3, 2)."""
    xi = (pos - np.array([x0, z0])) / h
    base = (xi - 0.5).astype(int)
    f = xi - base
    a = np.arange(3)
    d = a[None, None, :] - f[:, :, None]  # (N, 2, 3) node - particle in cells
    r = np.abs(d)
    w = np.where(r < 0.5, 0.75 - r**2, 0.5 * (1.5 - r) ** 2)
    dw = np.where(r < 0.5, -2.0 * (-d), np.sign(-d) * -(1.5 - r)) / h
    # dw/dx of N(x_p - x_i) with respect to x_p: for |d| < 0.5, -2 (x_p - x_i); else -sign(x_p-x_i)(1.5-|d|)
    wgt = w[:, 0, :, None] * w[:, 1, None, :]
    grad = np.stack([dw[:, 0, :, None] * w[:, 1, None, :], w[:, 0, :, None] * dw[:, 1, None, :]], axis=-1)
    idx = np.stack(
        [
            np.broadcast_to(base[:, 0, None, None] + a[None, :, None], wgt.shape),
            np.broadcast_to(base[:, 1, None, None] + a[None, None, :], wgt.shape),
        ],
        axis=-1,
    )
    off = np.stack(
        [np.broadcast_to(d[:, 0, :, None], wgt.shape), np.broadcast_to(d[:, 1, None, :], wgt.shape)], -1
    )
    return idx, wgt, grad, off * h


def p2g_reference(pos, vel, aff, stress, mass, vol, x0, z0, h, dt, shape):
    """Returns ``(grid_mass (nx, nz), grid_mom (nx, nz, 2))`` as :func:`~terradyn.mpm._kernels.p2g`."""
    idx, wgt, grad, off = _stencil(pos, x0, z0, h)
    sig = np.zeros((len(pos), 2, 2))
    sig[:, 0, 0], sig[:, 1, 1] = stress[:, 0], stress[:, 1]
    sig[:, 0, 1] = sig[:, 1, 0] = stress[:, 2]
    vnode = vel[:, None, None, :] + np.einsum("pab,pijb->pija", aff, off)
    mom = (wgt * mass[:, None, None])[..., None] * vnode
    mom -= dt * vol[:, None, None, None] * np.einsum("pab,pijb->pija", sig, grad)
    gm = np.zeros(shape)
    gp = np.zeros((*shape, 2))
    ii, jj = idx[..., 0].ravel(), idx[..., 1].ravel()
    np.add.at(gm, (ii, jj), (wgt * mass[:, None, None]).ravel())
    np.add.at(gp, (ii, jj), mom.reshape(-1, 2))
    return gm, gp


def grid_update_reference(grid_mass, grid_mom, dt, gravity, damping, pad, wall_kind, wall_mu):
    """Grid velocities as :func:`~terradyn.mpm._kernels.grid_update` (walls with loops; small grids)."""
    keep = max(0.0, 1.0 - damping * dt)
    has = grid_mass > 1e-14
    vel = np.zeros_like(grid_mom)
    vel[has] = grid_mom[has] / grid_mass[has][:, None]
    vel[..., 1][has] -= dt * gravity
    vel[has] *= keep
    nx, nz = grid_mass.shape
    walls = [(np.arange(nx) <= pad, (1.0, 0.0)), (np.arange(nx) >= nx - 1 - pad, (-1.0, 0.0))]
    for (mask, n), kind, mu in zip(walls, wall_kind[:2], wall_mu[:2], strict=True):
        sel = has & mask[:, None]
        vel[sel] = _wall_reference(vel[sel], np.array(n), kind, mu)
    sel = has & (np.arange(nz) <= pad)[None, :]
    vel[sel] = _wall_reference(vel[sel], np.array([0.0, 1.0]), wall_kind[2], wall_mu[2])
    return vel


def _wall_reference(v, n, kind, mu):
    v = v.copy()
    if kind == 1:
        return np.zeros_like(v)
    vn = v @ n
    app = vn < 0
    if kind == 0:
        v[app] -= vn[app, None] * n
        return v
    t = v - vn[:, None] * n
    vt = np.linalg.norm(t, axis=1)
    stick = app & (vt <= -mu * vn)
    slide = app & ~stick
    v[stick] = 0.0
    v[slide] = t[slide] * (1.0 + mu * vn[slide] / vt[slide])[:, None]
    return v


def g2p_reference(pos, vel, aff, stress, mass, vol, grid_vel, x0, z0, h, dt, bounds, material, sides=None):
    """New ``(pos, vel, aff, stress, vol, gdot)`` as :func:`~terradyn.mpm._kernels.g2p`;
    ``sides = (grid_vel_m, geo, node)`` gives the far-side reads of a body (None: no body)."""
    idx, wgt, grad, off = _stencil(pos, x0, z0, h)
    vi = grid_vel[idx[..., 0], idx[..., 1]]  # (N, 3, 3, 2)
    if sides is not None:
        grid_vel_m, geo, node = sides
        nd = node[idx[..., 0], idx[..., 1]]
        npn = np.broadcast_to(geo[:, None, None, :2], nd[..., :2].shape)
        far = (nd[..., 2] < 1e299) & (np.einsum("pija,pija->pij", npn, nd[..., :2]) < 0)
        far &= ((geo[:, 0] != 0) | (geo[:, 1] != 0))[:, None, None]
        vi = np.where(far[..., None], grid_vel_m[idx[..., 0], idx[..., 1]], vi)
    v = np.einsum("pij,pija->pa", wgt, vi)
    c = 4.0 / h**2 * np.einsum("pij,pija,pijb->pab", wgt, vi, off)
    lg = np.einsum("pija,pijb->pab", vi, grad)
    x = pos + dt * v
    x[:, 0] = np.clip(x[:, 0], bounds[0], bounds[1])
    x[:, 1] = np.clip(x[:, 1], bounds[2], bounds[3])
    vol_new = vol * np.exp(dt * np.trace(lg, axis1=1, axis2=2))
    s, gd = dk_stress_update_reference(stress, lg, mass / vol_new, dt, *material)
    return x, v, c, s, vol_new, gd


def polygon_sdf_reference(points, seg):
    """Signed distance (M,) of body-frame points (M, 2) to closed polygons ``seg`` (S, 4); < 0 inside."""
    p = points[:, None, :]
    a, b = seg[None, :, :2], seg[None, :, 2:]
    e = b - a
    t = np.clip(np.einsum("msk,msk->ms", p - a, e) / np.einsum("msk,msk->ms", e, e), 0.0, 1.0)
    d = np.linalg.norm(a + t[..., None] * e - p, axis=-1).min(axis=1)
    z1, z2 = a[..., 1], b[..., 1]
    crosses = (z1 > p[..., 1]) != (z2 > p[..., 1])
    with np.errstate(divide="ignore", invalid="ignore"):
        xc = a[..., 0] + (p[..., 1] - z1) * e[..., 0] / e[..., 1]
    inside = (np.sum(crosses & (p[..., 0] < xc), axis=1) % 2) == 1
    return np.where(inside, -d, d)


def polygon_sdf_normals_reference(points, seg):
    """Signed distance (M,) and unit outward normal (M, 2) of body-frame points to ``seg`` (S, 4) as
    :func:`~terradyn.mpm._kernels.polygon_sdf` (first nearest segment on ties)."""
    p = points[:, None, :]
    a, b = seg[None, :, :2], seg[None, :, 2:]
    e = b - a
    t = np.clip(np.einsum("msk,msk->ms", p - a, e) / np.einsum("msk,msk->ms", e, e), 0.0, 1.0)
    q = a + t[..., None] * e
    d_all = np.linalg.norm(q - p, axis=-1)
    k = np.argmin(d_all, axis=1)
    rows = np.arange(len(points))
    d = d_all[rows, k]
    phi = polygon_sdf_reference(points, seg)
    off = points - q[rows, k]  # from the nearest point to the point
    with np.errstate(divide="ignore", invalid="ignore"):
        n = np.where(d[:, None] > 1e-300, off / d[:, None], np.array([0.0, 1.0]))
    n = np.where((phi < 0)[:, None], -n, n)
    return phi, n


def p2g_sides_reference(pos, vel, aff, stress, mass, vol, geo, node, x0, z0, h, dt, gap_check=False):
    """The two-field sums ``side`` (nx, nz, 9) of :func:`~terradyn.mpm._kernels.p2g_sides` for the
    particles with a body normal in ``geo`` (N, 3) and the band nodes of ``node`` (nx, nz, 3)."""
    near = np.flatnonzero((geo[:, 0] != 0) | (geo[:, 1] != 0))
    idx, wgt, grad, off = _stencil(pos[near], x0, z0, h)
    ii, jj = idx[..., 0], idx[..., 1]
    nd = node[ii, jj]  # (n, 3, 3, 3)
    band = nd[..., 2] < 1e299
    npn = geo[near, None, None, :2]
    far = band & (np.einsum("pija,pija->pij", np.broadcast_to(npn, nd[..., :2].shape), nd[..., :2]) < -1e-9)
    wm = wgt * mass[near, None, None]
    sig = np.zeros((len(near), 2, 2))
    sig[:, 0, 0], sig[:, 1, 1] = stress[near, 0], stress[near, 1]
    sig[:, 0, 1] = sig[:, 1, 0] = stress[near, 2]
    vnode = vel[near, None, None, :] + np.einsum("pab,pijb->pija", aff[near], off)
    mom = wm[..., None] * vnode - dt * vol[near, None, None, None] * np.einsum("pab,pijb->pija", sig, grad)
    gap = np.einsum("pija,pija->pij", off, np.broadcast_to(npn, off.shape)) + geo[near, 2, None, None]
    side = np.zeros((*node.shape[:2], 11 if gap_check else 9))
    if gap_check:  # the smallest gap of a field's grains (each half its side beyond its centre)
        side[..., 9:11] = 1e300
        reach = np.broadcast_to((geo[near, 2] - 0.5 * np.sqrt(vol[near]))[:, None, None], wm.shape)
    for sel, o in ((band & ~far, 3), (far, 6)):
        if o == 6:
            np.add.at(side[..., 0], (ii[sel], jj[sel]), wm[sel])
            np.add.at(side[..., 1], (ii[sel], jj[sel]), mom[sel][:, 0])
            np.add.at(side[..., 2], (ii[sel], jj[sel]), mom[sel][:, 1])
        nw = wm[..., None] * np.broadcast_to(npn, off.shape)
        np.add.at(side[..., o], (ii[sel], jj[sel]), nw[sel][:, 0])
        np.add.at(side[..., o + 1], (ii[sel], jj[sel]), nw[sel][:, 1])
        np.add.at(side[..., o + 2], (ii[sel], jj[sel]), (wm * gap)[sel])
        if gap_check:
            np.minimum.at(side[..., 9 if o == 3 else 10], (ii[sel], jj[sel]), reach[sel])
    return side


def body_contact_sides_reference(grid_mass, grid_mom, side, node, x0, z0, h, dt, pose, twist, mu):
    """Near- and far-side velocities (nx, nz, 2) x 2 and the force on the body as
    :func:`~terradyn.mpm._kernels.body_contact_sides` without gravity, damping or walls."""
    band = (node[..., 2] < 1e299) & (grid_mass > 1e-14)
    m_far = side[..., 0]
    m_near = grid_mass - m_far
    p_far = side[..., 1:3]
    p_near = grid_mom - p_far
    nx, nz = grid_mass.shape
    xi = x0 + h * np.arange(nx)[:, None] - pose[0]
    zi = z0 + h * np.arange(nz)[None, :] - pose[1]
    ub = np.stack(np.broadcast_arrays(twist[0] + twist[2] * zi, twist[1] - twist[2] * xi), -1)
    out, force = [], np.zeros(3)
    for m, p, o in ((m_near, p_near, 3), (m_far, p_far, 6)):
        has = band & (m > 1e-9 * grid_mass)
        v = np.zeros_like(p)
        v[has] = p[has] / m[has][:, None]
        new = v.copy()
        s = side[..., o : o + 2]
        ns = np.linalg.norm(s, axis=-1)
        act = has & (side[..., o + 2] <= 1e-9 * h * m) & (ns > 0)  # gap zero to rounding: contact
        n = s[act] / ns[act][:, None]
        rel = v[act] - ub[act]
        vn = np.einsum("ka,ka->k", rel, n)
        tang = rel - vn[:, None] * n
        vt = np.linalg.norm(tang, axis=1)
        app = vn < 0
        with np.errstate(divide="ignore", invalid="ignore"):
            scale = np.where(vt <= -mu * vn, 0.0, 1.0 + mu * vn / vt)
        rel = np.where(app[:, None], tang * scale[:, None], rel)
        new[act] = ub[act] + rel
        dj = -m[..., None] * (new - v) / dt
        dj[~has] = 0.0
        force[0] += dj[..., 0].sum()
        force[1] += dj[..., 1].sum()
        force[2] += (zi * dj[..., 0] - xi * dj[..., 1]).sum()
        out.append(new)
    return out[0], out[1], force
