"""Method of characteristics for strip footings (terradyn.plasticity.moc): closed forms, convergence,
physics invariants."""

from __future__ import annotations

import math

import numpy as np
import pytest

from terradyn.errors import InputError, SolverError
from terradyn.plasticity import bearing, moc

PHI30 = math.radians(30.0)


@pytest.mark.parametrize("phi_deg", [20.0, 30.0, 40.0])
@pytest.mark.parametrize("base", ["smooth", "rough"])
def test_weightless_moc_reproduces_reissner_nq_and_prandtl_nc(phi_deg, base):
    phi = math.radians(phi_deg)
    f = moc.moc_bearing_factors(phi, base=base, fan_count=32, ray_count=24)
    assert f["N_q"] == pytest.approx(bearing.reissner1924_nq(phi), rel=5e-3)
    assert f["N_c"] == pytest.approx(bearing.prandtl1921_nc(phi), rel=5e-3)


def test_weightless_solution_is_linear_in_surcharge_plus_c_cot_phi():
    kw = {"fan_count": 12, "ray_count": 30}
    one = moc.moc_strip_footing(PHI30, surcharge=1.0, **kw).bearing_pressure
    ten = moc.moc_strip_footing(PHI30, surcharge=10.0, **kw).bearing_pressure
    cq = moc.moc_strip_footing(PHI30, surcharge=1.0, cohesion=1.0, **kw).bearing_pressure
    c = moc.moc_strip_footing(PHI30, cohesion=1.0, **kw).bearing_pressure
    assert ten == pytest.approx(10.0 * one, rel=1e-9)
    assert cq == pytest.approx(one + c, rel=1e-9)  # superposition is exact without self-weight


def test_rough_weightless_wedge_is_prandtls():
    sol = moc.moc_strip_footing(PHI30, surcharge=1.0, base="rough", fan_count=12, ray_count=30)
    # the fan closes at pi/2 up to the scheme's O(dtheta^2) drift of theta along the fan lines
    assert sol.fan_angle == pytest.approx(math.pi / 2, abs=5e-3)
    wedge = sol.alpha_lines[-1]
    tip = wedge[-1]
    assert tip[0] == pytest.approx(0.0, abs=1e-12)
    assert tip[3] == pytest.approx(math.pi / 2, abs=1e-9)
    assert tip[1] == pytest.approx(0.5 * math.tan(math.pi / 4 + PHI30 / 2), rel=5e-3)
    assert np.allclose(
        np.diff(wedge[:, 1]) / np.diff(wedge[:, 0]), -math.tan(math.pi / 4 + PHI30 / 2), rtol=5e-3
    )


def test_ngamma_converges_at_second_order_with_mesh_refinement():
    conv = moc.moc_n_gamma_convergence(PHI30, levels=3, fan_count=8, ray_count=40)
    values = conv["n_gamma"]
    assert isinstance(values, list)
    assert abs(values[2] - values[1]) < abs(values[1] - values[0])
    assert conv["observed_order"] is not None and 1.5 < conv["observed_order"] < 2.6
    # the finest level lies within 0.2 % of the shipped reference (fan 30, rays 160)
    assert values[-1] == pytest.approx(7.650, rel=2e-3)


def test_ngamma_surcharge_extrapolation_is_monotone_and_below_the_smallest_ratio():
    r = moc.moc_n_gamma(PHI30, fan_count=10, ray_count=60)
    v = r.n_gamma_at_ratio
    assert v[0] > v[1] > v[2] > r.n_gamma
    assert v[2] - r.n_gamma < 0.01 * r.n_gamma


def test_smooth_ngamma_sits_at_about_half_the_rough_design_fits():
    # Han et al. (2016): smooth N_gamma is about half (or more) of rough; Hansen's formula is a fit to
    # rough-base characteristics values
    for phi_deg in (30.0, 34.0):
        phi = math.radians(phi_deg)
        ratio = moc.moc_n_gamma(phi, fan_count=10, ray_count=60).n_gamma / bearing.hansen1970_ngamma(phi)
        assert 0.45 < ratio < 0.75


