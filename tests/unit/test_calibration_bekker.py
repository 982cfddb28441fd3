"""Calibrating Bekker and Janosi-Hanamoto parameters from data the models themselves generate."""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from terradyn.errors import InputError, SolverError
from terradyn.materials import BekkerParameters, load
from terradyn.terramechanics import (
    PlateSinkageData,
    ShearData,
    bekker_pressure,
    combine_fits,
    fit_bekker,
    fit_shear,
    janosi_hanamoto_shear,
    read_plate_sinkage_csv,
    read_shear_csv,
    wong_reece_wheel,
    write_material_toml,
)

# A LETE-like sand (Wong's tables) and shear parameters of a firm sand.
K_C, K_PHI, N = 102.0e3, 5301.0e3, 0.793
COHESION, PHI, K = 1500.0, math.radians(34.0), 0.012
WIDTHS = (0.05, 0.1, 0.2)
STRESSES = (5.0e3, 10.0e3, 20.0e3, 40.0e3)


def _plate_tests(noise: float, seed: int = 7, k_c: float = K_C) -> dict[float, tuple[np.ndarray, np.ndarray]]:
    rng = np.random.default_rng(seed)
    tests = {}
    for b in WIDTHS:
        z = np.linspace(0.002, 0.05, 20)
        p = bekker_pressure(z, b, k_c, K_PHI, N) * (1.0 + noise * rng.standard_normal(z.size))
        tests[b] = (z, p)
    return tests


def _shear_tests(noise: float, seed: int = 11, cohesion: float = COHESION):
    rng = np.random.default_rng(seed)
    tests = {}
    for sigma in STRESSES:
        j = np.linspace(0.0, 0.08, 25)
        tau = janosi_hanamoto_shear(j, sigma, cohesion, PHI, K) * (1.0 + noise * rng.standard_normal(j.size))
        tests[sigma] = (j, tau)
    return tests


def test_exact_plate_data_are_recovered_exactly():
    fit = fit_bekker(_plate_tests(0.0))
    assert fit.k_c == pytest.approx(K_C, rel=1e-6)
    assert fit.k_phi == pytest.approx(K_PHI, rel=1e-7)
    assert fit.n == pytest.approx(N, rel=1e-7)
    assert fit.r_squared == pytest.approx(1.0, abs=1e-10)
    assert fit.plate_widths == WIDTHS and fit.point_count == 60


@pytest.mark.parametrize("seed", [7, 8, 9])
def test_noisy_plate_data_give_parameters_within_a_few_percent(seed):
    fit = fit_bekker(_plate_tests(0.015, seed))
    assert fit.k_c == pytest.approx(K_C, rel=0.05)
    assert fit.k_phi == pytest.approx(K_PHI, rel=0.02)
    assert fit.n == pytest.approx(N, rel=0.02)
    assert 0.99 < fit.r_squared < 1.0
    assert 0.005 < fit.rms_relative_residual < 0.03
    z = np.array([0.01, 0.03])
    np.testing.assert_allclose(fit.pressure(z, 0.1), bekker_pressure(z, 0.1, K_C, K_PHI, N), rtol=0.02)


def test_negative_k_c_is_recovered():
    fit = fit_bekker(_plate_tests(0.01, k_c=-1.0e5))
    assert fit.k_c == pytest.approx(-1.0e5, rel=0.05)
    assert fit.k_phi == pytest.approx(K_PHI, rel=0.02)


def test_exact_shear_data_are_recovered_exactly():
    fit = fit_shear(_shear_tests(0.0))
    assert fit.cohesion == pytest.approx(COHESION, rel=1e-6)
    assert fit.friction_angle == pytest.approx(PHI, rel=1e-8)
    assert fit.shear_modulus == pytest.approx(K, rel=1e-6)
    assert fit.normal_stresses == STRESSES


@pytest.mark.parametrize("seed", [11, 12, 13])
def test_noisy_shear_data_give_parameters_within_a_few_percent(seed):
    fit = fit_shear(ShearData.from_tests(_shear_tests(0.015, seed)))
    assert fit.cohesion == pytest.approx(COHESION, rel=0.05)
    assert fit.friction_angle == pytest.approx(PHI, rel=0.02)
    assert fit.shear_modulus == pytest.approx(K, rel=0.03)
    assert fit.r_squared > 0.99


def test_cohesionless_shear_fit_keeps_cohesion_non_negative_and_small():
    fit = fit_shear(_shear_tests(0.015, 5, cohesion=0.0))
    assert 0.0 <= fit.cohesion < 0.01 * STRESSES[-1] * math.tan(PHI)
    assert fit.friction_angle == pytest.approx(PHI, rel=0.02)


def test_fitted_soil_predicts_the_same_wheel():
    """End to end: plate + shear data of a soil -> fitted soil -> Wong-Reece wheel within a few %."""
    true = BekkerParameters(K_C, K_PHI, N, COHESION, PHI, K)
    fitted = combine_fits(fit_bekker(_plate_tests(0.015)), fit_shear(_shear_tests(0.015)))
    a = wong_reece_wheel(0.13, 0.16, true, 0.3, 130.0)
    b = wong_reece_wheel(0.13, 0.16, fitted, 0.3, 130.0)
    assert b.sinkage == pytest.approx(a.sinkage, rel=0.03)
    assert b.drawbar_pull == pytest.approx(a.drawbar_pull, rel=0.03)
    assert b.drive_torque == pytest.approx(a.drive_torque, rel=0.03)


