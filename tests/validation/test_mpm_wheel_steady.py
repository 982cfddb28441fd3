"""Forced-slip MPM wheels settle: the drawbar pull reaches a steady value during the drive (read from
its time series, not from a cut-off window) and rises with slip, and so does the sinkage.

The 0.13 m x 0.16 m wheel on MS under 130 N at 11 mm cells (diameter / 24; the default is / 32, see
docs/mpm.md for the resolution study), 4 rad of drive. Slow: three runs. (At 16 mm cells the pull at
slip 0.5 still drifted by 1.7 N between the last two quarters of a 4.5 rad drive.)
"""

from __future__ import annotations

import math

import pytest

from terradyn import materials
from terradyn.geometry import WheelCircular, WheelGrousered
from terradyn.mpm import Drive, Resolution, run_wheel


@pytest.mark.slow
def test_forced_slip_pull_is_steady_and_rises_with_slip():
    wheel, ms = WheelCircular(0.13, 0.16), materials.get("MS")
    pulls, sinkages = [], []
    for slip in (0.1, 0.3, 0.5):
        res = run_wheel(wheel, ms, load=130.0, omega=1.0, slip=slip, cell_size=0.011, duration=4.0)
        drive = res.series["phase"] == "drive"
        pull = res.series["drawbar_pull_N"][drive]
        quarter = len(pull) // 4
        # steady: the means of the last two quarters of the drive agree within 1 % of the load
        assert abs(pull[-quarter:].mean() - pull[-2 * quarter : -quarter].mean()) < 1.3, slip
        pulls.append(res.summary["drawbar_pull_N"])
        sinkages.append(res.summary["sinkage_m"])
    assert pulls[0] < pulls[1] < pulls[2], pulls
    assert sinkages[0] < sinkages[1] < sinkages[2], sinkages


def _quarters(res, radius):
    """Mean slip of each quarter of a self-propelled drive, and the sink rate [m/s] from the second
    quarter's mean sinkage to the last's (means, not end points: lug passings ripple the sinkage)."""
    s = res.series
    drive = s["phase"] == "drive"
    t, z = s["time_s"][drive], s["sinkage_m"][drive]
    slip = 1.0 - s["vx_m_s"][drive] / (s["omega_rad_s"][drive] * radius)
    q = len(t) // 4
    cut = [slice(i * q, (i + 1) * q) for i in range(4)]
    rate = (z[cut[3]].mean() - z[cut[1]].mean()) / (t[cut[3]].mean() - t[cut[1]].mean())
    return [float(slip[c].mean()) for c in cut], float(rate)


@pytest.mark.slow
def test_the_high_speed_wheel_at_mass_ratio_6_settles_with_flip_and_digs_in_with_apic():
    """The grousered wheel of the high-speed study (poppy-cp, mass ratio 6, omega sqrt(l/g) = 0.5,
    9 mm cells, 4 s): with the APIC transfer it keeps digging in and its slip keeps rising; with the
    FLIP 0.99 blend (docs/mpm.md "What the rate error is") it levels off. Two runs, about 6 min each."""
    wheel, poppy = WheelGrousered(0.088, 0.05, 15, 0.018, 0.004), materials.get("poppy-cp")
    load = 6.0 * 638.0 * 0.212**2 * 0.05 * 9.81
    omega = 0.5 * math.sqrt(9.81 / 0.212)
    out = {}
    for flip in (0.0, 0.99):
        res = run_wheel(
            wheel, poppy, load=load, omega=omega, resolution=Resolution(cell_size=0.009, flip=flip),
            drive=Drive(duration=4.0),
        )  # fmt: skip
        out[flip] = _quarters(res, 0.088 + 0.018)
    (slip_a, rate_a), (slip_f, rate_f) = out[0.0], out[0.99]
    # APIC: slip still rising by more than 0.1 over the last three quarters, sinking at > 8 mm/s
    assert slip_a[3] - slip_a[1] > 0.1 and rate_a > 0.008, out
    # FLIP 0.99: slip within 0.1 over the same quarters, sinking at under half APIC's rate
    assert abs(slip_f[3] - slip_f[1]) < 0.1 and rate_f < 0.5 * rate_a, out


