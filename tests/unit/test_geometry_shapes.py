"""Shapes of terradyn.geometry: exact perimeters and areas, outward normals, origins and validation."""

from __future__ import annotations

import json
import math
import time

import numpy as np
import pytest

from terradyn.errors import InputError
from terradyn.geometry import (
    Body,
    CLeg,
    Composite,
    Cylinder,
    FlatSide,
    HalfCylinder,
    Placed,
    Plate,
    Polygon,
    Square,
    SurfaceElements,
    Wedge,
    WheelCircular,
    WheelFlapped,
    WheelGrousered,
)
from terradyn.geometry._path import discretize_loops

W = 0.05  # out-of-plane width [m]


# ---------------------------------------------------------------- helpers


def net_normal(el: SurfaceElements) -> np.ndarray:
    """Sum of normal * length [m]: zero for a closed surface."""
    return (el.normals * el.lengths[:, None]).sum(axis=0)


def divergence_area(el: SurfaceElements) -> float:
    """Enclosed area [m^2] by the divergence theorem, 1/2 sum (x . n) ds (exact for lines and arcs)."""
    return 0.5 * float(np.sum(np.einsum("ij,ij->i", el.midpoints, el.normals) * el.lengths))


def inside(poly: np.ndarray, pts: np.ndarray) -> np.ndarray:
    """Even-odd point-in-polygon test of points (P, 2) against a closed polygon (M, 2)."""
    x, z = pts[:, :1], pts[:, 1:]
    x0, z0 = poly[:, 0], poly[:, 1]
    x1, z1 = np.roll(x0, -1), np.roll(z0, -1)
    straddle = (z0 > z) != (z1 > z)
    with np.errstate(divide="ignore", invalid="ignore"):
        x_cross = x0 + (z - z0) * (x1 - x0) / (z1 - z0)
    return (straddle & (x < x_cross)).sum(axis=1) % 2 == 1


def assert_outward(body: Body, el: SurfaceElements | None = None) -> None:
    """A point just outside along each normal is outside the body, just inside is inside."""
    el = body.discretize() if el is None else el
    polys = body.outline(body.default_element_size / 10)
    eps = 0.1 * float(el.lengths.min())

    def any_inside(pts: np.ndarray) -> np.ndarray:
        return np.any([inside(p, pts) for p in polys], axis=0)

    assert not any_inside(el.midpoints + eps * el.normals).any()
    assert any_inside(el.midpoints - eps * el.normals).all()


def assert_closed(el: SurfaceElements, rtol: float = 1e-9) -> None:
    assert np.all(np.isfinite(el.normals))
    np.testing.assert_allclose(np.hypot(*el.normals.T), 1.0, atol=1e-12)
    np.testing.assert_allclose(net_normal(el), 0.0, atol=rtol * el.perimeter)


def assert_input_error(field: str, fn, *args, **kwargs) -> InputError:
    with pytest.raises(InputError) as info:
        fn(*args, **kwargs)
    assert info.value.field == field
    assert field in str(info.value)
    return info.value


def same_elements(a: SurfaceElements, b: SurfaceElements, atol: float = 1e-12) -> None:
    """Equal element sets up to order."""
    ka = np.lexsort(np.round(np.column_stack((a.midpoints, a.normals)), 9).T[::-1])
    kb = np.lexsort(np.round(np.column_stack((b.midpoints, b.normals)), 9).T[::-1])
    np.testing.assert_allclose(a.midpoints[ka], b.midpoints[kb], atol=atol)
    np.testing.assert_allclose(a.normals[ka], b.normals[kb], atol=atol)
    np.testing.assert_allclose(a.lengths[ka], b.lengths[kb], atol=atol)


def grouser_area_perimeter(r: float, n: int, h: float, t: float) -> tuple[float, float]:
    delta = math.asin(t / (2 * r))
    lug_outside = t * (r + h - r * math.cos(delta)) - 0.5 * r**2 * (2 * delta - math.sin(2 * delta))
    perimeter = n * r * (2 * math.pi / n - 2 * delta) + n * (2 * (r + h - r * math.cos(delta)) + t)
    return math.pi * r**2 + n * lug_outside, perimeter


# ---------------------------------------------------------------- closed bodies: area and perimeter

