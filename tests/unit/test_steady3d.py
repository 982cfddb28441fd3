"""Steady 3D-RFT wheel solves: load balance, symmetry, slip-angle parity, invariances, errors."""

import math
import re

import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError, SolverError
from terradyn.geometry3d import (
    Pose3D,
    Twist3D,
    load_mesh,
    rotation_from_rpy,
    wheel_cylinder,
    wheel_grousered,
)
from terradyn.locomotion.steady3d import (
    WheelSteady3DResult,
    steady3d_record,
    sweep_3d,
    wheel_nominal_radius_3d,
    wheel_period_3d,
    wheel_steady_3d,
)
from terradyn.rft.rft3d import rft3d_wrench

R, W = 0.13, 0.16
MS = materials.get("MS")


@pytest.fixture(scope="module")
def wheel():
    return wheel_cylinder(R, W, circumferential_resolution=120, axial_resolution=4, radial_resolution=2)


@pytest.fixture(scope="module")
def grousered():
    return wheel_grousered(
        R, W, grouser_count=12, grouser_height=0.01, grouser_thickness=0.006,
        circumferential_resolution=120, axial_resolution=2, radial_resolution=1,
    )  # fmt: skip


@pytest.mark.parametrize(
    ("load", "slip", "angle_deg"),
    [(80.0, 0.0, 0.0), (150.0, 0.4, 15.0), (40.0, -0.6, -30.0), (80.0, 1.0, 5.0)],
)
def test_load_balance(wheel, load, slip, angle_deg):
    r = wheel_steady_3d(wheel, MS, load, slip, slip_angle=math.radians(angle_deg))
    assert r.vertical_force_N == pytest.approx(load, rel=1e-6)
    assert r.sinkage_m > 0 and r.axle_height_m == pytest.approx(R - r.sinkage_m, abs=1e-12)
    assert r.longitudinal_velocity_m_s == pytest.approx((1 - slip) * R)
    assert r.lateral_velocity_m_s == pytest.approx(
        r.longitudinal_velocity_m_s * math.tan(math.radians(angle_deg))
    )
    assert r.power_W == pytest.approx(r.drive_torque_Nm * r.omega_rad_s)


def test_load_balance_periodic_wheel(grousered):
    r = wheel_steady_3d(grousered, MS, 100.0, 0.3, phase_count=6, period=2 * math.pi / 12)
    assert r.vertical_force_N == pytest.approx(100.0, rel=1e-6)
    assert r.vertical_force_min_N < 100.0 < r.vertical_force_max_N
    assert r.drawbar_pull_min_N <= r.drawbar_pull_N <= r.drawbar_pull_max_N
    assert r.sinkage_min_m <= r.sinkage_m <= r.sinkage_max_m
    assert r.nominal_radius_m == pytest.approx(wheel_nominal_radius_3d(grousered))
    assert r.nominal_radius_m > R + 0.0099


def test_cylinder_phases_match_single_phase(wheel):
    # 120 rim quads: quarter turns map the mesh onto itself, so the average equals one phase.
    one = wheel_steady_3d(wheel, MS, 80.0, 0.3)
    four = wheel_steady_3d(wheel, MS, 80.0, 0.3, phase_count=4, period=2 * math.pi)
    for key in ("sinkage_m", "drawbar_pull_N", "drive_torque_Nm"):
        assert getattr(four, key) == pytest.approx(getattr(one, key), rel=1e-9)
    assert four.drawbar_pull_max_N - four.drawbar_pull_min_N < 1e-9 * abs(one.drawbar_pull_N)
    # Over the detected period (one rim quad) the facet ripple is small.
    ripple = wheel_steady_3d(wheel, MS, 80.0, 0.3, phase_count=4)
    assert ripple.period_rad == pytest.approx(2 * math.pi / 120)
    assert ripple.sinkage_m == pytest.approx(one.sinkage_m, rel=2e-3)


@pytest.mark.parametrize("slip", [-0.5, 0.0, 0.3, 0.8])
def test_mirror_symmetry_at_zero_slip_angle(wheel, slip):
    r = wheel_steady_3d(wheel, MS, 80.0, slip)
    assert abs(r.side_force_N) < 1e-10 * 80.0
    assert abs(r.aligning_moment_Nm) < 1e-10 * 80.0 * R
    assert abs(r.overturning_moment_Nm) < 1e-10 * 80.0 * R
    assert r.contact_y_min_m == pytest.approx(-r.contact_y_max_m, abs=1e-15)


