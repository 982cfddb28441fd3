"""Return-map tests of the Dunatunga-Kamrin update (terradyn.mpm.constitutive)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from terradyn.mpm.constitutive import (
    dk_stress_update,
    dk_stress_update_many,
    dk_stress_update_reference,
    mu_of_inertial_number,
)

E, NU = 5.0e6, 0.33
G = E / (2 * (1 + NU))
LAM = E / (3 * (1 - 2 * NU)) - 2 * G / 3
RHO_S, RHO_C, D = 2600.0, 1500.0, 1e-3
MU_S, MU_2, I0 = 0.5, 0.8, 0.278


def update(stress, grad, rho=1600.0, dt=1e-5, mu_2=MU_S):
    out = dk_stress_update(
        *stress,
        grad[0][0],
        grad[0][1],
        grad[1][0],
        grad[1][1],
        dt,
        rho,
        G,
        LAM,
        MU_S,
        mu_2,
        I0,
        D,
        RHO_S,
        RHO_C,
    )
    return np.array(out[:4]), out[4]


def invariants(s):
    p = -(s[0] + s[1] + s[3]) / 3
    dev = np.array([s[0] + p, s[1] + p, s[3] + p])
    tau = math.sqrt(0.5 * (dev @ dev + 2 * s[2] ** 2))
    return p, tau


def test_elastic_step_is_hookean_in_plane_strain():
    s0 = np.array([-1000.0, -1000.0, 0.0, -1000.0])
    e = 1e-7  # small volumetric compression rate x dt keeps it elastic
    s, gdot = update(s0, [[-e / 1e-5, 0.0], [0.0, 0.0]])
    assert gdot == 0.0
    assert s[0] == pytest.approx(-1000.0 - (2 * G + LAM) * e)
    assert s[1] == pytest.approx(-1000.0 - LAM * e)
    # plane strain: the out-of-plane stress follows lambda tr(D)
    assert s[3] == pytest.approx(-1000.0 - LAM * e)


def test_yield_returns_radially_to_cone_at_fixed_pressure():
    s0 = np.array([-1000.0, -1000.0, 0.0, -1000.0])
    s, gdot = update(s0, [[0.0, 0.05 / 1e-5], [0.0, 0.0]])  # large simple shear increment
    p, tau = invariants(s)
    assert p == pytest.approx(1000.0, rel=1e-9)  # isochoric flow: no pressure change
    assert tau == pytest.approx(MU_S * p, rel=1e-9)
    assert gdot > 0


def test_disconnected_below_critical_density_or_in_tension():
    s0 = np.array([-1000.0, -2000.0, 100.0, -1500.0])
    s, _ = update(s0, [[1.0, 0.0], [0.0, 0.0]], rho=0.99 * RHO_C)
    assert np.all(s == 0.0)
    s, gdot = update(np.zeros(4), [[1.0, 0.0], [0.0, 2.0]])  # dilating from zero stress: p_tr < 0
    assert np.all(s == 0.0)
    assert gdot >= 0.0


def test_mu_of_i_root_satisfies_rheology():
    dt = 1e-5
    s0 = np.array([-1000.0, -1000.0, 0.0, -1000.0])
    s, gdot = update(s0, [[0.0, 0.3 / dt], [0.0, 0.0]], dt=dt, mu_2=MU_2)
    p, tau = invariants(s)
    inertial = gdot * D / math.sqrt(p / RHO_S)
    assert tau == pytest.approx(p * float(mu_of_inertial_number(inertial, MU_S, MU_2, I0)), rel=1e-9)
    assert MU_S * p < tau < MU_2 * p
    # and the plastic rate is consistent with the elastic shortfall (trial shear stress G * 0.3)
    tau_tr = G * 0.3
    assert gdot == pytest.approx((tau_tr - tau) / (G * dt), rel=1e-9)


def test_rigid_rotation_keeps_invariants():
    s0 = np.array([-2000.0, -1500.0, 300.0, -1700.0])  # inside the cone
    p0, t0 = invariants(s0)
    s, _ = update(s0, [[0.0, 10.0], [-10.0, 0.0]], dt=1e-6)  # spin only
    p, t = invariants(s)
    assert p == pytest.approx(p0, rel=1e-9)
    assert t == pytest.approx(t0, rel=1e-6)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**31 - 1))
def test_numba_batch_equals_numpy_reference(seed):
    rng = np.random.default_rng(seed)
    n = 64
    stress = -np.abs(rng.normal(1000.0, 500.0, (n, 4)))
    stress[:, 2] = rng.normal(0.0, 300.0, n)
    grad = rng.normal(0.0, 50.0, (n, 2, 2))
    rho = rng.uniform(0.95 * RHO_C, 1.1 * RHO_C, n)
    args = (1e-5, G, LAM, MU_S, MU_2, I0, D, RHO_S, RHO_C)
    ref, gref = dk_stress_update_reference(stress, grad, rho, *args)
    got = stress.copy()
    gdot = dk_stress_update_many(got, grad, rho, *args)
    np.testing.assert_allclose(got, ref, rtol=1e-9, atol=1e-7)
    np.testing.assert_allclose(gdot, gref, rtol=1e-9, atol=1e-7)
