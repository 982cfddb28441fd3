"""The ``dem-calibrated`` study: DEM plate tests calibrate RFT (zeta) and MPM (mu_s), then a DEM
wheel is set beside the RFT and MPM predictions.

The first tests replace the DEM and MPM runs by stand-ins with known answers to check the plumbing
(the fits recover the stand-ins' parameters, every run gets the calibrated medium, results are
dimensionless); the quick study with real LAMMPS and MPM runs is in the slow tier.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from terradyn.errors import InputError
from terradyn.studies.dem_calibrated import dem_calibrated_wheel

ZETA_DEM = 0.6e6  # N/m^3 of the DEM stand-in's plate law
MU_DEM = 0.42  # the mu_s at which the MPM stand-in's plate matches the DEM stand-in


@pytest.fixture
def stand_ins(monkeypatch):
    """DEM plate: F = ZETA_DEM * L * W * depth; MPM plate: F = ZETA_DEM * L * W * depth *
    (mu / MU_DEM)^2; DEM and MPM wheels return fixed dimensionless values. Returns the calls."""
    import terradyn.dem
    import terradyn.dem.runs
    import terradyn.dem.wheel
    import terradyn.mpm

    calls: dict[str, list] = {"dem_plate": [], "mpm_plate": [], "dem_wheel": [], "mpm_wheel": []}

    def dem_plate(body, material, *, depth, speed, bed_spec, **kw):
        calls["dem_plate"].append({"seed": bed_spec.seed, "depth": depth, "material": material})
        d = np.linspace(-0.002, depth, 30)
        f = np.where(d > 0, ZETA_DEM * body.length * body.width * d, 0.0)
        return SimpleNamespace(history={"depth_m": d, "force_z_N": f})

    def mpm_plate(plate, material, *, depth, friction_coefficient, **kw):
        calls["mpm_plate"].append(friction_coefficient)
        d = np.linspace(0.0, depth * 1.2, 40)
        f = ZETA_DEM * plate.length * plate.width * d * (friction_coefficient / MU_DEM) ** 2
        return SimpleNamespace(to_dataframe=lambda: pd.DataFrame({"depth_m": d, "force_z_N": f}))

    def dem_wheel(body, material, *, load, omega, slip, duration, gravity, seed, record_interval, **kw):
        calls["dem_wheel"].append({"seed": seed, "load": load, "material": material})
        r = body.outer_radius
        t = np.arange(1, 11) * record_interval
        hist = {
            "time_s": t,
            "x_m": (1 - slip) * omega * r * t,
            "sinkage_m": np.full(10, 0.25 * r),
            "drawbar_pull_N": np.full(10, -0.3 * load),
            "drive_torque_Nm": np.full(10, 0.2 * load * r),
            "vertical_force_N": np.full(10, load),
        }
        summary = {
            "sinkage_m": 0.25 * r + 1e-4 * seed,
            "drawbar_pull_N": -0.3 * load,
            "drive_torque_Nm": 0.2 * load * r,
            "vertical_force_N": load,
            "grain_count": 900,
        }
        return SimpleNamespace(summary=summary, history=hist, bed={"packing_fraction": 0.59})

    def mpm_wheel(wheel, material, *, load, omega, slip, resolution, drive):
        calls["mpm_wheel"].append({"material": material, "cell_size": resolution.cell_size, "drive": drive})
        r = wheel.outer_radius
        n = 8
        series = {
            "phase": np.array(["sink"] * 2 + ["drive"] * n),
            "x_m": np.linspace(0, 0.01, n + 2),
            "sinkage_m": np.full(n + 2, 0.3 * r),
            "drawbar_pull_N": np.full(n + 2, -0.1 * load),
            "drive_torque_Nm": np.full(n + 2, 0.33 * load * r),
            "force_z_N": np.full(n + 2, load),
        }
        summary = {
            "sinkage_m": 0.3 * r,
            "drawbar_pull_N": -0.1 * load,
            "drive_torque_Nm": 0.33 * load * r,
            "force_z_N": load,
        }
        return SimpleNamespace(summary=summary, series=series)

    monkeypatch.setattr(terradyn.dem, "load_lammps", lambda: None)
    monkeypatch.setattr(terradyn.dem.runs, "run_intrusion", dem_plate)
    monkeypatch.setattr(terradyn.dem.wheel, "run_wheel", dem_wheel)
    monkeypatch.setattr(terradyn.mpm, "run_intrusion", mpm_plate)
    monkeypatch.setattr(terradyn.mpm, "run_wheel", mpm_wheel)
    return calls


def test_the_fits_recover_the_plate_law_and_every_model_gets_its_calibrated_medium(stand_ins):
    res = dem_calibrated_wheel(
        seeds=(4, 5),
        plate_length=0.03,
        width=0.05,
        plate_depth=0.01,
        radius=0.016,
        load=1.0,
        travel=0.02,
        mpm_cell_size=0.004,
    )
    assert [c["seed"] for c in stand_ins["dem_plate"]] == [4, 5]
    # RFT's generic alpha_z of a horizontal plate moving down is 1: zeta is the DEM's plate law
    assert res.fits["zeta_N_per_cm3"] == pytest.approx(ZETA_DEM / 1e6, rel=0.02)
    assert res.fits["rft_r_squared"] > 0.99
    assert res.fits["mpm_friction_coefficient"] == pytest.approx(MU_DEM, rel=0.01)
    assert res.fits["mpm_friction_table"] == 0.5  # generic's own mu_s, left in the base medium
    # the plate table holds the fitted rows only (centre below the surface, down to plate_depth)
    p = res.plate.columns
    assert p["depth_m"].min() > 0 and p["depth_m"].max() <= 0.01 + 1e-12
    assert set(p["seed"]) == {4, 5}
    assert np.allclose(
        p["mpm_force_z_N"] * res.fits["mpm_scale_data_over_model"], p["dem_force_z_N"], rtol=0.02
    )
    # wheels: two DEM seeds, then RFT and MPM calibrated, then with the table values
    w = res.wheels.columns
    assert list(w["model"]) == ["DEM", "DEM", "RFT", "MPM", "RFT", "MPM"]
    assert list(w["calibrated"]) == [True, True, True, True, False, False]
    fitted_mu = stand_ins["mpm_wheel"][0]["material"].continuum.friction_coefficient
    assert fitted_mu == pytest.approx(res.fits["mpm_friction_coefficient"])
    assert stand_ins["mpm_wheel"][1]["material"].continuum.friction_coefficient == 0.5
    assert stand_ins["mpm_wheel"][0]["cell_size"] == 0.004
    assert stand_ins["mpm_wheel"][0]["drive"].duration == pytest.approx(0.02 / (0.7 * 6.0 * 0.016))
    assert w["drive_torque_over_MgL"][0] == pytest.approx(0.2)  # DEM: torque / (M g L)
    assert w["sinkage_over_L"][3] == pytest.approx(0.3)  # MPM
    # the calibrated RFT medium is weaker than generic's zeta = 1 N/cm^3: its wheel sinks deeper
    assert w["sinkage_over_L"][2] > w["sinkage_over_L"][4] > 0
    labels = [label for label, _ in res.histories]
    assert labels == ["DEM, seed 4", "DEM, seed 5", "MPM, calibrated mu_s", "MPM, table mu_s"]
    mpm_hist = res.histories[2][1]
    assert mpm_hist["travel_over_L"][0] == 0.0 and len(mpm_hist["travel_over_L"]) == 8  # drive rows only


def test_the_study_writes_its_tables_and_figure(stand_ins, run_cli, tmp_path):
    code, _, err = run_cli("study", "run", "dem-calibrated", "--quick", "--out", str(tmp_path / "a"))
    assert code == 0, err
    for name in (
        "dem_calibrated_plate",
        "dem_calibrated_fits",
        "dem_calibrated_wheels",
        "dem_calibrated_histories",
    ):
        assert (tmp_path / "a" / f"{name}.csv").is_file(), name
    wheels = pd.read_csv(tmp_path / "a" / "dem_calibrated_wheels.csv")
    assert list(wheels["model"]) == ["DEM", "DEM", "RFT", "MPM"]  # quick: two seeds, calibrated only
    assert (tmp_path / "a" / "dem_calibrated.png").stat().st_size > 20_000


def test_bad_inputs_are_named(stand_ins):
    with pytest.raises(InputError, match="seeds"):
        dem_calibrated_wheel(seeds=(1, 1))
    with pytest.raises(InputError, match="slip"):
        dem_calibrated_wheel(slip=-1.0)
    with pytest.raises(InputError, match="mpm_cell_size"):
        dem_calibrated_wheel(mpm_cell_size=0.0)
    # a plate depth shallower than the first recorded row below the surface leaves nothing to fit
    with pytest.raises(InputError, match="plate_depth"):
        dem_calibrated_wheel(plate_depth=1e-5)
    assert not stand_ins["mpm_plate"]  # refused before any MPM run


def test_the_study_without_the_dem_extra_is_one_line(run_cli, tmp_path, monkeypatch):
    import terradyn.dem
    from terradyn.dem import DEMUnavailable

    def missing() -> None:
        raise DEMUnavailable()

    monkeypatch.setattr(terradyn.dem, "load_lammps", missing)
    code, _, err = run_cli("study", "run", "dem-calibrated", "--quick", "--out", str(tmp_path / "a"))
    assert code == 1
    assert err.strip() == "terradyn: error: DEM needs the optional extra: pip install 'terradyn[dem]'"
    assert not (tmp_path / "a").exists()
