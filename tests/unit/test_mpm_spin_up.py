"""The MPM wheel's spin-up (a linear staircase from rest, exact at its end, independent of chunking,
free components untouched, resumable) and initial forward speed, and their errors."""

from __future__ import annotations

import numpy as np
import pytest

from mpm_reference import MODEL
from terradyn.errors import InputError
from terradyn.geometry import WheelCircular
from terradyn.mpm import Drive, run_wheel
from terradyn.mpm.solver import RAMP_LEVELS, Phase, RunInterrupted

WHEEL = WheelCircular(0.04, 0.05)
RUN = dict(load=2.0, omega=2.0, cell_size=0.01, settle_time=0.02)


def _drive(**kw) -> Drive:
    return Drive(sink_time=0.02, **kw)


def _fractions(phase: Phase, chunks: list[int]) -> np.ndarray:
    """The twist fraction of every step when the phase is run in ``chunks`` of steps."""
    out, done = [], 0
    for n in chunks:
        pieces = phase.ramp_pieces(done, n)
        assert [p[0] for p in pieces] == list(np.cumsum([0] + [p[1] for p in pieces[:-1]]))
        assert sum(p[1] for p in pieces) == n
        for _, count, fraction in pieces:
            out += [fraction] * count
        done += n
    return np.array(out)


