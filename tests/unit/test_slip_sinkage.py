"""Slip-sinkage RFT: reduces to RFT when off, sinkage grows with slip, the surface profile's invariants."""

from __future__ import annotations

import math

import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.geometry import WheelCircular, WheelGrousered
from terradyn.geometry3d import wheel_cylinder
from terradyn.kinematics import Pose2D, Twist2D
from terradyn.locomotion import wheel_steady
from terradyn.replay import ReplayModel, replay, runs_from_records
from terradyn.replay.synthetic import design_runs, synthetic_records
from terradyn.rft import RFTModel
from terradyn.rft.rft3d import agarwal2023_xi_material, rft3d_wrench_many
from terradyn.rft.slip_sinkage import (
    SlipSinkageParameters,
    SlipSinkageRFTModel,
    slip_sinkage_surface,
    slip_sinkage_wrench_3d,
)

MS = materials.get("MS")
WHEEL = WheelCircular(0.0625, 0.06)
LUGGED = WheelGrousered(0.0625, 0.06, 12, 0.00625, 0.003125)
OFF = SlipSinkageParameters.off()


@pytest.mark.parametrize("body", [WHEEL, LUGGED], ids=["circular", "grousered"])
@pytest.mark.parametrize(("vx", "omega"), [(0.05, 1.0), (0.0625, 1.0), (0.12, 1.0), (0.03, 0.0), (0.0, 1.0)])
def test_off_is_plane_rft_to_rounding(body, vx, omega):
    model = SlipSinkageRFTModel(MS, OFF)
    for z, theta in ((0.055, 0.0), (0.05, 0.3), (0.04, -1.1)):
        a = model.wrench(body, Pose2D(0.01, z, theta), Twist2D(vx, -0.001, omega)).as_array()
        b = RFTModel(MS).wrench(body, Pose2D(0.01, z, theta), Twist2D(vx, -0.001, omega)).as_array()
        assert np.allclose(a, b, rtol=1e-12, atol=1e-12 * np.abs(b).max()), (a, b)


def test_off_steady_solve_is_the_rft_solve():
    for s in (-0.5, 0.0, 0.4, 0.8):
        a = wheel_steady(WHEEL, SlipSinkageRFTModel(MS, OFF), 20.0, s)
        b = wheel_steady(WHEEL, RFTModel(MS), 20.0, s)
        assert a.sinkage_m == pytest.approx(b.sinkage_m, rel=1e-9)
        assert a.drawbar_pull_N == pytest.approx(b.drawbar_pull_N, rel=1e-8, abs=1e-9)
        assert a.drive_torque_Nm == pytest.approx(b.drive_torque_Nm, rel=1e-8, abs=1e-9)


def test_off_3d_is_rft3d_to_rounding():
    mesh = wheel_cylinder(0.0625, 0.06, circumferential_resolution=120, axial_resolution=2)
    xi = agarwal2023_xi_material(MS)
    heights = np.array([0.06, 0.05, 0.04])
    rot = np.eye(3)[None]
    for linear in ([0.05, 0.0, 0.0], [0.03, 0.03, 0.0], [0.0, 0.02, 0.0]):
        lin, ang = np.array(linear), np.array([0.0, 1.0, 0.0])
        a = slip_sinkage_wrench_3d(mesh, xi, heights, rot, lin, ang, OFF, surface_friction=0.4)[:, 0]
        pos = np.column_stack((np.zeros(3), np.zeros(3), heights))
        b = rft3d_wrench_many(
            mesh,
            xi,
            pos,
            np.repeat(rot, 3, axis=0),
            np.tile(lin, (3, 1)),
            np.tile(ang, (3, 1)),
            surface_friction=0.4,
        )
        assert np.allclose(a, b, rtol=1e-10, atol=1e-10 * np.abs(b).max())


