"""The small-strain finite-element strip footing (terradyn.plasticity.fe_footing).

Independent references: the plane-strain limits of the cone (closed forms), linear elasticity
(superposition), and the method of characteristics for the associated cone (exact).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from terradyn.errors import InputError
from terradyn.plasticity import fe_footing as fe
from terradyn.plasticity.moc import moc_n_gamma
from terradyn.plasticity.references import cone_plane_strain_friction_angle

E, NU, RHO = 5.0e6, 0.33, 1591.2
G = E / (2 * (1 + NU))
LAM = E * NU / ((1 + NU) * (1 - 2 * NU))
K = LAM + 2 * G / 3
MU = math.sin(math.radians(34.0))


def _biaxial_ratio(associated: bool) -> float:
    """sigma_zz / sigma_xx at the end of a plane-strain compression at constant sigma_xx."""
    s = np.array([-1000.0, -1000.0, 0.0, -1000.0])
    dez = -1e-5
    for _ in range(3000):
        # lateral strain that keeps sigma_xx (secant iterations on the return-mapped stress)
        d0, r0 = 0.0, None
        dex = 0.0
        for k in range(40):
            tr = dex + dez
            out = fe._cone_return(s[0] + LAM * tr + 2 * G * dex, s[1] + LAM * tr + 2 * G * dez, s[2],
                                  s[3] + LAM * tr, G, K, MU, associated)  # fmt: skip
            r = out[0] + 1000.0
            if k == 0:
                d0, r0, dex = dex, r, 1e-7
                continue
            if r == r0 or abs(r) < 1e-9:
                break
            dex, d0, r0 = dex - r * (dex - d0) / (r - r0), dex, r
        s = np.array(out[:4])
    return float(s[1] / s[0])


def test_the_cone_in_plane_strain_is_mohr_coulomb_at_its_two_angles():
    """Isochoric flow: Mohr-Coulomb at asin(mu); associated: at the cone's plane-strain angle."""
    iso = _biaxial_ratio(False)
    assert iso == pytest.approx((1 + MU) / (1 - MU), rel=1e-6)
    s_a = math.sin(cone_plane_strain_friction_angle(math.radians(34.0)))
    assert _biaxial_ratio(True) == pytest.approx((1 + s_a) / (1 - s_a), rel=1e-6)


def _mesh(n: int = 4) -> tuple[np.ndarray, np.ndarray]:
    h = 0.02 / n
    return fe._graded(0.03, 0.12, h, 1.1, 0.01), -fe._graded(0.02, 0.06, h, 1.1, 0.01)[::-1]


def test_a_bed_under_gravity_alone_stays_at_rest_and_elastic():
    xs, zs = _mesh()
    rows, _ = fe._run(xs, zs, RHO, 9.81, G, LAM, MU, False, 1 - MU, 5, False, 0.0, 200, 4000, 0, 500, 0.8)
    assert np.all(rows[:, 2] == 0.0)  # no Gauss point at yield
    assert np.max(np.abs(rows[:, 1])) < 1e-6  # [N/m]: no load on the (motionless) footing


def test_the_elastic_footing_is_linear_in_settlement_and_modulus():
    """No yield (mu = 5, a tiny settlement, a bed pre-compressed by a large gravity so no point
    opens in tension): pressure proportional to settlement and to E."""
    res = [fe.fe_strip_footing(5.0, elements_per_half_width=4, domain_widths=(3.0, 1.5), youngs_modulus=e,
                               gravity=1000.0, settlement_ratio=1e-4, crossings=100.0)
           for e in (5e6, 1e7)]  # fmt: skip
    for r in res:
        assert r.plastic_fraction == 0.0
        # the second half of the push (the first carries the start-up transient of the explicit run)
        half = len(r.curve) // 2
        stiffness = r.curve[half:, 1] / r.curve[half:, 0]
        assert np.max(stiffness) / np.min(stiffness) < 1.001
    assert res[1].curve[-1, 1] / res[0].curve[-1, 1] == pytest.approx(2.0, rel=0.01)


def test_isochoric_flow_carries_less_than_associated_and_refinement_lowers_both():
    runs = {
        (flow, n): fe.fe_strip_footing(MU, flow=flow, elements_per_half_width=n).N_gamma
        for flow in ("isochoric", "associated")
        for n in (4, 8)
    }
    exact_cone = 21.71  # characteristics at 36.22 deg (checked in test_plasticity_references)
    for n in (4, 8):
        assert runs["isochoric", n] < 0.6 * runs["associated", n]
    # displacement elements overestimate the collapse load and approach it from above
    assert runs["associated", 4] > runs["associated", 8] > exact_cone
    assert runs["isochoric", 4] > runs["isochoric", 8]


