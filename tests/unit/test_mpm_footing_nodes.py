"""The node-footing diagnostic (the MPM continuum under a footing that is a grid boundary condition)."""

import itertools
import json
import math

import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.mpm import FootingBase, FootingPush, NodeFootingCase, Resolution, run_node_footing
from terradyn.studies.mpm_footing_nodes import (
    PLATEAU_DRIFT,
    PLATEAU_PEAK_RATIO,
    node_footing_convergence,
    node_strip_footing,
    plateau_measures,
)


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"cell_size": 0.003}, "cell_size"),
        ({"base": "sticky"}, "base"),
        ({"domain_widths": (0.5, 1.0)}, "domain_widths"),
        ({"volumetric": "cell"}, "volumetric"),
        ({"speed": 1.0}, "speed"),
        ({"hold_time": -0.1}, "hold_time"),
    ],
)
def test_bad_input_names_the_field(kwargs, field):
    args = {"base": "smooth", **kwargs}
    base = args.pop("base")
    with pytest.raises(InputError) as err:
        node_strip_footing(34.0, base, **args)
    assert err.value.field == field


def test_a_coarse_run_loads_from_zero_to_a_plateau():
    r = node_strip_footing(34.0, "smooth", cell_size=0.005, domain_widths=(2.0, 1.0), settlement_ratio=0.02)
    s, q = r.curve
    n = 2.0 * q / (r.unit_weight_N_m3 * r.width_m)
    assert abs(n[0]) < 0.1 * r.N_gamma  # the ramp starts from rest
    assert math.isfinite(r.N_gamma) and r.N_gamma > 1.0
    assert r.N_gamma_spread < 0.05 * r.N_gamma  # a plateau, not a rising or ringing curve
    assert r.plateau and r.record()["plateau"] is True
    assert r.N_gamma_peak_ratio == pytest.approx(1.0, abs=0.01)
    assert s[-1] == pytest.approx(r.settlement_m, rel=0.02)


S = np.linspace(0.0, 1.0, 401)


@pytest.mark.parametrize(
    ("curve", "drift", "peak", "plateau"),
    [
        # loads to a flat plateau: no drift, the last quarter is the highest stretch
        (np.minimum(S / 0.2, 1.0) * 10.0, 0.0, 1.0, True),
        # noise about the plateau does not move the measures (a deterministic ringing)
        (np.minimum(S / 0.2, 1.0) * 10.0 + np.sin(S * 800.0), 0.0, 1.0, True),
        # still climbing: the last quarter's second half 1.6 above its first, over a mean of 18
        (10.0 + 10.0 * S, 1.25 / 18.75, 1.0, True),
        # climbing steeply (embedment more than the collapse load)
        (2.0 + 30.0 * S, 3.75 / 28.25, 1.0, False),
        # peaks at 15 and falls to 10: the reading is no collapse load (the window from S = 0.25
        # holds 0.15 at 15 and 0.1 at 10, a mean of 13)
        (np.where(S < 0.4, 15.0, 10.0), 0.0, 1.3, False),
    ],
)
def test_plateau_measures_flag_a_curve_that_peaked_or_climbs(curve, drift, peak, plateau):
    d, p = plateau_measures(S, curve)
    assert d == pytest.approx(drift, abs=0.01)
    assert p == pytest.approx(peak, abs=0.01)
    assert (abs(d) <= PLATEAU_DRIFT and p <= PLATEAU_PEAK_RATIO) is plateau


def test_plateau_measures_of_a_zero_reading_are_nan():
    assert all(math.isnan(v) for v in plateau_measures(S, np.zeros_like(S)))


def test_convergence_runs_each_resolution_and_estimates_from_the_three_finest():
    calls = []
    conv = node_footing_convergence(
        34.0,
        "smooth",
        cells_per_width=(8, 4, 6),
        domain_widths=(2.0, 1.0),
        settlement_ratio=0.02,
        progress=lambda done, total: calls.append((done, total)),
    )
    assert [r.cell_size_m for r in conv.runs] == pytest.approx([0.01, 0.04 / 6, 0.005])  # coarse to fine
    rec = conv.record()
    assert [r["cells_per_width"] for r in rec["runs"]] == pytest.approx([4, 6, 8])
    assert rec["N_gamma_finest"] == conv.runs[-1].N_gamma
    assert set(rec) >= {"observed_order", "N_gamma_extrapolated", "error_band_of_finest", "monotone", "note"}
    # work counted as n^3, reported after each run, ending at the total
    assert [c[0] for c in calls] == pytest.approx([64.0, 280.0, 792.0])
    assert all(c[1] == 792.0 for c in calls)


