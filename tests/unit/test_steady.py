import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError, SolverError
from terradyn.geometry import WheelCircular
from terradyn.kinematics import Pose2D, Twist2D
from terradyn.locomotion import wheel_self_propelled, wheel_steady
from terradyn.rft import RFTModel, rft_wrench

MS = materials.get("MS")
WHEEL = WheelCircular(0.13, 0.16)


@pytest.mark.parametrize("slip", [-0.7, -0.1, 0.0, 0.3, 0.7])
def test_load_balance(slip):
    r = wheel_steady(WHEEL, MS, 130.0, slip)
    w = rft_wrench(WHEEL, MS, Pose2D(0, r.axle_height_m, 0), Twist2D(r.forward_velocity_m_s, 0, 1.0))
    assert w.fz == pytest.approx(130.0, rel=1e-6)
    assert r.drawbar_pull_N == pytest.approx(w.fx, rel=1e-9)
    assert r.drive_torque_Nm == pytest.approx(-w.torque_y, rel=1e-9)
    assert r.sinkage_m == pytest.approx(0.13 - r.axle_height_m, rel=1e-9)
    assert r.power_W == pytest.approx(r.drive_torque_Nm * 1.0)


def test_independent_of_omega():
    a = wheel_steady(WHEEL, MS, 130.0, 0.3, omega=0.5)
    b = wheel_steady(WHEEL, MS, 130.0, 0.3, omega=20.0)
    assert a.sinkage_m == pytest.approx(b.sinkage_m, rel=1e-9)
    assert a.drawbar_pull_N == pytest.approx(b.drawbar_pull_N, rel=1e-9)
    assert a.drive_torque_Nm == pytest.approx(b.drive_torque_Nm, rel=1e-9)


def test_monotonic_trends():
    sink = [wheel_steady(WHEEL, MS, w, 0.2).sinkage_m for w in (80, 130, 150, 190)]
    assert np.all(np.diff(sink) > 0)
    dp = [wheel_steady(WHEEL, MS, 130, s).drawbar_pull_N for s in np.linspace(-0.7, 0.7, 15)]
    assert np.all(np.diff(dp) > 0)


def test_free_rolling_slip_where_pull_crosses_zero():
    r = wheel_self_propelled(WHEEL, MS, 130.0)
    assert abs(r.drawbar_pull_N) < 1e-6
    assert 0.0 < r.slip < 0.5
    lo = wheel_steady(WHEEL, MS, 130.0, r.slip - 0.01).drawbar_pull_N
    hi = wheel_steady(WHEEL, MS, 130.0, r.slip + 0.01).drawbar_pull_N
    assert lo < 0 < hi
    loaded = wheel_self_propelled(WHEEL, MS, 130.0, drawbar_load=10.0)
    assert loaded.slip > r.slip
    assert loaded.drawbar_pull_N == pytest.approx(10.0, abs=1e-6)


def test_element_size_convergence_at_default_resolution():
    h = WHEEL.default_element_size
    a = wheel_steady(WHEEL, RFTModel(MS, element_size=h), 130.0, 0.3)
    b = wheel_steady(WHEEL, RFTModel(MS, element_size=h / 2), 130.0, 0.3)
    assert abs(a.drawbar_pull_N - b.drawbar_pull_N) / abs(b.drawbar_pull_N) < 0.005


@pytest.mark.parametrize("factor", [0.5, 2.0, 3.0])
def test_rft_scaling_keeps_slip_and_relative_sinkage(factor):
    # Forces scale as zeta L^3: scaling size by k and load by k^3 keeps sinkage/L and DP/W.
    base = wheel_steady(WHEEL, MS, 130.0, 0.25)
    big = WheelCircular(0.13 * factor, 0.16 * factor)
    scaled = wheel_steady(big, MS, 130.0 * factor**3, 0.25)
    assert scaled.sinkage_m / factor == pytest.approx(base.sinkage_m, rel=1e-4)
    assert scaled.drawbar_pull_N / factor**3 == pytest.approx(base.drawbar_pull_N, rel=1e-3)
    free = wheel_self_propelled(WHEEL, MS, 130.0).slip
    free_big = wheel_self_propelled(big, MS, 130.0 * factor**3).slip
    assert free_big == pytest.approx(free, abs=1e-4)


