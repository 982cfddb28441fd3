"""Dynamic RFT: reduction to RFT, numba = NumPy, the inertial and structural terms, inputs."""

import math

import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.geometry import Plate, SurfaceElements, WheelCircular, WheelGrousered
from terradyn.kinematics import Pose2D, Twist2D
from terradyn.locomotion import wheel_steady
from terradyn.rft import RFTModel, rft_wrench
from terradyn.rft.drft import DRFTModel, drft_element_forces, drft_structural_drop, drft_wrench
from terradyn.terrain import TerrainModel

POPPY = materials.get("poppy-cp")
CIRCLE = WheelCircular(0.106, 0.05)
GROUSERED = WheelGrousered(0.1, 0.05, 15, 0.006, 0.004)
RNG = np.random.default_rng(7)


def _states(count):
    for _ in range(count):
        pose = Pose2D(RNG.uniform(-0.1, 0.1), RNG.uniform(0.02, 0.1), RNG.uniform(-3, 3))
        twist = Twist2D(RNG.uniform(-0.5, 1.0), RNG.uniform(-0.3, 0.3), RNG.uniform(-2, 12))
        yield pose, twist


@pytest.mark.parametrize("body", [CIRCLE, GROUSERED, Plate(0.05, 0.05)])
def test_reduces_to_rft_without_inertia_at_low_spin(body):
    model = DRFTModel(POPPY, inertial_coefficient=0.0)
    for pose, twist in _states(20):
        slow = Twist2D(twist.vx, twist.vz, 1e-9 * np.sign(twist.omega))
        a = rft_wrench(body, POPPY, pose, slow)
        b = drft_wrench(body, model, pose, slow)
        np.testing.assert_allclose(b.as_array(), a.as_array(), rtol=1e-14, atol=1e-14)
    # structural correction off: any spin
    off = DRFTModel(POPPY, inertial_coefficient=0.0, structural_correction=False)
    for pose, twist in _states(10):
        np.testing.assert_allclose(
            drft_wrench(body, off, pose, twist).as_array(),
            rft_wrench(body, POPPY, pose, twist).as_array(),
            rtol=1e-14,
            atol=1e-14,
        )


@pytest.mark.parametrize("body", [CIRCLE, GROUSERED])
@pytest.mark.parametrize("band", [0.0, 0.05])
def test_numba_matches_numpy_reference(body, band):
    model = DRFTModel(POPPY, inertial_coefficient=1.3)
    for pose, twist in _states(30):
        a = drft_wrench(body, model, pose, twist, leading_band=band)
        b = drft_wrench(body, model, pose, twist, backend="numpy", leading_band=band)
        np.testing.assert_allclose(a.as_array(), b.as_array(), rtol=1e-10, atol=1e-10)


def test_smoothed_leading_edge_rule_is_close_to_the_sharp_one():
    model = DRFTModel(POPPY, structural_correction=False)
    pose, twist = Pose2D(0.0, 0.07, 0.0), Twist2D(0.3, 0.0, 3.0)
    sharp = drft_wrench(CIRCLE, model, pose, twist)
    smooth = drft_wrench(CIRCLE, model, pose, twist, leading_band=0.01)
    np.testing.assert_allclose(smooth.as_array(), sharp.as_array(), rtol=0.02)


def test_inertial_term_of_a_plate_pushed_down():
    plate = Plate(0.04, 0.05)
    pose = Pose2D(0.0, -0.03, 0.0)
    lam, rho = 1.1, 638.0
    model = DRFTModel(POPPY, inertial_coefficient=lam, density=rho)
    for v in (0.05, 0.4, 1.6):
        twist = Twist2D(0.0, -v, 0.0)
        extra = drft_wrench(plate, model, pose, twist).fz - rft_wrench(plate, POPPY, pose, twist).fz
        assert extra == pytest.approx(lam * rho * v**2 * 0.04 * 0.05, rel=1e-12)
    # above the surface nothing, whatever the speed
    assert drft_wrench(plate, model, Pose2D(0, 0.01, 0), Twist2D(0, -2.0, 0)).fz == 0.0