@pytest.mark.parametrize("cells", [(10, 20), (10, 10, 20), (10, 15, 20), (2, 4, 6)])
def test_convergence_refuses_bad_resolutions(cells):
    with pytest.raises(InputError) as err:
        node_footing_convergence(34.0, cells_per_width=cells)
    assert err.value.field == "cells_per_width"


def test_the_node_footing_command_prints_every_resolution_and_the_reference(run_cli, tmp_path):
    plot = tmp_path / "nodes.png"
    code, out, err = run_cli("mpm", "verify", "node-footing", "--phi", "34", "--cells", "4,6,8",
                             "--domain", "2,1", "--hold-time", "0.01", "--plot", str(plot),
                             "--flip", "0.5", "--format", "json")  # fmt: skip
    assert code == 0, err
    rec = json.loads(out)
    assert all(r["N_gamma_held"] > 0 and r["flip"] == 0.5 for r in rec["runs"])
    assert rec["base"] == "smooth" and rec["phi_deg"] == 34.0
    assert [r["cells_per_width"] for r in rec["runs"]] == pytest.approx([4, 6, 8])
    assert rec["N_gamma_finest"] == rec["runs"][-1]["N_gamma"]
    # the isochoric reference of the case, and the finest reading against it
    assert rec["N_gamma_reference"] > 0 and rec["reference_kind"]
    assert rec["ratio_finest_to_reference"] == pytest.approx(rec["N_gamma_finest"] / rec["N_gamma_reference"])
    # a coarse study has a wide band: not a converged reading, whatever its ratio
    assert rec["error_band_of_finest"] > 0.1 * rec["N_gamma_reference"]
    assert rec["within_10_percent_of_reference"] is False
    assert plot.stat().st_size > 10_000


@pytest.mark.parametrize(
    ("args", "flag"),
    [
        (("--phi", "34", "--cells", "10,20"), "--cells"),
        (("--phi", "34", "--cells", "10,x,40"), "--cells"),
        (("--phi", "34", "--domain", "4"), "--domain"),
        (("--phi", "34", "--domain", "0.5,2"), "--domain"),
        (("--phi", "34", "--base", "sticky"), "--base"),
        (("--phi", "60"), "--phi"),
        (("--phi", "34", "--speed", "5"), "--speed"),
        (("--phi", "34", "--settlement-ratio", "0.5"), "--settlement-ratio"),
        (("--phi", "34", "--volumetric", "cell"), "--volumetric"),
        (("--phi", "34", "--hold-time", "-1"), "--hold-time"),
        (("--phi", "34", "--flip", "1.2"), "--flip"),
    ],
)
def test_the_node_footing_command_names_a_bad_flag(run_cli, args, flag):
    code, out, err = run_cli("mpm", "verify", "node-footing", *args)
    assert code == 1 and out == ""
    assert err.startswith(f"terradyn: error: {flag} = "), err
    assert len(err.strip().splitlines()) == 1


def test_the_following_grid_keeps_its_floor_past_half_a_cell():
    # 0.05 B at B/16 is 0.8 of a cell: a floor on the node line at or below the world floor moved down
    # with the grid, the bed sank with it and the plateau fell (last quarter / second quarter 0.74);
    # the floor on the nearest node line keeps it (1.09)
    r = node_strip_footing(
        34.0, "rough", cell_size=0.04 / 16, domain_widths=(2.0, 1.0), settlement_ratio=0.05, follow=True
    )
    s, q = r.curve
    assert s[-1] > 0.75 * r.cell_size_m
    second_quarter = q[(s >= 0.25 * s[-1]) & (s <= 0.5 * s[-1])].mean()
    last_quarter = q[s >= 0.75 * s[-1]].mean()
    assert last_quarter >= 0.9 * second_quarter


def test_a_held_footing_keeps_its_load_only_after_a_slow_push():
    """The MPM reading depends on the loading rate as the FE's does (test_plasticity_fe): pushed at
    0.01 m/s and held, the B/4 footing loses half its load (29.6 to 13.8); pushed 64 times slower it
    reads lower (12.0) and held keeps 95 % of it (11.5). The rate-independent collapse load is the
    slow limit, where pushing and held readings meet."""
    runs = {
        v: node_strip_footing(
            34.0, "smooth", cell_size=0.01, domain_widths=(4.0, 2.0), speed=v, hold_time=0.05
        )
        for v in (0.01, 0.00015625)
    }
    fast, slow = runs[0.01], runs[0.00015625]
    assert slow.N_gamma < 0.6 * fast.N_gamma
    assert fast.N_gamma_held < 0.6 * fast.N_gamma
    assert slow.N_gamma_held == pytest.approx(slow.N_gamma, rel=0.1)
    assert fast.record()["N_gamma_held"] == fast.N_gamma_held
    times, pressure = fast.held_curve
    assert times[-1] == pytest.approx(0.05, rel=0.02) and len(times) == len(pressure)


