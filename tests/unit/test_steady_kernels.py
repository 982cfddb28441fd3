"""The compiled steady solves against their references: Brent's method against SciPy's brentq, the
compiled 2D and 3D points against the generic (pure Python / batched) paths."""

import dataclasses
import math

import numpy as np
import pytest
from scipy.optimize import brentq

import terradyn.locomotion.steady3d as steady3d
from terradyn import materials
from terradyn.errors import SolverError
from terradyn.geometry import WheelCircular, WheelGrousered
from terradyn.geometry3d import wheel_cylinder, wheel_grousered
from terradyn.geometry3d.kinematics import rotations_y
from terradyn.locomotion import _steady_kernels as k
from terradyn.locomotion import wheel_steady
from terradyn.rft import RFTModel

MS = materials.get("MS")


def _brent(f, a, b, xtol, rtol, step):
    """Drive the reverse-communication Brent step to a root; returns (root, evaluations)."""
    state = np.empty(10)
    k.brent_start(a, f(a), b, f(b), xtol, rtol, state)
    for n in range(200):
        done, x = step(state)
        if done:
            return x, n
        state[4] = f(x)
    raise AssertionError("no convergence")


@pytest.mark.parametrize("compiled", [True, False])
@pytest.mark.parametrize(
    ("f", "a", "b"),
    [
        (lambda x: x**3 - 2.0 * x - 5.0, 2.0, 3.0),
        (lambda x: math.cos(x) - x, 0.0, 1.0),
        (lambda x: math.exp(x) - 10.0, 0.0, 5.0),
        (lambda x: (x - 0.3) * (1.0 + x * x), 0.0, 1.0),
        (lambda x: 1.0 - x if x < 0.7 else 0.3 - 2 * (x - 0.7), 0.0, 2.0),
    ],
)
def test_brent_matches_scipy_brentq(compiled, f, a, b):
    step = k.brent_step if compiled else k.brent_step.py_func
    root, _ = _brent(f, a, b, 1e-12, 1e-13, step)
    expected = brentq(f, a, b, xtol=1e-12, rtol=1e-13)
    assert root == expected  # the same iteration: the same iterates


class _Wrapped:
    """RFT behind the generic terrain-model protocol (the pure-Python reference path)."""

    def __init__(self, model):
        self.model, self.name, self.surface_level = model, model.name, model.surface_level

    def wrench(self, body, pose, twist, *, about=None):
        return self.model.wrench(body, pose, twist, about=about)

    def contact_angles(self, body, pose, twist):
        from terradyn.locomotion.steady import _contact_angles

        return _contact_angles(self.model, body, pose, twist)


def _assert_same(a, b, rel):
    for f in dataclasses.fields(a):
        va, vb = getattr(a, f.name), getattr(b, f.name)
        if isinstance(va, float):
            assert va == pytest.approx(vb, rel=rel, abs=1e-12), f.name
        else:
            assert va == vb, f.name


@pytest.mark.parametrize(
    "body", [WheelCircular(0.13, 0.16), WheelGrousered(0.12, 0.16, 12, 0.01, 0.005)], ids=["plain", "lugs"]
)
@pytest.mark.parametrize("slip", [-0.5, 0.0, 0.3, 0.7])
def test_compiled_2d_point_matches_generic_path(body, slip):
    model = RFTModel(MS, surface_level=0.01)
    _assert_same(
        wheel_steady(body, model, 130.0, slip), wheel_steady(body, _Wrapped(model), 130.0, slip), 1e-10
    )


def test_compiled_2d_errors_match_generic_path():
    wheel = WheelCircular(0.05, 0.02)
    for model in (RFTModel(MS), _Wrapped(RFTModel(MS))):
        with pytest.raises(SolverError, match="carries at most"):
            wheel_steady(wheel, model, 1e6, 0.2)


def _mesh_pair():
    cylinder = wheel_cylinder(
        0.13, 0.16, circumferential_resolution=120, axial_resolution=4, radial_resolution=2
    )
    lugs = wheel_grousered(
        0.13, 0.16, grouser_count=8, grouser_height=0.01, grouser_thickness=0.005,
        circumferential_resolution=96, axial_resolution=4, radial_resolution=2,
    )  # fmt: skip
    return [(cylinder, 1), (lugs, 3)]


@pytest.mark.parametrize("case", [0, 1], ids=["cylinder", "grousered"])
@pytest.mark.parametrize("slip", [-0.5, 0.3])
def test_compiled_3d_point_matches_reference(monkeypatch, case, slip):
    mesh, phases = _mesh_pair()[case]
    kwargs = dict(slip_angle=math.radians(5.0), phase_count=phases, surface_level=0.002)
    compiled = steady3d.wheel_steady_3d(mesh, MS, 60.0, slip, **kwargs)
    monkeypatch.setattr(steady3d, "_solve_state", steady3d._solve_reference)
    reference = steady3d.wheel_steady_3d(mesh, MS, 60.0, slip, **kwargs)
    _assert_same(compiled, reference, 1e-9)


def test_compiled_3d_overload_message(monkeypatch):
    mesh, _ = _mesh_pair()[0]
    with pytest.raises(SolverError, match="carries at most"):
        steady3d.wheel_steady_3d(mesh, MS, 1e7, 0.2)
    monkeypatch.setattr(steady3d, "_solve_state", steady3d._solve_reference)
    with pytest.raises(SolverError, match="carries at most"):
        steady3d.wheel_steady_3d(mesh, MS, 1e7, 0.2)


@pytest.mark.parametrize("compiled", [True, False])
def test_facet_order_prefixes_hold_every_submerged_facet(compiled):
    mesh, _ = _mesh_pair()[1]
    fn = k.rft3d_facet_order_kernel if compiled else k.rft3d_facet_order_kernel.py_func
    thetas = np.array([0.0, 0.2, 0.4])
    rotations = rotations_y(thetas)
    low, high, surface = 0.0, 0.14, 0.0
    c, _n, a, counts = fn(*mesh.kernel_arrays, rotations, surface, low, high)
    assert np.all(np.diff(counts) <= 0) and counts[0] == a.size
    assert np.isclose(a.sum() + mesh.areas[_never(mesh, rotations, surface, low)].sum(), mesh.area)
    grid = np.linspace(low, high, k.SCAN_POINTS)
    for i, h in enumerate(grid):
        # every facet below the surface at height h (any phase) is within the first counts[i]
        for rot in rotations:
            rz = (rot @ c)[2]
            assert not np.any(rz[counts[i] :] + h < surface)


def _never(mesh, rotations, surface, low):
    rz = np.einsum("pj,jf->pf", rotations[:, 2, :], mesh.kernel_arrays[0]).min(axis=0)
    return rz + low >= surface + 1e-6 * 0.14 / 16
