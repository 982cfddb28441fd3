"""Slip definitions (classic 1 - V/(omega r), bounded (omega r - V)/max(omega r, V)) and the solvers."""

from __future__ import annotations

import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.geometry import WheelCircular
from terradyn.kinematics import SlipDefinition, slip_convert, slip_from_speeds, speeds_from_slip
from terradyn.locomotion import wheel_steady


def test_bounded_is_continuous_through_omega_zero():
    v = 0.01  # carriage 10 mm/s, rim speed from -1 mm/s to 1 mm/s
    rims = np.linspace(-1e-3, 1e-3, 2001)
    s = np.array([slip_from_speeds(u, v) for u in rims])
    assert slip_from_speeds(0.0, v) == -1.0
    step = rims[1] - rims[0]
    assert np.max(np.diff(s)) <= step / v * (1.0 + 1e-6)  # no jump anywhere: slope 1/V on both sides
    assert np.all(np.diff(s) > 0.0)
    for eps in (1e-12, 1e-14):
        assert slip_from_speeds(eps, v) == pytest.approx(-1.0, abs=1e-9)
        assert slip_from_speeds(-eps, v) == pytest.approx(-1.0, abs=1e-9)


def test_bounded_range_and_antisymmetry():
    rng = np.random.default_rng(3)
    for u, v in rng.uniform(0.0, 0.2, size=(200, 2)):
        s = slip_from_speeds(u, v)
        assert -1.0 <= s <= 1.0
        assert slip_from_speeds(v, u) == pytest.approx(-s, abs=1e-15)
    assert slip_from_speeds(0.1, 0.0) == 1.0  # spinning in place


def test_definitions_agree_when_driving_and_convert_when_skidding():
    for s in (0.0, 0.2, 0.9, 1.0):
        assert slip_from_speeds(1.0, 1.0 - s, definition="classic") == pytest.approx(s)
        assert slip_from_speeds(1.0, 1.0 - s, definition="bounded") == pytest.approx(s)
    # classic -1 means V = 2 U: bounded (U - 2U)/(2U) = -0.5
    assert slip_convert(-1.0, source="classic", target="bounded") == pytest.approx(-0.5)
    for s in np.linspace(-0.99, 1.0, 50):
        back = slip_convert(
            slip_convert(s, source="bounded", target="classic"), source="classic", target="bounded"
        )
        assert back == pytest.approx(s, abs=1e-12)
    u, v = speeds_from_slip(-1.0, definition=SlipDefinition.BOUNDED, speed=0.01)
    assert (u, v) == (0.0, 0.01)


@pytest.mark.parametrize(
    ("call", "field"),
    [
        (lambda: slip_from_speeds(0.0, 0.0), "rim_speed"),
        (lambda: slip_from_speeds(0.0, 1.0, definition="classic"), "rim_speed"),
        (lambda: slip_from_speeds(1.0, -1.0), "carriage_speed"),
        (lambda: slip_convert(-1.0, source="bounded", target="classic"), "slip"),
        (lambda: speeds_from_slip(-1.5, definition="bounded"), "slip"),
        (lambda: slip_from_speeds(1.0, 1.0, definition="rig"), "slip_definition"),
    ],
)
def test_bad_input_names_field(call, field):
    with pytest.raises(InputError) as info:
        call()
    assert info.value.field == field


def test_2d_solver_locked_wheel_and_continuity():
    wheel, ms = WheelCircular(0.13, 0.16), materials.get("MS")
    locked = wheel_steady(wheel, ms, 130.0, -1.0, slip_definition="bounded")
    assert locked.omega_rad_s == 0.0 and locked.power_W == 0.0
    near = wheel_steady(wheel, ms, 130.0, -0.999, slip_definition="bounded")
    for key in ("sinkage_m", "drawbar_pull_N", "drive_torque_Nm"):
        assert getattr(near, key) == pytest.approx(getattr(locked, key), rel=2e-3)
    # a locked dragged wheel resists motion: pull negative, and the soil turns it forward (drive < 0)
    assert locked.drawbar_pull_N < 0.0 and locked.drive_torque_Nm < 0.0
    # the same skid state under both definitions gives the same forces
    classic = wheel_steady(wheel, ms, 130.0, -0.5, slip_definition="classic")
    bounded = wheel_steady(wheel, ms, 130.0, slip_convert(-0.5, source="classic", target="bounded"),
                           slip_definition="bounded")  # fmt: skip
    assert bounded.drawbar_pull_N == pytest.approx(classic.drawbar_pull_N, rel=1e-9)
    assert bounded.sinkage_m == pytest.approx(classic.sinkage_m, rel=1e-9)
