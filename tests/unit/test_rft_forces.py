import math

import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.geometry import Plate, WheelCircular
from terradyn.kinematics import Pose2D, Twist2D
from terradyn.rft import RFTModel, rft_element_forces, rft_wrench, rft_wrench_many

GEN = materials.get("generic")
MS = materials.get("MS")


def test_horizontal_plate_down_is_zeta_area_depth():
    plate = Plate(0.05, 0.02)
    for depth in (0.01, 0.03, 0.07):
        w = rft_wrench(plate, GEN, Pose2D(0.0, -depth, 0.0), Twist2D(0.0, -0.1, 0.0))
        assert w.fz == pytest.approx(1e6 * 0.05 * 0.02 * depth, rel=1e-12)
        assert abs(w.fx) < 1e-9 and abs(w.torque_y) < 1e-9


def test_linear_in_depth_for_submerged_body():
    # Any fully submerged body translating: F(d) is affine in d, and for a horizontal plate linear.
    plate = Plate(0.04, 0.01)
    f = [
        rft_wrench(plate, MS, Pose2D(0, -d, 0.4), Twist2D(0.3, -0.2, 0)).as_array() for d in (0.05, 0.1, 0.15)
    ]
    np.testing.assert_allclose(f[2] - f[1], f[1] - f[0], rtol=1e-10, atol=1e-9)


def test_linear_in_width_and_zeta():
    w1 = rft_wrench(WheelCircular(0.1, 0.05), MS, Pose2D(0, 0.08, 0), Twist2D(0.1, 0, 1.5))
    w2 = rft_wrench(WheelCircular(0.1, 0.15), MS, Pose2D(0, 0.08, 0), Twist2D(0.1, 0, 1.5))
    np.testing.assert_allclose(w2.as_array(), 3 * w1.as_array(), rtol=1e-12)
    w3 = rft_wrench(
        WheelCircular(0.1, 0.05), MS.with_zeta(2 * MS.zeta), Pose2D(0, 0.08, 0), Twist2D(0.1, 0, 1.5)
    )
    np.testing.assert_allclose(w3.as_array(), 2 * w1.as_array(), rtol=1e-12)


def test_horizontal_translation_invariance():
    wheel = WheelCircular(0.1, 0.05)
    a = rft_wrench(wheel, MS, Pose2D(0, 0.07, 0.3), Twist2D(0.1, -0.02, 1.0))
    b = rft_wrench(wheel, MS, Pose2D(12.5, 0.07, 0.3), Twist2D(0.1, -0.02, 1.0))
    np.testing.assert_allclose(a.as_array(), b.as_array(), rtol=1e-10, atol=1e-12)


def test_numba_equals_numpy_random():
    rng = np.random.default_rng(1)
    bodies = [WheelCircular(0.1, 0.05), Plate(0.05, 0.02), Plate(0.05, 0.02, thickness=0.01)]
    for _ in range(60):
        body = bodies[rng.integers(len(bodies))]
        pose = Pose2D(rng.normal(), rng.uniform(-0.15, 0.05), rng.uniform(-4, 4))
        twist = Twist2D(*rng.normal(size=3))
        about = tuple(rng.normal(size=2))
        a = rft_wrench(body, MS, pose, twist, about=about)
        b = rft_wrench(body, MS, pose, twist, about=about, backend="numpy")
        np.testing.assert_allclose(a.as_array(), b.as_array(), rtol=1e-9, atol=1e-9)


def test_many_equals_single():
    wheel = WheelCircular(0.1, 0.05)
    rng = np.random.default_rng(2)
    poses = np.column_stack((rng.normal(size=20), rng.uniform(-0.1, 0.1, 20), rng.normal(size=20)))
    twists = rng.normal(size=(20, 3))
    many = rft_wrench_many(wheel, MS, poses, twists)
    for k in range(20):
        one = rft_wrench(wheel, MS, Pose2D(*poses[k]), Twist2D(*twists[k]))
        np.testing.assert_allclose(many[k], one.as_array(), rtol=1e-10, atol=1e-12)


