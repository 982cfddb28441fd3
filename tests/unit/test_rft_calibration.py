import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.geometry import Plate
from terradyn.rft.calibration import PlateData, fit_rft, read_plate_force_csv, write_rft_material_toml
from terradyn.studies.intrusion import intrusion_forces


def _synthetic(mat, angles, directions, depths, noise, seed=0):
    rng = np.random.default_rng(seed)
    rows = {"depth_m": [], "force_z_N": [], "force_x_N": [], "angle_deg": [], "direction_deg": []}
    plate = Plate(0.0381, 0.0254)
    for a in angles:
        for g in directions:
            t = intrusion_forces(plate, mat, depths, angle=np.radians(a), direction=np.radians(g))
            fz = t.columns["force_z_N"]
            fx = t.columns["force_x_N"]
            scale = noise * max(np.abs(fz).max(), 1e-9)
            rows["depth_m"] += list(depths)
            rows["force_z_N"] += list(fz + rng.normal(0, scale, fz.size))
            rows["force_x_N"] += list(fx + rng.normal(0, scale, fx.size))
            rows["angle_deg"] += [a] * len(depths)
            rows["direction_deg"] += [g] * len(depths)
    return PlateData(
        *(np.array(rows[k]) for k in ("depth_m", "force_z_N", "force_x_N")),
        np.array(rows["angle_deg"]),
        np.array(rows["direction_deg"]),
    )


def test_recovers_zeta_from_noisy_data():
    ms = materials.get("MS")
    data = _synthetic(ms, [0.0], [90.0], np.linspace(0.02, 0.1, 9), noise=0.02)
    fit = fit_rft(data, plate_length=0.0381, plate_width=0.0254)
    assert fit.zeta == pytest.approx(ms.zeta, rel=0.02)
    assert fit.r_squared > 0.99


def test_recovers_full_coefficient_set():
    lp = materials.get("poppy-lp")
    angles = [-60, -30, 0, 30, 60]
    dirs = [30, 60, 90, 120, 150]
    data = _synthetic(lp, angles, dirs, np.linspace(0.05, 0.1, 3), noise=0.0)
    fit = fit_rft(data, plate_length=0.0381, plate_width=0.0254, full=True)
    got = fit.rft.coefficients.as_array() * fit.rft.scale
    want = lp.rft.coefficients.as_array() * lp.rft.scale
    # Directions within (0, 180) deg and angles in [-60, 60] identify every term.
    np.testing.assert_allclose(got, want, rtol=1e-6, atol=1e-3 * np.abs(want).max())


def test_csv_roundtrip_and_toml(tmp_path):
    ms = materials.get("MS")
    data = _synthetic(ms, [0.0], [90.0], np.linspace(0.02, 0.1, 5), noise=0.0)
    csv = tmp_path / "plate.csv"
    csv.write_text(
        "depth_m,force_z_N\n"
        + "\n".join(f"{d},{f}" for d, f in zip(data.depth_m, data.force_z_N, strict=True))
    )
    fit = fit_rft(read_plate_force_csv(csv), plate_length=0.0381, plate_width=0.0254)
    assert fit.zeta == pytest.approx(ms.zeta, rel=1e-9)
    out = write_rft_material_toml(tmp_path / "fit.toml", "my-sand", fit, source="plate.csv")
    assert materials.load(out).zeta == pytest.approx(ms.zeta, rel=1e-12)


def test_bad_data(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("depth_m,force_z_N\n0.01,1.0\n0.02,abc\n")
    with pytest.raises(InputError, match="row 3 column force_z_N"):
        read_plate_force_csv(bad)
    missing = tmp_path / "m.csv"
    missing.write_text("depth,force\n1,2\n")
    with pytest.raises(InputError, match="depth_m"):
        read_plate_force_csv(missing)
    ms = materials.get("MS")
    data = _synthetic(ms, [0.0], [90.0], np.linspace(0.02, 0.1, 3), noise=0.0)
    with pytest.raises(InputError, match="distinct"):
        fit_rft(data, plate_length=0.0381, plate_width=0.0254, full=True)