CLOSED = [
    (Square(0.1, W), 0.01, 0.4),
    (Cylinder(0.05, W), math.pi * 0.05**2, 2 * math.pi * 0.05),
    (HalfCylinder(0.05, W), 0.5 * math.pi * 0.05**2, math.pi * 0.05 + 0.1),
    (HalfCylinder(0.05, W, "down"), 0.5 * math.pi * 0.05**2, math.pi * 0.05 + 0.1),
    (Wedge(0.06, 0.08, W), 0.5 * 0.06 * 0.08, 0.06 + 2 * math.hypot(0.03, 0.08)),
    (
        Wedge(0.06, 0.08, W, tip_offset=0.05),
        0.5 * 0.06 * 0.08,
        0.06 + math.hypot(0.08, 0.08) + math.hypot(0.02, 0.08),
    ),
    (CLeg(0.04, W, 0.006), 0.04 * 0.006 * math.pi, 2 * math.pi * 0.04 + 0.012),
    (CLeg(0.04, W, 0.006, sweep=4.0), 0.04 * 0.006 * 4.0, 2 * 4.0 * 0.04 + 0.012),
    (WheelGrousered(0.09, W, 15, 0.016, 0.005), *grouser_area_perimeter(0.09, 15, 0.016, 0.005)),
    (WheelGrousered(0.05, W, 1, 0.02, 0.08), *grouser_area_perimeter(0.05, 1, 0.02, 0.08)),
    (Polygon([[0, 0], [0.1, 0], [0.1, 0.05], [0.05, 0.02], [0, 0.05]], W), 0.0035, None),
]


@pytest.mark.parametrize(("body", "area", "perimeter"), CLOSED, ids=lambda v: type(v).__name__)
def test_closed_bodies_area_perimeter_normals(body, area, perimeter):
    for size in (body.default_element_size, body.size / 7):
        el = body.discretize(size)
        assert el.lengths.max() <= size * (1 + 1e-9)
        assert_closed(el, rtol=1e-3)
        # Exact for lines and arcs about the origin; O(h^2) for the C-leg's off-centre arcs.
        rel = 0.1 * (size / body.radius) ** 2 if isinstance(body, CLeg) else 1e-9
        assert divergence_area(el) == pytest.approx(area, rel=rel)
        if perimeter is not None:
            assert el.perimeter == pytest.approx(perimeter, rel=1e-9)
    assert_outward(body)


def test_closed_surface_residual_converges_at_second_order():
    # Arc elements use the midpoint normal: the residual of sum(n ds) on a half disc is O(h^2).
    body = HalfCylinder(0.05, W)
    sizes = math.pi * 0.05 / (8 * 2.0 ** np.arange(6))  # 8, 16, ... 256 elements on the arc
    res = [np.hypot(*net_normal(body.discretize(h))) for h in sizes]
    rates = np.log2(np.array(res[:-1]) / np.array(res[1:]))
    np.testing.assert_allclose(rates, 2.0, atol=0.01)


# ---------------------------------------------------------------- grousered wheel


def test_published_570_element_wheel():
    wheel = WheelGrousered(0.09, W, 15, 0.016, 0.005)
    el = wheel.discretize_counts(14, 8)
    assert el.element_count == 570 == 15 * (14 + 3 * 8)
    area, perimeter = grouser_area_perimeter(0.09, 15, 0.016, 0.005)
    assert el.perimeter == pytest.approx(perimeter, rel=1e-12)
    assert divergence_area(el) == pytest.approx(area, rel=1e-12)
    assert_outward(wheel, el)
    # Per lug: 8 equal elements on each face and 14 equal ones on the following rim arc.
    lug = el.lengths[:38]
    for block in (lug[0:8], lug[8:16], lug[16:24], lug[24:38]):
        np.testing.assert_allclose(block, block[0], rtol=1e-12)
    np.testing.assert_allclose(lug[8:16].sum(), 0.005, rtol=1e-12)  # outer face = thickness
    assert_input_error("rim_elements", wheel.discretize_counts, 0, 8)
    assert_input_error("face_elements", wheel.discretize_counts, 14, 2.5)