def test_torque_transfer_between_points():
    wheel = WheelCircular(0.1, 0.05)
    pose, twist = Pose2D(0.2, 0.05, 0.1), Twist2D(0.1, -0.05, 2.0)
    w0 = rft_wrench(wheel, MS, pose, twist)
    p = (0.5, -0.3)
    w1 = rft_wrench(wheel, MS, pose, twist, about=p)
    # T_p = T_o + (o - p) x F  (about +y: r_z F_x - r_x F_z)
    rx, rz = pose.x - p[0], pose.z - p[1]
    assert w1.torque_y == pytest.approx(w0.torque_y + rz * w0.fx - rx * w0.fz, rel=1e-10)


def test_leading_edge_rule_and_surface():
    plate = Plate(0.05, 0.02)
    el = rft_element_forces(plate, GEN, Pose2D(0, -0.03, 0), Twist2D(0, -1, 0), element_size=0.005)
    assert np.all(el.active == (el.normals[:, 1] < 0))  # only the bottom face leads
    above = rft_wrench(plate, GEN, Pose2D(0, 0.01, 0), Twist2D(0, -1, 0))
    assert above.as_array().tolist() == [0.0, 0.0, 0.0]
    still = rft_wrench(plate, GEN, Pose2D(0, -0.03, 0), Twist2D(0, 0, 0))
    assert still.as_array().tolist() == [0.0, 0.0, 0.0]


def test_mirror_symmetry_of_bodies():
    # A plate at angle t moving in direction g mirrors to angle -t moving in direction pi - g.
    plate = Plate(0.05, 0.02)
    for t, g in [(0.3, 1.0), (-0.7, 0.2), (1.2, 2.5)]:
        a = rft_wrench(plate, MS, Pose2D(0, -0.05, t), Twist2D(math.cos(g), -math.sin(g), 0))
        b = rft_wrench(
            plate, MS, Pose2D(0, -0.05, -t), Twist2D(math.cos(math.pi - g), -math.sin(math.pi - g), 0)
        )
        assert b.fx == pytest.approx(-a.fx, rel=1e-9, abs=1e-9)
        assert b.fz == pytest.approx(a.fz, rel=1e-9, abs=1e-9)
        assert b.torque_y == pytest.approx(-a.torque_y, rel=1e-9, abs=1e-12)


def test_converges_with_element_size():
    wheel = WheelCircular(0.13, 0.16)
    pose, twist = Pose2D(0, 0.115, 0), Twist2D(0.1, 0, 1.0)
    sizes = [0.004, 0.002, 0.001, 0.0005]
    vals = np.array([rft_wrench(wheel, MS, pose, twist, element_size=h).as_array() for h in sizes])
    ref = rft_wrench(wheel, MS, pose, twist, element_size=0.0000625).as_array()
    errs = np.abs(vals - ref).max(axis=1)
    # Elements entering the contact one by one make the error jumpy, but it falls roughly as h.
    assert errs[-1] < errs[0] / 20
    assert errs[-1] / abs(ref[1]) < 2e-3
    slope = np.polyfit(np.log(sizes), np.log(errs), 1)[0]
    assert slope > 0.8


def test_model_interface_and_errors():
    model = RFTModel(MS)
    assert model.name == "rft"
    w = model.wrench(WheelCircular(0.1, 0.05), Pose2D(0, 0.08, 0), Twist2D(0.1, 0, 1.0))
    assert w.fz > 0
    with pytest.raises(InputError, match="backend"):
        rft_wrench(Plate(0.05, 0.02), MS, Pose2D(), Twist2D(), backend="gpu")
    with pytest.raises(InputError, match=r"pose\.z"):
        Pose2D(0, math.nan, 0)
    with pytest.raises(InputError, match="element_size"):
        rft_wrench(Plate(0.05, 0.02), MS, Pose2D(), Twist2D(), element_size=-1)
    with pytest.raises(InputError, match="poses"):
        rft_wrench_many(Plate(0.05, 0.02), MS, np.zeros((3, 2)), np.zeros((3, 2)))
    with pytest.raises(InputError, match="rft"):
        RFTModel(materials.Material("empty"))
