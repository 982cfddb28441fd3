"""Wong-Reece rigid wheel: equilibrium, physics trends, quadrature, kernels, errors, terrain model."""

from __future__ import annotations

import math

import numpy as np
import pytest

from terradyn.errors import InputError, SolverError
from terradyn.geometry import Plate, WheelCircular
from terradyn.kinematics import Pose2D, Twist2D
from terradyn.materials import BekkerParameters, Material, get
from terradyn.terrain import TerrainModel
from terradyn.terramechanics import WongReeceModel, wong_reece_wheel, wong_reece_wheel_forces
from terradyn.terramechanics import _kernels as wrk
from terradyn.terramechanics import wong_reece as wr

R, B = 0.13, 0.16
MEDIA = ("MS", "MMS", "LPS", "CPS")
# A cohesionless sand with a literature-sized shear modulus (K = 2 cm).
SAND = BekkerParameters(
    k_c=1.0e4, k_phi=2.0e6, n=1.1, cohesion=0.0, friction_angle=math.radians(32.0), shear_modulus=0.02
)


@pytest.mark.parametrize("medium", MEDIA)
@pytest.mark.parametrize("slip", [-0.7, -0.1, 0.0, 0.3, 0.7])
def test_solved_vertical_force_reproduces_the_load(medium, slip):
    res = wong_reece_wheel(R, B, medium, slip, 130.0)
    assert res.load == pytest.approx(130.0, rel=1e-8)
    again = wong_reece_wheel_forces(R, B, medium, slip, entry_angle=res.entry_angle)
    assert again.load == pytest.approx(130.0, rel=1e-8)
    assert again.sinkage == pytest.approx(R * (1.0 - math.cos(res.entry_angle)), rel=1e-12)
    assert res.max_stress_angle == pytest.approx((0.43 + 0.32 * slip) * res.entry_angle)


@pytest.mark.parametrize("soil", ["MS", "LPS", SAND])
def test_sinkage_rises_with_load(soil):
    sinks = [wong_reece_wheel(R, B, soil, 0.2, w).sinkage for w in (40.0, 80.0, 130.0, 150.0, 190.0)]
    assert np.all(np.diff(sinks) > 0)


@pytest.mark.parametrize("soil", ["LPS", "CPS", SAND])
def test_drawbar_pull_rises_with_driving_slip(soil):
    pulls = [wong_reece_wheel(R, B, soil, s, 130.0).drawbar_pull for s in np.linspace(0.0, 0.7, 8)]
    assert np.all(np.diff(pulls) > 0)


@pytest.mark.parametrize("soil", [*MEDIA, SAND])
def test_skidding_wheel_is_braked(soil):
    # Even at s = 0, j = r[(t1 - t) - (sin t1 - sin t)] > 0: the torque of a free-rolling wheel vanishes
    # at a slightly negative slip, so "clearly skidding" starts a little below zero.
    for s in (-0.7, -0.3, -0.15):
        res = wong_reece_wheel(R, B, soil, s, 130.0)
        assert res.drive_torque < 0  # the motor holds the wheel back
        assert res.drawbar_pull < 0  # the soil pushes the wheel backwards
        assert res.thrust < 0
        assert res.soil_torque == -res.drive_torque


@pytest.mark.parametrize("soil", ["LPS", "CPS", SAND])
def test_skid_resistance_grows_with_skid_for_cohesionless_soil(soil):
    pulls = [wong_reece_wheel(R, B, soil, s, 130.0).drawbar_pull for s in (-0.7, -0.4, -0.1)]
    assert pulls[0] < pulls[1] < pulls[2]


@pytest.mark.parametrize("soil", ["LPS", "CPS", SAND])
def test_free_rolling_wheel_feels_compaction_resistance(soil):
    res = wong_reece_wheel(R, B, soil, 0.0, 130.0)
    assert res.drawbar_pull < 0
    assert res.compaction_resistance > 0
    assert res.drawbar_pull == pytest.approx(res.thrust - res.compaction_resistance)
    assert res.thrust < res.compaction_resistance