@pytest.mark.parametrize("slip", [-0.3, 0.3])
def test_slip_angle_parity(wheel, slip):
    a = math.radians(12.0)
    plus = wheel_steady_3d(wheel, MS, 80.0, slip, slip_angle=a)
    minus = wheel_steady_3d(wheel, MS, 80.0, slip, slip_angle=-a)
    straight = wheel_steady_3d(wheel, MS, 80.0, slip)
    # ISO sign: velocity to the left (+) -> the soil pushes the wheel to the right.
    assert plus.side_force_N < -0.05 * 80.0
    assert minus.side_force_N == pytest.approx(-plus.side_force_N, rel=1e-9)
    assert minus.aligning_moment_Nm == pytest.approx(-plus.aligning_moment_Nm, rel=1e-9)
    assert minus.overturning_moment_Nm == pytest.approx(-plus.overturning_moment_Nm, rel=1e-9)
    for key in ("drawbar_pull_N", "drive_torque_Nm", "sinkage_m"):
        assert getattr(minus, key) == pytest.approx(getattr(plus, key), rel=1e-9)
    # The leading side wall bulldozes: the wheel sinks deeper than when rolling straight.
    assert plus.sinkage_m > straight.sinkage_m
    assert plus.contact_y_max_m - plus.contact_y_min_m == pytest.approx(plus.contact_width_m)


def test_side_force_grows_with_slip_angle(wheel):
    forces = [
        -wheel_steady_3d(wheel, MS, 80.0, 0.2, slip_angle=math.radians(a)).side_force_N
        for a in (2, 5, 10, 20)
    ]
    assert forces[0] > 0 and np.all(np.diff(forces) > 0)


def test_independent_of_omega(wheel):
    base = wheel_steady_3d(wheel, MS, 80.0, 0.3, slip_angle=0.1)
    fast = wheel_steady_3d(wheel, MS, 80.0, 0.3, slip_angle=0.1, omega=7.5)
    for key in ("sinkage_m", "drawbar_pull_N", "side_force_N", "drive_torque_Nm", "aligning_moment_Nm"):
        assert getattr(fast, key) == pytest.approx(getattr(base, key), rel=1e-9)
    assert fast.power_W == pytest.approx(7.5 * base.power_W, rel=1e-9)


def test_heading_does_not_matter(wheel):
    """The wheel-frame wrench equals the world wrench of the yawed wheel rotated back (isotropy)."""
    r = wheel_steady_3d(wheel, MS, 80.0, 0.3, slip_angle=0.2)
    yaw = 0.7
    rot = rotation_from_rpy(0.0, 0.0, yaw)
    pose = Pose3D(np.array([1.0, -2.0, r.axle_height_m]), rot)
    twist = Twist3D(rot @ [r.longitudinal_velocity_m_s, r.lateral_velocity_m_s, 0.0], rot @ [0.0, 1.0, 0.0])
    w = rft3d_wrench(wheel, MS, pose, twist)
    force, moment = rot.T @ w.force, rot.T @ w.moment
    expected = [r.drawbar_pull_N, r.side_force_N, r.vertical_force_N]
    np.testing.assert_allclose(force, expected, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(
        moment, [r.overturning_moment_Nm, -r.drive_torque_Nm, r.aligning_moment_Nm], rtol=1e-9, atol=1e-9
    )


def test_convergence_with_facet_size():
    def solve(n):
        mesh = wheel_cylinder(R, W, circumferential_resolution=n, axial_resolution=1, radial_resolution=1)
        r = wheel_steady_3d(mesh, MS, 80.0, 0.3)
        return np.array([r.sinkage_m, r.drawbar_pull_N, r.drive_torque_Nm])

    ref = solve(1440)
    errors = [np.max(np.abs(solve(n) / ref - 1.0)) for n in (45, 90, 180, 360)]
    assert np.all(np.diff(errors) < 0), errors
    assert errors[-1] < 5e-3
    # Roughly first order (or better) in facet size.
    assert errors[0] / errors[-1] > 4.0


def test_mesh_round_trip(tmp_path, wheel):
    trimesh = pytest.importorskip("trimesh")
    path = tmp_path / "wheel.stl"
    trimesh.Trimesh(vertices=np.array(wheel.vertices), faces=np.array(wheel.faces), process=False).export(
        path
    )
    loaded = load_mesh(path)
    assert loaded.facet_count == wheel.facet_count
    a = wheel_steady_3d(wheel, MS, 80.0, 0.3, slip_angle=0.1)
    b = wheel_steady_3d(loaded, MS, 80.0, 0.3, slip_angle=0.1)
    # STL stores float32 coordinates: agreement to single precision.
    for key in ("sinkage_m", "drawbar_pull_N", "side_force_N", "drive_torque_Nm", "aligning_moment_Nm"):
        assert getattr(b, key) == pytest.approx(getattr(a, key), rel=1e-5)


def test_medium_as_xi(wheel):
    from terradyn.rft.rft3d import agarwal2023_xi_material

    a = wheel_steady_3d(wheel, MS, 80.0, 0.3)
    b = wheel_steady_3d(wheel, agarwal2023_xi_material(MS), 80.0, 0.3)
    assert b.drawbar_pull_N == pytest.approx(a.drawbar_pull_N, rel=1e-12)


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"slip": 1.2}, "slip"),
        ({"slip": -1.01}, "slip"),
        ({"slip_angle": math.pi / 2}, "slip_angle"),
        ({"slip_angle": -1.6}, "slip_angle"),
        ({"load": 0.0}, "load"),
        ({"omega": 0.0}, "omega"),
        ({"phase_count": 0}, "phase_count"),
        ({"period": -1.0}, "period"),
        ({"nominal_radius": -0.1}, "nominal_radius"),
    ],
)
def test_bad_input_names_field(wheel, kwargs, field):
    args = {"load": 80.0, "slip": 0.3, **kwargs}
    load, slip = args.pop("load"), args.pop("slip")
    with pytest.raises(InputError) as info:
        wheel_steady_3d(wheel, MS, load, slip, **args)
    assert info.value.field == field


