import json

import pytest


def test_version(run_cli):
    code, out, _ = run_cli("--version")
    assert code == 0 and out.startswith("terradyn ")


def test_materials_list_and_show(run_cli):
    code, out, _ = run_cli("materials", "list", "--format", "json")
    assert code == 0
    names = {row["name"] for row in json.loads(out)}
    assert {"generic", "MS", "MMS", "LPS", "CPS", "poppy-lp", "poppy-cp"} <= names
    code, out, _ = run_cli("materials", "show", "MS", "--format", "json")
    rec = json.loads(out)
    assert rec["rft_zeta_N_per_m3"] == pytest.approx(2.02e6)
    assert "Agarwal" in rec["citation"]


def test_rft_alpha_generic(run_cli):
    code, out, _ = run_cli(
        "rft", "alpha", "--material", "generic", "--beta", "0", "--gamma", "90", "--format", "json"
    )
    assert code == 0
    rec = json.loads(out)
    assert rec["alpha_z_N_per_m3"] == pytest.approx(1.0e6)
    assert abs(rec["alpha_x_N_per_m3"]) < 1e-6


def test_rft_alpha_grid_writes_csv_and_plot(run_cli, tmp_path):
    csv, png = tmp_path / "map.csv", tmp_path / "map.png"
    code, _, err = run_cli(
        "rft", "alpha", "--grid", "--step", "15", "--format", "csv", "--out", str(csv), "--plot", str(png)
    )
    assert code == 0, err
    assert csv.read_text().startswith("beta_deg,gamma_deg,alpha_x_N_per_m3,alpha_z_N_per_m3")
    assert len(csv.read_text().splitlines()) == 1 + 13 * 13
    assert png.stat().st_size > 1000


def test_intrude_plate_json(run_cli):
    code, out, _ = run_cli(
        "intrude",
        "plate",
        "--length",
        "0.05",
        "--width",
        "0.02",
        "--depth",
        "0.03",
        "--angle",
        "0",
        "--direction",
        "90",
        "--material",
        "generic",
        "--format",
        "json",
    )
    assert code == 0
    rec = json.loads(out)
    assert set(rec) == {"force_x_N", "force_z_N", "torque_y_Nm"}
    assert rec["force_z_N"] == pytest.approx(1e6 * 0.05 * 0.02 * 0.03)


def test_intrude_sweep_csv(run_cli, tmp_path):
    out = tmp_path / "sweep.csv"
    code, _, _ = run_cli(
        "intrude",
        "plate",
        "--length",
        "0.05",
        "--depth",
        "0:0.1:11",
        "--format",
        "csv",
        "--out",
        str(out),
        "--plot",
        str(tmp_path / "f.png"),
    )
    assert code == 0
    lines = out.read_text().splitlines()
    assert lines[0] == "depth_m,force_x_N,force_z_N,torque_y_Nm"
    assert len(lines) == 12


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["intrude", "plate", "--length", "-0.05", "--depth", "0.03"], "length"),
        (["intrude", "plate", "--radius", "0.05", "--depth", "0.03"], "--radius"),
        (["intrude", "plate", "--depth", "0.03"], "--length"),
        (["intrude", "plate", "--length", "0.05", "--depth", "x"], "--depth"),
        (["intrude", "plate", "--length", "0.05", "--depth", "0.1", "--material", "nope"], "material"),
        (["intrude", "blob", "--depth", "0.1"], "blob"),
        (["rft", "alpha", "--beta", "0"], "--beta"),
        (["rft", "alpha", "--grid", "--step", "0"], "--step"),
        (["materials", "show", "nope"], "material"),
    ],
)
def test_bad_input_one_line_no_traceback(run_cli, args, needle):
    code, out, err = run_cli(*args)
    assert code != 0
    assert "Traceback" not in err and "Traceback" not in out
    assert needle in err
    assert len(err.strip().splitlines()) == 1


def test_bad_input_writes_no_partial_file(run_cli, tmp_path):
    target = tmp_path / "out.json"
    code, _, _ = run_cli("intrude", "plate", "--length", "-1", "--depth", "0.1", "--out", str(target))
    assert code != 0
    assert not target.exists()
    assert list(tmp_path.iterdir()) == []
    code, _, err = run_cli(
        "intrude",
        "plate",
        "--length",
        "0.05",
        "--depth",
        "0.1",
        "--out",
        str(tmp_path / "missing" / "x.json"),
    )
    assert code != 0 and "--out" in err


def test_demo_writes_outputs(run_cli, tmp_path):
    code, _, err = run_cli("demo", "--out", str(tmp_path / "demo"))
    assert code == 0, err
    files = sorted(p.name for p in (tmp_path / "demo").iterdir())
    assert any(f.endswith(".csv") for f in files)
    assert any(f.endswith(".png") for f in files)


def test_validate_passes(run_cli):
    code, out, err = run_cli("validate", "--format", "json")
    assert code == 0, err
    rows = json.loads(out)
    assert rows and all(r["passed"] for r in rows)


def test_study_run_and_bad_study_file(run_cli, tmp_path):
    code, out, err = run_cli(
        "study", "run", "plate-depth", "--quick", "--out", str(tmp_path / "s"), "--format", "json"
    )
    assert code == 0, err
    assert {r["material"] for r in json.loads(out)} >= {"MS", "generic"}
    assert (tmp_path / "s" / "plate_depth.png").exists()
    bad = tmp_path / "bad.toml"
    bad.write_text('[study]\nkind = "plate-depth"\n[parameters]\nlenght_m = 0.1\n')
    code, _, err = run_cli("study", "run", str(bad), "--out", str(tmp_path / "t"))
    assert code == 1 and "lenght_m" in err
    assert not (tmp_path / "t").exists()
