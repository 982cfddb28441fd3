import json

import numpy as np
import pytest

from terradyn import materials


def _plates(path, rng):
    from terradyn.terramechanics import bekker_pressure

    rows = ["plate_width_m,sinkage_m,pressure_Pa"]
    for b in (0.05, 0.1, 0.2):
        for z in np.linspace(0.005, 0.05, 8):
            rows.append(f"{b},{z},{bekker_pressure(z, b, 5e4, 2e6, 1.1) * (1 + rng.normal(0, 0.01))}")
    path.write_text("\n".join(rows) + "\n")


def _shear(path, rng):
    from terradyn.terramechanics import janosi_hanamoto_shear

    rows = ["normal_stress_Pa,shear_displacement_m,shear_stress_Pa"]
    for s in (5e3, 1e4, 2e4):
        for j in np.linspace(0.001, 0.05, 10):
            t = janosi_hanamoto_shear(j, s, 800.0, np.radians(32), 0.01)
            rows.append(f"{s},{j},{t * (1 + rng.normal(0, 0.01))}")
    path.write_text("\n".join(rows) + "\n")


def test_calibrate_bekker_recovers_and_writes_material(run_cli, tmp_path):
    rng = np.random.default_rng(0)
    _plates(tmp_path / "p.csv", rng)
    _shear(tmp_path / "s.csv", rng)
    toml = tmp_path / "soil.toml"
    code, out, err = run_cli(
        "calibrate",
        "bekker",
        "--plates",
        str(tmp_path / "p.csv"),
        "--shear",
        str(tmp_path / "s.csv"),
        "--material-out",
        str(toml),
        "--name",
        "soil",
        "--format",
        "json",
    )
    assert code == 0, err
    rec = json.loads(out)
    assert rec["k_phi_N_per_m_n2"] == pytest.approx(2e6, rel=0.05)
    assert rec["n"] == pytest.approx(1.1, rel=0.05)
    assert rec["friction_angle_deg"] == pytest.approx(32, abs=1.0)
    assert rec["shear_modulus_m"] == pytest.approx(0.01, rel=0.1)
    mat = materials.load(toml)
    assert mat.bekker.k_phi == pytest.approx(rec["k_phi_N_per_m_n2"])


def test_calibrate_rft_cli_and_errors(run_cli, tmp_path):
    csv = tmp_path / "plate.csv"
    csv.write_text("depth_m,force_z_N\n0.02,12.12\n0.04,24.24\n0.06,36.36\n")
    code, out, err = run_cli(
        "calibrate", "rft", str(csv), "--length", "0.05", "--width", "0.06", "--format", "json"
    )
    assert code == 0, err
    assert json.loads(out)["zeta_N_per_m3"] == pytest.approx(12.12 / (0.05 * 0.06 * 0.02), rel=1e-6)
    code, _, err = run_cli(
        "calibrate", "rft", str(tmp_path / "missing.csv"), "--length", "0.05", "--width", "0.06"
    )
    assert code == 1 and "missing.csv" in err
    code, _, err = run_cli("calibrate", "bekker", "--plates", str(csv))
    assert code == 1 and "plate_width_m" in err
