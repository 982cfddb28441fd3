"""MPM checkpoints: never removed implicitly, clear errors, frames kept, interrupts resumable bit for bit."""

from __future__ import annotations

import inspect
import signal
import zipfile

import numpy as np
import pytest

from mpm_reference import MODEL
from terradyn.errors import InputError
from terradyn.geometry import Plate, WheelCircular
from terradyn.kinematics import Pose2D
from terradyn.mpm import MPMTerrain, run_intrusion, run_wheel
from terradyn.mpm import solver as mpm_solver
from terradyn.mpm.checkpoint import atomic_write, input_differences
from terradyn.mpm.solver import RunInterrupted, Runner

FAST = dict(cell_size=0.01, speed=0.2, bed_width=0.2, bed_depth=0.12, settle_time=0.02)
FRAMES = 8


def _intrude(**kw):
    return run_intrusion(Plate(0.08, 0.1), MODEL, depth=0.02, **{**FAST, "frame_count": FRAMES, **kw})


def _wheel(**kw):
    args = dict(load=2.0, omega=2.0, slip=0.2, cell_size=0.01, duration=0.1, sink_time=0.02)
    return run_wheel(WheelCircular(0.04, 0.05), MODEL, settle_time=0.02, frame_count=5, **{**args, **kw})


def _stop_after(calls: int):
    """A progress callback that raises KeyboardInterrupt (Ctrl-C) on its ``calls``-th call."""
    seen = []

    def progress(t, frac):
        seen.append(t)
        if len(seen) == calls:
            raise KeyboardInterrupt

    return progress


def _assert_same(a, b):
    assert a.series.keys() == b.series.keys()
    for key in a.series:
        np.testing.assert_array_equal(a.series[key], b.series[key], err_msg=key)
    assert a.summary == b.summary
    assert a.metadata["steps"] == b.metadata["steps"]
    assert len(a.frames) == len(b.frames)
    for fa, fb in zip(a.frames, b.frames, strict=True):
        assert fa.keys() == fb.keys()
        for key in fa:
            np.testing.assert_array_equal(fa[key], fb[key], err_msg=f"frame {key}")
    for key in a.final_particles:
        np.testing.assert_array_equal(a.final_particles[key], b.final_particles[key], err_msg=key)


@pytest.fixture(scope="module")
def reference():
    return _intrude()


def test_interrupted_and_resumed_run_equals_an_uninterrupted_one(tmp_path, reference):
    ckpt = tmp_path / "run.npz"
    with pytest.raises(RunInterrupted) as info:
        _intrude(checkpoint_path=ckpt, progress=_stop_after(15))
    err = info.value
    assert isinstance(err, KeyboardInterrupt)
    assert err.checkpoint_path == ckpt and ckpt.exists()
    assert 0 < err.step < err.total_steps
    assert err.time_s > 0
    assert str(err).startswith(f"interrupted at t = {err.time_s:.6g} s")
    assert f"checkpoint written to {ckpt}" in str(err)
    # the interrupt came after some frames, before all of them
    with np.load(ckpt) as data:
        assert 0 < int(data["frame_count"]) < FRAMES
    # output-only settings may change between the killed and the resumed run
    calls = []
    res = _intrude(
        checkpoint_path=ckpt,
        resume=True,
        checkpoint_interval=5.0,
        snapshot_dir=tmp_path / "snap",
        progress=lambda t, f: calls.append(t),
    )
    assert abs(len(reference.frames) - FRAMES) <= 1  # "about frame_count" frames
    _assert_same(res, reference)
    assert min(calls) > err.time_s  # continued, not restarted


@pytest.mark.parametrize("sig", ["SIGINT", "SIGTERM"])
def test_signal_inside_a_chunk_waits_for_its_end(tmp_path, monkeypatch, reference, sig):
    """A signal raised right after the compiled steps changed the particles (the step counter not yet
    moved) is held to the end of the chunk, so the checkpoint resumes bit-identically."""
    signum = getattr(signal, sig)

    def to_interrupt(s, frame):  # what the CLI installs for SIGTERM
        raise KeyboardInterrupt

    original = Runner._advance
    count = [0]

    def advance_then_signal(self, n, damping, forces):
        original(self, n, damping, forces)
        count[0] += 1
        if count[0] == 20:
            signal.raise_signal(signum)

    monkeypatch.setattr(Runner, "_advance", advance_then_signal)
    ckpt = tmp_path / "run.npz"
    # Python's own SIGINT handler, as in a foreground run (a job started with '&' by a shell without
    # job control inherits SIGINT ignored, and the runner rightly leaves an ignored signal alone)
    inherited = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        old = signal.signal(signum, to_interrupt) if sig == "SIGTERM" else None
        try:
            with pytest.raises(RunInterrupted) as info:
                _intrude(checkpoint_path=ckpt)
        finally:
            if old is not None:
                signal.signal(signum, old)
        assert info.value.step > 0
        monkeypatch.setattr(Runner, "_advance", original)
        _assert_same(_intrude(checkpoint_path=ckpt, resume=True), reference)
        assert signal.getsignal(signal.SIGINT) is signal.default_int_handler  # handlers put back
    finally:
        signal.signal(signal.SIGINT, inherited)