def test_grousered_origin_outer_radius_and_symmetry():
    r, h, t, n = 0.09, 0.016, 0.005, 15
    wheel = WheelGrousered(r, W, n, h, t)
    assert wheel.outer_radius == pytest.approx(r + h) == wheel.size
    el = wheel.discretize()
    # First lug at the bottom: its outer face is the lowest point, at z = -(r + h), normal -z.
    assert el.midpoints[:, 1].min() == pytest.approx(-(r + h))
    low = el.midpoints[:, 1] < -(r + h) + 1e-12
    np.testing.assert_allclose(el.normals[low], [[0.0, -1.0]] * int(low.sum()), atol=1e-12)
    assert abs(el.midpoints[low, 0].mean()) < 1e-12
    # Farthest points: outer lug corners.
    assert wheel.bounding_radius == pytest.approx(math.hypot(r + h, t / 2))
    # Turning by one lug spacing maps the wheel onto itself.
    same_elements(el.rotated(2 * math.pi / n), el, atol=1e-9)


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"grouser_count": 0}, "grouser_count"),
        ({"grouser_count": 2.5}, "grouser_count"),
        ({"grouser_count": True}, "grouser_count"),
        ({"grouser_height": 0.0}, "grouser_height"),
        ({"grouser_height": math.nan}, "grouser_height"),
        ({"grouser_thickness": 0.0}, "grouser_thickness"),
        ({"grouser_thickness": 0.04}, "grouser_thickness"),  # 15 lugs of 40 mm overlap on r = 90 mm
        ({"radius": -0.1}, "radius"),
        ({"width": 0.0}, "width"),
    ],
)
def test_grousered_validation(kwargs, field):
    args = {"radius": 0.09, "width": W, "grouser_count": 15, "grouser_height": 0.016}
    args |= {"grouser_thickness": 0.005} | kwargs
    assert_input_error(field, WheelGrousered, **args)


def test_grousered_lugs_just_fit():
    limit = 2 * 0.09 * math.sin(math.pi / 15)
    assert WheelGrousered(0.09, W, 15, 0.01, 0.999 * limit).discretize().element_count > 0
    assert_input_error("grouser_thickness", WheelGrousered, 0.09, W, 15, 0.01, limit)
    assert WheelGrousered(0.09, W, 15.0, 0.01, 0.005).grouser_count == 15


# ---------------------------------------------------------------- flapped wheel


@pytest.mark.parametrize("angle", [0.0, 0.4, -0.7])
def test_flapped_thin_tip_distance_sign_and_faces(angle):
    r, length, n = 0.03, 0.065, 4
    wheel = WheelFlapped(r, W, n, length, angle)
    tip = math.sqrt(r**2 + length**2 + 2 * r * length * math.cos(angle))
    assert wheel.outer_radius == pytest.approx(tip) == wheel.size
    assert wheel.bounding_radius == pytest.approx(tip)
    el = wheel.discretize()
    assert el.perimeter == pytest.approx(2 * math.pi * r + 2 * n * length)
    assert divergence_area(el) == pytest.approx(math.pi * r**2)  # spikes enclose nothing
    assert_closed(el)
    # Every flap element has a partner at the same midpoint with the opposite normal (both faces).
    flap = np.hypot(*el.midpoints.T) > r * (1 + 1e-9)
    mid, nrm = el.midpoints[flap], el.normals[flap]
    d = np.hypot(*(mid[:, None] - mid[None]).T) + np.abs(nrm[:, None] + nrm[None]).sum(-1).T
    assert np.all(np.sum(d < 1e-9, axis=1) == 1)
    # Sign: first flap rooted at the bottom; a positive angle puts its tip ahead (+x) of the root, so
    # under clockwise spin (velocity omega * (z, -x)) the tip trails the root.
    first = wheel.loops()[0][0]
    np.testing.assert_allclose(first.start, (0.0, -r), atol=1e-15)
    tip_dir = np.subtract(first.end, first.start)
    root_velocity = np.array([first.start[1], -first.start[0]])
    lean = np.round([tip_dir[0], tip_dir @ root_velocity], 15)
    np.testing.assert_array_equal(np.sign(lean), [np.sign(angle), -np.sign(angle)])
    assert math.atan2(tip_dir[0], -tip_dir[1]) == pytest.approx(angle)  # angle from radial (down)


