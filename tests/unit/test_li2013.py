import numpy as np
import pytest

from terradyn import materials
from terradyn.materials import LiCoefficients
from terradyn.rft import li2013_alpha, li2013_alpha_from_directions, rft_angles

GEN = LiCoefficients.generic()
rng = np.random.default_rng(0)
BETA = rng.uniform(-np.pi, np.pi, 500)
GAMMA = rng.uniform(-np.pi, np.pi, 500)


def test_plate_pushed_down_equals_zeta():
    for name in materials.available():
        mat = materials.get(name)
        rft = mat.require_rft()
        _, az = li2013_alpha(0.0, np.pi / 2, rft.coefficients, rft.scale)
        assert float(az) == pytest.approx(mat.zeta, rel=1e-12)


def test_beta_period_pi():
    a = li2013_alpha(BETA, GAMMA, GEN)
    b = li2013_alpha(BETA + np.pi, GAMMA, GEN)
    np.testing.assert_allclose(a, b, atol=1e-12)


def test_mirror_symmetry():
    ax, az = li2013_alpha(BETA, GAMMA, GEN)
    mx, mz = li2013_alpha(-BETA, np.pi - GAMMA, GEN)
    np.testing.assert_allclose(mz, az, atol=1e-12)
    np.testing.assert_allclose(mx, -ax, atol=1e-12)


def test_cm11_term_is_a_cosine():
    # Only Cm11 set: alpha_x = cos(-2 beta + gamma).
    c = LiCoefficients(0, 0, 0, 0, 0, 0, 0, 1.0, 0)
    ax, _ = li2013_alpha(BETA, GAMMA, c)
    np.testing.assert_allclose(ax, np.cos(-2 * BETA + GAMMA), atol=1e-14)


def test_trig_free_form_matches_angles():
    phi = rng.uniform(-np.pi, np.pi, 500)
    normals = np.column_stack((np.cos(phi), np.sin(phi)))
    vel = rng.normal(size=(500, 2)) * rng.uniform(0.1, 10, (500, 1))
    beta, gamma = rft_angles(normals, vel)
    ref = li2013_alpha(beta, gamma, GEN, 3.0)
    got = li2013_alpha_from_directions(normals, vel, GEN.as_array(), 3.0)
    np.testing.assert_allclose(got, ref, atol=1e-12)


def test_known_values_generic():
    # Horizontal drag of a horizontal plate (beta = 0, gamma = 0): alpha_x = C01 + C11 + Cm11.
    ax, az = li2013_alpha(0.0, 0.0, GEN)
    assert float(ax) == pytest.approx(0.253 - 0.124 + 0.007)
    assert float(az) == pytest.approx(0.206 + 0.169)
    # A horizontal plate pulled straight up is resisted downward.
    _, az_up = li2013_alpha(0.0, -np.pi / 2, GEN)
    assert float(az_up) == pytest.approx(0.206 + 0.169 - 0.358 - 0.212 - 0.055)
    assert az_up < 0
