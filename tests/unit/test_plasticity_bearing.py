"""Closed-form bearing factors, depth factors and the Davis reduced angle (terradyn.plasticity.bearing)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from terradyn.errors import InputError
from terradyn.plasticity import bearing

PHI30 = math.radians(30.0)


def test_reissner_nq_and_prandtl_nc_closed_forms():
    # hand values: exp(pi/sqrt3) * 3 and (N_q - 1) * sqrt(3)
    nq = math.exp(math.pi / math.sqrt(3.0)) * 3.0
    assert bearing.reissner1924_nq(PHI30) == pytest.approx(nq, rel=1e-12)
    assert bearing.reissner1924_nq(PHI30) == pytest.approx(18.401, abs=1e-3)
    assert bearing.prandtl1921_nc(PHI30) == pytest.approx((nq - 1.0) * math.sqrt(3.0), rel=1e-12)
    assert bearing.prandtl1921_nc(0.0) == pytest.approx(2.0 + math.pi)
    assert bearing.prandtl1921_nc(1e-7) == pytest.approx(2.0 + math.pi, rel=1e-5)  # continuous at 0
    assert bearing.reissner1924_nq(0.0) == pytest.approx(1.0)
    assert bearing.passive_earth_pressure_coefficient(PHI30) == pytest.approx(3.0)


def test_factors_broadcast_over_arrays_and_grow_with_phi():
    phi = np.radians([20.0, 30.0, 40.0])
    for f in (
        bearing.reissner1924_nq,
        bearing.prandtl1921_nc,
        bearing.vesic1973_ngamma,
        bearing.hansen1970_ngamma,
        bearing.meyerhof1963_ngamma,
        bearing.ec7_ngamma,
    ):
        v = f(phi)
        assert isinstance(v, np.ndarray) and v.shape == (3,)
        assert np.all(np.diff(v) > 0)


def test_ngamma_approximations_match_their_formulas_at_30_deg():
    nq = bearing.reissner1924_nq(PHI30)
    t = math.tan(PHI30)
    assert bearing.vesic1973_ngamma(PHI30) == pytest.approx(2 * (nq + 1) * t)
    assert bearing.hansen1970_ngamma(PHI30) == pytest.approx(1.5 * (nq - 1) * t)
    assert bearing.ec7_ngamma(PHI30) == pytest.approx(2 * (nq - 1) * t)
    assert bearing.meyerhof1963_ngamma(PHI30) == pytest.approx((nq - 1) * math.tan(1.4 * PHI30))
    # the ordering the research digest tabulates at 30 deg: Hansen < Meyerhof < EC7 < Vesic
    vals = [f(PHI30) for f in (bearing.hansen1970_ngamma, bearing.meyerhof1963_ngamma, bearing.ec7_ngamma)]
    assert vals == sorted(vals) and vals[-1] < bearing.vesic1973_ngamma(PHI30)


def test_hansen_depth_factor_at_the_surface_and_its_published_jump_at_d_equal_b():
    assert bearing.hansen1970_depth_factor_q(PHI30, 0.0, 0.1) == pytest.approx(1.0)
    a = 2 * math.tan(PHI30) * (1 - math.sin(PHI30)) ** 2
    below = bearing.hansen1970_depth_factor_q(PHI30, 0.1 * (1 - 1e-12), 0.1)
    above = bearing.hansen1970_depth_factor_q(PHI30, 0.1 * (1 + 1e-12), 0.1)
    # k = D/B up to D = B, arctan(D/B) beyond: the published factor drops from 1 + a to 1 + a pi/4
    assert below == pytest.approx(1 + a)
    assert above == pytest.approx(1 + a * math.pi / 4)
    cap = 1 + math.pi * math.tan(PHI30) * (1 - math.sin(PHI30)) ** 2
    assert bearing.hansen1970_depth_factor_q(PHI30, 1e4, 0.1) == pytest.approx(cap, rel=1e-4)


def test_deep_footing_pressure_grows_without_saturation():
    depth = np.linspace(0.0, 2.0, 201)
    q = bearing.hansen1970_strip_pressure(PHI30, 0.05, depth, 15e3)
    assert q[0] == pytest.approx(0.5 * 15e3 * 0.05 * bearing.hansen1970_ngamma(PHI30))
    slope = np.diff(q) / np.diff(depth)
    # never flatter than gamma N_q (the surcharge term alone, d_q >= 1): no saturation with depth
    assert np.all(slope >= 15e3 * bearing.reissner1924_nq(PHI30) * (1 - 1e-9))
    with_exact = bearing.hansen1970_strip_pressure(PHI30, 0.05, 0.0, 15e3, n_gamma=7.65)
    assert with_exact == pytest.approx(0.5 * 15e3 * 0.05 * 7.65)


def test_davis_reduced_angle():
    assert math.tan(bearing.davis1968_reduced_friction_angle(PHI30, 0.0)) == pytest.approx(0.5)
    assert bearing.davis1968_reduced_friction_angle(PHI30, PHI30) == pytest.approx(PHI30)
    phi34 = math.radians(34.0)
    assert math.degrees(bearing.davis1968_reduced_friction_angle(phi34)) == pytest.approx(29.21, abs=0.01)
    with pytest.raises(InputError, match="dilatancy_angle"):
        bearing.davis1968_reduced_friction_angle(PHI30, math.radians(31.0))


@pytest.mark.parametrize("bad", [-0.1, math.radians(61.0), float("nan"), "x"])
def test_bad_friction_angle_is_refused(bad):
    with pytest.raises(InputError, match="friction_angle"):
        bearing.reissner1924_nq(bad)


def test_bad_width_is_refused():
    with pytest.raises(InputError, match="width"):
        bearing.hansen1970_depth_factor_q(PHI30, 0.1, 0.0)