def test_inertial_term_is_along_minus_normal_on_leading_elements():
    model = DRFTModel(POPPY, inertial_coefficient=1.0, structural_correction=False)
    pose, twist = Pose2D(0, 0.06, 0.2), Twist2D(0.3, -0.2, 4.0)
    el = drft_element_forces(GROUSERED, model, pose, twist)
    vn = np.einsum("ij,ij->i", el.normals, el.velocities)
    assert np.all(vn[el.active] > 0)
    expect = -el.normals * (638.0 * vn**2 * el.areas)[:, None]
    np.testing.assert_allclose(el.inertial_forces[el.active], expect[el.active], rtol=1e-12)
    assert np.all(el.inertial_forces[~el.active] == 0)


def test_structural_drop_law():
    assert drft_structural_drop(0.106, 6.8, 9.81) == pytest.approx(0.106**2 * 6.8**2 / 9.81)
    model = DRFTModel(POPPY)
    assert model.structural_drop(CIRCLE, 5.0) == pytest.approx(0.106 * 0.106 * 25 / 9.81)
    # not a wheel, or raw elements: no structural correction
    assert model.structural_drop(Plate(0.05, 0.05), 5.0) == 0.0
    assert model.structural_drop(CIRCLE.discretize(), 5.0) == 0.0


def test_structural_correction_lowers_the_surface_of_the_rear_half():
    model = DRFTModel(POPPY, inertial_coefficient=0.0)
    pose, twist = Pose2D(0, 0.04, 0.1), Twist2D(0.2, 0.0, 5.0)
    el = drft_element_forces(GROUSERED, model, pose, twist)
    drop = 0.106**2 * 25 / 9.81
    assert el.drop == pytest.approx(drop)
    # The same sum done by plain RFT: front elements at the surface, rear ones at -drop.
    elems = GROUSERED.discretize()
    rear = el.rear

    def subset(mask):
        return SurfaceElements(elems.midpoints[mask], elems.normals[mask], elems.lengths[mask], elems.width)

    front_w = rft_wrench(subset(~rear), POPPY, pose, twist)
    rear_w = rft_wrench(subset(rear), POPPY, pose, twist, surface_level=-drop)
    np.testing.assert_allclose(
        el.wrench.as_array(), front_w.as_array() + rear_w.as_array(), rtol=1e-9, atol=1e-12
    )
    # the rear set lies behind the front set (smaller angle from the downward vertical)
    rel = el.positions - np.array([pose.x, pose.z])
    phi = np.arctan2(rel[:, 0], -rel[:, 1])
    assert phi[rear].max() <= phi[el.active & ~rear].min() + 1e-12
    # the correction removes support: less lift than RFT
    assert el.wrench.fz < rft_wrench(GROUSERED, POPPY, pose, twist).fz


def test_model_protocol_and_steady_solver_limit():
    model = DRFTModel(POPPY, inertial_coefficient=0.0)
    assert isinstance(model, TerrainModel)
    assert model.name == "drft"
    a = wheel_steady(CIRCLE, model, 10.0, 0.2, omega=1e-4)
    b = wheel_steady(CIRCLE, RFTModel(POPPY), 10.0, 0.2, omega=1e-4)
    assert a.sinkage_m == pytest.approx(b.sinkage_m, rel=1e-7)
    assert a.drawbar_pull_N == pytest.approx(b.drawbar_pull_N, rel=1e-6)
    fast = wheel_steady(CIRCLE, DRFTModel(POPPY), 10.0, 0.2, omega=8.0)
    assert fast.sinkage_m > b.sinkage_m


def test_defaults_from_material():
    model = DRFTModel(POPPY)
    assert model.inertial_coefficient == 1.0 and model.density == 638.0
    assert model.inertial_density == 638.0


def test_bad_inputs():
    bare = POPPY.with_changes(critical_density=None, drft_lambda=None)
    with pytest.raises(InputError) as exc:
        DRFTModel(bare)
    assert exc.value.field == "density"
    assert DRFTModel(bare, inertial_coefficient=0.0).inertial_density == 0.0
    assert DRFTModel(bare, density=700.0).inertial_density == 700.0
    for kwargs, field in (
        ({"inertial_coefficient": -1.0}, "inertial_coefficient"),
        ({"density": -5.0}, "density"),
        ({"gravity": 0.0}, "gravity"),
        ({"surface_level": math.nan}, "surface_level"),
        ({"structural_correction": "yes"}, "structural_correction"),
    ):
        with pytest.raises(InputError) as exc:
            DRFTModel(POPPY, **kwargs)
        assert exc.value.field == field
    with pytest.raises(InputError):
        drft_wrench(CIRCLE, DRFTModel(POPPY), Pose2D(), Twist2D(), backend="gpu")
