import json

import pytest


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["intrude", "plate", "--length", "0.06", "--depth", "0.03", "--cell-size", "0.05"], "cell_size"),
        (["intrude", "plate", "--length", "0.06", "--depth", "0.03", "--direction", "0"], "direction"),
        (["intrude", "plate", "--length", "0.06", "--depth", "0.03", "--resume"], "--resume"),
        (["wheel", "--load", "10", "--omega", "1", "--shape", "blob"], "--shape"),
        (["intrude", "plate", "--length", "0.06", "--depth", "0.03", "--animate", "a.avi"], "--animate"),
        (["intrude", "plate", "--length", "0.06", "--depth", "0.03", "--fields", "f.txt"], "--fields"),
        (["intrude", "plate", "--length", "0.06", "--depth", "0.03", "--plot", "/no/such/p.png"], "--plot"),
        (["wheel", "--load", "10", "--omega", "1", "--animate", "a.gif", "--frames", "1"], "--frames"),
    ],
)
def test_mpm_bad_input(run_cli, args, needle):
    code, _, err = run_cli("mpm", *args)
    assert code == 2
    assert needle in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


@pytest.mark.slow
def test_mpm_intrude_plate_coarse(run_cli, tmp_path):
    series = tmp_path / "s.csv"
    code, out, err = run_cli("mpm", "intrude", "plate", "--length", "0.06", "--width", "0.02", "--depth",
                             "0.03", "--material", "MS", "--cell-size", "0.01", "--format", "json",
                             "--series", str(series))
    assert code == 0, err
    rec = json.loads(out)
    assert rec["force_z_N"] > 0 and abs(rec["force_x_N"]) < 0.05 * rec["force_z_N"]
    assert series.exists()


@pytest.mark.slow
def test_mpm_alpha_study_quick(run_cli, tmp_path):
    code, out, err = run_cli("study", "run", "mpm-alpha", "--quick", "--out", str(tmp_path / "a"),
                             "--format", "json")
    assert code == 0, err
    rec = json.loads(out)[0]
    assert rec["alpha_z_ratio_mean"] > 0


def test_mpm_intrude_writes_field_plot_and_animation(run_cli, tmp_path):
    fields, anim = tmp_path / "fields.png", tmp_path / "run.gif"
    code, out, err = run_cli("mpm", "intrude", "plate", "--length", "0.06", "--width", "0.02", "--depth",
                             "0.02", "--material", "MS", "--cell-size", "0.01", "--format", "json",
                             "--fields", str(fields), "--animate", str(anim), "--frames", "4")
    assert code == 0, err
    assert json.loads(out)["force_z_N"] > 0
    assert fields.stat().st_size > 10_000
    assert anim.read_bytes()[:6] in (b"GIF89a", b"GIF87a")
    assert not list(tmp_path.glob(".*"))  # no temporary files left behind