def test_fit_errors():
    one_width = {0.1: _plate_tests(0.0)[0.1]}
    with pytest.raises(InputError, match="plate_width"):
        fit_bekker(one_width)
    bad = _plate_tests(0.0)
    z, p = bad[0.1]
    p = p.copy()
    p[3] = 0.0
    bad[0.1] = (z, p)
    with pytest.raises(InputError, match="pressure"):
        fit_bekker(bad)
    with pytest.raises(InputError, match="normal_stress"):
        fit_shear({1.0e4: _shear_tests(0.0)[1.0e4]})
    with pytest.raises(InputError, match="sinkage"):
        PlateSinkageData(np.array([0.1, 0.1]), np.array([0.01, -0.01]), np.array([1.0, 2.0]))
    with pytest.raises(InputError, match="shear_stress"):
        ShearData(np.array([1.0, 2.0]), np.array([0.0, 0.1]), np.array([1.0]))


def test_plate_data_that_are_not_a_bekker_soil_are_a_solver_error():
    # Pressure falling with width at fixed sinkage faster than any k_phi > 0 allows.
    z = np.array([0.01, 0.02, 0.04])
    tests = {0.05: (z, 1.0e4 * z / 0.02), 0.2: (z, 1.0e2 * z / 0.02)}
    with pytest.raises(SolverError, match="k_phi"):
        fit_bekker(tests)


# ---------------------------------------------------------------------------- files


def test_csv_round_trip_and_fit(tmp_path):
    plate = tmp_path / "plates.csv"
    lines = ["# plate tests, SI", "plate_width_m,sinkage_m,pressure_Pa", "0.05,0,0"]
    for b, (z, p) in _plate_tests(0.0).items():
        lines += [f"{b!r},{float(zi)!r},{float(pi)!r}" for zi, pi in zip(z, p, strict=True)]
    plate.write_text("\n".join(lines) + "\n", encoding="utf-8")
    data = read_plate_sinkage_csv(plate)
    assert data.source == "plates.csv" and data.plate_width.size == 61
    fit = fit_bekker(data)  # the zero row is skipped
    assert fit.point_count == 60 and fit.n == pytest.approx(N, rel=1e-7)

    shear = tmp_path / "shear.csv"
    rows = ["shear_stress_Pa,normal_stress_Pa,shear_displacement_m"]  # any column order
    for sigma, (j, tau) in _shear_tests(0.0).items():
        rows += [f"{float(t)!r},{sigma!r},{float(x)!r}" for x, t in zip(j, tau, strict=True)]
    shear.write_text("\n".join(rows) + "\n", encoding="utf-8")
    sfit = fit_shear(read_shear_csv(shear))
    assert sfit.shear_modulus == pytest.approx(K, rel=1e-6)


def test_csv_errors_name_file_line_and_column(tmp_path):
    with pytest.raises(InputError, match="existing CSV"):
        read_plate_sinkage_csv(tmp_path / "missing.csv")
    f = tmp_path / "p.csv"
    f.write_text("plate_width_m,sinkage_m\n0.1,0.01\n", encoding="utf-8")
    with pytest.raises(InputError, match="pressure_Pa"):
        read_plate_sinkage_csv(f)
    f.write_text("plate_width_m,sinkage_m,pressure_Pa,depth\n0.1,0.01,5,1\n", encoding="utf-8")
    with pytest.raises(InputError, match="depth"):
        read_plate_sinkage_csv(f)
    f.write_text("plate_width_m,sinkage_m,pressure_Pa\n0.1,0.01,5\n0.1,abc,6\n", encoding="utf-8")
    with pytest.raises(InputError, match=r"p\.csv line 3 column sinkage_m"):
        read_plate_sinkage_csv(f)
    f.write_text("plate_width_m,sinkage_m,pressure_Pa\n0.1,0.01,5\n-0.1,0.02,6\n", encoding="utf-8")
    with pytest.raises(InputError, match="line 3 column plate_width_m"):
        read_plate_sinkage_csv(f)
    s = tmp_path / "s.csv"
    s.write_text("normal_stress_Pa,shear_displacement_m,shear_stress_Pa\n1000,0.01,nan\n", encoding="utf-8")
    with pytest.raises(InputError, match="line 2 column shear_stress_Pa"):
        read_shear_csv(s)


def test_written_toml_loads_back(tmp_path):
    soil = combine_fits(fit_bekker(_plate_tests(0.01)), fit_shear(_shear_tests(0.01)))
    notes = 'Fitted by "terradyn" to plates.csv\nand shear.csv \\ R^2 = 0.999'
    path = write_material_toml(
        tmp_path / "lete.toml", "LETE-fit", bekker=soil, citation="own tests", notes=notes
    )
    mat = load(path)
    assert mat.name == "LETE-fit"
    assert mat.provenance.notes == notes
    assert mat.provenance.citation == "own tests"
    got = mat.require_bekker()
    for field in ("k_c", "k_phi", "n", "cohesion", "shear_modulus"):
        assert getattr(got, field) == getattr(soil, field)
    assert got.friction_angle == pytest.approx(soil.friction_angle, rel=1e-14)
    raw = tomllib.loads(path.read_text(encoding="utf-8"))
    assert raw["bekker"]["friction_angle_deg"] == pytest.approx(math.degrees(soil.friction_angle))
    assert [p.name for p in tmp_path.iterdir()] == ["lete.toml"]  # no temporary file left behind


def test_write_toml_errors(tmp_path):
    soil = BekkerParameters(K_C, K_PHI, N, COHESION, PHI, K)
    with pytest.raises(InputError, match="name"):
        write_material_toml(tmp_path / "x.toml", "  ", bekker=soil)
    with pytest.raises(InputError, match="path"):
        write_material_toml(tmp_path / "no" / "x.toml", "x", bekker=soil)