def test_flapped_thick_radial_equals_grousered():
    flapped = WheelFlapped(0.05, W, 6, 0.02, 0.0, flap_thickness=0.006)
    grousered = WheelGrousered(0.05, W, 6, 0.02, 0.006)
    same_elements(flapped.discretize(0.002), grousered.discretize(0.002))
    assert flapped.outer_radius == pytest.approx(math.hypot(0.07, 0.003))


@pytest.mark.parametrize("angle", [0.5, -1.2])
def test_flapped_thick_closed_and_outward(angle):
    wheel = WheelFlapped(0.03, W, 5, 0.05, angle, flap_thickness=0.004)
    el = wheel.discretize()
    assert_closed(el, rtol=1e-4)
    assert_outward(wheel, el)
    # Area against the shoelace area of the finely sampled outline (arcs drawn as short chords).
    poly = wheel.outline(1e-5)[0]
    shoelace = 0.5 * np.sum(poly[:, 0] * np.roll(poly[:, 1], -1) - np.roll(poly[:, 0], -1) * poly[:, 1])
    assert divergence_area(el) == pytest.approx(shoelace, rel=1e-7)


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"flap_count": 0}, "flap_count"),
        ({"flap_length": -0.01}, "flap_length"),
        ({"flap_angle": math.pi / 2}, "flap_angle"),
        ({"flap_angle": math.inf}, "flap_angle"),
        ({"flap_thickness": -0.001}, "flap_thickness"),
        ({"flap_thickness": 0.05}, "flap_thickness"),  # 4 roots this wide overlap on the hub
        ({"flap_thickness": 0.002, "flap_angle": 1.4}, "flap_thickness"),  # a side misses the hub
        ({"flap_thickness": 0.002, "flap_length": 0.0002}, "flap_thickness"),  # tip inside the hub
        ({"hub_radius": 0.0}, "hub_radius"),
    ],
)
def test_flapped_validation(kwargs, field):
    args = {"hub_radius": 0.03, "width": W, "flap_count": 4, "flap_length": 0.065}
    args |= {"flap_angle": 0.3} | kwargs
    assert_input_error(field, WheelFlapped, **args)


def test_flapped_roots_just_fit():
    # Radial flaps of thickness t cover 2 asin(t / 2r) of the hub: 4 of them fit below t = r sqrt(2).
    limit = 0.03 * math.sqrt(2)
    assert WheelFlapped(0.03, W, 4, 0.02, 0.0, 0.999 * limit).discretize().element_count > 0
    assert_input_error("flap_thickness", WheelFlapped, 0.03, W, 4, 0.02, 0.0, 1.001 * limit)


# ---------------------------------------------------------------- C-leg


def test_cleg_origin_and_orientation():
    r, t = 0.04, 0.006
    leg = CLeg(r, W, t)
    assert leg.size == 2 * r
    pts = np.concatenate(leg.outline(1e-4))
    # Hip at the middle of the top end cap; arc below the hip, bulging forward (+x).
    assert pts[:, 1].max() == pytest.approx(t / 2)
    assert pts[:, 0].max() == pytest.approx(r + t / 2, rel=1e-6)
    assert pts[:, 0].min() == pytest.approx(0.0, abs=1e-12)
    assert pts[:, 1].min() == pytest.approx(-2 * r - t / 2)
    assert leg.bounding_radius == pytest.approx(2 * r + t / 2)


def test_cleg_thin_is_both_faces():
    leg = CLeg(0.04, W, sweep=2.0)
    el = leg.discretize()
    assert el.perimeter == pytest.approx(2 * 2.0 * 0.04)
    assert divergence_area(el) == pytest.approx(0.0, abs=1e-15)
    assert_closed(el)
    dist = np.hypot(el.midpoints[:, 0], el.midpoints[:, 1] + 0.04)
    np.testing.assert_allclose(dist, 0.04)


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"radius": 0.0}, "radius"),
        ({"thickness": -0.001}, "thickness"),
        ({"thickness": 0.08}, "thickness"),
        ({"sweep": 0.0}, "sweep"),
        ({"sweep": 2 * math.pi}, "sweep"),
        ({"width": -1.0}, "width"),
    ],
)
def test_cleg_validation(kwargs, field):
    assert_input_error(field, CLeg, **({"radius": 0.04, "width": W, "thickness": 0.005} | kwargs))


# ---------------------------------------------------------------- wedge, square, cylinders


