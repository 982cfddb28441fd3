"""Plate, WheelCircular, SurfaceElements and the Line/Arc segments they are built from."""

from __future__ import annotations

import math

import numpy as np
import pytest

from terradyn.errors import InputError
from terradyn.geometry import Arc, Line, Plate, SurfaceElements, WheelCircular

W = 0.05


def net_normal(el: SurfaceElements) -> np.ndarray:
    return (el.normals * el.lengths[:, None]).sum(axis=0)


def divergence_area(el: SurfaceElements) -> float:
    return 0.5 * float(np.sum(np.einsum("ij,ij->i", el.midpoints, el.normals) * el.lengths))


def field_of(fn, *args, **kwargs) -> str:
    with pytest.raises(InputError) as info:
        fn(*args, **kwargs)
    assert info.value.field in str(info.value)
    return info.value.field


# ---------------------------------------------------------------- plate


def test_thin_plate_has_both_faces():
    plate = Plate(0.1, W)
    el = plate.discretize(0.01)
    assert el.element_count == 20
    assert el.perimeter == pytest.approx(0.2)
    up, down = el.normals[:, 1] > 0, el.normals[:, 1] < 0
    assert up.sum() == down.sum() == 10
    np.testing.assert_allclose(np.abs(el.normals[:, 1]), 1.0)
    np.testing.assert_allclose(el.midpoints[:, 1], 0.0)
    np.testing.assert_allclose(np.sort(el.midpoints[up, 0]), np.sort(el.midpoints[down, 0]))
    np.testing.assert_allclose(net_normal(el), 0.0, atol=1e-15)
    assert divergence_area(el) == pytest.approx(0.0, abs=1e-15)
    assert el.width == W and el.areas.sum() == pytest.approx(0.2 * W)


def test_thick_plate_is_a_rectangle():
    el = Plate(0.1, W, thickness=0.02).discretize(0.003)
    assert el.perimeter == pytest.approx(0.24)
    assert divergence_area(el) == pytest.approx(0.002)
    np.testing.assert_allclose(net_normal(el), 0.0, atol=1e-15)
    assert np.all(np.abs(el.midpoints).max(axis=0) <= [0.05, 0.01])


@pytest.mark.parametrize(
    ("args", "field"),
    [
        ((0.0, W), "length"),
        ((-1.0, W), "length"),
        ((math.nan, W), "length"),
        ((0.1, 0.0), "width"),
        ((0.1, W, -0.01), "thickness"),
        ((0.1, W, 0.1), "thickness"),
        (("long", W), "length"),
    ],
)
def test_plate_validation(args, field):
    assert field_of(Plate, *args) == field


# ---------------------------------------------------------------- circular wheel


def test_circular_wheel_elements():
    wheel = WheelCircular(0.1, W)
    assert wheel.outer_radius == wheel.size == 0.1
    el = wheel.discretize()
    assert el.element_count == 360
    np.testing.assert_allclose(np.hypot(*el.midpoints.T), 0.1)
    np.testing.assert_allclose(el.normals, el.midpoints / 0.1, atol=1e-15)  # radial, outward
    assert el.perimeter == pytest.approx(2 * math.pi * 0.1)
    assert divergence_area(el) == pytest.approx(math.pi * 0.01)
    np.testing.assert_allclose(net_normal(el), 0.0, atol=1e-15)
    # The first element starts at the bottom and the rim runs counter-clockwise.
    assert el.midpoints[0, 1] < 0 < el.midpoints[0, 0]
    assert wheel.bounding_radius == pytest.approx(0.1)


def test_circular_wheel_validation():
    assert field_of(WheelCircular, 0.0, W) == "radius"
    assert field_of(WheelCircular, 0.1, -W) == "width"


@pytest.mark.parametrize("bad", [0.0, -0.01, math.nan, math.inf, True, "0.01", 0.2])
def test_element_size_validation(bad):
    assert field_of(WheelCircular(0.1, W).discretize, bad) == "element_size"


def test_element_size_accepts_numpy_scalars_and_caches():
    wheel = WheelCircular(0.1, W)
    a = wheel.discretize(np.float32(0.01))
    b = wheel.discretize(0.009999999776482582)  # the same float
    assert a is b
    assert wheel.discretize(np.int64(1) / 100).element_count == 63


