"""Dilatancy of the granular model (tan psi = K (phi - phi_c), Pailha & Pouliquen 2009).

Pointwise: drained and undrained simple shear of one material point driven through the numba update,
the kernel against its pure-Python reference, the off switch against the isochoric update. Bed: a loose
bed stays loose while it settles. Runs: off is the unchanged model; a dense bed pushes back harder.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from mpm_reference import MODEL
from terradyn.errors import InputError
from terradyn.mpm import GranularModel
from terradyn.mpm.checkpoint import plain
from terradyn.mpm.constitutive import (
    TAN_PSI_LIMIT,
    dilatancy_slope,
    dk_dilatant_stress_update,
    dk_dilatant_stress_update_reference,
    dk_stress_update,
)

E, NU = 5.0e6, 0.33
G = E / (2 * (1 + NU))
KB = E / (3 * (1 - 2 * NU))
LAM = KB - 2 * G / 3
RHO_S, RHO_C, D = 2600.0, 1500.0, 1e-3
MU_S, MU_2, I0 = 0.5, 0.8, 0.278
K_DIL = 4.0
RHO_LOOSE = 0.95 * RHO_C


def _update(stress, grad, rho, dt, *, k=K_DIL, mu_2=MU_S, loose=RHO_LOOSE):
    return dk_dilatant_stress_update(
        *stress, grad[0][0], grad[0][1], grad[1][0], grad[1][1], dt, rho,
        G, LAM, MU_S, mu_2, I0, D, RHO_S, RHO_C, k, loose,
    )  # fmt: skip


def _invariants(s):
    p = -(s[0] + s[1] + s[3]) / 3.0
    dev = np.array([s[0] + p, s[1] + p, s[3] + p])
    return p, math.sqrt(0.5 * (dev @ dev + 2.0 * s[2] ** 2))


def drained_shear(rho0, *, p0=1e4, strain=3.0, rate=1.0, dt=1e-4, k=K_DIL):
    """Simple shear (v_x = rate z) of one point under a constant normal stress s_zz = -p0 [Pa]; the
    normal stretching rate is solved each step. Returns per step: shear strain, volume ratio
    V/V0, density and tau/p."""
    s = np.array([-p0, -p0, 0.0, -p0])
    mass, vol = rho0, 1.0
    out = []
    lzz = 0.0
    stiff = (2.0 * G + LAM) * dt  # d s_zz / d l_zz while elastic
    for n in range(round(strain / (rate * dt))):
        rho = mass / vol
        lo = lzz
        for _ in range(60):  # secant on s_zz(l_zz) = -p0
            new = _update(s, ((0.0, rate), (0.0, lo)), rho, dt, k=k)
            f = new[1] + p0
            if abs(f) < 1e-10 * p0:
                break
            trial = _update(s, ((0.0, rate), (0.0, lo + 1e-6)), rho, dt, k=k)
            slope = (trial[1] - new[1]) / 1e-6 or stiff
            lo -= f / slope
        lzz = lo
        s = np.array(new[:4])
        vol *= math.exp(dt * lzz)
        p, tau = _invariants(s)
        out.append(((n + 1) * rate * dt, vol, mass / vol, tau / p))
    return np.array(out)


def undrained_shear(rho, *, p0=1e4, strain=0.5, rate=1.0, dt=1e-4):
    """Simple shear at fixed volume (a saturated, undrained sample): returns the pressure history."""
    s = np.array([-p0, -p0, 0.0, -p0])
    ps = []
    for _ in range(round(strain / (rate * dt))):
        s = np.array(_update(s, ((0.0, rate), (0.0, 0.0)), rho, dt)[:4])
        ps.append(_invariants(s)[0])
    return np.array(ps)


# --- the switch ------------------------------------------------------------------------------------

OLD_FIELDS = {
    "type", "youngs_modulus", "poisson_ratio", "friction_coefficient", "friction_coefficient_2",
    "inertial_number_0", "grain_diameter", "grain_density", "critical_density", "bulk_density",
    "surface_friction",
}  # fmt: skip


def test_off_model_keeps_kernel_array_and_fingerprint():
    off = MODEL.with_changes(dilatancy=0.0)
    assert off == MODEL
    assert set(plain(off)) == OLD_FIELDS  # old checkpoints' fingerprints are unchanged
    assert "dilatancy" not in repr(off) and "dilatancy=3.0" in repr(MODEL.with_changes(dilatancy=3.0))
    assert np.array_equal(off.as_kernel_array(), MODEL.as_kernel_array())
    assert len(MODEL.as_kernel_array()) == 8
    assert off.disconnection_density == MODEL.critical_density
    on = MODEL.with_changes(dilatancy=3.0)
    assert plain(on)["dilatancy"] == 3.0 and "dilatancy" not in plain(MODEL)
    arr = on.as_kernel_array()
    assert len(arr) == 10 and arr[8] == 3.0
    assert arr[9] == pytest.approx(0.95 * MODEL.critical_density)
    assert np.array_equal(arr[:8], MODEL.as_kernel_array())


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        (dict(dilatancy=-1.0), "dilatancy"),
        (dict(dilatancy=1e3), "dilatancy"),
        (dict(loose_density=1400.0), "loose_density"),  # without dilatancy
        (dict(dilatancy=2.0, loose_density=1600.0), "loose_density"),  # above critical
    ],
)
def test_bad_dilatancy_parameters(changes, field):
    with pytest.raises(InputError) as err:
        MODEL.with_changes(**changes)
    assert err.value.field == field


def test_off_equals_isochoric_update():
    """K = 0 with the critical density as threshold is the isochoric return map (both branches)."""
    rng = np.random.default_rng(3)
    for _ in range(200):
        s = -rng.uniform(1e3, 2e4, 4)
        s[2] = rng.uniform(-5e3, 5e3)
        grad = rng.normal(0.0, 50.0, (2, 2))
        rho = rng.uniform(0.97, 1.05) * RHO_C
        for mu_2 in (MU_S, MU_2):
            ref = dk_stress_update(
                *s, grad[0, 0], grad[0, 1], grad[1, 0], grad[1, 1], 1e-4, rho,
                G, LAM, MU_S, mu_2, I0, D, RHO_S, RHO_C,
            )  # fmt: skip
            new = _update(s, grad, rho, 1e-4, k=0.0, mu_2=mu_2, loose=RHO_C)
            scale = max(1.0, np.abs(ref[:4]).max())
            assert np.allclose(new[:4], ref[:4], rtol=0, atol=1e-9 * scale)
            assert new[4] == pytest.approx(ref[4], rel=1e-8, abs=1e-9)


@pytest.mark.parametrize("mu_2", [MU_S, MU_2])
def test_kernel_matches_reference(mu_2):
    rng = np.random.default_rng(11)
    n = 300
    stress = -rng.uniform(1e3, 2e4, (n, 4))
    stress[:, 2] = rng.uniform(-8e3, 8e3, n)
    grad = rng.normal(0.0, 80.0, (n, 2, 2))
    rho = rng.uniform(0.93, 1.08, n) * RHO_C
    args = (1e-4, G, LAM, MU_S, mu_2, I0, D, RHO_S, RHO_C, K_DIL, RHO_LOOSE)
    ref, ref_rate = dk_dilatant_stress_update_reference(stress, grad, rho, *args)
    flowing = 0
    for k in range(n):
        out = _update(stress[k], grad[k], rho[k], 1e-4, mu_2=mu_2)
        assert np.allclose(out[:4], ref[k], rtol=1e-7, atol=1e-6)
        assert out[4] == pytest.approx(ref_rate[k], rel=1e-7, abs=1e-6)
        flowing += out[4] > 0 and ref[k].any()
    assert flowing > n // 4  # the sample exercises the plastic branch


def test_slope_sign_and_bound():
    assert dilatancy_slope(RHO_C, K_DIL, RHO_C, RHO_S, MU_S) == 0.0
    assert dilatancy_slope(1.02 * RHO_C, K_DIL, RHO_C, RHO_S, MU_S) == pytest.approx(
        K_DIL * 0.02 * RHO_C / RHO_S
    )
    assert dilatancy_slope(0.98 * RHO_C, K_DIL, RHO_C, RHO_S, MU_S) < 0.0
    assert dilatancy_slope(2.0 * RHO_C, 40.0, RHO_C, RHO_S, MU_S) == TAN_PSI_LIMIT * MU_S


# --- one material point ---------------------------------------------------------------------------


def test_dense_point_dilates_to_critical_with_peak_friction():
    rho0 = 1.04 * RHO_C
    h = drained_shear(rho0)
    strain, vol, rho, mu = h.T
    beta0 = K_DIL * (rho0 - RHO_C) / RHO_S
    assert vol[-1] > 1.03  # dilated by most of the 4 % density excess
    assert rho[-1] == pytest.approx(RHO_C, rel=2e-3)  # toward critical, not beyond
    assert np.all(np.diff(rho[strain > 0.05]) <= 1e-9 * RHO_C)  # monotonic loosening
    assert mu.max() > MU_S + 0.8 * beta0  # peak friction above mu_s (mu = mu_s + tan psi)
    assert mu[-1] == pytest.approx(MU_S, abs=0.01)  # critical state: mu_s again


def test_loose_point_compacts_to_critical_and_is_weaker():
    rho0 = 0.97 * RHO_C
    h = drained_shear(rho0)
    strain, vol, rho, mu = h.T
    assert vol[-1] < 0.975
    assert rho[-1] == pytest.approx(RHO_C, rel=2e-3)
    assert np.all(np.diff(rho[strain > 0.05]) >= -1e-9 * RHO_C)
    first_flow = mu[strain > 0.05][0]
    assert first_flow < MU_S - 0.5 * K_DIL * 0.03 * RHO_C / RHO_S  # weaker while loose
    assert mu.max() <= MU_S + 1e-3
    assert mu[-1] == pytest.approx(MU_S, abs=0.01)


def test_critical_point_keeps_its_volume():
    h = drained_shear(RHO_C, strain=1.0)
    assert abs(h[-1, 1] - 1.0) < 2e-4  # only the elastic strain of the shear stress
    dense = drained_shear(1.02 * RHO_C, strain=1.0)
    assert dense[-1, 1] - 1.0 > 50 * abs(h[-1, 1] - 1.0)


def test_off_point_keeps_its_volume():
    h = drained_shear(1.04 * RHO_C, strain=1.0, k=0.0)
    assert abs(h[-1, 1] - 1.0) < 2e-4
    assert h[:, 3].max() < MU_S + 1e-6


def test_dilation_per_strain_independent_of_pressure():
    """Rate-independent: the volume-strain curve does not depend on the confining pressure."""
    lo = drained_shear(1.03 * RHO_C, p0=2e3, strain=1.5)
    hi = drained_shear(1.03 * RHO_C, p0=2e4, strain=1.5)
    assert lo[-1, 1] - 1.0 > 0.01
    assert lo[-1, 1] == pytest.approx(hi[-1, 1], abs=1e-3)  # elastic strains differ by p/E


def test_undrained_dense_gains_and_loose_loses_pressure():
    dense = undrained_shear(1.03 * RHO_C)
    loose = undrained_shear(0.98 * RHO_C)
    crit = undrained_shear(RHO_C)
    assert dense[-1] > 1.5e4  # constrained dilation loads the skeleton
    assert loose[-1] < 0.5e4  # constrained compaction unloads it (toward liquefaction)
    assert crit[-1] == pytest.approx(1e4, rel=1e-3)


def test_loose_threshold():
    """Between the loose and the critical density a point carries stress; below it, none."""
    s = (-1e4, -1e4, 0.0, -1e4)
    still = ((0.0, 0.0), (0.0, 0.0))
    connected = _update(s, still, 0.97 * RHO_C, 1e-4)
    assert connected[1] == pytest.approx(-1e4)
    assert _update(s, still, 0.94 * RHO_C, 1e-4)[:4] == (0.0, 0.0, 0.0, 0.0)
    assert _update(s, still, 0.97 * RHO_C, 1e-4, k=0.0, loose=RHO_C)[:4] == (0.0, 0.0, 0.0, 0.0)


def test_shipped_fields_are_defaults():
    f = {x.name: x for x in dataclasses.fields(GranularModel)}
    assert f["dilatancy"].default == 0.0 and f["loose_density"].default is None


# --- beds and runs --------------------------------------------------------------------------------


def _settled_density(model, packing, density):
    """Mean density (mass / volume) of a small bed after damped settling under gravity."""
    from terradyn.mpm.bodies import BodyState
    from terradyn.mpm.model import BedPacking, default_settle_time
    from terradyn.mpm.solver import BedGrid, Phase, Runner, make_bed, stable_time_step

    grid = BedGrid(0.1, 0.06, 0.02, 0.01)
    p = make_bed(model, grid, packing=packing, density=density)
    dt = stable_time_step(model, grid.cell_size)
    n = round(default_settle_time(model, grid.depth, BedPacking(packing), 9.81) / dt)
    phase = Phase("settle", n, damping=model.wave_speed() / grid.depth)
    runner = Runner(model, grid, p, BodyState.empty(), dt, [phase], has_body=False)
    runner.run()
    q = runner.particles
    return q.mass.sum() / q.vol.sum(), q


def test_loose_bed_stays_loose_with_dilatancy():
    rho0 = 0.97 * MODEL.critical_density
    on = MODEL.with_changes(dilatancy=K_DIL)
    rho_on, q = _settled_density(on, "unconsolidated", rho0)
    assert rho_on == pytest.approx(rho0, rel=2e-3)  # as prepared (elastic settlement only)
    assert np.all(q.mass / q.vol < MODEL.critical_density)
    rho_off, _ = _settled_density(MODEL, "unconsolidated", rho0)
    assert rho_off > 0.999 * MODEL.critical_density  # without dilatancy it compacts to critical
    dense0 = 1.03 * MODEL.critical_density
    rho_dense, _ = _settled_density(on, "consolidated", dense0)
    assert rho_dense == pytest.approx(dense0, rel=2e-3)


FAST = dict(cell_size=0.01, speed=0.2, bed_width=0.2, bed_depth=0.12, settle_time=0.02)


def test_run_with_dilatancy_off_is_the_default_run():
    from terradyn.geometry import Plate
    from terradyn.mpm import run_intrusion

    ref = run_intrusion(Plate(0.08, 0.1), MODEL, depth=0.02, **FAST)
    off = run_intrusion(Plate(0.08, 0.1), MODEL, depth=0.02, dilatancy=0.0, **FAST)
    for name, col in ref.series.items():
        assert np.array_equal(col, off.series[name]), name
    timing = {"wall_time_s"}
    assert {k: v for k, v in off.metadata.items() if k not in timing} == {
        k: v for k, v in ref.metadata.items() if k not in timing
    }
    assert "dilatancy" not in off.metadata["model"]  # results of runs without it read as before


def test_dense_bed_pushes_back_harder_than_loose():
    """Same plate, same K: a bed 3 % above critical against one 3 % below (both connected)."""
    from terradyn.geometry import Plate
    from terradyn.mpm import run_intrusion

    model = MODEL.with_changes(dilatancy=K_DIL)
    rc = MODEL.critical_density
    args = dict(depth=0.03, **FAST)
    dense = run_intrusion(Plate(0.08, 0.1), model, packing="consolidated", bed_density=1.03 * rc, **args)
    loose = run_intrusion(Plate(0.08, 0.1), model, packing="unconsolidated", bed_density=0.97 * rc, **args)
    f_dense, f_loose = dense.summary["force_z_N"], loose.summary["force_z_N"]
    assert f_dense > 1.5 * f_loose  # measured 1.92 (1.17 with dilatancy off)


@pytest.mark.slow
def test_ms_plate_dense_against_loose():
    """The shipped MS medium, 40 mm plate to 20 mm depth, 6.6 mm cells (about 2 min): with K = 4 the
    consolidated bed (1.02 rho_c) carries 12.24 N and the unconsolidated one (0.98 rho_c) 7.13 N (1.72);
    without dilatancy 8.91 N and 7.50 N (1.19)."""
    from terradyn import materials
    from terradyn.geometry import Plate
    from terradyn.mpm import run_intrusion

    ms = materials.get("MS")
    args = dict(depth=0.02, cell_size=0.0066, dilatancy=K_DIL)
    dense = run_intrusion(Plate(0.04, 0.01), ms, packing="consolidated", **args).summary["force_z_N"]
    loose = run_intrusion(Plate(0.04, 0.01), ms, packing="unconsolidated", **args).summary["force_z_N"]
    assert dense > 1.4 * loose


# --- CLI ------------------------------------------------------------------------------------------

PLATE_ARGS = ["mpm", "intrude", "plate", "--length", "0.06", "--depth", "0.03"]


@pytest.mark.parametrize("value", ["-1", "nan", "1e3"])
def test_cli_bad_dilatancy(run_cli, value):
    code, _, err = run_cli(*PLATE_ARGS, "--dilatancy", value)
    assert code == 1, err
    assert "--dilatancy" in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


@pytest.mark.parametrize(
    ("args", "function"),
    [(PLATE_ARGS, "run_intrusion"), (["mpm", "wheel", "--load", "10", "--omega", "1"], "run_wheel")],
)
@pytest.mark.parametrize(("flag", "expected"), [(["--dilatancy", "4"], 4.0), ([], None)])
def test_cli_passes_dilatancy(run_cli, monkeypatch, args, function, flag, expected):
    import terradyn.mpm

    seen = {}

    def stub(*_args, **kwargs):
        seen.update(kwargs)
        raise InputError("stub", 0, "not run")

    monkeypatch.setattr(terradyn.mpm, function, stub)
    code, _, err = run_cli(*args, *flag)
    assert code == 1 and "stub" in err
    assert seen["dilatancy"] == expected