def test_interrupt_while_a_periodic_checkpoint_is_written(tmp_path, monkeypatch, reference):
    real = mpm_solver.save_checkpoint
    count = [0]

    def save_interrupted(path, arrays, inputs):
        count[0] += 1
        if count[0] == 4:  # Ctrl-C half-way through writing the file

            def half(tmp):
                with open(tmp, "wb") as fh:
                    fh.write(b"PK\x03\x04 half a file")
                raise KeyboardInterrupt

            atomic_write(path, half, suffix=".npz")
        return real(path, arrays, inputs)

    monkeypatch.setattr(mpm_solver, "save_checkpoint", save_interrupted)
    ckpt = tmp_path / "run.npz"
    with pytest.raises(RunInterrupted) as info:
        _intrude(checkpoint_path=ckpt, checkpoint_interval=1e-9)
    assert info.value.checkpoint_path == ckpt
    assert count[0] == 5  # the interrupted write, then the checkpoint of the interrupt
    assert [p.name for p in tmp_path.iterdir()] == ["run.npz"]  # no temporary file left
    monkeypatch.setattr(mpm_solver, "save_checkpoint", real)
    _assert_same(_intrude(checkpoint_path=ckpt, resume=True), reference)


def test_wheel_resume_keeps_frames_and_results(tmp_path):
    ref = _wheel()
    ckpt = tmp_path / "wheel.npz"
    with pytest.raises(RunInterrupted):
        _wheel(checkpoint_path=ckpt, progress=_stop_after(200))
    res = _wheel(checkpoint_path=ckpt, resume=True, average_fraction=0.5)
    assert len(ref.frames) == 6
    _assert_same(res, ref)


def test_interrupt_without_a_checkpoint_path_says_so():
    with pytest.raises(RunInterrupted) as info:
        _intrude(progress=_stop_after(3))
    assert info.value.checkpoint_path is None
    assert "no checkpoint written" in str(info.value)


def test_existing_checkpoint_is_refused_not_deleted(tmp_path, reference):
    ckpt = tmp_path / "run.npz"
    first = _intrude(checkpoint_path=ckpt)  # a finished run keeps its final checkpoint
    before = ckpt.read_bytes()
    with pytest.raises(InputError) as err:
        _intrude(checkpoint_path=ckpt)
    assert err.value.field == "checkpoint_path"
    msg = str(err.value)
    assert str(ckpt) in msg and "resume" in msg and "remove the file" in msg
    assert "\n" not in msg and "PosixPath" not in msg
    assert ckpt.read_bytes() == before
    # resuming a finished run returns its result without a single step
    calls = []
    again = _intrude(checkpoint_path=ckpt, resume=True, progress=lambda t, f: calls.append(t))
    assert calls == []
    assert ckpt.read_bytes() == before
    _assert_same(again, first)
    _assert_same(first, reference)


def test_resume_without_a_file_is_an_input_error(tmp_path):
    ckpt = tmp_path / "nothing.npz"
    with pytest.raises(InputError) as err:
        _intrude(checkpoint_path=ckpt, resume=True)
    assert err.value.field == "checkpoint_path"
    assert f"no checkpoint at {ckpt}" in str(err.value)
    assert not ckpt.exists()
    with pytest.raises(InputError) as err:
        _intrude(resume=True)
    assert err.value.field == "resume"


