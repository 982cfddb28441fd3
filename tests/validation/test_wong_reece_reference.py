"""Wong-Reece wheel against hand-worked closed forms (textbook-style reference cases).

1. n = 1, cohesionless, K -> 0 (shear saturated: tau = sigma tan phi), theta_m inside the contact and a
   rear (negative) exit angle: every integral is elementary; the rear region uses the mapped angle
   theta* = alpha + beta theta, so the integrands are products of cosines of linear functions.
2. Bekker's classical rigid wheel (c1 = c2 = 0, no shear): the compaction resistance is the work of
   pressing a rut, R = b k z0^(n+1) / (n+1), exactly, for any n.
3. Small sinkage: with the rim approximated by a parabola, W = b k sqrt(2 r) z0^(n + 1/2) B_n,
   B_n = int_0^1 (1 - t^2)^n dt = sqrt(pi) Gamma(n + 1) / (2 Gamma(n + 3/2)) (= 2/3 for n = 1, Bekker's
   (3 - n)/3 factor), valid to O(z0 / r).
"""

from __future__ import annotations

import math

import pytest

from terradyn.materials import BekkerParameters
from terradyn.terramechanics import wong_reece_wheel, wong_reece_wheel_forces

R, B = 0.13, 0.16


def _closed_form_n1(k, mu, r, b, theta1, theta2, theta_m):
    """(W, DP, T) for sigma = k r (cos theta* - cos theta1), tau = mu sigma."""
    cc = math.cos(theta1)

    # Front region [theta_m, theta1]: sigma / (k r) = cos t - C.
    def f_cos(t):  # int (cos t - C) cos t
        return t / 2 + math.sin(2 * t) / 4 - cc * math.sin(t)

    def f_sin(t):  # int (cos t - C) sin t
        return math.sin(t) ** 2 / 2 + cc * math.cos(t)

    def f_one(t):  # int (cos t - C)
        return math.sin(t) - cc * t

    i_cos = f_cos(theta1) - f_cos(theta_m)
    i_sin = f_sin(theta1) - f_sin(theta_m)
    i_one = f_one(theta1) - f_one(theta_m)

    # Rear region [theta2, theta_m]: theta* = alpha + beta t.
    beta = -(theta1 - theta_m) / (theta_m - theta2)
    alpha = theta1 - beta * theta2

    def r_cos(t):  # int (cos(alpha + beta t) - C) cos t
        return 0.5 * (
            math.sin(alpha + (beta - 1) * t) / (beta - 1) + math.sin(alpha + (beta + 1) * t) / (beta + 1)
        ) - cc * math.sin(t)

    def r_sin(t):  # int (cos(alpha + beta t) - C) sin t
        return 0.5 * (
            math.cos(alpha + (beta - 1) * t) / (beta - 1) - math.cos(alpha + (beta + 1) * t) / (beta + 1)
        ) + cc * math.cos(t)

    def r_one(t):  # int (cos(alpha + beta t) - C)
        return math.sin(alpha + beta * t) / beta - cc * t

    i_cos += r_cos(theta_m) - r_cos(theta2)
    i_sin += r_sin(theta_m) - r_sin(theta2)
    i_one += r_one(theta_m) - r_one(theta2)

    scale = k * r
    w = r * b * scale * (i_cos + mu * i_sin)
    dp = r * b * scale * (mu * i_cos - i_sin)
    torque = r * r * b * scale * mu * i_one
    return w, dp, torque


@pytest.mark.parametrize(
    ("slip", "theta1", "theta2"),
    [(0.4, 0.45, -0.05), (0.8, 0.3, 0.0), (0.1, 0.9, -0.2)],
)
def test_linear_soil_saturated_shear_matches_closed_form(slip, theta1, theta2):
    soil = BekkerParameters(
        k_c=-1.0e4, k_phi=1.5e6, n=1.0, cohesion=0.0, friction_angle=math.radians(30.0), shear_modulus=1e-12
    )
    k = soil.k_c / B + soil.k_phi
    theta_m = (0.43 + 0.32 * slip) * theta1
    w, dp, torque = _closed_form_n1(k, math.tan(soil.friction_angle), R, B, theta1, theta2, theta_m)
    res = wong_reece_wheel_forces(R, B, soil, slip, entry_angle=theta1, exit_angle=theta2)
    assert res.load == pytest.approx(w, rel=1e-10)
    assert res.drawbar_pull == pytest.approx(dp, rel=1e-10)
    assert res.drive_torque == pytest.approx(torque, rel=1e-10)
    # And the inverse problem: the load gives back the entry angle.
    solved = wong_reece_wheel(R, B, soil, slip, w, exit_angle=theta2)
    assert solved.entry_angle == pytest.approx(theta1, rel=1e-9)
    assert solved.drawbar_pull == pytest.approx(dp, rel=1e-6)


@pytest.mark.parametrize("n", [1.0, 1.4, 2.0])
@pytest.mark.parametrize("load", [30.0, 130.0])
def test_bekker_compaction_resistance(n, load):
    soil = BekkerParameters(
        k_c=0.0, k_phi=2.0e6 * 0.02 ** (1.0 - n), n=n, cohesion=0.0, friction_angle=0.0, shear_modulus=0.01
    )
    res = wong_reece_wheel(R, B, soil, 0.3, load, c1=0.0, c2=0.0)
    k = soil.k_phi
    z0 = res.sinkage
    assert res.thrust == 0.0 and res.drive_torque == 0.0
    assert res.compaction_resistance == pytest.approx(B * k * z0 ** (n + 1) / (n + 1), rel=1e-6)
    assert res.drawbar_pull == pytest.approx(-B * k * z0 ** (n + 1) / (n + 1), rel=1e-6)


@pytest.mark.parametrize("n", [0.8, 1.0, 1.3])
def test_small_sinkage_load_matches_parabolic_rim(n):
    soil = BekkerParameters(k_c=2.0e3, k_phi=8.0e5, n=n, cohesion=0.0, friction_angle=0.0, shear_modulus=0.01)
    k = soil.k_c / B + soil.k_phi
    z0 = 1e-4 * R
    res = wong_reece_wheel_forces(R, B, soil, 0.0, sinkage=z0, c1=0.0, c2=0.0)
    b_n = math.sqrt(math.pi) * math.gamma(n + 1) / (2 * math.gamma(n + 1.5))
    expected = B * k * math.sqrt(2 * R) * z0 ** (n + 0.5) * b_n
    assert res.load == pytest.approx(expected, rel=5e-4)
