"""Two-field rigid-body contact: kernels equal their NumPy references; thin bodies block grains on
both sides; degenerate footprints are refused; composite and placed bodies take the bare path."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mpm_reference import KERNEL_H, KERNEL_ORIGIN, KERNEL_SHAPE, MODEL, kernel_particles
from terradyn.errors import InputError
from terradyn.geometry import Composite, Plate, WheelCircular
from terradyn.mpm import _kernels as K
from terradyn.mpm._reference import (
    body_contact_sides_reference,
    g2p_reference,
    p2g_sides_reference,
    polygon_sdf_normals_reference,
)
from terradyn.mpm.bodies import ContactScheme, body_segments, check_footprint, effective_body

H = KERNEL_H
X0, Z0 = KERNEL_ORIGIN
SHAPE = KERNEL_SHAPE
particles = kernel_particles

POSE = np.array([X0 + 6.37 * H, Z0 + 5.52 * H, 0.3])  # a tilted zero-thickness plate
SEG = body_segments(Plate(0.05, 0.1), H)
BOX_REACH = 0.025 + 2 * H


def geometry(pos, seg=SEG, pose=POSE):
    geo = np.zeros((len(pos), 3))
    near = np.zeros(len(pos), dtype=np.int64)
    n_near = K.body_particles(pos, seg, pose, BOX_REACH + 2.5 * H, geo, near)
    node = np.zeros((*SHAPE, 3))
    node[:, :, 2] = 1e300
    box = K.body_nodes(X0, Z0, H, seg, pose, BOX_REACH, K.BAND_CELLS * H, node, (0, -1, 0, -1))
    return geo, near, n_near, node, box


def test_body_particles_normals_equal_reference():
    pos = particles(3)[0]
    geo, near, n_near, _, _ = geometry(pos)
    assert 0 < n_near <= len(pos)
    c, s = math.cos(POSE[2]), math.sin(POSE[2])
    r = pos[near[:n_near]] - POSE[:2]
    body = np.column_stack([c * r[:, 0] - s * r[:, 1], s * r[:, 0] + c * r[:, 1]])
    phi, n = polygon_sdf_normals_reference(body, SEG)
    world = np.column_stack([c * n[:, 0] + s * n[:, 1], -s * n[:, 0] + c * n[:, 1]])
    np.testing.assert_allclose(geo[near[:n_near], 2], phi, atol=1e-12)
    np.testing.assert_allclose(geo[near[:n_near], :2], world, atol=1e-9)
    # a zero-thickness plate: every particle is outside, its normal points from the plate to it
    assert np.all(phi >= 0)


@pytest.mark.parametrize("gap_check", [False, True])
@pytest.mark.parametrize("seed", [0, 1])
def test_p2g_sides_equals_reference(seed, gap_check):
    pos, vel, aff, stress, mass, vol = particles(seed)
    geo, near, n_near, node, box = geometry(pos)
    side = np.zeros((*SHAPE, 11 if gap_check else 9))
    K.p2g_sides(
        pos, vel, aff, stress, mass, vol, geo, near, n_near, node, box, X0, Z0, H, 1e-4, side, gap_check
    )
    ref = p2g_sides_reference(pos, vel, aff, stress, mass, vol, geo, node, X0, Z0, H, 1e-4, gap_check)
    np.testing.assert_allclose(side[..., :9], ref[..., :9], rtol=1e-10, atol=1e-12)
    if gap_check:  # the nearest grain of each field, where it has one
        has = ref[..., 9:] < 1e299
        assert has[..., 0].sum() > 4 and has[..., 1].sum() > 4
        np.testing.assert_allclose(side[..., 9:][has], ref[..., 9:][has], rtol=1e-12, atol=1e-15)
        assert np.all((side[..., 9:][~has] >= 1e299) | (side[..., 9:][~has] == 0))  # none, or outside the box
    # both sides of the thin plate are populated on the band nodes
    assert (side[..., 0] > 0).sum() > 4
    assert (side[..., 3:5] != 0).any(axis=-1).sum() > 4


def _two_field_grid(seed):
    pos, vel, aff, stress, mass, vol = particles(seed)
    geo, near, n_near, node, box = geometry(pos)
    buf = np.zeros((2, *SHAPE, 3))
    K.p2g(pos, vel, aff, stress, mass, vol, X0, Z0, H, 1e-4, buf)
    side = np.zeros((*SHAPE, 9))
    K.p2g_sides(pos, vel, aff, stress, mass, vol, geo, near, n_near, node, box, X0, Z0, H, 1e-4, side)
    gm, gp = K.grid_totals(buf)
    return pos, geo, node, box, buf, side, gm, gp


def test_body_contact_sides_equals_reference():
    _, _, node, box, buf, side, gm, gp = _two_field_grid(5)
    twist = np.array([0.05, -0.1, 0.7])
    gv = np.zeros((*SHAPE, 2))
    has = gm > 1e-14
    gv[has] = gp[has] / gm[has][:, None]
    gvm = np.zeros_like(gv)
    walls = np.zeros(3, dtype=np.int64)
    f = K.body_contact_sides(
        buf, gm, gv, gvm, side, node, np.array(box), X0, Z0, H, 1e-4, 0.0, 0.0, -1, walls,
        np.zeros(3), POSE, twist, 0.4,
    )  # fmt: skip
    near_v, far_v, force = body_contact_sides_reference(gm, gp, side, node, X0, Z0, H, 1e-4, POSE, twist, 0.4)
    band = (node[..., 2] < 1e299) & has
    far = band & (side[..., 0] > 1e-9 * gm)
    near = band & (gm - side[..., 0] > 1e-9 * gm)
    np.testing.assert_allclose(gv[near], near_v[near], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(gvm[far], far_v[far], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(f, force, rtol=1e-8, atol=1e-9)
    assert abs(f[1]) > 0


def test_g2p_two_field_reads_equal_reference():
    pos, vel, aff, stress, mass, vol = particles(6)
    geo, _, _, node, _ = geometry(pos)
    rng = np.random.default_rng(2)
    gv = rng.normal(0, 0.05, (*SHAPE, 2))
    gvm = rng.normal(0, 0.05, (*SHAPE, 2))
    bounds = np.array([X0 + 2 * H, X0 + 11 * H, Z0 + 2 * H, Z0 + 9 * H])
    mat = MODEL.as_kernel_array()
    ref = g2p_reference(pos, vel, aff, stress, mass, vol, gv, X0, Z0, H, 1e-4, bounds, mat, (gvm, geo, node))
    plain = g2p_reference(pos, vel, aff, stress, mass, vol, gv, X0, Z0, H, 1e-4, bounds, mat)
    gdot = np.zeros(len(pos))
    K.g2p(pos, vel, aff, stress, mass, vol, gdot, gv, gvm, geo, node, X0, Z0, H, 1e-4, bounds, *mat)
    for got, want in zip((pos, vel, aff, stress, vol, gdot), ref, strict=True):
        np.testing.assert_allclose(got, want, rtol=1e-9, atol=1e-9)
    assert not np.allclose(ref[1], plain[1])  # some particles did read the far-side field


def test_zero_thickness_plate_stops_grains_on_both_sides():
    """Grains above a horizontal zero-thickness plate move down, grains below move up. A single grid
    field would average the two sides to rest on the nodes next to the plate and let both through;
    with two fields, on every band node the field from across the plate is stopped, and the grains
    next to the plate read a reduced approach (the particle projection does the rest)."""
    seg = body_segments(Plate(0.06, 0.1), H)
    pose = np.array([X0 + 6.5 * H, Z0 + 5.5 * H, 0.0])  # plate half-way between node rows
    xs, zs = np.meshgrid(np.arange(X0 + 3.5 * H, X0 + 9.5 * H, H / 2), np.arange(-2.75, 2.8, 0.5) * H)
    pos = np.column_stack([xs.ravel(), zs.ravel() + pose[1]])
    above = pos[:, 1] > pose[1]
    n = len(pos)
    vel = np.zeros((n, 2))
    vel[:, 1] = np.where(above, -0.1, 0.1)
    aff = np.zeros((n, 2, 2))
    stress = np.zeros((n, 4))
    mass = np.full(n, 0.01)
    vol = mass / 1600.0
    geo, near, n_near, node, box = geometry(pos, seg, pose)
    buf = np.zeros((1, *SHAPE, 3))
    K.p2g(pos, vel, aff, stress, mass, vol, X0, Z0, H, 1e-4, buf)
    side = np.zeros((*SHAPE, 9))
    K.p2g_sides(pos, vel, aff, stress, mass, vol, geo, near, n_near, node, box, X0, Z0, H, 1e-4, side)
    gm = buf[0, ..., 0].copy()
    gv = np.zeros((*SHAPE, 2))
    gvm = np.zeros_like(gv)
    walls = np.zeros(3, dtype=np.int64)
    f = K.body_contact_sides(
        buf, gm, gv, gvm, side, node, np.array(box), X0, Z0, H, 1e-4, 0.0, 0.0, -1, walls,
        np.zeros(3), pose, np.zeros(3), 0.0,
    )  # fmt: skip
    zi = Z0 + H * np.arange(SHAPE[1])[None, :] + 0 * np.arange(SHAPE[0])[:, None]
    xi = X0 + H * np.arange(SHAPE[0])[:, None] + 0 * zi
    span = np.abs(xi - pose[0]) < 0.03
    far = (node[..., 2] < 1e299) & (side[..., 0] > 1e-9 * gm) & span
    assert far.sum() >= 8
    below = zi < pose[1]
    # far-side field below the plate (grains from above, moving down) and above it (from below): stopped
    assert np.all(gvm[far & below, 1] >= -1e-12) and np.all(gvm[far & ~below, 1] <= 1e-12)
    assert np.all(np.abs(gvm[far, 1]) < 1e-12)
    # the near-side fields keep their velocity
    near_field = (node[..., 2] < 1e299) & (gm - side[..., 0] > 1e-9 * gm) & span
    assert np.allclose(np.abs(gv[near_field, 1]), 0.1)
    # symmetric loading: equal and opposite pushes on the plate
    push = 0.1 * side[..., 0][far].sum() / 1e-4
    assert abs(f[1]) < 1e-9 * push
    gdot = np.zeros(n)
    bounds = np.array([-1.0, 1.0, -1.0, 1.0])
    p2 = [a.copy() for a in (pos, vel, aff, stress, mass, vol)]
    K.g2p(*p2[:6], gdot, gv, gvm, geo, node, X0, Z0, H, 1e-4, bounds, *MODEL.as_kernel_array())
    close = (np.abs(pos[:, 0] - pose[0]) < 0.02) & (np.abs(pos[:, 1] - pose[1]) < 0.5 * H)
    assert close.sum() >= 8
    approach = np.where(above, -p2[1][:, 1], p2[1][:, 1])  # speed towards the plate
    assert np.all(approach[close] < 0.075)


def test_particle_crossing_a_zero_thickness_plate_is_put_back():
    seg = body_segments(Plate(0.06, 0.1), H)
    pose = np.array([0.0, 0.0, 0.0])
    dt = 1e-3
    # particle just above the plate, moving down through it; one beside the plate, not affected
    pos = np.array([[0.01, 0.0005], [0.05, 0.0005]])
    vel = np.array([[0.0, -1.0], [0.0, -1.0]])
    geo = np.zeros((2, 3))
    near = np.zeros(2, dtype=np.int64)
    n_near = K.body_particles(pos, seg, pose, 0.1, geo, near)
    pos += dt * vel  # the g2p move: now 0.5 mm below the plate
    f = K.body_project_sides(
        pos, vel, np.ones(2), geo, near, n_near, dt, seg, pose, pose, np.zeros(3), 0.0, 1e-6
    )
    assert pos[0, 1] == pytest.approx(1e-6)
    assert vel[0, 1] == pytest.approx(0.0)
    assert pos[1, 1] == pytest.approx(-0.0005)
    assert f[1] == pytest.approx(-1.0 / dt)  # the grain's momentum change pushes the plate down


@pytest.mark.parametrize(
    "body",
    [
        Plate(0.004, 0.1),
        Composite([Plate(0.05, 0.1), Plate(0.002, 0.1).placed(0.1, 0.0)]),
        WheelCircular(0.001, 0.1),
    ],
)
def test_degenerate_footprint_is_a_clear_error(body):
    with pytest.raises(InputError) as err:
        effective_body(body, 0.005)
    msg = str(err.value)
    assert "cell_size = 0.005" in msg and "degenerate" in msg
    assert type(body).__name__ in msg


def test_thin_bodies_are_not_thickened_under_two_field_contact():
    plate = Plate(0.04, 0.1)
    assert effective_body(plate, 0.005) is plate
    assert effective_body(plate, 0.005, "cover").thickness == pytest.approx(0.015)
    comp = Composite([plate.placed(-0.1), plate.placed(0.1)])
    assert effective_body(comp, 0.005) is comp
    check_footprint(comp, 0.005)
    with pytest.raises(InputError, match="contact"):
        ContactScheme.coerce("sticky")


RECT = body_segments(Plate(0.06, 0.1, thickness=0.03), 0.01)  # faces at x = +-0.03, z = +-0.015


@pytest.mark.parametrize(
    ("point", "normal"),
    [
        ((0.01, -0.015 + 1e-18), (0.0, -1.0)),  # on the bottom face (a grid node's rounding)
        ((-0.03 + 3e-18, 0.004), (-1.0, 0.0)),  # on a side face
        ((0.03, -0.015), (math.sqrt(0.5), -math.sqrt(0.5))),  # on a corner
    ],
)
def test_a_point_on_the_outline_takes_the_outline_normal(point, normal):
    """On the outline to rounding, the offset to the nearest point has no direction: phi is 0 and
    the normal the outline's own (the mean of the two faces at a corner), so a mirrored point gets
    the mirrored normal. Main took the offset's direction: a node on a face got (-0.99, 0.15)."""
    phi, nx, nz = K.polygon_sdf(point[0], point[1], RECT)
    assert phi == 0.0
    assert (nx, nz) == pytest.approx(normal, abs=1e-15)
    phi_m, nx_m, nz_m = K.polygon_sdf(-point[0], point[1], RECT)
    assert (phi_m, nx_m, nz_m) == (0.0, -nx, nz)