def test_bad_mesh_and_medium(wheel):
    with pytest.raises(InputError, match="mesh"):
        wheel_steady_3d("wheel.stl", MS, 80.0, 0.3)  # type: ignore[arg-type]
    with pytest.raises(InputError, match="internal_friction_angle"):
        wheel_steady_3d(wheel, materials.get("poppy-cp"), 80.0, 0.3)


def test_load_too_large_names_the_maximum(wheel):
    with pytest.raises(SolverError, match="at most") as info:
        wheel_steady_3d(wheel, MS, 1e6, 0.3)
    carried = float(re.search(r"at most ([0-9.e+]+) N", str(info.value)).group(1))
    twist = Twist3D.from_components((1 - 0.3) * R, wy=1.0)
    fmax = rft3d_wrench(wheel, MS, Pose3D.from_rpy(0.0, 0.0, 0.0), twist).force[2]
    assert carried == pytest.approx(fmax, rel=1e-5)


def test_record_and_sweep(wheel):
    r = wheel_steady_3d(wheel, MS, 80.0, 0.3, slip_angle=math.radians(5.0))
    assert isinstance(r, WheelSteady3DResult)
    rec = steady3d_record(r)
    assert set(rec) == {
        "sinkage_m", "drawbar_pull_N", "drive_torque_Nm", "power_W", "side_force_N", "aligning_moment_Nm",
        "vertical_force_N", "slip", "slip_angle_deg",
    }  # fmt: skip
    assert rec["slip_angle_deg"] == pytest.approx(5.0)
    assert all(isinstance(v, float) and math.isfinite(v) for v in rec.values())
    t = sweep_3d(wheel, MS, [80.0, 1e6], [0.0, 0.3], [0.0, 0.1])
    assert len(t) == 8
    solved = t.columns["solved"].astype(bool)
    assert solved.sum() == 4 and np.all(t.columns["load_N"][solved] == 80.0)
    assert len(t.metadata["failures"]) == 4
    row = np.nonzero(solved & (t.columns["slip"] == 0.3) & (t.columns["slip_angle_rad"] == 0.0))[0][0]
    assert t.columns["drawbar_pull_N"][row] == pytest.approx(
        wheel_steady_3d(wheel, MS, 80.0, 0.3).drawbar_pull_N
    )


def test_contact_patch_matches_reference(wheel):
    from terradyn.rft.rft3d import rft3d_facet_forces

    r = wheel_steady_3d(wheel, MS, 80.0, 0.3, slip_angle=0.15)
    pose = Pose3D.from_rpy(0.0, 0.0, r.axle_height_m)
    twist = Twist3D.from_components(r.longitudinal_velocity_m_s, r.lateral_velocity_m_s, wy=1.0)
    ff = rft3d_facet_forces(wheel, MS, pose, twist)
    rel = ff.centroids[ff.active] - pose.position
    assert r.contact_x_min_m == pytest.approx(rel[:, 0].min(), abs=1e-12)
    assert r.contact_x_max_m == pytest.approx(rel[:, 0].max(), abs=1e-12)
    assert r.contact_y_min_m == pytest.approx(rel[:, 1].min(), abs=1e-12)
    assert r.contact_y_max_m == pytest.approx(rel[:, 1].max(), abs=1e-12)
    assert r.entry_angle_rad == pytest.approx(np.arctan2(rel[:, 0], -rel[:, 2]).max(), abs=1e-12)
    # The left side wall leads at a positive slip angle: the patch reaches y = +width / 2.
    assert r.contact_y_max_m > 0.5 * W - 1e-3
    assert 0.0 < r.contact_length_m < r.nominal_radius_m


def test_period_detection(tmp_path, wheel, grousered):
    from terradyn.geometry3d import save_mesh

    assert wheel_period_3d(grousered) == pytest.approx(2 * math.pi / 12, rel=1e-12)
    assert wheel_period_3d(wheel) == pytest.approx(2 * math.pi / 120, rel=1e-12)
    pytest.importorskip("trimesh")
    loaded = load_mesh(save_mesh(grousered, tmp_path / "grousered.stl"))
    assert wheel_period_3d(loaded) == pytest.approx(2 * math.pi / 12, rel=1e-12)
    auto = wheel_steady_3d(grousered, MS, 100.0, 0.3, phase_count=6)
    given = wheel_steady_3d(grousered, MS, 100.0, 0.3, phase_count=6, period=2 * math.pi / 12)
    assert auto.period_rad == pytest.approx(given.period_rad)
    assert auto.drawbar_pull_N == pytest.approx(given.drawbar_pull_N, rel=1e-9)