@pytest.mark.parametrize(
    ("medium", "slip", "load"),
    [("MS", 0.3, 130.0), ("MMS", -0.1, 190.0), ("MMS", 0.7, 80.0), ("LPS", -0.7, 150.0), ("CPS", 0.0, 190.0)],
)
def test_quadrature_converged(medium, slip, load):
    a = wong_reece_wheel(R, B, medium, slip, load)
    b = wong_reece_wheel(R, B, medium, slip, load, node_count=2 * wr.DEFAULT_NODE_COUNT)
    for field in ("sinkage", "drawbar_pull", "drive_torque", "entry_angle"):
        assert getattr(a, field) == pytest.approx(getattr(b, field), rel=1e-6), field


def test_skid_sign_change_of_shear_is_split():
    # MMS at s = -0.1 and 190 N: j changes sign inside the contact; the quadrature cuts there.
    t1 = np.array([0.56])
    ends = wrk._breakpoints_reference(t1, 0.0, -0.1, 0.43 - 0.032)
    zero = ends[0, 2]
    assert 0.0 < zero < 0.56
    g = (0.56 - zero) - 1.1 * (math.sin(0.56) - math.sin(zero))
    assert abs(g) < 1e-14
    # Driving: no interior sign change; the cut collapses onto theta_m.
    ends = wrk._breakpoints_reference(t1, 0.0, 0.3, 0.43 + 0.096)
    assert ends[0, 1] == ends[0, 2]


@pytest.mark.parametrize("exit_angle", [0.0, -0.15])
@pytest.mark.parametrize("slip", [-1.0, -0.3, -0.05, 0.0, 0.2, 1.0])
def test_numba_kernel_matches_numpy_reference(slip, exit_angle):
    theta1 = np.linspace(0.02, math.pi / 2, 25)
    for medium in MEDIA:
        b = get(medium).require_bekker()
        args = (
            theta1,
            exit_angle,
            R,
            B,
            b.k_c / B + b.k_phi,
            b.n,
            b.cohesion,
            math.tan(b.friction_angle),
            b.shear_modulus,
            slip,
            0.43 + 0.32 * slip,
            32,
        )
        np.testing.assert_allclose(
            wrk._wong_reece_integrals_many(*args),
            wrk._wong_reece_integrals_reference(*args),
            rtol=1e-11,
            atol=1e-11,
        )


def test_profiles_shape_and_consistency():
    res = wong_reece_wheel(R, B, "LPS", 0.3, 130.0, profiles=True, profile_points=2001)
    prof = res.profiles
    assert prof is not None
    assert prof.angle[0] == res.exit_angle and prof.angle[-1] == pytest.approx(res.entry_angle)
    assert prof.normal_stress[0] == pytest.approx(0.0, abs=1e-6)
    assert prof.normal_stress[-1] == pytest.approx(0.0, abs=1e-6)
    peak = prof.angle[np.argmax(prof.normal_stress)]
    assert peak == pytest.approx(res.max_stress_angle, abs=2.0 * (prof.angle[1] - prof.angle[0]))
    th, sig, tau = prof.angle, prof.normal_stress, prof.shear_stress
    w = R * B * np.trapezoid(sig * np.cos(th) + tau * np.sin(th), th)
    assert w == pytest.approx(130.0, rel=1e-4)
    assert R * R * B * np.trapezoid(tau, th) == pytest.approx(res.drive_torque, rel=1e-4)


def test_sinkage_and_entry_angle_inputs_agree():
    a = wong_reece_wheel_forces(R, B, "MS", 0.2, entry_angle=0.4)
    b = wong_reece_wheel_forces(R, B, "MS", 0.2, sinkage=R * (1.0 - math.cos(0.4)))
    assert a.drawbar_pull == pytest.approx(b.drawbar_pull, rel=1e-12)
    assert a.load == pytest.approx(b.load, rel=1e-12)


def test_exit_angle_adds_rear_contact():
    base = wong_reece_wheel(R, B, SAND, 0.2, 130.0)
    rebound = wong_reece_wheel(R, B, SAND, 0.2, 130.0, exit_angle=-0.1)
    assert rebound.exit_angle == -0.1
    assert rebound.sinkage < base.sinkage  # more contact carries the same load at less sinkage


