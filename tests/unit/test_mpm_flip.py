"""The FLIP blend of the grains' velocity update (``terradyn.mpm._kernels.flip_blend``): exact on
single-field nodes, next to a body too, and APIC kept where a thin body's far-side field is formed."""

from __future__ import annotations

import numpy as np
import pytest

from terradyn.mpm._contact_kernels import _FAR
from terradyn.mpm._kernels import flip_blend, mark_two_fields


def _grid(nx=12, nz=12):
    rng = np.random.default_rng(3)
    grid_dv = np.zeros((nx, nz, 3))
    grid_dv[:, :, :2] = rng.normal(size=(nx, nz, 2))
    return grid_dv


def test_the_blend_is_the_stated_mix_of_flip_and_apic():
    """With no two-field node, each point's new velocity is f (v_old + interpolated change) +
    (1 - f) v_apic; the interpolated change of a uniform grid change is that change."""
    h, x0, z0 = 0.1, 0.0, 0.0
    grid_dv = np.zeros((12, 12, 3))
    grid_dv[:, :, 0] = 0.3
    grid_dv[:, :, 1] = -0.7
    pos = np.array([[0.43, 0.51], [0.62, 0.37]])
    vel_old = np.array([[1.0, 2.0], [-1.0, 0.5]])
    apic = np.array([[1.1, 1.2], [-0.4, 0.1]])
    for f in (0.0, 0.5, 0.99, 1.0):
        vel = apic.copy()
        flip_blend(pos, vel_old, vel, grid_dv, x0, z0, h, f)
        expected = f * (vel_old + np.array([0.3, -0.7])) + (1 - f) * apic
        np.testing.assert_allclose(vel, expected, rtol=0, atol=1e-12)


def test_a_point_next_to_a_far_side_field_keeps_apic_and_the_others_blend():
    """``mark_two_fields`` flags only band nodes of the box where a far-side field has mass; a point
    whose 3 x 3 stencil holds a flagged node keeps its APIC velocity, a point two cells away blends."""
    h = 0.1
    grid_dv = _grid()
    node = np.zeros((12, 12, 3))
    node[:, :, 2] = _FAR
    node[5, 5, 2] = 0.01  # a band node with a far-side field
    node[8, 2, 2] = 0.01  # a band node without one
    side = np.zeros((12, 12, 9))
    side[5, 5, 0] = 1.0
    side[2, 9, 0] = 1.0  # mass outside the band: not a two-field node
    mark_two_fields(node, side, (0, 11, 0, 11), grid_dv)
    flagged = np.argwhere(grid_dv[:, :, 2] != 0.0)
    np.testing.assert_array_equal(flagged, [[5, 5]])
    # stencil base of a point at (x, z): floor(x / h - 0.5); (0.52, 0.52) -> nodes 4..6 (holds 5, 5)
    pos = np.array([[0.52, 0.52], [0.92, 0.92]])
    vel_old = np.zeros((2, 2))
    apic = np.array([[1.0, -1.0], [2.0, -2.0]])
    vel = apic.copy()
    flip_blend(pos, vel_old, vel, grid_dv, 0.0, 0.0, h, 1.0)
    np.testing.assert_array_equal(vel[0], apic[0])
    assert not np.allclose(vel[1], apic[1])


@pytest.mark.parametrize("f", [0.5, 1.0])
def test_the_blend_moves_every_point_of_a_single_field_grid(f):
    grid_dv = _grid()
    pos = np.random.default_rng(1).uniform(0.2, 0.9, size=(50, 2))
    apic = np.zeros((50, 2))
    vel = apic.copy()
    flip_blend(pos, np.ones((50, 2)), vel, grid_dv, 0.0, 0.0, 0.1, f)
    assert np.all(np.abs(vel - apic).sum(axis=1) > 0)


def test_a_run_says_which_transfer_it_used():
    from mpm_reference import MODEL
    from terradyn.geometry import Plate
    from terradyn.mpm import Resolution, run_intrusion

    fast = dict(speed=0.2, bed_width=0.2, bed_depth=0.12, settle_time=0.02)
    apic = run_intrusion(Plate(0.08, 0.1), MODEL, depth=0.01, cell_size=0.01, **fast).metadata
    fine = Resolution(cell_size=0.01, flip=0.99)
    blend = run_intrusion(Plate(0.08, 0.1), MODEL, depth=0.01, resolution=fine, **fast).metadata
    assert apic["flip"] == 0.0 and "APIC, quadratic" in apic["model"]
    assert blend["flip"] == 0.99 and "FLIP 0.99 / APIC blend" in blend["model"]
