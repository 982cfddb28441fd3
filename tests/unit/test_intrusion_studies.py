import numpy as np
import pytest

from terradyn import materials
from terradyn.geometry import Plate
from terradyn.rft import li2013_alpha_material
from terradyn.studies.intrusion import alpha_map_plate, intrusion_forces

MS = materials.get("MS")


def test_alpha_map_from_plate_intrusion_reproduces_the_law():
    angles = np.radians(np.arange(-90, 91, 15))
    dirs = np.radians(np.arange(0, 181, 15))
    t = alpha_map_plate(MS, angles=angles, directions=dirs)
    ax, az = li2013_alpha_material(t.columns["beta_rad"], t.columns["direction_rad"], MS)
    np.testing.assert_allclose(t.columns["alpha_z_N_per_m3"], az, atol=1e-6 * MS.zeta)
    np.testing.assert_allclose(t.columns["alpha_x_N_per_m3"], ax, atol=1e-6 * MS.zeta)


def test_force_linear_in_depth_once_submerged():
    plate = Plate(0.05, 0.02)
    d = np.linspace(0.03, 0.1, 8)
    t = intrusion_forces(plate, MS, d, angle=0.4, direction=1.1)
    for key in ("force_x_N", "force_z_N"):
        coef = np.polyfit(d, t.columns[key], 1)
        assert coef[1] == pytest.approx(0.0, abs=1e-9 * abs(coef[0]))
        np.testing.assert_allclose(np.polyval(coef, d), t.columns[key], rtol=1e-9, atol=1e-12)


def test_partially_buried_tilted_plate_matches_closed_form():
    # Buried part of a plate tilted by t with centre depth d: F_z = alpha_z w (d + a sin t)^2 / (2 sin t).
    length, width, t = 0.05, 0.02, 0.5
    _, az = li2013_alpha_material(-t, np.pi / 2, MS)
    a, k = length / 2, np.sin(t)
    for d in (0.002, 0.005, 0.01):
        got = intrusion_forces(Plate(length, width), MS, [d], angle=t, element_size=2e-5)
        want = float(az) * width * (d + a * k) ** 2 / (2 * k)
        assert got.columns["force_z_N"][0] == pytest.approx(want, rel=2e-3)