def test_material_and_name_and_parameters_give_the_same_answer():
    mat = get("CPS")
    a = wong_reece_wheel(R, B, "CPS", 0.3, 150.0)
    b = wong_reece_wheel(R, B, mat, 0.3, 150.0)
    c = wong_reece_wheel(R, B, mat.require_bekker(), 0.3, 150.0)
    assert a == b == c


# ---------------------------------------------------------------------------- errors


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"radius": 0.0}, "radius"),
        ({"width": -0.1}, "width"),
        ({"load": 0.0}, "load"),
        ({"slip": 1.2}, "slip"),
        ({"slip": -1.5}, "slip"),
        ({"c1": 0.9, "c2": 1.0}, "c1 \\+ c2 \\* slip"),
        ({"c1": -0.5, "c2": 0.0}, "c1 \\+ c2 \\* slip"),
        ({"exit_angle": 0.1}, "exit_angle"),
        ({"node_count": 2}, "node_count"),
    ],
)
def test_bad_inputs_raise_input_error_naming_the_field(kwargs, field):
    args = {"radius": R, "width": B, "soil": "LPS", "slip": 0.2, "load": 130.0}
    args.update(kwargs)
    with pytest.raises(InputError, match=field):
        wong_reece_wheel(**args)


def test_negative_theta_m_ratio_allowed_only_with_room_behind():
    # c1 + c2 s = -0.05: theta_m < 0, fine with a rear contact reaching -0.1 rad, not with theta_2 = 0.
    res = wong_reece_wheel(R, B, SAND, 0.5, 100.0, c1=-0.05, c2=0.0, exit_angle=-0.1)
    assert res.max_stress_angle < 0
    with pytest.raises(InputError, match="c1"):
        wong_reece_wheel(R, B, SAND, 0.5, 100.0, c1=-0.05, c2=0.0)


def test_forces_input_errors():
    with pytest.raises(InputError, match="entry_angle / sinkage"):
        wong_reece_wheel_forces(R, B, "LPS", 0.1)
    with pytest.raises(InputError, match="entry_angle / sinkage"):
        wong_reece_wheel_forces(R, B, "LPS", 0.1, entry_angle=0.3, sinkage=0.01)
    with pytest.raises(InputError, match="entry_angle"):
        wong_reece_wheel_forces(R, B, "LPS", 0.1, entry_angle=2.0)
    with pytest.raises(InputError, match="sinkage"):
        wong_reece_wheel_forces(R, B, "LPS", 0.1, sinkage=0.2)
    with pytest.raises(InputError, match="profile_points"):
        wong_reece_wheel_forces(R, B, "LPS", 0.1, entry_angle=0.3, profiles=True, profile_points=1)
    with pytest.raises(InputError, match="k_c / width"):
        wong_reece_wheel_forces(R, 0.01, "LPS", 0.1, entry_angle=0.3)  # -2.06e5/0.01 + 7.07e6 < 0


def test_material_without_bekker_parameters():
    with pytest.raises(InputError, match="bekker"):
        wong_reece_wheel(R, B, Material("rft-only"), 0.1, 100.0)


def test_load_too_large_is_a_solver_error_with_the_capacity():
    top = wong_reece_wheel_forces(R, B, "LPS", 0.3, entry_angle=math.pi / 2).load
    with pytest.raises(SolverError, match="at most") as info:
        wong_reece_wheel(R, B, "LPS", 0.3, 2.0 * top)
    assert f"{top:.4g}" in str(info.value)
    assert "pi/2" in str(info.value)
    assert wong_reece_wheel(R, B, "LPS", 0.3, 0.99 * top).entry_angle < math.pi / 2


# ---------------------------------------------------------------------------- terrain model


def _twist(slip: float, omega: float = 2.0) -> Twist2D:
    return Twist2D((1.0 - slip) * omega * R, 0.0, omega)


