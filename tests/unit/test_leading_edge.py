"""The leading-edge rule of plane RFT and DRFT is continuous in the direction of motion."""

import math

import numpy as np
import pytest

from terradyn import materials
from terradyn.geometry import Plate, Square, WheelCircular
from terradyn.kinematics import Pose2D, Twist2D
from terradyn.rft import drft_wrench, li2013_alpha_material, rft_element_forces, rft_wrench
from terradyn.rft.drft import DRFTModel
from terradyn.rft.li2013 import LEADING_BAND, leading_share

GENERIC = materials.get("generic")
SQUARE = Square(0.02, 0.01)
DEPTH = 0.05  # of the square's centre [m]


def _down(deg):
    a = math.radians(deg)
    return Twist2D(math.cos(a), -math.sin(a), 0.0)


def _wrenches(deg, backend):
    return np.array(
        [
            rft_wrench(SQUARE, GENERIC, Pose2D(0.0, -DEPTH, 0.0), _down(d), backend=backend).as_array()
            for d in deg
        ]
    )


def test_share_is_odd_about_the_switch_and_sharp_outside_the_band():
    c = np.array([-1.0, -2 * LEADING_BAND, -LEADING_BAND, -0.5 * LEADING_BAND, 0.0, 0.5 * LEADING_BAND, 1.0])
    n = np.column_stack((np.sqrt(1 - c**2), -c))  # n . v / |v| = c
    v = np.tile([0.0, -3.0], (len(c), 1))
    s = leading_share(n, v)
    np.testing.assert_allclose(s, [0.0, 0.0, 0.0, 0.25, 0.5, 0.75, 1.0], atol=1e-12)
    np.testing.assert_allclose(leading_share(n, v) + leading_share(-n, v), 1.0, atol=1e-12)
    assert leading_share(n[:1], np.zeros((1, 2)))[0] == 0.0  # at rest: no load


@pytest.mark.parametrize("backend", ["numba", "numpy"])
def test_square_pushed_down_continuous_through_90_deg(backend):
    deg = np.array([89.999, 90.0, 90.001])
    w = _wrenches(deg, backend)
    step = math.radians(0.001)
    # Side face (one wall's worth: the law's alpha of a vertical face moving along itself, at the walls'
    # mean depth): the scale of what used to switch between the walls.
    _, az = li2013_alpha_material(0.5 * math.pi, 0.5 * math.pi, GENERIC)
    side = float(az) * SQUARE.side * SQUARE.width * DEPTH
    torque_side = side * 0.5 * SQUARE.side
    # Changes across one 0.001 deg step are at most (face force / band) * step, not a switched wall.
    bound_f = side / LEADING_BAND * step
    bound_t = torque_side / LEADING_BAND * step
    assert np.all(np.abs(np.diff(w[:, 1])) <= 1.01 * bound_f + 1e-12)
    assert np.all(np.abs(np.diff(w[:, 2])) <= 1.01 * bound_t + 1e-12)
    assert np.all(np.abs(np.diff(w[:, 0])) <= 1.01 * bound_f + 1e-12)
    # Mirror symmetry straight down: no torque and no sideways force, to rounding.
    assert abs(w[1, 0]) < 1e-12 * abs(w[1, 1])
    assert abs(w[1, 2]) < 1e-12 * abs(w[1, 1]) * SQUARE.side
    # Antisymmetric about 90 deg.
    assert w[0, 2] == pytest.approx(-w[2, 2], rel=1e-6)
    assert w[0, 0] == pytest.approx(-w[2, 0], rel=1e-6)


