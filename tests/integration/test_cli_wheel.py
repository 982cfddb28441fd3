import json

import pytest


def test_wheel_steady_json(run_cli, tmp_path):
    code, out, err = run_cli(
        "wheel",
        "steady",
        "--material",
        "MS",
        "--radius",
        "0.13",
        "--width",
        "0.16",
        "--load",
        "130",
        "--slip",
        "0.3",
        "--format",
        "json",
        "--plot",
        str(tmp_path / "w.png"),
    )
    assert code == 0, err
    rec = json.loads(out)
    for key in ("sinkage_m", "drawbar_pull_N", "drive_torque_Nm", "power_W"):
        assert key in rec
    assert 0 < rec["sinkage_m"] < 0.13
    assert rec["power_W"] == pytest.approx(rec["drive_torque_Nm"] * 1.0)
    assert (tmp_path / "w.png").stat().st_size > 1000


def test_wheel_steady_independent_of_omega_flag(run_cli):
    _, a, _ = run_cli("wheel", "steady", "--load", "130", "--slip", "0.2", "--format", "json")
    _, b, _ = run_cli("wheel", "steady", "--load", "130", "--slip", "0.2", "--omega", "9", "--format", "json")
    ra, rb = json.loads(a), json.loads(b)
    assert rb["drawbar_pull_N"] == pytest.approx(ra["drawbar_pull_N"], rel=1e-9)
    assert rb["power_W"] == pytest.approx(9 * ra["power_W"], rel=1e-9)


def test_self_propelled_and_sweep(run_cli, tmp_path):
    code, out, _ = run_cli("wheel", "self-propelled", "--load", "130", "--format", "json")
    assert code == 0
    assert abs(json.loads(out)["drawbar_pull_N"]) < 1e-6
    csv = tmp_path / "sweep.csv"
    code, _, err = run_cli(
        "wheel",
        "sweep",
        "--model",
        "rft",
        "--material",
        "MS,CPS",
        "--load",
        "80,190",
        "--slip",
        "-0.5:0.5:5",
        "--format",
        "csv",
        "--out",
        str(csv),
        "--plot",
        str(tmp_path / "s.png"),
    )
    assert code == 0, err
    assert len(csv.read_text().splitlines()) == 1 + 2 * 2 * 5


@pytest.mark.parametrize(
    ("args", "needle", "exit_code"),
    [
        (["--load", "130", "--slip", "1.5"], "slip", 1),
        (["--load", "130", "--slip", "0.2", "--omega", "0"], "omega", 1),
        (["--load", "-1", "--slip", "0.2"], "load", 1),
        (["--load", "1e6", "--slip", "0.2"], "carries at most", 3),
        (["--load", "130", "--slip", "0.2", "--model", "dem"], "--model", 1),
        (["--load", "130", "--slip", "0.2", "--grouser-count", "3"], "--grouser-count", 1),
    ],
)
def test_wheel_bad_input(run_cli, args, needle, exit_code):
    code, _, err = run_cli("wheel", "steady", *args)
    assert code == exit_code
    assert needle in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


def test_optimize_flapped_wheel_small(run_cli, tmp_path):
    code, out, err = run_cli(
        "optimize",
        "flapped-wheel",
        "--iterations",
        "2",
        "--population",
        "4",
        "--format",
        "json",
        "--plot",
        str(tmp_path / "o.png"),
        "--trace",
        str(tmp_path / "t.csv"),
    )
    assert code == 0, err
    rec = json.loads(out)
    assert 2 <= rec["flap_count"] <= 12 and 0 < rec["objective"] <= 1
    assert rec["generations"] == 2
    assert len((tmp_path / "t.csv").read_text().splitlines()) == 1 + rec["evaluations"]
    code, _, err = run_cli("optimize", "flapped-wheel", "--plot-params", "flap_count,nope")
    assert code == 1 and "--plot-params" in err


def test_wheel_simulate_summary_and_outputs(run_cli, tmp_path):
    ts = tmp_path / "ts.csv"
    code, out, err = run_cli(
        "wheel",
        "simulate",
        "--material",
        "CPS",
        "--mass",
        "5",
        "--omega",
        "2",
        "--duration",
        "1.5",
        "--format",
        "json",
        "--out",
        str(ts),
        "--plot",
        str(tmp_path / "ts.png"),
    )
    assert code == 0, err
    rec = json.loads(out)
    for key in ("forward_velocity_m_s", "slip", "sinkage_m", "drive_torque_Nm"):
        assert key in rec
    assert 0 < rec["slip"] < 0.5
    assert ts.read_text().splitlines()[0].startswith("t")
    code, _, err = run_cli("wheel", "simulate", "--mass", "-1", "--omega", "2", "--duration", "1")
    assert code == 1 and "mass" in err and "Traceback" not in err
    code, _, err = run_cli(
        "wheel",
        "simulate",
        "--mass",
        "5",
        "--omega",
        "2",
        "--duration",
        "1",
        "--out",
        str(tmp_path / "x.txt"),
    )
    assert code == 1 and "--out" in err


def test_study_high_speed_reduced(run_cli, tmp_path):
    code, out, err = run_cli(
        "study", "high-speed", "--quick", "--format", "json", "--out", str(tmp_path / "hs")
    )
    assert code == 0, err
    rec = json.loads(out)
    assert rec["omega_onset_rad_s"] > 0
    assert 0.2 < rec["omega_onset_normalised"] < 2.0
    assert (tmp_path / "hs" / "high_speed.csv").exists()


def test_wheel_steady_rft3d_primitive_and_mesh(run_cli, tmp_path):
    pytest.importorskip("trimesh")
    from terradyn.geometry3d import save_mesh, wheel_cylinder

    code, out, err = run_cli(
        "wheel",
        "steady",
        "--model",
        "rft3d",
        "--radius",
        "0.13",
        "--width",
        "0.16",
        "--load",
        "130",
        "--slip",
        "0.3",
        "--slip-angle",
        "10",
        "--format",
        "json",
    )
    assert code == 0, err
    rec = json.loads(out)
    assert rec["vertical_force_N"] == pytest.approx(130.0, rel=1e-6)
    assert rec["side_force_N"] < 0 and "aligning_moment_Nm" in rec
    _, out0, _ = run_cli(
        "wheel", "steady", "--model", "rft3d", "--load", "130", "--slip", "0.3", "--format", "json"
    )
    assert abs(json.loads(out0)["side_force_N"]) < 1e-6 * 130
    stl = tmp_path / "w.stl"
    save_mesh(wheel_cylinder(0.13, 0.16, circumferential_resolution=120, axial_resolution=2), stl)
    code, out, err = run_cli(
        "wheel",
        "steady",
        "--model",
        "rft3d",
        "--mesh",
        str(stl),
        "--load",
        "130",
        "--slip",
        "0.3",
        "--format",
        "json",
    )
    assert code == 0, err
    code, _, err = run_cli(
        "wheel",
        "steady",
        "--model",
        "rft3d",
        "--mesh",
        str(tmp_path / "no.stl"),
        "--load",
        "130",
        "--slip",
        "0.3",
    )
    assert code == 1 and "no.stl" in err
    code, _, err = run_cli("wheel", "steady", "--load", "130", "--slip", "0.3", "--slip-angle", "5")
    assert code == 1 and "rft3d" in err