def test_wedge_origin_tip_and_projected_width():
    wedge = Wedge(0.06, 0.08, W, tip_offset=0.05)
    pts = wedge.outline()[0]
    assert pts[:, 1].min() == 0.0
    np.testing.assert_allclose(pts[np.argmin(pts[:, 1])], [0.0, 0.0])
    assert wedge.projected_width == pytest.approx(0.03 + 0.05 + 0.0)  # tip beyond the base end
    assert Wedge(0.06, 0.08, W, tip_offset=0.01).projected_width == pytest.approx(0.06)
    assert Wedge(0.06, 0.08, W, tip_offset=-0.05).projected_width == pytest.approx(0.08)


def test_wedge_symmetric_mirror_and_from_angles():
    wedge = Wedge.from_angles(math.radians(60), W, height=0.1)
    assert wedge.base == pytest.approx(2 * 0.1 * math.tan(math.radians(30)))
    other = Wedge.from_angles(math.radians(60), W, base=wedge.base)
    assert other.height == pytest.approx(0.1)
    el = wedge.discretize()
    mirrored = SurfaceElements(el.midpoints * [-1, 1], el.normals * [-1, 1], el.lengths, el.width)
    same_elements(el, mirrored, atol=1e-12)
    # Face normals make half the tip angle with the horizontal, pointing down and out.
    face = el.normals[el.normals[:, 1] < -1e-9]
    np.testing.assert_allclose(np.abs(face[:, 0]), math.cos(math.radians(30)), atol=1e-12)
    np.testing.assert_allclose(face[:, 1], -math.sin(math.radians(30)), atol=1e-12)


@pytest.mark.parametrize(
    ("call", "field"),
    [
        (lambda: Wedge(0.0, 0.1, W), "base"),
        (lambda: Wedge(0.1, -0.1, W), "height"),
        (lambda: Wedge(0.1, 0.1, W, tip_offset=math.nan), "tip_offset"),
        (lambda: Wedge.from_angles(math.pi, W, height=0.1), "tip_angle"),
        (lambda: Wedge.from_angles(0.5, W), "height/base"),
        (lambda: Wedge.from_angles(0.5, W, height=0.1, base=0.1), "height/base"),
        (lambda: Wedge.from_angles(0.5, W, base=-0.1), "base"),
        (lambda: Square(0.0, W), "side"),
        (lambda: Cylinder(0.05, 0.0), "width"),
        (lambda: HalfCylinder(0.05, W, "left"), "flat_side"),
    ],
)
def test_solid_validation(call, field):
    assert_input_error(field, call)


def test_half_cylinder_flat_face_and_origin():
    up, down = HalfCylinder(0.05, W), HalfCylinder(0.05, W, FlatSide.DOWN)
    assert up.flat_side is FlatSide.UP and HalfCylinder(0.05, W, "down") == down
    for body, sign in ((up, 1.0), (down, -1.0)):
        el = body.discretize()
        flat = np.abs(el.midpoints[:, 1]) < 1e-15
        np.testing.assert_allclose(el.normals[flat], [[0.0, sign]] * int(flat.sum()))
        assert el.lengths[flat].sum() == pytest.approx(0.1)
        z = np.concatenate(body.outline(1e-4))[:, 1]
        expected = (0.0, -0.05) if sign > 0 else (0.05, 0.0)
        assert (z.max(), z.min()) == pytest.approx(expected, abs=1e-6)


def test_cylinder_is_a_named_circular_wheel_and_square_is_centred():
    cyl, wheel = Cylinder(0.05, W), WheelCircular(0.05, W)
    same_elements(cyl.discretize(), wheel.discretize())
    assert cyl != wheel
    np.testing.assert_allclose(np.concatenate(Square(0.1, W).outline()).mean(axis=0), 0.0)


# ---------------------------------------------------------------- polygon