def test_replay_with_the_effect_off_gives_the_rft_predictions():
    recs = synthetic_records(ReplayModel("rft"), design_runs(loads=(20.0,), slips=(-1.0, -0.3, 0.3, 0.8)))
    t = runs_from_records(recs)
    a = replay(t, ReplayModel("rft-ss", excavation=0.0, bulldozing=0.0, phase_count=4))
    b = replay(t, ReplayModel("rft", phase_count=4))
    for ra, rb in zip(a.runs, b.runs, strict=True):
        for q in ("sinkage_m", "drawbar_pull_N", "drive_torque_Nm"):
            assert ra[f"predicted_{q}"] == pytest.approx(rb[f"predicted_{q}"], rel=1e-8, abs=1e-9)


def test_sinkage_rises_with_slip_and_pull_saturates_on_a_circular_wheel():
    model, plain = SlipSinkageRFTModel(MS), RFTModel(MS)
    slips = (0.0, 0.2, 0.4, 0.6, 0.8)
    ss = [wheel_steady(WHEEL, model, 20.0, s) for s in slips]
    rft = [wheel_steady(WHEEL, plain, 20.0, s) for s in slips]
    sink = np.array([r.sinkage_m for r in ss])
    extra = sink - np.array([r.sinkage_m for r in rft])
    assert np.all(np.diff(sink) > 0)
    assert extra[0] == pytest.approx(0.0, abs=1e-12)  # no slip velocity at s = 0: no excavation
    assert np.all(np.diff(extra) > 0)  # the slip sinkage itself grows with slip
    dp_ss = np.array([r.drawbar_pull_N for r in ss])
    dp_rft = np.array([r.drawbar_pull_N for r in rft])
    assert np.all(dp_ss[1:] < dp_rft[1:])
    assert dp_ss[4] - dp_ss[2] < 0.5 * (dp_rft[4] - dp_rft[2])  # the pull levels off


def test_sinkage_grows_with_the_excavation_coefficient_and_skids_dig_in_too():
    sink = [
        wheel_steady(WHEEL, SlipSinkageRFTModel(MS, SlipSinkageParameters(excavation=k)), 20.0, 0.5).sinkage_m
        for k in (0.0, 0.25, 0.5, 1.0)
    ]
    assert np.all(np.diff(sink) > 0)
    skid = wheel_steady(WHEEL, SlipSinkageRFTModel(MS), 20.0, -1.0).sinkage_m  # V = 2 omega r
    assert skid > wheel_steady(WHEEL, RFTModel(MS), 20.0, -1.0).sinkage_m


def test_bulldozing_raises_the_resistance_of_a_skidding_wheel_and_the_side_force():
    dozer = SlipSinkageRFTModel(MS, SlipSinkageParameters(excavation=0.0, bulldozing=1.0))
    a = wheel_steady(WHEEL, dozer, 20.0, -0.9)
    b = wheel_steady(WHEEL, RFTModel(MS), 20.0, -0.9)
    assert a.drawbar_pull_N < b.drawbar_pull_N < 0  # more resistance from the berm in front
    driving = wheel_steady(WHEEL, dozer, 20.0, 0.5)  # a driving contact pushes nothing forward
    assert driving.sinkage_m == pytest.approx(
        wheel_steady(WHEEL, RFTModel(MS), 20.0, 0.5).sinkage_m, rel=1e-9
    )
    mesh = wheel_cylinder(0.0625, 0.06, circumferential_resolution=120, axial_resolution=2)
    xi = agarwal2023_xi_material(MS)
    lin, ang = np.array([0.0, 0.02, 0.0]), np.array([0.0, 0.0, 0.0])  # sliding sideways, locked
    side = [
        slip_sinkage_wrench_3d(mesh, xi, np.array([0.05]), np.eye(3)[None], lin, ang, p)[0, 0, 1]
        for p in (OFF, SlipSinkageParameters(excavation=0.0, bulldozing=1.0))
    ]
    assert side[1] < side[0] < 0  # the berm against the side face resists the slide more


