"""Hypothesis properties of the 3D-RFT law for any facet orientation and motion."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from terradyn.geometry3d import Pose3D, Twist3D, rotation_from_rpy, sphere
from terradyn.rft.rft3d import (
    UPWARD_TOLERANCE,
    agarwal2023_alpha,
    agarwal2023_alpha_local,
    agarwal2023_angles,
    rft3d_facet_tractions,
    rft3d_wrench,
)

# Exact special directions (axes, vertical and horizontal cases, zero) mixed with random ones.
SPECIAL = [
    (0.0, 0.0, 1.0), (0.0, 0.0, -1.0), (1.0, 0.0, 0.0), (-1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, -1.0, 0.0),
    (0.6, 0.8, 0.0), (0.0, 0.6, -0.8), (0.6, 0.0, 0.8), (0.0, 0.0, 0.0), (1e-300, 0.0, -1e-300),
    (1e-160, 0.0, -1e-170), (0.0, 3e-176, 1.0), (1e200, -1e200, 1e199), (0.0, 1.0, 1e-11), (0.6, 0.8, -1e-12),
]  # fmt: skip
component = st.floats(-1.0, 1.0, allow_nan=False, allow_subnormal=True)
vectors = st.one_of(st.sampled_from(SPECIAL), st.tuples(component, component, component))
batches = st.lists(st.tuples(vectors, vectors, st.floats(0.1, 10.0)), min_size=1, max_size=40)


def _unit(x: np.ndarray) -> np.ndarray:
    """x / |x| without overflow or underflow."""
    y = x / np.abs(x).max()
    return y / np.linalg.norm(y)


def _arrays(batch):
    n = np.array([b[0] for b in batch], dtype=np.float64)
    v = np.array([b[1] for b in batch], dtype=np.float64) * np.array([b[2] for b in batch])[:, None]
    return n, v


@settings(max_examples=150, deadline=None)
@given(batches, st.booleans(), st.sampled_from([None, 0.0, 0.5]))
def test_finite_everywhere_and_numba_equals_numpy(batch, leading, friction):
    n, v = _arrays(batch)
    c = np.zeros_like(n)
    c[:, 2] = -0.1
    opts = {"xi": 1.0, "leading_edge": leading, "surface_friction": friction}
    ref = rft3d_facet_tractions(c, n, v, backend="numpy", **opts)
    got = rft3d_facet_tractions(c, n, v, **opts)
    assert np.all(np.isfinite(ref)) and np.all(np.isfinite(got))
    np.testing.assert_allclose(got, ref, rtol=1e-9, atol=1e-8)
    beta, gamma, psi = agarwal2023_angles(n, v)
    for angle in (beta, gamma, psi):
        assert np.all(np.isfinite(angle)) and np.all(np.abs(angle) <= math.pi / 2 + 1e-12)


def _local_frame(p: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """r_hat, theta_hat by the recipe of the paper (independent of the library's helper)."""
    for d in (v, p):
        length = math.hypot(d[0], d[1])  # hypot: no underflow for tiny components
        if length > 0:
            r = np.array([d[0] / length, d[1] / length, 0.0])
            break
    else:
        r = np.array([1.0, 0.0, 0.0])
    return r, np.cross([0.0, 0.0, 1.0], r)


@settings(max_examples=150, deadline=None)
@given(batches)
def test_world_form_equals_the_literal_local_formula(batch):
    n, v = _arrays(batch)
    keep = (np.abs(n).max(axis=1) > 1e-3) & (np.abs(v).max(axis=1) > 1e-3)
    n, v = n[keep], v[keep]
    if n.shape[0] == 0:
        return
    alpha = agarwal2023_alpha(n, v, leading_edge=False)
    beta, gamma, psi = agarwal2023_angles(n, v)
    local = np.column_stack(agarwal2023_alpha_local(beta, gamma, psi))
    for i in range(n.shape[0]):
        u = _unit(n[i])
        p = -u if u[2] > UPWARD_TOLERANCE else u
        r, t = _local_frame(p, v[i])
        world = local[i, 0] * r + local[i, 1] * t + local[i, 2] * np.array([0.0, 0.0, 1.0])
        # Normals within ~1e-9 of horizontal sit at the upward-facet threshold: round-off ~1e-11 there.
        np.testing.assert_allclose(alpha[i], world, atol=1e-9)


@settings(max_examples=100, deadline=None)
@given(vectors, st.floats(-3.0, 3.0), st.sampled_from([-1.0, 1.0]))
def test_vertical_motion_is_independent_of_the_horizontal_axis(normal, axis_angle, sign):
    # For vertical motion the local formula gives the same world alpha whatever horizontal r_hat is used.
    n = np.array(normal, dtype=np.float64)
    if np.abs(n).max() < 1e-3:
        return
    n = _unit(n)
    p = -n if n[2] > UPWARD_TOLERANCE else n
    v = np.array([0.0, 0.0, sign])
    expected = agarwal2023_alpha(n[None, :], v[None, :], leading_edge=False)[0]
    r = np.array([math.cos(axis_angle), math.sin(axis_angle), 0.0])
    t = np.cross([0.0, 0.0, 1.0], r)
    p_r, p_t = p @ r, p @ t
    s = 1.0 if p_r >= 0 else -1.0
    beta, psi, gamma = s * math.acos(min(1.0, -p[2])), math.atan2(s * p_t, abs(p_r)), -sign * math.pi / 2
    a_r, a_t, a_z = agarwal2023_alpha_local(beta, gamma, psi)
    np.testing.assert_allclose(a_r * r + a_t * t + np.array([0.0, 0.0, a_z]), expected, atol=1e-8)


SPHERE = sphere(0.04, subdivisions=2)


@settings(max_examples=40, deadline=None)
@given(
    st.tuples(st.floats(-1, 1), st.floats(-1, 1), st.floats(-0.1, 0.03)),
    st.tuples(st.floats(-3, 3), st.floats(-1.5, 1.5), st.floats(-3, 3)),
    st.tuples(st.floats(-1, 1), st.floats(-1, 1), st.floats(-1, 1)),
    st.tuples(st.floats(-5, 5), st.floats(-5, 5), st.floats(-5, 5)),
    st.floats(-math.pi, math.pi),
)
def test_rigid_body_wrench_is_frame_covariant(position, rpy, linear, angular, yaw):
    pose = Pose3D(np.array(position), rotation_from_rpy(*rpy))
    twist = Twist3D(np.array(linear), np.array(angular))
    base = rft3d_wrench(SPHERE, 1e6, pose, twist)
    assert np.all(np.isfinite(base.as_array()))
    rz = rotation_from_rpy(0.0, 0.0, yaw)
    turned = rft3d_wrench(
        SPHERE,
        1e6,
        Pose3D(rz @ pose.position, rz @ pose.rotation),
        Twist3D(rz @ twist.linear, rz @ twist.angular),
    )
    scale = 1e-9 * max(1.0, np.abs(base.as_array()).max())
    np.testing.assert_allclose(turned.force, rz @ base.force, atol=scale)
    np.testing.assert_allclose(turned.moment, rz @ base.moment, atol=scale)
