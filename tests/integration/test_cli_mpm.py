import json

import numpy as np
import pytest


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["intrude", "plate", "--length", "0.06", "--depth", "0.03", "--cell-size", "0.05"], "--cell-size"),
        (["intrude", "plate", "--length", "0.06", "--depth", "0.03", "--direction", "0"], "--direction"),
        (["intrude", "plate", "--length", "0.06", "--depth", "0.03", "--resume"], "--resume"),
        (["wheel", "--load", "10", "--omega", "1", "--shape", "blob"], "--shape"),
        (["intrude", "plate", "--length", "0.06", "--depth", "0.03", "--animate", "a.avi"], "--animate"),
        (["intrude", "plate", "--length", "0.06", "--depth", "0.03", "--fields", "f.txt"], "--fields"),
        (["intrude", "plate", "--length", "0.06", "--depth", "0.03", "--plot", "/no/such/p.png"], "--plot"),
        (["wheel", "--load", "10", "--omega", "1", "--animate", "a.gif", "--frames", "1"], "--frames"),
        (["wheel", "--load", "10"], "--omega"),
        (["wheel", "--load", "10", "--drive-torque", "1", "--slip", "0.2"], "--slip"),
    ],
)
def test_mpm_bad_input(run_cli, args, needle):
    code, _, err = run_cli("mpm", *args)
    assert code == 1, err
    assert needle in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


@pytest.mark.slow
def test_mpm_intrude_plate_coarse(run_cli, tmp_path):
    series = tmp_path / "s.csv"
    code, out, err = run_cli(
        "mpm",
        "intrude",
        "plate",
        "--length",
        "0.06",
        "--width",
        "0.02",
        "--depth",
        "0.03",
        "--material",
        "MS",
        "--cell-size",
        "0.01",
        "--format",
        "json",
        "--series",
        str(series),
    )
    assert code == 0, err
    rec = json.loads(out)
    assert rec["force_z_N"] > 0 and abs(rec["force_x_N"]) < 0.05 * rec["force_z_N"]
    assert series.exists()


def test_mpm_alpha_study_quick(run_cli, tmp_path):
    """One MPM point of the alpha study: a flat plate pushed down to 4 cm in MS.

    Independent reference: its bearing pressure against plane-strain strip-footing theory at the same
    friction angle (continuum.md 7.1): q = gamma D N_q d_q + gamma B N_gamma / 2, between Brinch Hansen's
    N_gamma without depth factor and Vesic's with d_q = 1 + 2 tan(phi) (1 - sin(phi))^2 D / B. The
    zero-dilatancy model sits at or below associated-flow values, hence the 0.8 margin below.
    """
    import math

    import pandas as pd

    from terradyn import materials
    from terradyn.mpm import GranularModel

    code, out, err = run_cli(
        "study", "run", "mpm-alpha", "--quick", "--out", str(tmp_path / "a"), "--format", "json"
    )
    assert code == 0, err
    rec = json.loads(out)[0]
    assert rec["points"] == 1
    df = pd.read_csv(tmp_path / "a" / "mpm_alpha.csv")
    assert (tmp_path / "a" / "mpm_alpha.png").stat().st_size > 10_000
    assert {"alpha_z_rft_body_N_per_m3", "alpha_x_rft_body_N_per_m3"} <= set(df.columns)
    row = df.iloc[0]
    assert abs(row["alpha_x_mpm_N_per_m3"]) < 0.05 * row["alpha_z_mpm_N_per_m3"]  # symmetric
    model = GranularModel.from_material(materials.get("MS"))
    gam = max(model.bulk_density, 1.02 * model.critical_density) * 9.81
    phi = model.friction_angle
    t = math.tan(phi)
    n_q = math.exp(math.pi * t) * math.tan(math.pi / 4 + phi / 2) ** 2
    b, h = 0.04, 0.04 / 6  # plate length and the quick cell size (MPM plate: three cells thick)
    d = 0.04 + 1.5 * h  # depth of the plate's bottom face
    d_q = 1 + 2 * t * (1 - math.sin(phi)) ** 2 * d / b
    low = gam * d * n_q + 0.5 * gam * b * 1.5 * (n_q - 1) * t
    high = gam * d * n_q * d_q + 0.5 * gam * b * 2 * (n_q + 1) * t
    q = row["alpha_z_mpm_N_per_m3"] * 0.04  # F / (B w) = alpha D
    assert 0.8 * low < q < high