def test_bad_input():
    with pytest.raises(InputError, match="slip"):
        wheel_steady(WHEEL, MS, 130.0, 1.5)
    with pytest.raises(InputError, match="omega"):
        wheel_steady(WHEEL, MS, 130.0, 0.2, omega=0.0)
    with pytest.raises(InputError, match="load"):
        wheel_steady(WHEEL, MS, -5.0, 0.2)
    with pytest.raises(SolverError, match="carries at most"):
        wheel_steady(WHEEL, materials.get("LPS"), 5000.0, 0.2)
    with pytest.raises(SolverError, match="exceeds"):
        wheel_self_propelled(WHEEL, MS, 130.0, drawbar_load=500.0)


def test_grousered_wheel_periodic_average_and_extremes():
    from terradyn.geometry import WheelGrousered

    wheel = WheelGrousered(0.1, 0.1, grouser_count=10, grouser_height=0.01, grouser_thickness=0.004)
    r = wheel_steady(wheel, materials.get("CPS"), 60.0, 0.3, phase_count=12)
    assert r.phase_count == 12
    assert r.drawbar_pull_min_N <= r.drawbar_pull_N <= r.drawbar_pull_max_N
    assert r.vertical_force_min_N < 60.0 < r.vertical_force_max_N
    assert r.sinkage_min_m <= r.sinkage_m <= r.sinkage_max_m
    # The phase average converges as the phase resolution is refined.
    fine = wheel_steady(wheel, materials.get("CPS"), 60.0, 0.3, phase_count=48)
    assert fine.drawbar_pull_N == pytest.approx(r.drawbar_pull_N, rel=0.02)
    # Grousers give more pull than a plain rim of the same outer radius at the same slip.
    plain = wheel_steady(WheelCircular(0.11, 0.1), materials.get("CPS"), 60.0, 0.3)
    assert r.drawbar_pull_N > plain.drawbar_pull_N


def test_flapped_wheel_self_propelled():
    from terradyn.optimize import flapped_wheel_performance

    perf = flapped_wheel_performance(
        materials.get("CPS"),
        hub_radius=0.05,
        width=0.05,
        flap_count=6,
        flap_length=0.03,
        flap_angle=0.0,
        load=10.0,
        phase_count=12,
    )
    assert 0.0 < perf["velocity_normalised"] <= 1.0
    assert perf["cost_of_transport"] > 0


def test_flapped_wheel_dynamic_average_matches_quasi_static():
    from terradyn.optimize import flapped_wheel_performance

    kw = dict(
        hub_radius=0.05, width=0.05, flap_count=6, flap_length=0.03, flap_angle=0.0, load=10.0, omega=2.0
    )
    quasi = flapped_wheel_performance(materials.get("CPS"), **kw)
    dyn = flapped_wheel_performance(materials.get("CPS"), method="dynamic", **kw)
    assert dyn["velocity_normalised"] == pytest.approx(quasi["velocity_normalised"], abs=0.01)


def test_c_leg_whose_reach_varies_with_phase_is_solved():
    # The C-leg's lowest point moves by a whole diameter over a turn; the solver must bracket the
    # load from the height at which no phase touches (regression: it used the shallowest phase).
    from terradyn.geometry import CLeg

    leg = CLeg(radius=0.05, width=0.02)
    r = wheel_steady(leg, materials.get("poppy-cp"), 2.0, 0.2, phase_count=16)
    assert r.vertical_force_min_N < 2.0 < r.vertical_force_max_N
    assert r.sinkage_min_m < r.sinkage_m < r.sinkage_max_m
