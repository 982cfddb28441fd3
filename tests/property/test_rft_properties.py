"""Hypothesis properties of plane RFT on random star-shaped bodies and motions."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from terradyn import materials
from terradyn.geometry import SurfaceElements
from terradyn.geometry._path import Line, discretize_loops
from terradyn.kinematics import Pose2D, Twist2D
from terradyn.rft import rft_wrench

MAT = materials.get("MS")

radii = st.lists(st.floats(0.01, 0.1), min_size=3, max_size=12)
poses = st.tuples(st.floats(-1, 1), st.floats(-0.15, 0.05), st.floats(-4, 4))
twists = st.tuples(st.floats(-2, 2), st.floats(-2, 2), st.floats(-10, 10))


def star(rs: list[float], mirror: bool = False, width: float = 0.05) -> SurfaceElements:
    n = len(rs)
    ang = 2 * math.pi * np.arange(n) / n
    pts = np.column_stack((np.array(rs) * np.cos(ang), np.array(rs) * np.sin(ang)))
    if mirror:
        pts = pts[::-1] * np.array([-1.0, 1.0])  # x -> -x, order reversed to stay counter-clockwise
    loop = [Line(tuple(pts[i]), tuple(pts[(i + 1) % n])) for i in range(n)]
    mid, nrm, lng, part = discretize_loops([loop], 0.004)
    return SurfaceElements(mid, nrm, lng, width, part)


@settings(max_examples=60, deadline=None)
@given(radii, poses, twists)
def test_numba_equals_numpy_and_finite(rs, pose, twist):
    el = star(rs)
    a = rft_wrench(el, MAT, Pose2D(*pose), Twist2D(*twist)).as_array()
    b = rft_wrench(el, MAT, Pose2D(*pose), Twist2D(*twist), backend="numpy").as_array()
    assert np.all(np.isfinite(a))
    np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-9)


@settings(max_examples=60, deadline=None)
@given(radii, poses, twists)
def test_mirror_symmetry(rs, pose, twist):
    x, z, th = pose
    vx, vz, om = twist
    a = rft_wrench(star(rs), MAT, Pose2D(x, z, th), Twist2D(vx, vz, om))
    b = rft_wrench(star(rs, mirror=True), MAT, Pose2D(-x, z, -th), Twist2D(-vx, vz, -om))
    scale = max(1.0, abs(a.fz), abs(a.fx))
    assert abs(b.fx + a.fx) < 1e-9 * scale
    assert abs(b.fz - a.fz) < 1e-9 * scale
    assert abs(b.torque_y + a.torque_y) < 1e-9 * scale


@settings(max_examples=40, deadline=None)
@given(radii, poses, twists, st.floats(-50, 50), st.floats(0.1, 10))
def test_translation_and_width(rs, pose, twist, shift, factor):
    el = star(rs)
    a = rft_wrench(el, MAT, Pose2D(*pose), Twist2D(*twist)).as_array()
    moved = rft_wrench(el, MAT, Pose2D(pose[0] + shift, pose[1], pose[2]), Twist2D(*twist)).as_array()
    np.testing.assert_allclose(moved, a, rtol=1e-8, atol=1e-8)
    wide = rft_wrench(el.with_width(0.05 * factor), MAT, Pose2D(*pose), Twist2D(*twist)).as_array()
    np.testing.assert_allclose(wide, factor * a, rtol=1e-9, atol=1e-9)


@settings(max_examples=40, deadline=None)
@given(radii, poses, twists, st.floats(0.01, 100))
def test_rate_independence(rs, pose, twist, speed):
    el = star(rs)
    a = rft_wrench(el, MAT, Pose2D(*pose), Twist2D(*twist)).as_array()
    b = rft_wrench(el, MAT, Pose2D(*pose), Twist2D(*(speed * np.array(twist)))).as_array()
    np.testing.assert_allclose(b, a, rtol=1e-9, atol=1e-9)