def test_a_point_close_to_a_face_takes_the_face_normal_exactly():
    """A grain a nanometre off a face (where the projection leaves them) has the face's normal to
    the last bit; main's normal carried rounding over phi (x component ~1e-9 here), which decided
    the grain field of a node on the side face differently for a grain and its mirror image."""
    for px in (0.0123456, -0.0123456, 0.0277, 0.001):
        phi, nx, nz = K.polygon_sdf(px, -0.015 - 1.2e-9, RECT)
        assert phi == pytest.approx(1.2e-9, rel=1e-5)
        assert (nx, nz) == (0.0, -1.0)
        phi, nx, nz = K.polygon_sdf(-0.03 - 1.2e-9, px * 0.5, RECT)
        assert (nx, nz) == (-1.0, 0.0)


def test_a_point_on_a_zero_thickness_plate_has_a_fixed_normal():
    """The two faces of a zero-thickness plate cancel: the point gets (0, 1), not a random
    direction."""
    seg = body_segments(Plate(0.05, 0.1), 0.01)
    phi, nx, nz = K.polygon_sdf(0.0101, 1e-19, seg)
    assert (phi, nx, nz) == (0.0, 0.0, 1.0)


def test_the_gap_check_waits_for_the_grains_to_reach_the_body():
    """One point 0.4 cells below a thick block (its side h / 2, so it stops 0.15 cells short): under
    the node test the node row inside the block that its stencil reaches is in contact at once; under
    the gap check no node is until the point is within half its side of the face, and then the nodes
    within half a cell of the face or behind it are (the row a cell out is not)."""
    seg = np.array([[-4 * H, 0.0, 4 * H, 0.0], [4 * H, 0.0, 4 * H, 3 * H],
                    [4 * H, 3 * H, -4 * H, 3 * H], [-4 * H, 3 * H, -4 * H, 0.0]])  # fmt: skip
    pose = np.array([X0 + 6.25 * H, Z0 + 6.0 * H, 0.0])  # base on the node row j = 6

    def contact_rows(depth, gap_check):
        pos = np.array([[pose[0], pose[1] - depth * H]])
        vel, aff = np.zeros((1, 2)), np.zeros((1, 2, 2))
        stress, mass, vol = np.zeros((1, 4)), np.ones(1), np.full(1, (0.5 * H) ** 2)
        geo, near, n_near, node, box = geometry(pos, seg, pose)
        side = np.zeros((*SHAPE, 11))
        K.p2g_sides(pos, vel, aff, stress, mass, vol, geo, near, n_near, node, box, X0, Z0, H, 1e-4, side,
                    gap_check)  # fmt: skip
        reached = (node[..., 2] < 1e299) & (side[..., 3:5] != 0).any(axis=-1)
        m = np.where(reached, np.abs(side[..., 3]) + np.abs(side[..., 4]), 1.0)  # the field's mass (|n| = 1)
        height = side[..., 5] / m  # the node's height above the face
        if gap_check:
            touching = reached & (side[..., 9] <= 0) & (height <= 0.5 * H)
        else:
            touching = reached & (height <= 1e-9 * H)
        return sorted({int(j) for j in np.argwhere(touching)[:, 1]}), sorted(
            {int(j) for j in np.argwhere(reached)[:, 1]}
        )

    assert contact_rows(0.4, False) == ([6, 7], [5, 6, 7])  # row 7 is inside the block: contact at a distance
    assert contact_rows(0.4, True)[0] == []  # the grain is 0.15 cells away: none
    assert contact_rows(0.2, True) == ([6, 7], [5, 6, 7])  # touching: the face row and the one behind it