def test_polygon_orientation_duplicates_and_center():
    ccw = [[0.0, 0.0], [0.3, 0.0], [0.3, 0.1], [0.1, 0.1], [0.1, 0.3], [0.0, 0.3]]  # L-shape
    cw = [ccw[0], ccw[0], *ccw[::-1]]  # clockwise, a repeated point and a closing point
    a, b = Polygon(ccw, W), Polygon(cw, W)
    assert a.area == pytest.approx(0.05) == b.area
    assert len(b.points) == 6
    same_elements(a.discretize(), b.discretize())
    assert_outward(a)
    centred = Polygon(ccw, W, center=True)
    cx = (0.03 * 0.15 + 0.02 * 0.05) / 0.05  # rectangles 0.3 x 0.1 and 0.1 x 0.2
    np.testing.assert_allclose(np.subtract(ccw, centred.vertices)[0], [cx, cx])
    el = centred.discretize()
    moment = np.sum(el.midpoints**2 * el.normals * el.lengths[:, None], axis=0) / 2  # = integral x dA
    np.testing.assert_allclose(moment, 0.0, atol=1e-15)
    assert hash(centred) == hash(Polygon(centred.vertices, W))


@pytest.mark.parametrize(
    ("points", "why"),
    [
        ([[0, 0], [1, 0]], "distinct"),
        ([[0, 0], [1, 0], [1, 0], [0, 0]], "distinct"),
        ([[0, 0], [1, 0], [math.nan, 1]], "vertex 2"),
        ([[0, 0], [1, 0], [2, 0]], "area"),
        ([[0, 0], [1, 1], [1, 0], [0, 1]], "crosses"),  # bow tie
        ([[0, 0], [1, 0], [1, 1], [0.5, 1], [0.5, 2], [0.5, 1.5], [0, 1]], "crosses"),  # spike
        ([[0, 0], [2, 0], [2, 2], [1, 0], [0, 2]], "crosses"),  # vertex touching an edge
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], "shape"),
        ("abc", "abc"),
    ],
)
def test_polygon_validation(points, why):
    err = assert_input_error("points", Polygon, points, W)
    assert why in str(err)


def test_polygon_large_is_validated_quickly():
    n = 3000
    ang = 2 * np.pi * np.arange(n) / n
    rad = 1.0 + 0.3 * np.sin(7 * ang)
    pts = np.column_stack((rad * np.cos(ang), rad * np.sin(ang)))
    start = time.perf_counter()
    poly = Polygon(pts, W)
    assert time.perf_counter() - start < 2.0
    assert poly.area > 0
    pts[1500] = [2.0, 0.0]  # a spike across the boundary on the far side
    assert_input_error("points", Polygon, pts, W)


def test_polygon_from_files(tmp_path):
    tri = [[0.0, 0.0], [0.2, 0.0], [0.0, 0.1]]
    expected = Polygon(tri, W)
    files = {
        "a.csv": "x,z\n0,0\n0.2,0\n0,0.1\n",
        "b.csv": "# comment\n0 0\n\n0.2 0\n0 0.1\n",
        "c.txt": "0, 0\n0.2, 0\n0, 0.1\n0, 0\n",
        "d.json": json.dumps({"points": tri}),
        "e.json": json.dumps(tri),
    }
    for name, text in files.items():
        (tmp_path / name).write_text(text)
        assert Polygon.from_file(tmp_path / name, W) == expected, name
    assert Polygon.from_file(str(tmp_path / "a.csv"), W, center=True).area == pytest.approx(0.01)


@pytest.mark.parametrize(
    ("name", "text", "why"),
    [
        ("missing.csv", None, "file not found"),
        ("bad.csv", "x,z\n0,0\n0.2,abc\n0,0.1\n", "line 3: 'abc' is not a number"),
        ("cols.csv", "0,0,0\n1,0,0\n", "line 1 has 3 columns"),
        ("empty.csv", "x,z\n", "no vertex rows"),
        ("bad.json", '{"points": [[0, 0], [1, "a"], [0, 1]]}', "points[1]"),
        ("key.json", '{"vertices": []}', '"points"'),
        ("syntax.json", '{"points": [[0, 0],', "invalid JSON"),
    ],
)
def test_polygon_file_errors_name_the_path(tmp_path, name, text, why):
    path = tmp_path / name
    if text is not None:
        path.write_text(text)
    err = assert_input_error("path", Polygon.from_file, path, W)
    assert str(path) in str(err)
    assert why in str(err)


def test_polygon_file_with_bad_shape_names_the_file(tmp_path):
    path = tmp_path / "bowtie.csv"
    path.write_text("0,0\n1,1\n1,0\n0,1\n")
    err = assert_input_error("points", Polygon.from_file, path, W)
    assert str(path) in str(err) and "crosses" in str(err)