def test_a_slow_push_reads_the_same_at_either_damping_and_holds_its_load():
    """The isochoric reading depends on the loading rate: pushed over 100 wave crossings the two
    dampings differ by 10 % and the footing, held still afterwards, loses 5-10 % of its load; pushed
    8 times slower they agree within 1 % and the held load stays within 1 % of the pushing one (at 5
    elements per half-width: 17.36 / 15.69 pushing and 15.77 / 14.37 held at 100 crossings, 16.54 /
    16.51 and 16.45 / 16.43 at 800)."""
    runs = {
        (d, c): fe.fe_strip_footing(MU, elements_per_half_width=5, damping=d, crossings=c, hold_crossings=50)
        for d in (0.8, 0.5)
        for c in (100.0, 800.0)
    }
    fast, slow = (runs[0.8, c].N_gamma / runs[0.5, c].N_gamma - 1.0 for c in (100.0, 800.0))
    assert fast > 0.05
    assert abs(slow) < 0.01
    for d in (0.8, 0.5):
        assert runs[d, 100.0].N_gamma_held < 0.95 * runs[d, 100.0].N_gamma
        assert runs[d, 800.0].N_gamma_held == pytest.approx(runs[d, 800.0].N_gamma, rel=0.01)
        assert runs[d, 800.0].record()["N_gamma_held"] == runs[d, 800.0].N_gamma_held
    assert "N_gamma_held" not in fe.fe_strip_footing(MU, elements_per_half_width=2).record()


@pytest.mark.slow
def test_the_associated_fe_footing_extrapolates_to_the_characteristics_value():
    """Richardson over 5 / 10 / 20 elements per half-width recovers the exact associated N_gamma of
    the cone (method of characteristics at its plane-strain angle) within 3 %."""
    conv = fe.fe_n_gamma_convergence(MU, flow="associated", elements=(5, 10, 20))
    exact = moc_n_gamma(cone_plane_strain_friction_angle(math.radians(34.0))).n_gamma
    assert conv.estimate.extrapolated == pytest.approx(exact, rel=0.03)
    assert 0.3 < conv.estimate.order < 2.0


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"flow": "dilatant"}, "flow"),
        ({"base": "sticky"}, "base"),
        ({"elements_per_half_width": 1}, "elements_per_half_width"),
        ({"settlement_ratio": 0.0}, "settlement_ratio"),
        ({"poisson_ratio": 0.5}, "poisson_ratio"),
        ({"damping": 1.0}, "damping"),
        ({"fine_widths": (0.2, 1.0)}, "fine_widths"),
        ({"hold_crossings": -1.0}, "hold_crossings"),
        ({"hold_crossings": float("nan")}, "hold_crossings"),
    ],
)
def test_bad_input_names_the_field(kwargs, field):
    with pytest.raises(InputError) as err:
        fe.fe_strip_footing(MU, **kwargs)
    assert err.value.field == field


def test_the_convergence_needs_three_meshes():
    with pytest.raises(InputError) as err:
        fe.fe_n_gamma_convergence(MU, elements=(5, 10))
    assert err.value.field == "elements"


def test_the_fe_footing_command_prints_every_mesh_and_the_estimate(run_cli, tmp_path):
    plot = tmp_path / "fe.png"
    code, out, err = run_cli("mpm", "verify", "fe-footing", "--phi", "34", "--elements", "3,4,5",
                             "--hold-crossings", "5", "--plot", str(plot), "--format", "json")  # fmt: skip
    assert code == 0, err
    import json

    rec = json.loads(out)
    assert rec["flow"] == "isochoric" and rec["base"] == "smooth"
    assert [r["elements_per_half_width"] for r in rec["runs"]] == [3, 4, 5]
    assert all(r["N_gamma_held"] > 0 for r in rec["runs"])
    assert rec["N_gamma_finest"] == rec["runs"][-1]["N_gamma"]
    assert {"observed_order", "N_gamma_extrapolated", "error_band_of_finest", "note"} <= set(rec)
    assert plot.stat().st_size > 10_000


@pytest.mark.parametrize(
    ("args", "flag"),
    [
        (("--phi", "34", "--flow", "dilatant"), "--flow"),
        (("--phi", "34", "--base", "sticky"), "--base"),
        (("--phi", "34", "--elements", "5,10"), "--elements"),
        (("--phi", "34", "--elements", "5,x,10"), "--elements"),
        (("--phi", "60"), "--phi"),
        (("--phi", "34", "--damping", "1"), "--damping"),
        (("--phi", "34", "--crossings", "0"), "--crossings"),
        (("--phi", "34", "--hold-crossings", "-1"), "--hold-crossings"),
        (("--phi", "34", "--elements", "3,4,500"), "--elements"),  # refused before any mesh runs
    ],
)
def test_the_fe_footing_command_names_a_bad_flag(run_cli, args, flag):
    code, out, err = run_cli("mpm", "verify", "fe-footing", *args)
    assert code == 1 and out == ""
    assert err.startswith(f"terradyn: error: {flag} = "), err
    assert len(err.strip().splitlines()) == 1
