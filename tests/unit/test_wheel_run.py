"""The one wheel-run contract: one case, any model and engine, the same result keys, clear refusals."""

from __future__ import annotations

import math

import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.geometry import WheelCircular, WheelGrousered
from terradyn.locomotion import (
    DEMSettings,
    Dynamics,
    Engine,
    MPMSettings,
    QuasiStatic,
    WheelCase,
    run_wheel,
    wheel_steady,
)
from terradyn.locomotion.wheel_case import HISTORY_KEYS, SUMMARY_KEYS
from terradyn.rft import RFTModel, rft_wrench

WHEEL = WheelCircular(0.05, 0.03)


def test_every_force_law_gives_the_same_keys():
    case = WheelCase(WHEEL, "MS", load=5.0, slip=0.3)
    for model in ("rft", "drft", "rft-ss", "wong-reece", "rft3d"):
        run = run_wheel(case, model)
        assert run.engine is Engine.QUASI_STATIC and run.model == model
        assert tuple(run.summary) == SUMMARY_KEYS
        assert run.summary["vertical_force_N"] == pytest.approx(5.0, rel=1e-3)
        assert (run.summary["side_force_N"] is None) == (model != "rft3d")
        assert run.to_dict()["engine"] == "quasi-static"


def test_quasi_static_run_is_the_steady_solve():
    case = WheelCase(WheelGrousered(0.05, 0.03, 8, 0.006, 0.003), "MMS", load=6.0, slip=0.2, omega=2.0)
    run = run_wheel(case, "rft", settings=QuasiStatic(phase_count=8))
    ref = wheel_steady(case.wheel, materials.get("MMS"), 6.0, 0.2, omega=2.0, phase_count=8)
    assert run.summary["drawbar_pull_N"] == ref.drawbar_pull_N
    assert run.summary["sinkage_m"] == ref.sinkage_m


def test_time_integration_reaches_the_quasi_static_answer():
    """The slow wheel integrated in time (x prescribed by the slip, z free under the load; the coupled
    driver) settles where the implicit steady solve puts it: two independent routes to one state."""
    case = WheelCase(WHEEL, "MS", load=5.0, slip=0.3, duration=4.0)
    steady = run_wheel(case, "rft").summary
    dynamic = run_wheel(case, "rft", settings=Dynamics())
    assert dynamic.engine is Engine.DYNAMICS
    assert set(dynamic.history) <= set(HISTORY_KEYS) and dynamic.history["time_s"].size > 10
    assert dynamic.summary["sinkage_m"] == pytest.approx(steady["sinkage_m"], rel=0.05)
    assert dynamic.summary["drive_torque_Nm"] == pytest.approx(steady["drive_torque_Nm"], rel=0.05)
    assert dynamic.summary["drawbar_pull_N"] == pytest.approx(steady["drawbar_pull_N"], abs=0.02 * 5.0)
    # a free wheel: the compiled integrator settles at the self-propelled slip of the steady solve
    free = WheelCase(WHEEL, "MS", load=5.0)
    rolling = run_wheel(free, "rft", settings=Dynamics())
    assert rolling.summary["slip"] == pytest.approx(run_wheel(free, "rft").summary["slip"], abs=0.01)


def test_speeds_and_locked_wheels():
    locked = WheelCase(WHEEL, "MS", load=5.0, rim_speed=0.0, carriage_speed=0.05, slip_definition="bounded")
    assert locked.drive() == (-1.0, pytest.approx(1.0))
    run = run_wheel(locked, "rft")
    assert run.summary["slip"] == -1.0 and run.summary["drawbar_pull_N"] < 0.0  # a dragged wheel resists
    from terradyn.locomotion._wheel_engines import _mpm_spin

    assert _mpm_spin(locked) == ({"omega": 0.0}, {"forward_speed": 0.05})


def test_a_user_model_runs_like_a_named_one():
    ms = materials.get("MS")

    class Mine:
        name = "mine"

        def wrench(self, body, pose, twist, *, about=None):
            return rft_wrench(body, ms, pose, twist, about=about)

    case = WheelCase(WHEEL, ms, load=5.0, slip=0.3)
    for model in (Mine(), RFTModel(ms), lambda b, p, t: rft_wrench(b, ms, p, t)):
        run = run_wheel(case, model)
        assert run.summary["sinkage_m"] == pytest.approx(
            run_wheel(case, "rft").summary["sinkage_m"], rel=1e-4
        )


@pytest.mark.parametrize(
    ("case", "model", "settings", "field"),
    [
        (dict(load=5.0, slip=0.3, slip_angle=0.2), "rft", None, "slip_angle"),
        (dict(load=5.0, drive_torque=0.1), "rft", None, "drive_torque"),
        (dict(load=5.0), "dem", None, "slip"),
        (dict(load=5.0, slip=0.3), "mpm", QuasiStatic(), "settings"),
        (dict(sinkage=0.01, slip=0.3), "mpm", MPMSettings(), "sinkage"),
        (dict(load=5.0, slip=0.3), "bekker", None, "model"),
        (dict(load=5.0, slip=0.3, drawbar_load=1.0), "dem", DEMSettings(), "drawbar_load"),
    ],
)
def test_refusals_name_the_field(case, model, settings, field):
    with pytest.raises(InputError) as info:
        run_wheel(WheelCase(WHEEL, "MS", **case), model, settings=settings)
    assert info.value.field == field


def test_case_checks():
    with pytest.raises(InputError, match="exactly one"):
        WheelCase(WHEEL, "MS", load=5.0, sinkage=0.01)
    with pytest.raises(InputError, match="slip_angle"):
        WheelCase(WHEEL, "MS", load=5.0, slip=0.1, slip_angle=math.pi / 2)
    with pytest.raises(InputError, match="rim_speed"):
        WheelCase(WHEEL, "MS", load=5.0, rim_speed=0.1)
    with pytest.raises(InputError, match="load"):
        WheelCase(WHEEL, "MS", load=float("nan"), slip=0.1)
    assert np.isclose(WheelCase(WHEEL, "MS", load=1.0).radius, 0.05)