# ---------------------------------------------------------------- placed and composite

MOVABLE = [
    CLeg(0.04, W, 0.006),
    HalfCylinder(0.05, W, "down"),
    WheelGrousered(0.09, W, 15, 0.016, 0.005),
    WheelFlapped(0.03, W, 4, 0.065, 0.3),
    Plate(0.1, W),
    Wedge(0.06, 0.08, W, tip_offset=0.01),
]


@pytest.mark.parametrize("body", MOVABLE, ids=lambda b: type(b).__name__)
def test_placed_matches_rotated_then_shifted(body):
    x, z, theta = 0.13, -0.07, 0.7
    placed = body.placed(x, z, theta)
    assert isinstance(placed, Placed) and placed.width == body.width
    h = body.default_element_size
    expected = body.discretize(h).rotated(theta).shifted(x, z)
    # Through the moved loops (lines and arcs transformed; arcs turn by -theta) ...
    mid, nrm, lng, _ = discretize_loops(placed.loops(), h)
    np.testing.assert_allclose(mid, expected.midpoints, atol=1e-13)
    np.testing.assert_allclose(nrm, expected.normals, atol=1e-13)
    np.testing.assert_allclose(lng, expected.lengths, rtol=1e-13)
    # ... and through discretize.
    got = placed.discretize(h)
    np.testing.assert_allclose(got.midpoints, expected.midpoints, atol=1e-13)
    # Same area (exact for lines and arcs about the origin, O(h^2) for moved arcs).
    assert divergence_area(got) == pytest.approx(divergence_area(body.discretize(h)), rel=1e-4)


def test_placed_composes_and_validates():
    body = WheelGrousered(0.09, W, 15, 0.016, 0.005)
    twice = body.placed(0.1, 0.0, 0.3).placed(-0.02, 0.05, 0.4)
    assert isinstance(twice.body, WheelGrousered)
    expected = body.discretize().rotated(0.3).shifted(0.1, 0.0).rotated(0.4).shifted(-0.02, 0.05)
    np.testing.assert_allclose(twice.discretize().midpoints, expected.midpoints, atol=1e-13)
    np.testing.assert_allclose(twice.discretize().normals, expected.normals, atol=1e-13)
    assert_input_error("theta", body.placed, 0.0, 0.0, math.nan)
    assert_input_error("body", Placed, "wheel")


def test_composite_parts_and_identities():
    wheel = WheelCircular(0.05, W)
    plate = Plate(0.04, W, thickness=0.01)
    leg = CLeg(0.02, W, 0.004)
    comp = Composite([wheel, plate.placed(0.0, 0.08, 0.5), leg.placed(0.2, 0.0, -1.0)])
    h = 0.002
    el = comp.discretize(h)
    counts = [b.discretize(h).element_count for b in (wheel, plate, leg)]
    assert el.element_count == sum(counts)
    np.testing.assert_array_equal(np.bincount(el.part), counts)
    areas = [math.pi * 0.05**2, 0.04 * 0.01, 0.02 * 0.004 * math.pi]
    assert divergence_area(el) == pytest.approx(sum(areas), rel=1e-4)  # disjoint parts
    assert_closed(el, rtol=1e-4)
    assert comp.width == W and comp.size == 0.05
    assert comp.default_element_size == min(b.default_element_size for b in (wheel, plate, leg))
    assert len(comp.loops()) == 3
    # A placed composite keeps its part numbers.
    moved = comp.placed(1.0, 2.0, 0.3).discretize(h)
    np.testing.assert_array_equal(moved.part, el.part)
    same_elements(moved, el.rotated(0.3).shifted(1.0, 2.0))
    # Nested composites renumber parts.
    nested = Composite([comp, wheel.placed(0.5)]).discretize(h)
    assert set(nested.part.tolist()) == {0, 1, 2, 3}


def test_composite_validation():
    assert_input_error("parts", Composite, [])
    assert_input_error("parts", Composite, 3)
    assert_input_error("parts[1]", Composite, [Plate(0.1, W), "plate"])
    assert_input_error("parts[1].width", Composite, [Plate(0.1, W), Plate(0.1, 2 * W).placed(1.0)])