@pytest.mark.slow
def test_the_high_speed_wheels_steady_state_does_not_depend_on_its_start():
    """The same wheel with FLIP 0.99 at omega sqrt(l/g) = 1.0: spun up over 1 s from rest, or spun up
    at once while already moving at the spin-up run's forward speed, it ends the 4 s at full spin at
    the same slip (within 0.05) and sinkage (within 10 %), as the experiments' wheel does (docs/mpm.md,
    "The start"; script runs of the same calls, summaries: 0.347 / 45.8 mm and 0.360 / 46.3 mm). Two
    runs, about 5 min each."""
    wheel, poppy = WheelGrousered(0.088, 0.05, 15, 0.018, 0.004), materials.get("poppy-cp")
    load = 6.0 * 638.0 * 0.212**2 * 0.05 * 9.81
    omega = 1.0 * math.sqrt(9.81 / 0.212)
    fine = Resolution(cell_size=0.009, flip=0.99)
    ramp = run_wheel(
        wheel, poppy, load=load, omega=omega, resolution=fine, drive=Drive(duration=5.0, spin_up=1.0)
    )
    s = ramp.series
    late = (s["phase"] == "drive") & (s["time_s"] >= s["time_s"][s["phase"] == "drive"][0] + 3.0)
    moving = run_wheel(wheel, poppy, load=load, omega=omega, resolution=fine,
                       drive=Drive(duration=4.0, initial_speed=float(s["vx_m_s"][late].mean())))  # fmt: skip
    a, b = ramp.summary, moving.summary
    # the summaries average the last half of each drive: 2.5-5 s and 2-4 s, both after full spin
    assert abs(a["slip"] - b["slip"]) < 0.05, (a, b)
    assert abs(a["sinkage_m"] - b["sinkage_m"]) < 0.1 * min(a["sinkage_m"], b["sinkage_m"]), (a, b)


@pytest.mark.slow
def test_the_self_propelled_slip_is_the_zero_of_the_forced_slip_pull():
    """The same wheel, FLIP 0.99, 9 mm cells, omega sqrt(l/g) = 1.0, 1 s spin-up: the forced-slip
    pull is negative at slip 0.3 and positive at 0.5, the free wheel runs between them, within 0.05
    of the straight line's zero (docs/mpm.md, "Why the slip does not converge": pulls -1.23 and +2.69
    N, zero at 0.36, free wheel 0.344), and at a fixed slip the sinkage rises with the slip. Three
    runs, about 6 min each."""
    wheel, poppy = WheelGrousered(0.088, 0.05, 15, 0.018, 0.004), materials.get("poppy-cp")
    load = 6.0 * 638.0 * 0.212**2 * 0.05 * 9.81
    omega = 1.0 * math.sqrt(9.81 / 0.212)
    fine = Resolution(cell_size=0.009, flip=0.99)
    drive = Drive(duration=5.0, spin_up=1.0)
    forced = {
        s: run_wheel(wheel, poppy, load=load, omega=omega, slip=s, resolution=fine, drive=drive).summary
        for s in (0.3, 0.5)
    }
    free = run_wheel(wheel, poppy, load=load, omega=omega, resolution=fine, drive=drive).summary
    low, high = forced[0.3]["drawbar_pull_N"], forced[0.5]["drawbar_pull_N"]
    assert low < 0.0 < high, forced
    zero = 0.3 + 0.2 * (-low) / (high - low)
    assert 0.3 < free["slip"] < 0.5 and abs(free["slip"] - zero) < 0.05, (free, forced)
    assert forced[0.3]["sinkage_m"] < free["sinkage_m"] < forced[0.5]["sinkage_m"], (free, forced)