def test_square_force_across_89_to_91_deg_is_continuous_and_matches_one_sided_limits():
    deg = np.linspace(89.0, 91.0, 2001)  # steps of 0.001 deg, 90 included
    w = _wrenches(deg, "numba")
    # Outside the band (0.057 deg) the sharp rule: one wall leads; F_z is the same on both sides.
    far = np.abs(deg - 90.0) > 0.06
    bottom = GENERIC.zeta * SQUARE.side * SQUARE.width * (DEPTH + 0.5 * SQUARE.side)
    assert np.all(w[:, 1] > bottom)
    jumps = np.abs(np.diff(w, axis=0))
    scale = np.abs(w).max(axis=0)
    # Largest change per 0.001 deg step: O(step / band) of the wall's share, never a wall switching.
    assert np.all(jumps.max(axis=0) < 0.02 * scale)
    assert np.ptp(w[far, 1]) < 0.01 * bottom


def test_thin_plate_carries_exactly_the_law_in_every_direction_including_edge_on():
    plate = Plate(0.04, 0.02)
    depth = 0.06
    for tilt in (0.0, 0.3, -1.1):
        for gamma in (tilt, tilt + 1e-7, tilt - 1e-7, -tilt + 0.0, 0.7):
            tw = Twist2D(math.cos(gamma), -math.sin(gamma), 0.0)
            el = rft_element_forces(plate, GENERIC, Pose2D(0.0, -depth, tilt), tw)
            # Both faces together: share sums to one per position, whatever rounding does.
            pos = np.round(el.positions, 12)
            _, inverse = np.unique(pos, axis=0, return_inverse=True)
            sums = np.bincount(inverse.ravel(), weights=el.share)
            np.testing.assert_allclose(sums, 1.0, atol=1e-9)


def test_horizontal_plate_pushed_down_is_exactly_zeta_area_depth():
    plate = Plate(0.05, 0.02)
    for backend in ("numba", "numpy"):
        w = rft_wrench(plate, GENERIC, Pose2D(0.0, -0.04, 0.0), Twist2D(0.0, -1.0, 0.0), backend=backend)
        assert w.fz == pytest.approx(GENERIC.zeta * 0.05 * 0.02 * 0.04, rel=1e-12)
        assert w.fx == pytest.approx(0.0, abs=1e-12 * w.fz)


@pytest.mark.parametrize("deg", [89.9995, 90.0, 90.0003])
def test_kernel_and_numpy_reference_agree_inside_the_band(deg):
    a = rft_wrench(SQUARE, GENERIC, Pose2D(0.0, -DEPTH, 0.0), _down(deg)).as_array()
    b = rft_wrench(SQUARE, GENERIC, Pose2D(0.0, -DEPTH, 0.0), _down(deg), backend="numpy").as_array()
    np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-12 * abs(b[1]))


@pytest.mark.parametrize("deg", [89.9995, 90.0, 90.0003, 45.0])
def test_drft_without_corrections_is_rft_inside_the_band(deg):
    m = DRFTModel(GENERIC, inertial_coefficient=0.0, structural_correction=False)
    pose = Pose2D(0.0, -DEPTH, 0.0)
    r = rft_wrench(SQUARE, GENERIC, pose, _down(deg)).as_array()
    for backend in ("numba", "numpy"):
        d = drft_wrench(SQUARE, m, pose, _down(deg), backend=backend).as_array()
        np.testing.assert_allclose(d, r, rtol=1e-9, atol=1e-12 * abs(r[1]))


def test_wheel_close_to_sharp_rule():
    """The odd ramp changes sums over a smooth rim only at second order in the band."""
    wheel = WheelCircular(0.13, 0.16)
    pose, twist = Pose2D(0.0, 0.115, 0.0), Twist2D(0.1, 0.0, 1.0)
    el = rft_element_forces(wheel, materials.get("MS"), pose, twist, element_size=6.25e-5)
    sharp = np.where(np.einsum("ij,ij->i", el.normals, el.velocities) > 0, 1.0, 0.0)
    f_sharp = (el.forces / np.where(el.share > 0, el.share, 1.0)[:, None] * sharp[:, None]).sum(axis=0)
    f = el.forces.sum(axis=0)
    assert np.abs(f - f_sharp).max() < 1e-6 * np.abs(f).max()