@pytest.mark.parametrize("ramp", [1, 7, 100, 250, 1001])
def test_ramp_is_a_staircase_to_the_target_whatever_the_chunks(ramp):
    phase = Phase("drive", 1500, twist=(0.0, 0.0, 1.0), ramp_steps=ramp)
    whole = _fractions(phase, [1500])
    levels = min(RAMP_LEVELS, ramp)
    assert np.all(np.diff(whole) >= 0)
    assert len(np.unique(whole[:ramp])) == levels  # every level is held for at least one step
    assert whole[0] == pytest.approx(1.0 / levels)
    assert np.all(whole[ramp - 1 :] == 1.0)  # the last ramp step is at the target, exactly
    first_full = -(-(levels - 1) * ramp // levels)  # the first step of the last level
    assert np.all(whole[:first_full] < 1.0) and np.all(whole[first_full:] == 1.0)
    # the mean over the ramp is the linear ramp's mean, to half a level
    assert abs(whole[:ramp].mean() - 0.5) <= 0.5 / levels + 1e-12
    for chunks in ([1] * 1500, [37] * 40 + [20], [999, 501]):
        assert np.array_equal(_fractions(phase, chunks), whole)


def test_a_phase_without_a_ramp_is_one_piece_at_full_twist():
    assert Phase("drive", 50, twist=(1.0, 0.0, 2.0)).ramp_pieces(10, 20) == [(0, 20, 1.0)]


def test_forced_slip_ramps_spin_and_speed_together():
    duration, spin_up = 0.12, 0.05
    res = run_wheel(WHEEL, MODEL, slip=0.2, drive=_drive(duration=duration, spin_up=spin_up), **RUN)
    s = res.series
    drive = s["phase"] == "drive"
    t = s["time_s"][drive] - s["time_s"][drive][0]
    omega, vx = s["omega_rad_s"][drive], s["vx_m_s"][drive]
    ramping = t < spin_up * 0.9
    assert np.all(np.diff(omega) >= -1e-12)
    assert omega[ramping].max() < 2.0
    assert np.all(omega[t > spin_up * 1.1] == 2.0)
    # the slip is the one asked for all through the ramp: vx = (1 - s) omega r
    assert np.allclose(vx, 0.8 * omega * 0.04, rtol=1e-12, atol=1e-15)
    assert res.summary["slip"] == pytest.approx(0.2, abs=1e-9)


def test_self_propelled_ramp_leaves_the_forward_motion_free():
    res = run_wheel(WHEEL, MODEL, drive=_drive(duration=0.12, spin_up=0.05), **RUN)
    s = res.series
    drive = s["phase"] == "drive"
    omega, vx = s["omega_rad_s"][drive], s["vx_m_s"][drive]
    assert omega[0] < 0.5 * omega[-1] and omega[-1] == 2.0
    assert len(np.unique(np.round(vx, 12))) > len(vx) // 2  # vx evolves under the soil's force


def test_a_self_propelled_wheel_can_start_the_drive_moving():
    res = run_wheel(WHEEL, MODEL, drive=_drive(duration=0.05, initial_speed=0.05), **RUN)
    s = res.series
    drive = s["phase"] == "drive"
    first = np.flatnonzero(drive)[0]
    assert s["vx_m_s"][first - 1] == 0.0  # at rest while it sank
    assert s["vx_m_s"][first] == pytest.approx(0.05, abs=0.01)  # one record after the start
    rest = run_wheel(WHEEL, MODEL, drive=_drive(duration=0.05), **RUN).series
    assert rest["x_m"][-1] - rest["x_m"][first] < s["x_m"][-1] - s["x_m"][first]


def test_spin_up_does_not_depend_on_the_record_interval():
    drive = _drive(duration=0.1, spin_up=0.04)
    a = run_wheel(WHEEL, MODEL, slip=0.2, drive=drive, **RUN)
    b = run_wheel(WHEEL, MODEL, slip=0.2, drive=drive, record_interval=0.0037, **RUN)
    assert np.array_equal(a.final_particles["x"], b.final_particles["x"])
    assert np.array_equal(a.final_particles["z"], b.final_particles["z"])
    assert np.array_equal(a.final_particles["vx"], b.final_particles["vx"])


def test_interrupted_during_the_ramp_resumes_bit_for_bit(tmp_path):
    drive = _drive(duration=0.12, spin_up=0.06)
    ref = run_wheel(WHEEL, MODEL, slip=0.2, drive=drive, **RUN)
    ckpt = tmp_path / "w.npz"
    calls = []

    def stop(t, frac):
        calls.append(t)
        if len(calls) == 120:
            raise KeyboardInterrupt

    with pytest.raises(RunInterrupted) as err:
        run_wheel(WHEEL, MODEL, slip=0.2, drive=drive, checkpoint_path=ckpt, progress=stop, **RUN)
    s = ref.series
    ramp_start = s["time_s"][s["phase"] == "drive"][0]
    assert ramp_start < err.value.time_s < ramp_start + 0.05  # stopped inside the ramp
    res = run_wheel(WHEEL, MODEL, slip=0.2, drive=drive, checkpoint_path=ckpt, resume=True, **RUN)
    assert np.array_equal(res.final_particles["x"], ref.final_particles["x"])
    for k in ("omega_rad_s", "force_x_N"):
        assert np.array_equal(res.series[k], ref.series[k])


def test_default_duration_adds_the_spin_up():
    res = run_wheel(WHEEL, MODEL, slip=0.2, drive=_drive(spin_up=0.05), **{**RUN, "omega": 60.0})
    s = res.series
    t = s["time_s"][s["phase"] == "drive"]
    assert t[-1] - t[0] == pytest.approx(0.05 + 4.5 / 60.0, rel=0.05)


@pytest.mark.parametrize(
    ("drive", "kw", "says"),
    [
        (dict(spin_up=-0.1), {}, "spin_up = -0.1"),
        (dict(spin_up=0.08, duration=0.1), dict(omega=2.0), "at most 0.05 s"),
        (dict(spin_up=0.01, duration=0.1), dict(omega=None, drive_torque=0.1), "nonzero omega"),
        (dict(spin_up=0.01, duration=0.1), dict(omega=0.0), "nonzero omega"),
        (dict(initial_speed=0.1, duration=0.1), dict(slip=0.2), "0 when slip is given"),
        (dict(initial_speed=float("nan")), {}, "initial_speed = nan"),
    ],
)
def test_bad_drive_is_a_clear_error(drive, kw, says):
    with pytest.raises(InputError) as err:
        run_wheel(WHEEL, MODEL, drive=_drive(**drive), **{**RUN, **kw})
    assert err.value.field == next(iter(drive)) and says in str(err.value)