def test_mpm_intrude_writes_field_plot_and_animation(run_cli, tmp_path):
    fields, anim = tmp_path / "fields.png", tmp_path / "run.gif"
    code, out, err = run_cli(
        "mpm",
        "intrude",
        "plate",
        "--length",
        "0.06",
        "--width",
        "0.02",
        "--depth",
        "0.02",
        "--speed",
        "0.2",  # a fast stroke (the outputs are under test, not the force)
        "--material",
        "MS",
        "--cell-size",
        "0.01",
        "--format",
        "json",
        "--fields",
        str(fields),
        "--animate",
        str(anim),
        "--frames",
        "4",
        "--series",
        str(tmp_path / "s.csv"),
        "--record-interval",
        "0.025",
    )
    assert code == 0, err
    import pandas as pd

    depth = pd.read_csv(tmp_path / "s.csv")["depth_m"].to_numpy()
    step = np.diff(depth)
    assert np.allclose(step[1:-1], 0.005, rtol=0.05)  # rows every 5 mm of travel
    assert json.loads(out)["force_z_N"] > 0
    assert fields.stat().st_size > 10_000
    assert anim.read_bytes()[:6] in (b"GIF89a", b"GIF87a")
    assert not list(tmp_path.glob(".*"))  # no temporary files left behind


def test_mpm_wheel_study_quick(run_cli, tmp_path):
    code, out, err = run_cli(
        "study", "run", "mpm-wheel", "--quick", "--out", str(tmp_path / "w"), "--format", "json"
    )
    assert code == 0, err
    rec = json.loads(out)[0]
    assert rec["force_z_mpm_N"] == pytest.approx(130.0, rel=0.05)  # vertical equilibrium under the load
    assert rec["sinkage_mpm_m"] > 0 and rec["sinkage_rft_m"] > 0
    assert (tmp_path / "w" / "mpm_wheel.png").exists() and (tmp_path / "w" / "mpm_wheel.csv").exists()


def test_mpm_wheel_warns_when_the_heap_reaches_the_end_of_a_short_bed(run_cli):
    """A locked wheel towed 0.15 m heaps grains about 0.075 m ahead of its axle. On a 0.3 m bed the
    heap reaches the bed's end, which holds it like a wall (pull -16.95 N against -11.96 N on the
    default bed, load 10 N): one warning line naming --bed-length, the result still written, exit 0.
    A bed shorter than the travel is refused."""
    args = ["mpm", "wheel", "--load", "10", "--omega", "0", "--forward-speed", "0.3", "--radius", "0.04",
            "--width", "0.05", "--cell-size", "0.01", "--duration", "0.5", "--format", "json"]  # fmt: skip
    code, out, err = run_cli(*args, "--bed-length", "0.3")
    assert code == 0, err
    assert json.loads(out)["drawbar_pull_N"] < 0
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("terradyn: warning: the grains heaped"), err
    assert "--bed-length above 0.3 m" in lines[0]
    code, out, err = run_cli(*args)
    assert code == 0 and "warning" not in err, err
    code, _, err = run_cli(*args, "--bed-length", "0.1")
    assert code == 1 and err.startswith("terradyn: error: --bed-length = 0.1 ") and "at least 0.23 m" in err


def test_mpm_wheel_warns_when_the_wheel_sinks_close_to_the_floor(run_cli):
    """The locked wheel of the test above sinks 32 mm, 0.8 radii, leaving 3.2 reaches of grains on the
    default bed (0.16 m deep; a 0.32 m bed moves its pull by 0.4 %): no warning there. On a 0.1 m bed
    it has 1.7 reaches left, fewer than the depth rule was checked for (docs/mpm.md, "The floor under
    a wheel that sinks"): one warning line naming --bed-depth and the metadata's flag, the result
    still written, exit 0. A depth that is not positive is refused."""
    args = ["mpm", "wheel", "--load", "10", "--omega", "0", "--forward-speed", "0.3", "--radius", "0.04",
            "--width", "0.05", "--cell-size", "0.01", "--duration", "0.5", "--format", "json"]  # fmt: skip
    code, out, err = run_cli(*args, "--bed-depth", "0.1")
    assert code == 0, err
    assert json.loads(out)["sinkage_m"] > 0.02
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("terradyn: warning: the wheel sank"), err
    assert "--bed-depth above 0.1 m" in lines[0]
    code, _, err = run_cli(*args, "--bed-depth", "0")
    assert code == 1 and err.startswith("terradyn: error: --bed-depth = 0 ") and "> 0" in err
