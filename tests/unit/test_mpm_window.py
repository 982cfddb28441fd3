"""The moving window of a wheel run: only the grains around the wheel are stepped, the rest are held;
the forces match a whole-bed run, resuming is bit-for-bit, and bad windows are refused."""

from __future__ import annotations

import numpy as np
import pytest

from mpm_reference import MODEL
from terradyn.errors import InputError
from terradyn.geometry import WheelCircular
from terradyn.mpm import Bed, MPMTerrain, Resolution, run_wheel
from terradyn.mpm.solver import RunInterrupted

WHEEL = WheelCircular(0.04, 0.05)
H = 0.01
# omega r (1 - s) = 0.19 m/s for 0.3 s: the wheel travels 0.058 m, about six cells of window motion
ARGS = dict(load=2.0, omega=6.0, slip=0.2, resolution=Resolution(cell_size=H), duration=0.3,
            sink_time=0.02, frame_count=4)  # fmt: skip


def _wheel(window=None, **kw):
    return run_wheel(WHEEL, MODEL, bed=Bed(window=window, settle_time=0.02), **{**ARGS, **kw})


@pytest.fixture(scope="module")
def runs():
    return _wheel(None), _wheel(0.0)


def test_the_window_steps_fewer_grains_and_holds_the_rest(runs):
    windowed, whole = runs
    meta = windowed.metadata
    assert meta["window_m"] == pytest.approx(2 * (0.04 + 0.08))  # the wheel and 2 reaches each side
    assert whole.metadata["window_m"] == 0.0
    assert meta["particles"] == whole.metadata["particles"]
    assert meta["stepped_particles"] < 0.85 * meta["particles"]
    # early in the drive, the grains beyond the window ahead of the wheel have not been stepped
    first, first_whole = windowed.frames[0], whole.frames[0]
    x_wheel = float(first["segments"][:, :, 0].mean())
    ahead = first["x"] > x_wheel + 0.5 * meta["window_m"] + H
    assert ahead.sum() > 50
    assert np.all(first["speed"][ahead] == 0.0)
    assert np.any(first_whole["speed"][ahead] != 0.0)  # the whole bed moves there


def test_the_window_keeps_the_forces_of_the_whole_bed(runs):
    windowed, whole = runs
    a, b = windowed.summary, whole.summary
    load = ARGS["load"]
    assert abs(a["drawbar_pull_N"] - b["drawbar_pull_N"]) < 0.02 * load
    assert a["drive_torque_Nm"] == pytest.approx(b["drive_torque_Nm"], rel=0.03)
    assert a["force_z_N"] == pytest.approx(b["force_z_N"], rel=0.01)
    assert abs(a["sinkage_m"] - b["sinkage_m"]) < 0.1 * H


def test_a_window_as_long_as_the_bed_is_the_whole_bed(runs):
    whole = runs[1]
    long = _wheel(10.0)
    assert long.metadata["window_m"] == 0.0
    for key in whole.series:
        np.testing.assert_array_equal(long.series[key], whole.series[key], err_msg=key)


def test_a_windowed_run_resumes_bit_for_bit(tmp_path, runs):
    ckpt = tmp_path / "w.npz"
    calls = []

    def stop(t, frac):
        calls.append(t)
        if len(calls) == 40:
            raise KeyboardInterrupt

    with pytest.raises(RunInterrupted):
        _wheel(None, checkpoint_path=ckpt, progress=stop)
    resumed = _wheel(None, checkpoint_path=ckpt, resume=True)
    reference = runs[0]
    for key in reference.series:
        np.testing.assert_array_equal(resumed.series[key], reference.series[key], err_msg=key)
    for key in reference.final_particles:
        np.testing.assert_array_equal(
            resumed.final_particles[key], reference.final_particles[key], err_msg=key
        )
    # a checkpoint of a windowed run is refused by a whole-bed run
    with pytest.raises(InputError, match="window"):
        _wheel(0.0, checkpoint_path=ckpt, resume=True)


def test_the_window_grows_ahead_of_a_bow_wave_and_keeps_the_whole_beds_forces():
    # a locked wheel towed at 0.9 radii of sinkage pushes a heap about 4.6 radii ahead of its axle;
    # a window of fixed length put its leading wall into that heap (pull 12.43 N against 12.52 N on
    # the whole bed, sinkage 30.2 against 34.5 mm, both on a bed whose end the heap had reached)
    plow = dict(load=10.0, omega=0.0, slip=None, forward_speed=0.3, duration=0.5)
    windowed, whole = _wheel(None, **plow), _wheel(0.0, **plow)
    meta = windowed.metadata
    assert meta["window_final_m"] > meta["window_m"] + 2 * H  # it grew
    assert meta["heap_ahead_m"] > 4 * 0.04
    assert not meta["heap_reached_bed_end"]
    assert meta["bed_beyond_heap_m"] >= meta["window_clearance_m"]
    # the whole-bed run reports its heap as well (its bed's ends hold a heap as a window's wall did)
    assert whole.metadata["heap_reached_bed_end"] is False
    assert whole.metadata["heap_ahead_m"] == pytest.approx(meta["heap_ahead_m"], abs=2 * H)
    a, b = windowed.summary, whole.summary
    assert abs(a["drawbar_pull_N"] - b["drawbar_pull_N"]) < 0.02 * plow["load"]
    assert abs(a["sinkage_m"] - b["sinkage_m"]) < 0.1 * H
    assert a["force_z_N"] == pytest.approx(b["force_z_N"], rel=0.01)


def test_bad_windows_are_refused():
    with pytest.raises(InputError, match=r"^window = "):
        Bed(window=-0.1)
    with pytest.raises(InputError, match=r"^window = 0.1 .*at least 0.16 m"):
        _wheel(0.1)
    with pytest.raises(InputError, match=r"^window = 0.2 .*MPMTerrain"):
        MPMTerrain(MODEL, bed=Bed(width=0.3, depth=0.1, window=0.2), resolution=Resolution(cell_size=H))