def test_the_pushing_excess_is_the_apic_transfers_dissipation():
    """At a fixed speed and step, blending the particle velocity update from APIC towards FLIP (which
    keeps the velocity modes APIC drops each step) lowers the pushing reading step by step: B/4,
    0.01 m/s reads 29.6 / 23.7 / 17.9 / 15.7 at FLIP fraction 0 / 0.9 / 0.99 / 1. Pure FLIP at
    0.01 m/s reads below APIC pushed 4 times slower (21.6): most of APIC's rate excess is the
    transfer's numerical dissipation, not the inertia of the bed (docs/mpm.md)."""
    kw = {"cell_size": 0.01, "domain_widths": (4.0, 2.0)}
    readings = [node_strip_footing(34.0, "smooth", speed=0.01, flip=f, **kw) for f in (0.0, 0.9, 0.99, 1.0)]
    values = [r.N_gamma for r in readings]
    assert all(a > b for a, b in itertools.pairwise(values)), values
    assert readings[-1].record()["flip"] == 1.0 and readings[0].flip == 0.0
    slower = node_strip_footing(34.0, "smooth", speed=0.0025, **kw)
    assert values[-1] < slower.N_gamma < values[0]
    with pytest.raises(InputError, match="flip"):
        node_strip_footing(34.0, "smooth", speed=0.01, flip=1.5, **kw)


def test_the_loading_rate_command_runs_both_models_at_every_rate(run_cli, tmp_path):
    plot = tmp_path / "rate.png"
    code, out, err = run_cli("mpm", "verify", "loading-rate", "--phi", "34", "--cells", "4",
                             "--speeds", "0.01,0.0025", "--crossings", "50,100", "--dampings", "0.8",
                             "--hold-time", "0.01", "--hold-crossings", "5", "--plot", str(plot),
                             "--flips", "0,0.99", "--format", "json")  # fmt: skip
    assert code == 0, err
    rec = json.loads(out)
    every = [r for r in rec["runs"] if r["model"] == "mpm"]
    mpm = [r for r in every if r["flip"] == 0.0]
    fe = [r for r in rec["runs"] if r["model"] == "fe"]
    assert [r["speed_m_s"] for r in mpm] == [0.01, 0.0025] and len(fe) == 2
    # each FLIP fraction runs every speed; at 0.01 m/s the FLIP blend reads below APIC
    flipped = [r for r in every if r["flip"] == 0.99]
    assert [r["speed_m_s"] for r in flipped] == [0.01, 0.0025]
    assert flipped[0]["N_gamma"] < mpm[0]["N_gamma"]
    # a slower push lasts longer and, at these coarse cells, reads lower in both models
    assert mpm[1]["push_time_s"] > 3 * mpm[0]["push_time_s"] and mpm[1]["N_gamma"] < mpm[0]["N_gamma"]
    assert (
        fe[1]["push_time_s"] == pytest.approx(2 * fe[0]["push_time_s"])
        and fe[1]["N_gamma"] < fe[0]["N_gamma"]
    )
    assert all(r["N_gamma_held"] > 0 for r in rec["runs"])
    assert rec["ratio_mpm_to_fe_slowest"] == pytest.approx(mpm[1]["N_gamma"] / fe[1]["N_gamma"])
    assert plot.stat().st_size > 10_000


@pytest.mark.parametrize(
    ("args", "flag"),
    [
        (("--cells", "5"), "--cells"),
        (("--speeds", "0.01,-1"), "--speeds"),
        (("--speeds", "fast"), "--speeds"),
        (("--crossings", "0"), "--crossings"),
        (("--dampings", "1"), "--dampings"),
        (("--base", "sticky"), "--base"),
        (("--hold-time", "-1"), "--hold-time"),
        (("--flips", "0,1.5"), "--flips"),
    ],
)
def test_the_loading_rate_command_names_a_bad_flag(run_cli, args, flag):
    code, out, err = run_cli("mpm", "verify", "loading-rate", "--phi", "34", *args)
    assert code == 1 and out == ""
    assert err.startswith(f"terradyn: error: {flag} = "), err
    assert len(err.strip().splitlines()) == 1