def test_model_is_a_terrain_model_and_matches_the_functions():
    model = WongReeceModel("MS")
    assert isinstance(model, TerrainModel)
    assert model.name == "wong-reece"
    wheel = WheelCircular(R, B)
    sink = 0.011
    pose = Pose2D(0.3, R - sink, 0.7)
    w = model.wrench(wheel, pose, _twist(0.25))
    ref = wong_reece_wheel_forces(R, B, "MS", 0.25, sinkage=sink)
    assert w.fx == pytest.approx(ref.drawbar_pull, rel=1e-12)
    assert w.fz == pytest.approx(ref.load, rel=1e-12)
    assert w.torque_y == pytest.approx(-ref.drive_torque, rel=1e-12)
    # Torque about another point: add (axle - point) x F.
    about = (0.1, -0.05)
    w2 = model.wrench(wheel, pose, _twist(0.25), about=about)
    rx, rz = pose.x - about[0], pose.z - about[1]
    assert w2.torque_y == pytest.approx(w.torque_y + rz * w.fx - rx * w.fz, rel=1e-12)
    state = model.wheel_state(wheel, pose, _twist(0.25))
    assert state is not None and state.drawbar_pull == pytest.approx(w.fx, rel=1e-12)


def test_model_surface_level_and_no_contact():
    wheel = WheelCircular(R, B)
    lifted = WongReeceModel("LPS", surface_level=0.5)
    base = WongReeceModel("LPS")
    a = base.wrench(wheel, Pose2D(0.0, R - 0.006), _twist(0.1))
    b = lifted.wrench(wheel, Pose2D(0.0, 0.5 + R - 0.006), _twist(0.1))
    assert a == b
    above = base.wrench(wheel, Pose2D(0.0, R + 0.01), _twist(0.1))
    assert above.as_array().tolist() == [0.0, 0.0, 0.0]
    assert base.contact_angles(wheel, Pose2D(0.0, R + 0.01), _twist(0.1)) == (0.0, 0.0)


def test_model_mirror_symmetry_for_backward_rolling():
    model = WongReeceModel("CPS")
    wheel = WheelCircular(R, B)
    pose = Pose2D(0.0, R - 0.005)
    fwd = model.wrench(wheel, pose, Twist2D(0.2, 0.0, 2.0))
    back = model.wrench(wheel, pose, Twist2D(-0.2, 0.0, -2.0))
    assert back.fx == pytest.approx(-fwd.fx, rel=1e-12)
    assert back.fz == pytest.approx(fwd.fz, rel=1e-12)
    assert back.torque_y == pytest.approx(-fwd.torque_y, rel=1e-12)


def test_model_errors():
    model = WongReeceModel("LPS")
    wheel = WheelCircular(R, B)
    with pytest.raises(InputError, match="WheelCircular"):
        model.wrench(Plate(0.1, 0.1), Pose2D(), _twist(0.1))
    with pytest.raises(InputError, match="omega"):
        model.wrench(wheel, Pose2D(0.0, R - 0.01), Twist2D(0.1, 0.0, 0.0))
    with pytest.raises(InputError, match="slip"):
        model.wrench(wheel, Pose2D(0.0, R - 0.01), Twist2D(-0.1, 0.0, 1.0))
    with pytest.raises(InputError, match=r"pose\.z"):
        model.wrench(wheel, Pose2D(0.0, -0.05), _twist(0.1))
    with pytest.raises(InputError, match="bekker"):
        WongReeceModel(Material("rft-only"))
    with pytest.raises(InputError, match="exit_angle"):
        WongReeceModel("LPS", exit_angle=0.3)


def test_model_in_the_steady_wheel_solver_agrees_with_the_direct_solve():
    from terradyn.locomotion.steady import wheel_steady

    wheel = WheelCircular(R, B)
    for medium, slip in (("LPS", 0.3), ("MS", -0.3)):
        steady = wheel_steady(wheel, WongReeceModel(medium), 130.0, slip)
        direct = WongReeceModel(medium).wheel(wheel, 130.0, slip)
        assert steady.sinkage_m == pytest.approx(direct.sinkage, rel=1e-7)
        assert steady.drawbar_pull_N == pytest.approx(direct.drawbar_pull, rel=1e-6)
        assert steady.drive_torque_Nm == pytest.approx(direct.drive_torque, rel=1e-6)
        assert steady.entry_angle_rad == pytest.approx(direct.entry_angle, rel=1e-7)