def test_surface_profile_invariants():
    p = SlipSinkageParameters(excavation=0.5, bulldozing=1.0, repose_angle=math.radians(30))
    x = np.linspace(-0.08, 0.08, 3201)
    d, front = 0.01, 0.035
    h = slip_sinkage_surface(
        x, front=front, bottom=0.0, sinkage=d, excavation_ratio=1.0, push_ratio=0.0, parameters=p
    )
    assert np.all(h[x >= front] == 0.0) and np.all(h <= 0.0)
    assert h[np.argmin(np.abs(x))] == pytest.approx(-0.5 * d)  # full drop at the lowest point
    assert np.all(h[x <= 0.0] == pytest.approx(-0.5 * d))  # and behind it
    slope = np.abs(np.diff(h) / np.diff(x))
    assert slope.max() <= math.tan(p.repose_angle) * (1 + 1e-9)
    deep = slip_sinkage_surface(
        x, front=front, bottom=0.0, sinkage=d, excavation_ratio=math.inf, push_ratio=0.0, parameters=p
    )
    assert np.allclose(deep[x < front], -(front - x[x < front]) * math.tan(p.repose_angle))  # repose-limited
    berm = slip_sinkage_surface(
        x, front=front, bottom=0.0, sinkage=d, excavation_ratio=0.0, push_ratio=1.0, parameters=p
    )
    assert berm.max() == pytest.approx(d) and np.all(berm[x < front] == 0.0)
    ahead = x >= front  # the berm leans on the wheel's front face and falls off ahead at the repose angle
    assert np.abs(np.diff(berm[ahead]) / np.diff(x[ahead])).max() <= math.tan(p.repose_angle) * (1 + 1e-9)
    flat = slip_sinkage_surface(
        x, front=front, bottom=0.0, sinkage=d, excavation_ratio=0.0, push_ratio=0.0, parameters=p
    )
    assert np.all(flat == 0.0)


@pytest.mark.parametrize(
    ("field", "value"), [("excavation", -0.1), ("bulldozing", float("nan")), ("repose_angle", 2.0)]
)
def test_bad_parameters_are_refused(field, value):
    with pytest.raises(InputError, match=field):
        SlipSinkageParameters(**{field: value})


def test_replay_calibration_recovers_the_excavation_coefficient():
    """A table made by rft-ss with excavation 0.8 (no noise): fitting scale, excavation and bulldozing
    from the defaults (1, 0.5, 1) recovers 0.8 within 0.1 and the scale within 3 %."""
    runs = design_runs(loads=(20.0,), slips=(-0.6, -0.2, 0.2, 0.4, 0.6), grousered=False)
    truth = ReplayModel("rft-ss", excavation=0.8, bulldozing=1.0)
    t = runs_from_records(synthetic_records(truth, runs))
    res = replay(t, ReplayModel("rft-ss"), calibrate_on=0.8, seed=1)
    fit = res.calibration.parameters
    assert fit["excavation"] == pytest.approx(0.8, abs=0.1)
    assert fit["scale"] == pytest.approx(1.0, rel=0.03)


def test_3d_replay_with_the_effect_off_matches_the_compiled_rft3d_solve():
    """rft3d-ss runs through terradyn.replay.solve (Python root find on rft3d_facet_tractions), rft3d
    through the compiled wheel_steady_3d: two independent paths, same answer when the effect is off."""
    runs = design_runs(loads=(20.0,), slips=(-1.0, 0.4), grousered=False, slip_angles_deg=(0.0, 90.0))
    runs.append({**runs[1], "run_id": "sinkage", "load_N": None, "prescribed_sinkage_m": 0.012})
    t = runs_from_records([{**r, "drawbar_pull_N": 0.0} for r in runs])
    a = replay(t, ReplayModel("rft3d-ss", excavation=0.0, bulldozing=0.0))
    b = replay(t, ReplayModel("rft3d"))
    for ra, rb in zip(a.runs, b.runs, strict=True):
        assert ra["solved"] and rb["solved"], (ra["reason"], rb["reason"])
        assert ra["predicted_sinkage_m"] == pytest.approx(rb["predicted_sinkage_m"], rel=1e-7)
        for q in ("drawbar_pull_N", "side_force_N", "drive_torque_Nm"):
            assert ra[f"predicted_{q}"] == pytest.approx(rb[f"predicted_{q}"], rel=1e-6, abs=1e-7), q