def test_local_damping_takes_alpha_of_each_change_against_the_old_velocity_at_free_nodes_only():
    """The kernel's contract on a 6 x 5 grid (pad 0, floor line 0, footing nodes i 1-2, j 4): a free
    node's velocity change dv loses alpha |dv| against the sign of its velocity before the step; a
    node at rest before, a node without mass, the walls, the floor and the footing are untouched."""
    from terradyn.mpm._footing_kernels import local_damp

    nx, nz, alpha = 6, 5, 0.5
    m = np.ones((nx, nz))
    m[3, 2] = 0.0
    old = np.zeros((1, nx, nz, 3))
    old[0, :, :, 0] = m
    old[0, :, :, 1] = 0.2  # old v_x = 0.2 everywhere (momentum / unit mass)
    old[0, :, :, 2] = -0.1  # old v_z = -0.1
    old[0, 2, 2, 1:] = 0.0  # at rest before the step
    vel = np.zeros((nx, nz, 2))
    vel[..., 0] = 0.2 + 0.04  # dv_x = +0.04
    vel[..., 1] = -0.1 - 0.02  # dv_z = -0.02
    new = vel.copy()
    local_damp(old, m, new, alpha, 0, 0, np.array([1, 2]), np.array([4, 4]))
    free = [(1, 1), (4, 3), (2, 3)]
    for i, j in free:
        assert new[i, j, 0] == pytest.approx(0.24 - alpha * 0.04)
        assert new[i, j, 1] == pytest.approx(-0.12 + alpha * 0.02)
    untouched = [(2, 2), (3, 2), (0, 2), (5, 2), (2, 0), (1, 4), (2, 4)]
    for i, j in untouched:
        assert new[i, j].tolist() == vel[i, j].tolist(), (i, j)
    assert np.all(np.abs(new[..., 0]) <= np.abs(vel[..., 0]))


def test_local_damping_does_not_stop_pure_flips_creep():
    """Pure FLIP's reading falls the longer the push lasts. A local damper (alpha 0.8), which takes
    out kinetic energy without a viscosity, does not stop that: at B/4 it reads 19.7 / 13.8 / 10.4 at
    0.01 / 0.0025 / 0.000625 m/s (undamped 15.7 / 12.3), and at the fast push it adds an excess
    (docs/mpm.md, "The creep is not ringing that a local damper removes")."""
    kw = {"cell_size": 0.01, "domain_widths": (4.0, 2.0), "flip": 1.0}
    bare = node_strip_footing(34.0, "smooth", speed=0.01, **kw)
    damped = [
        node_strip_footing(34.0, "smooth", speed=v, local_damping=0.8, **kw) for v in (0.01, 0.0025, 0.000625)
    ]
    values = [r.N_gamma for r in damped]
    assert values[0] > 1.1 * bare.N_gamma
    assert values[0] > values[1] > values[2] and values[2] < 0.8 * values[1]
    assert damped[0].record()["local_damping"] == 0.8 and bare.local_damping == 0.0
    with pytest.raises(InputError, match="local_damping"):
        node_strip_footing(34.0, "smooth", speed=0.01, local_damping=1.0, **kw)


@pytest.mark.parametrize(
    ("make", "field"),
    [
        (lambda: NodeFootingCase(base="sticky"), "base"),
        (lambda: NodeFootingCase(width=-0.04), "width"),
        (lambda: NodeFootingCase(domain_widths=(0.5, 1.0)), "domain_widths"),
        (lambda: NodeFootingCase(domain_widths=(4.0,)), "domain_widths"),
        (lambda: NodeFootingCase(base_rows=0), "base_rows"),
        (lambda: NodeFootingCase(symmetric="yes"), "symmetric"),
        (lambda: FootingPush(speed=0.0), "speed"),
        (lambda: FootingPush(settlement_ratio=0.5), "settlement_ratio"),
        (lambda: FootingPush(hold_time=-1.0), "hold_time"),
        (lambda: run_node_footing(materials.get("MS"), resolution=Resolution(cell_size=0.003)), "cell_size"),
        (lambda: run_node_footing(materials.get("MS"), local_damping=1.0), "local_damping"),
        (lambda: run_node_footing("MS"), "material"),
    ],
)
def test_the_public_footing_specs_name_the_bad_field(make, field):
    with pytest.raises(InputError) as err:
        make()
    assert err.value.field == field


def test_the_public_node_footing_run_loads_the_half_footing_from_rest_and_holds():
    """terradyn.mpm.run_node_footing, which the study reads: B/4 cells, symmetric, held after the push."""
    case = NodeFootingCase(base=FootingBase.ROUGH, domain_widths=(2.0, 1.0))
    run = run_node_footing(materials.get("MS"), case, resolution=Resolution(cell_size=0.01),
                           push=FootingPush(hold_time=0.01))  # fmt: skip
    assert case.base is FootingBase.ROUGH and run.loaded_width_m == pytest.approx(0.02)
    assert run.settlement_m[-1] == pytest.approx(0.02 * case.width, rel=0.02)
    assert np.all(np.diff(run.settlement_m) > 0.0)
    assert abs(run.pressure_Pa[0]) < 0.1 * run.pressure_Pa[-1]  # the ramp starts from rest
    assert run.held_time_s[-1] == pytest.approx(0.01, rel=0.05)
    assert len(run.held_pressure_Pa) == len(run.held_time_s)
    assert run.steps > 0 and run.particles > 0 and run.push_time_s > 0.0
