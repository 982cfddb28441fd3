"""Hypothesis properties of terradyn bodies: closed surfaces, exact areas, outward normals, placement."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy.spatial import ConvexHull

from terradyn.errors import InputError
from terradyn.geometry import Polygon, SurfaceElements, WheelFlapped, WheelGrousered
from terradyn.geometry._path import discretize_loops

W = 0.05


def net_normal(el: SurfaceElements) -> np.ndarray:
    return (el.normals * el.lengths[:, None]).sum(axis=0)


def divergence_area(el: SurfaceElements) -> float:
    return 0.5 * float(np.sum(np.einsum("ij,ij->i", el.midpoints, el.normals) * el.lengths))


def shoelace(p: np.ndarray) -> float:
    q = np.roll(p, -1, axis=0)
    return 0.5 * float(np.sum(p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]))


def inside(poly: np.ndarray, pts: np.ndarray) -> np.ndarray:
    x, z = pts[:, :1], pts[:, 1:]
    x0, z0 = poly[:, 0], poly[:, 1]
    x1, z1 = np.roll(x0, -1), np.roll(z0, -1)
    straddle = (z0 > z) != (z1 > z)
    with np.errstate(divide="ignore", invalid="ignore"):
        x_cross = x0 + (z - z0) * (x1 - x0) / (z1 - z0)
    return (straddle & (x < x_cross)).sum(axis=1) % 2 == 1


@st.composite
def star_polygons(draw) -> np.ndarray:
    """Vertices of a star-shaped polygon about the origin, counter-clockwise or not."""
    n = draw(st.integers(3, 40))
    radii = np.array(draw(st.lists(st.floats(0.02, 1.0), min_size=n, max_size=n)))
    jitter = np.array(draw(st.lists(st.floats(-0.4, 0.4), min_size=n, max_size=n)))
    ang = 2 * np.pi * (np.arange(n) + jitter) / n
    pts = np.column_stack((radii * np.cos(ang), radii * np.sin(ang)))
    return pts[::-1] if draw(st.booleans()) else pts


@st.composite
def convex_polygons(draw) -> np.ndarray:
    n = draw(st.integers(3, 30))
    xy = np.array(draw(st.lists(st.tuples(st.floats(-1, 1), st.floats(-1, 1)), min_size=n, max_size=n)))
    hull = ConvexHull(xy) if _spread(xy) else None
    return xy[hull.vertices] if hull is not None else np.array([[0, 0], [1, 0], [0, 1.0]])


def _spread(xy: np.ndarray) -> bool:
    centred = xy - xy.mean(axis=0)
    return len(np.unique(xy, axis=0)) >= 3 and np.linalg.svd(centred, compute_uv=False)[-1] > 1e-3


def check_polygon(pts: np.ndarray) -> None:
    poly = Polygon(pts, W)
    v = poly.vertices
    assert shoelace(v) > 0  # stored counter-clockwise
    assert math.isclose(poly.area, abs(shoelace(pts)), rel_tol=1e-12)
    el = poly.discretize(poly.size / 40)
    assert np.all(np.isfinite(el.midpoints)) and np.all(np.isfinite(el.normals))
    np.testing.assert_allclose(np.hypot(*el.normals.T), 1.0, atol=1e-12)
    np.testing.assert_allclose(net_normal(el), 0.0, atol=1e-12 * el.perimeter)
    assert math.isclose(divergence_area(el), poly.area, rel_tol=1e-9)
    edges = np.hypot(*(np.roll(v, -1, axis=0) - v).T)
    assert math.isclose(el.perimeter, edges.sum(), rel_tol=1e-12)
    eps = 1e-6 * poly.size
    assert not inside(v, el.midpoints + eps * el.normals).any()
    assert inside(v, el.midpoints - eps * el.normals).all()


@settings(max_examples=60, deadline=None)
@given(star_polygons())
def test_star_polygons_are_closed_with_outward_normals(pts):
    check_polygon(pts)


@settings(max_examples=60, deadline=None)
@given(convex_polygons())
def test_convex_polygons_are_closed_with_outward_normals(pts):
    check_polygon(pts)


@settings(max_examples=40, deadline=None)
@given(
    star_polygons(),
    st.floats(-1, 1),
    st.floats(-1, 1),
    st.floats(-2 * math.pi, 2 * math.pi),
)
def test_placement_is_a_rigid_motion(pts, x, z, theta):
    poly = Polygon(pts, W)
    h = poly.size / 20
    moved = poly.placed(x, z, theta)
    mid, nrm, lng, _ = discretize_loops(moved.loops(), h)
    expected = poly.discretize(h).rotated(theta).shifted(x, z)
    np.testing.assert_allclose(mid, expected.midpoints, atol=1e-12)
    np.testing.assert_allclose(nrm, expected.normals, atol=1e-12)
    np.testing.assert_allclose(lng, expected.lengths, rtol=1e-12)


@settings(max_examples=40, deadline=None)
@given(
    st.integers(1, 30),
    st.floats(0.02, 0.2),
    st.floats(0.01, 1.0),
    st.floats(0.01, 0.99),
)
def test_grousered_wheels_are_closed(count, radius, height_ratio, thickness_ratio):
    limit = 2 * radius * math.sin(min(math.pi / count, math.pi / 2))
    wheel = WheelGrousered(radius, W, count, height_ratio * radius, thickness_ratio * limit)
    # Arc elements carry their midpoint normal over the arc, so the closure error of the midpoint rule
    # falls as (arc angle per element)^2: keep it below about 0.1 rad.
    rim = max(5, math.ceil((2 * math.pi / count) / 0.1))
    el = wheel.discretize_counts(rim, 3)
    assert el.element_count == count * (rim + 9)
    np.testing.assert_allclose(net_normal(el), 0.0, atol=1e-3 * el.perimeter)
    assert divergence_area(el) > math.pi * radius**2
    assert np.hypot(*el.midpoints.T).max() <= math.hypot(wheel.outer_radius, limit / 2)


@settings(max_examples=60, deadline=None)
@given(
    st.integers(1, 24),
    st.floats(0.1, 3.0),
    st.floats(-1.45, 1.45),
    st.floats(0.01, 0.99),
)
def test_thick_flapped_wheels_are_simple_and_closed(count, length_ratio, angle, thickness_ratio):
    # Any valid flapped wheel outlines a simple polygon: flaps that fit on the hub never cross.
    r = 0.05
    spacing = 2 * math.pi / count
    thickness = thickness_ratio * 2 * r * min(1 - abs(math.sin(angle)), math.sin(min(spacing, 3) / 2))
    try:
        wheel = WheelFlapped(r, W, count, length_ratio * r, angle, thickness)
    except InputError as exc:  # roots overlap on the hub: not a case for this property
        assert exc.field == "flap_thickness"
        assume(False)
    Polygon(wheel.outline(r / 50)[0], W)  # raises if the boundary crosses itself
    el = wheel.discretize()
    np.testing.assert_allclose(net_normal(el), 0.0, atol=1e-3 * el.perimeter)
    tips = math.hypot(r * math.cos(angle) + length_ratio * r, r * math.sin(angle))
    assert wheel.outer_radius >= tips * (1 - 1e-12)