def test_ngamma_grows_with_friction_angle():
    vals = [moc.moc_n_gamma(math.radians(d), fan_count=8, ray_count=40).n_gamma for d in (26.0, 30.0, 34.0)]
    assert vals[0] < vals[1] < vals[2]


def test_weighted_pressure_is_linear_in_width_at_fixed_surcharge_ratio():
    kw = {"unit_weight": 1.0, "fan_count": 8, "ray_count": 40}
    one = moc.moc_strip_footing(PHI30, width=1.0, surcharge=1e-3, **kw).bearing_pressure
    two = moc.moc_strip_footing(PHI30, width=2.0, surcharge=2e-3, **kw).bearing_pressure
    assert two == pytest.approx(2.0 * one, rel=1e-6)


def test_rough_base_carries_more_than_smooth_with_self_weight():
    kw = {"width": 1.0, "unit_weight": 1.0, "surcharge": 0.3, "fan_count": 12, "ray_count": 60}
    smooth = moc.moc_strip_footing(PHI30, base="smooth", **kw)
    rough = moc.moc_strip_footing(PHI30, base="rough", **kw)
    assert rough.bearing_pressure > smooth.bearing_pressure
    assert math.pi / 2 < rough.fan_angle < math.pi - (math.pi / 4 - PHI30 / 2)
    # the wedge boundary meets the centre line with symmetric stresses
    assert rough.alpha_lines[-1][-1][3] == pytest.approx(math.pi / 2, abs=1e-6)


def test_rough_ngamma_limit_is_refused_with_a_reason():
    with pytest.raises(SolverError, match="rough"):
        moc.moc_n_gamma(PHI30, base="rough")
    with pytest.raises(SolverError, match="surcharge ratio"):
        moc.moc_strip_footing(PHI30, unit_weight=1.0, surcharge=1e-3, base="rough", fan_count=8, ray_count=30)


def test_net_is_a_consistent_slip_line_field():
    sol = moc.moc_strip_footing(PHI30, unit_weight=1.0, surcharge=1e-2, fan_count=8, ray_count=30)
    mu = math.pi / 4 - PHI30 / 2
    for arr in sol.alpha_lines:
        d = np.diff(arr[:, :2], axis=0)
        ang = np.arctan2(d[:, 1], d[:, 0])
        mid = 0.5 * (arr[1:, 3] + arr[:-1, 3]) + mu
        # each segment runs along theta + mu (either sense)
        assert np.allclose(np.sin(ang - mid), 0.0, atol=1e-6)
    assert np.all(np.concatenate([a[:, 2] for a in sol.alpha_lines]) > 0.0)  # compressive everywhere
    assert np.all(np.concatenate([a[:, 1] for a in sol.alpha_lines]) >= -1e-12)  # below the surface


def test_mirrored_net_is_symmetric_about_the_footing_centre():
    sol = moc.moc_strip_footing(PHI30, surcharge=1.0, fan_count=6, ray_count=12)
    lines = sol.slip_lines(center_x=0.3, surface_z=-0.1)
    assert len(lines) % 2 == 0
    for right, left in zip(lines[::2], lines[1::2], strict=True):
        assert np.allclose(left.x - 0.3, -(right.x - 0.3))
        assert np.allclose(left.z, right.z)
        assert np.all(right.z <= -0.1 + 1e-12)
        assert {right.family, left.family} == {"alpha", "beta"}


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"friction_angle": 0.0, "surcharge": 1.0}, "friction_angle"),
        ({"friction_angle": PHI30}, "surcharge"),
        ({"friction_angle": PHI30, "surcharge": 1.0, "base": "sticky"}, "base"),
        ({"friction_angle": PHI30, "surcharge": 1.0, "fan_count": 2}, "fan_count"),
        ({"friction_angle": PHI30, "surcharge": -1.0}, "surcharge"),
    ],
)
def test_bad_inputs_are_refused(kwargs, field):
    with pytest.raises(InputError, match=field):
        moc.moc_strip_footing(**kwargs)