def test_discretisation_converges_to_the_element_size():
    wheel = WheelCircular(0.1, W)
    for size in (0.05, 0.01, 0.001):
        el = wheel.discretize(size)
        assert el.lengths.max() <= size
        assert el.element_count == math.ceil(2 * math.pi * 0.1 / size)


# ---------------------------------------------------------------- segments


def test_line_and_arc_normals():
    line = Line((0.0, 0.0), (1.0, 0.0))
    _, nrm, lng = line.elements(0.3)
    assert len(lng) == 4 and lng.sum() == pytest.approx(1.0)
    np.testing.assert_allclose(nrm, [[0.0, -1.0]] * 4)  # moving +x, the outside is below
    convex = Arc((1.0, 2.0), 0.5, 0.0, math.pi)
    concave = Arc((1.0, 2.0), 0.5, math.pi, 0.0)
    m1, n1, _ = convex.elements(0.1)
    m2, n2, _ = concave.elements(0.1)
    np.testing.assert_allclose(n1, (m1 - [1.0, 2.0]) / 0.5, atol=1e-15)  # away from the centre
    np.testing.assert_allclose(n2, ([1.0, 2.0] - m2) / 0.5, atol=1e-15)  # towards the centre
    assert convex.length == concave.length == pytest.approx(0.5 * math.pi)


# ---------------------------------------------------------------- surface elements


def elements() -> SurfaceElements:
    return WheelCircular(0.1, W).discretize(0.02)


def test_rotation_is_clockwise_and_invertible():
    el = SurfaceElements(np.array([[1.0, 0.0]]), np.array([[1.0, 0.0]]), np.array([0.1]), W)
    turned = el.rotated(math.pi / 2)
    np.testing.assert_allclose(turned.midpoints, [[0.0, -1.0]], atol=1e-15)  # +x turns to -z
    np.testing.assert_allclose(turned.normals, [[0.0, -1.0]], atol=1e-15)
    base = Plate(0.1, W, thickness=0.02).discretize(0.01)
    back = base.rotated(0.7).rotated(-0.7)
    np.testing.assert_allclose(back.midpoints, base.midpoints, atol=1e-15)
    np.testing.assert_allclose(back.normals, base.normals, atol=1e-15)
    np.testing.assert_array_equal(base.rotated(0.7).lengths, base.lengths)
    assert divergence_area(base.rotated(0.7)) == pytest.approx(divergence_area(base))


def test_shift_and_width():
    el = elements()
    moved = el.shifted(0.3, -0.2)
    np.testing.assert_allclose(moved.midpoints - el.midpoints, [[0.3, -0.2]] * el.element_count)
    np.testing.assert_array_equal(moved.normals, el.normals)
    wide = el.with_width(0.2)
    assert wide.width == 0.2 and wide.areas.sum() == pytest.approx(4 * el.areas.sum())


def test_arrays_are_read_only():
    el = elements()
    for arr in (el.midpoints, el.normals, el.lengths, el.part):
        with pytest.raises(ValueError):
            arr[0] = 0


def test_concatenate_keeps_parts_distinct():
    a, b = elements(), Plate(0.1, W).discretize(0.05)
    both = SurfaceElements.concatenate([a, b, a])
    assert both.element_count == 2 * a.element_count + b.element_count
    np.testing.assert_array_equal(np.unique(both.part), [0, 1, 2])
    assert field_of(SurfaceElements.concatenate, []) == "elements"
    assert field_of(SurfaceElements.concatenate, [a, a.with_width(1.0)]) == "width"


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"midpoints": np.zeros((3, 3))}, "elements.midpoints"),
        ({"normals": np.zeros((2, 2))}, "elements.normals"),
        ({"lengths": np.ones(2)}, "elements.lengths"),
        ({"lengths": np.array([0.1, 0.0, 0.1])}, "elements.lengths"),
        ({"normals": np.array([[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])}, "elements.normals"),
        ({"midpoints": np.array([[0, 0], [0, math.nan], [1, 1]])}, "elements"),
        ({"width": 0.0}, "width"),
        ({"part": np.zeros(2)}, "elements.part"),
    ],
)
def test_elements_validation(kwargs, field):
    args = {
        "midpoints": np.zeros((3, 2)),
        "normals": np.tile([0.0, 1.0], (3, 1)),
        "lengths": np.full(3, 0.1),
        "width": W,
    } | kwargs
    assert field_of(SurfaceElements, **args) == field