def _truncated(tmp_path):
    src = tmp_path / "full.npz"
    with pytest.raises(RunInterrupted):
        _intrude(checkpoint_path=src, progress=_stop_after(2))
    data = src.read_bytes()
    src.unlink()
    return data[: len(data) // 2]


def _npy(tmp_path):
    path = tmp_path / "a.npy"
    np.save(path, np.arange(3.0))
    return path.read_bytes()


def _foreign_npz(tmp_path):
    path = tmp_path / "b.npz"
    np.savez(path, p_pos=np.zeros((3, 2)))
    return path.read_bytes()


def _bad_member(tmp_path):
    path = tmp_path / "c.npz"
    with zipfile.ZipFile(path, "w") as zf:
        zf.writestr("__format__.npy", b"not an npy header")
    return path.read_bytes()


@pytest.mark.parametrize(
    "content",
    [
        lambda tmp: b"",
        lambda tmp: b"certainly not a checkpoint\n",
        _truncated,
        _npy,
        _foreign_npz,
        _bad_member,
    ],
    ids=["empty", "text", "truncated", "npy", "foreign-npz", "bad-member"],
)
def test_unreadable_checkpoint_is_an_input_error(tmp_path, content):
    ckpt = tmp_path / "run.npz"
    ckpt.write_bytes(content(tmp_path))
    with pytest.raises(InputError) as err:
        _intrude(checkpoint_path=ckpt, resume=True)
    assert err.value.field == "checkpoint_path"
    msg = str(err.value)
    assert "not a readable terradyn checkpoint" in msg and str(ckpt) in msg
    assert "\n" not in msg and "PosixPath" not in msg and "Error" not in msg


def test_checkpoint_of_other_inputs_names_the_difference(tmp_path):
    ckpt = tmp_path / "run.npz"
    with pytest.raises(RunInterrupted):
        _intrude(checkpoint_path=ckpt, progress=_stop_after(2))
    cases = [
        (dict(speed=0.25), "speed: checkpoint 0.2, this run 0.25"),
        (dict(frame_count=4), "frame_count: checkpoint 8, this run 4"),
        (dict(particles_per_cell=3), "particles_per_cell: checkpoint 2, this run 3"),
        (dict(walls="no-slip"), "walls.left.kind: checkpoint free-slip, this run no-slip"),
        (dict(surface_friction=0.3), "model.surface_friction: checkpoint 0.4, this run 0.3"),
    ]
    for kw, expected in cases:
        with pytest.raises(InputError) as err:
            _intrude(checkpoint_path=ckpt, resume=True, **kw)
        assert err.value.field == "checkpoint_path"
        assert expected in str(err.value), str(err.value)
        assert "derived." not in str(err.value)  # the named input, not what follows from it
    with pytest.raises(InputError, match=r"body.length: checkpoint 0.08, this run 0.07"):
        run_intrusion(
            Plate(0.07, 0.1), MODEL, depth=0.02, **FAST, frame_count=FRAMES, checkpoint_path=ckpt, resume=True
        )
    with pytest.raises(InputError, match=r"run: checkpoint intrusion, this run wheel"):
        _wheel(checkpoint_path=ckpt, resume=True)


def test_input_differences_names_nested_inputs_and_hides_derived_ones():
    saved = {"cell_size": 0.005, "n": 2, "model": {"mu": 0.5}, "derived": {"dt": 1e-4}}
    assert input_differences(saved, {**saved, "n": 2.0}) == []
    assert input_differences(saved, {**saved, "cell_size": 0.004, "derived": {"dt": 2e-4}}) == [
        "cell_size: checkpoint 0.005, this run 0.004"
    ]
    assert input_differences(saved, {**saved, "derived": {"dt": 2e-4}}) == [
        "derived.dt: checkpoint 0.0001, this run 0.0002"
    ]
    assert input_differences(saved, {**saved, "model": {"mu": 0.5, "e": 1}}) == [
        "model.e: checkpoint absent, this run 1"
    ]
    assert input_differences({"flag": True}, {"flag": 1}) == ["flag: checkpoint true, this run 1"]


def test_default_checkpoint_interval_loses_at_most_a_minute():
    for fn in (run_intrusion, run_wheel):
        assert inspect.signature(fn).parameters["outputs"].default.checkpoint_interval == 60.0


TERRAIN = dict(bed_width=0.2, bed_depth=0.1, cell_size=0.01, max_speed=0.1, settle_time=0.0)


def test_terrain_restore_errors_are_clear(tmp_path):
    plate = Plate(0.06, 0.02)
    path = tmp_path / "bed.npz"
    with pytest.raises(InputError) as err:
        MPMTerrain(MODEL, **TERRAIN).restore(plate, path)
    assert err.value.field == "path" and f"no checkpoint at {path}" in str(err.value)
    path.write_bytes(b"PK\x03\x04 broken")
    with pytest.raises(InputError, match="not a readable terradyn checkpoint"):
        MPMTerrain(MODEL, **TERRAIN).restore(plate, path)
    terrain = MPMTerrain(MODEL, **TERRAIN)
    terrain.init(plate, Pose2D(0.0, 0.02))
    terrain.save(path)
    with pytest.raises(InputError) as err:
        MPMTerrain(MODEL, **{**TERRAIN, "cell_size": 0.008}).restore(plate, path)
    assert "cell_size: checkpoint 0.01, this run 0.008" in str(err.value)
    with pytest.raises(InputError, match=r"body.length: checkpoint 0.06, this run 0.05"):
        MPMTerrain(MODEL, **TERRAIN).restore(Plate(0.05, 0.02), path)
    other = MPMTerrain(MODEL, **TERRAIN)
    other.restore(plate, path)
    np.testing.assert_array_equal(other.fields()["x"], terrain.fields()["x"])
