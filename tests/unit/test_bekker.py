"""Bekker and Reece pressure-sinkage laws and the Janosi-Hanamoto shear law."""

from __future__ import annotations

import math

import numpy as np
import pytest

from terradyn.errors import InputError
from terradyn.terramechanics import bekker_pressure, janosi_hanamoto_shear, reece_pressure


def test_bekker_is_linear_in_the_moduli():
    z = np.linspace(0.0, 0.05, 11)
    b = 0.1
    p1 = bekker_pressure(z, b, 2.0e4, 1.0e6, 1.1)
    p2 = bekker_pressure(z, b, -5.0e3, 3.0e6, 1.1)
    both = bekker_pressure(z, b, 2.0e4 - 5.0e3, 4.0e6, 1.1)
    np.testing.assert_allclose(both, p1 + p2, rtol=1e-13)
    np.testing.assert_allclose(bekker_pressure(z, b, 6.0e4, 3.0e6, 1.1), 3.0 * p1, rtol=1e-13)


@pytest.mark.parametrize("n", [0.5, 1.0, 1.4])
def test_bekker_scales_with_sinkage_to_the_n(n):
    z = np.array([0.003, 0.01, 0.02])
    p = bekker_pressure(z, 0.16, -2.05e4, 3.13e6, n)
    p2 = bekker_pressure(2.0 * z, 0.16, -2.05e4, 3.13e6, n)
    np.testing.assert_allclose(p2 / p, 2.0**n, rtol=1e-13)


def test_bekker_width_dependence_and_broadcasting():
    widths = np.array([[0.05], [0.1], [0.2]])
    z = np.array([0.01, 0.02])
    p = bekker_pressure(z, widths, 1.0e5, 5.0e6, 1.0)
    assert p.shape == (3, 2)
    # p b / z = k_c + k_phi b: linear in b with slope k_phi and intercept k_c.
    slope, intercept = np.polyfit(widths[:, 0], (p * widths / z)[:, 0], 1)
    assert slope == pytest.approx(5.0e6, rel=1e-10)
    assert intercept == pytest.approx(1.0e5, rel=1e-8)


def test_bekker_scalar_in_scalar_out_and_no_pressure_above_surface():
    value = bekker_pressure(0.01, 0.1, 0.0, 1.0e6, 1.0)
    assert isinstance(value, float)
    assert value == pytest.approx(1.0e4)
    assert bekker_pressure(-0.01, 0.1, 0.0, 1.0e6, 1.0) == 0.0


@pytest.mark.parametrize(
    ("args", "field"),
    [
        ((0.01, 0.0, 1.0, 1.0e6, 1.0), "plate_width"),
        ((0.01, 0.1, 1.0, 1.0e6, 5.0), "n"),
        ((0.01, 0.1, -2.0e5, 1.0e6, 1.0), "k_c / plate_width + k_phi"),
        ((float("nan"), 0.1, 0.0, 1.0e6, 1.0), "sinkage"),
    ],
)
def test_bekker_bad_inputs_name_the_field(args, field):
    with pytest.raises(InputError, match=field.replace("+", r"\+")):
        bekker_pressure(*args)


def test_reece_equals_bekker_for_n_one():
    # For n = 1: p = (c k'_c / b + gamma k'_phi) z, i.e. Bekker with k_c = c k'_c, k_phi = gamma k'_phi.
    c, gamma, kc1, kphi1 = 800.0, 15000.0, 20.0, 300.0
    z = np.linspace(0.0, 0.04, 9)
    for b in (0.05, 0.16, 0.4):
        np.testing.assert_allclose(
            reece_pressure(z, b, c, gamma, kc1, kphi1, 1.0),
            bekker_pressure(z, b, c * kc1, gamma * kphi1, 1.0),
            rtol=1e-13,
        )


def test_reece_cohesionless_grows_linearly_with_width_at_fixed_relative_sinkage():
    ratio = 0.1  # z / b
    b = np.array([0.05, 0.1, 0.2])
    p = reece_pressure(ratio * b, b, 0.0, 15000.0, 10.0, 500.0, 0.8)
    np.testing.assert_allclose(p / b, p[0] / b[0], rtol=1e-13)


def test_reece_bad_modulus():
    with pytest.raises(InputError, match="k_phi_prime"):
        reece_pressure(0.01, 0.1, 0.0, 15000.0, 10.0, -1.0, 1.0)
    with pytest.raises(InputError, match="unit_weight"):
        reece_pressure(0.01, 0.1, 0.0, -1.0, 10.0, 1.0, 1.0)


def test_janosi_hanamoto_limits():
    sigma = np.array([0.0, 1.0e3, 1.0e4])
    c, phi, k = 500.0, math.radians(30.0), 0.01
    strength = c + sigma * math.tan(phi)
    np.testing.assert_allclose(janosi_hanamoto_shear(0.0, sigma, c, phi, k), 0.0, atol=0.0)
    np.testing.assert_allclose(janosi_hanamoto_shear(1.0e3, sigma, c, phi, k), strength, rtol=1e-14)
    np.testing.assert_allclose(
        janosi_hanamoto_shear(k, sigma, c, phi, k), strength * (1.0 - math.exp(-1.0)), rtol=1e-14
    )


def test_janosi_hanamoto_is_monotonic_and_odd():
    j = np.linspace(0.0, 0.1, 101)
    tau = janosi_hanamoto_shear(j, 2.0e4, 0.0, math.radians(35.0), 0.02)
    assert np.all(np.diff(tau) > 0)
    np.testing.assert_allclose(janosi_hanamoto_shear(-j, 2.0e4, 0.0, math.radians(35.0), 0.02), -tau)


@pytest.mark.parametrize(
    ("args", "field"),
    [
        ((0.01, -1.0, 0.0, 0.5, 0.01), "normal_stress"),
        ((0.01, 1.0, -1.0, 0.5, 0.01), "cohesion"),
        ((0.01, 1.0, 0.0, 2.0, 0.01), "friction_angle"),
        ((0.01, 1.0, 0.0, 0.5, 0.0), "shear_modulus"),
    ],
)
def test_janosi_hanamoto_bad_inputs(args, field):
    with pytest.raises(InputError, match=field):
        janosi_hanamoto_shear(*args)
