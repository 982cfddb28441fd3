"""Reading N_gamma from a strip-footing run: the intercept of the embedment line (stand-in solver)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.studies.mpm_verification import strip_footing


def _fake(n_gamma, slope, width=0.04, out_of_plane=0.01, noise=0.0, seed=0, per_offset=0.0):
    """A stand-in solver whose bed has the density of a consolidated MS bed as terradyn makes it;
    ``per_offset`` adds that much N_gamma per cell of grid surface offset."""
    ms = materials.get("MS")
    gamma = max(ms.bulk_density, 1.02 * ms.critical_density) * 9.81
    calls = {"offsets": []}
    rng = np.random.default_rng(seed)

    def run(body, material, *, depth, **kw):
        calls.update(kw, depth=depth, length=body.length)
        calls["offsets"].append(kw["bed"].surface_offset)
        n_gamma_here = n_gamma + per_offset * kw["bed"].surface_offset
        s = np.linspace(-0.001, depth, 400)
        q_u = 0.5 * gamma * width * n_gamma_here
        # elastic rise to the collapse pressure over 2 % of B, then the embedment line
        q = np.where(s < 0.02 * width, q_u * np.clip(s, 0, None) / (0.02 * width), q_u + gamma * slope * s)
        q = q + noise * q_u * rng.standard_normal(len(s))  # relative white noise on the pressure
        import pandas as pd

        return SimpleNamespace(
            to_dataframe=lambda: pd.DataFrame({"depth_m": s, "force_z_N": q * width * out_of_plane})
        )

    return run, calls


@pytest.mark.parametrize("base", ["rough", "smooth"])
def test_intercept_of_the_embedment_line_gives_n_gamma(base):
    run, calls = _fake(n_gamma=11.0, slope=15.0)
    res = strip_footing(30.0, base, run=run)
    assert res.N_gamma_mpm == pytest.approx(11.0, rel=1e-6)
    assert res.embedment_slope == pytest.approx(15.0, rel=1e-6)
    assert res.N_gamma_raw > res.N_gamma_mpm  # the embedment term is not bearing capacity
    assert calls["friction_coefficient"] == pytest.approx(math.sin(math.radians(30.0)))
    assert calls["surface_friction"] == (0.0 if base == "smooth" else 2.0)
    assert calls["resolution"].cell_size == pytest.approx(0.04 / 20)
    assert calls["stroke"].averaging_window == pytest.approx(0.2 * 0.1 * 0.04)
    assert calls["outputs"].record_spacing == pytest.approx(min(0.25 * 0.04 / 20, 0.02 * 0.1 * 0.04))
    rec = res.record()
    assert {"N_gamma_mpm", "N_gamma_reference", "reference"} <= set(rec)
    # 11 lies inside Radenkovic's bracket at 30 deg: smooth [4.42, 7.65] no, rough (upper 14.8) yes
    if base == "smooth":
        assert rec["N_gamma_lower_bound"] == pytest.approx(4.424, abs=1e-3)
        assert rec["N_gamma_upper_bound"] == pytest.approx(7.650, abs=1e-3)
        assert rec["within_bounds"] is False
        # against the finite-element value 6.51 +- 0.41 (slow push): 11 is not within 10 %
        assert rec["reference_kind"] == "computed, finite elements"
        assert rec["N_gamma_reference_band"] == pytest.approx(0.41)
        assert rec["ratio_mpm_to_reference"] == pytest.approx(11.0 / 6.51)
        assert rec["within_10_percent_of_reference"] is False
    else:
        assert rec["N_gamma_lower_bound"] is None and rec["N_gamma_upper_bound"] == pytest.approx(14.8)
        assert rec["within_bounds"] is True


def test_settlement_must_span_cells_and_inputs_are_checked():
    run, _ = _fake(10.0, 10.0)
    with pytest.raises(InputError, match="cell_size"):
        strip_footing(30.0, "rough", cell_size=0.004, settlement_ratio=0.1, run=run)
    with pytest.raises(InputError, match="base"):
        strip_footing(30.0, "sticky", run=run)
    with pytest.raises(InputError, match="friction_angle_deg"):
        strip_footing(60.0, "rough", run=run)


def test_the_intercept_standard_error_matches_the_scatter_of_repeated_noisy_runs():
    """White noise of 10 % of q_u: the reported standard error of N_gamma agrees with the spread of
    the intercepts over 40 noisy repeats (within the sampling error of a 40-sample spread)."""
    exact = strip_footing(30.0, "rough", run=_fake(11.0, 15.0)[0])
    assert exact.N_gamma_stderr == pytest.approx(0.0, abs=1e-9)
    runs = [strip_footing(30.0, "rough", run=_fake(11.0, 15.0, noise=0.1, seed=k)[0]) for k in range(40)]
    spread = np.std([r.N_gamma_mpm for r in runs], ddof=1)
    reported = np.mean([r.N_gamma_stderr for r in runs])
    assert spread > 0.05  # the noise moves the intercept
    assert reported == pytest.approx(spread, rel=0.35)
    assert abs(np.mean([r.N_gamma_mpm for r in runs]) - 11.0) < 3 * spread / math.sqrt(40)
    assert "N_gamma_mpm_stderr" in runs[0].record()


def test_the_unit_weight_is_that_of_the_bed_as_made():
    """A consolidated bed is made at max(bulk, 1.02 critical) density (MS: 1591 against a bulk 1560
    kg/m^3); N_gamma is normalised by that bed's unit weight, or by the density the bed is given."""
    from terradyn.mpm.specs import Bed

    ms = materials.get("MS")
    res = strip_footing(30.0, "rough", run=_fake(11.0, 15.0)[0])
    assert res.unit_weight_N_m3 == pytest.approx(1.02 * ms.critical_density * 9.81)
    assert res.unit_weight_N_m3 > ms.bulk_density * 9.81
    given = strip_footing(30.0, "rough", bed=Bed(density=1700.0), run=_fake(11.0, 15.0)[0])
    assert given.unit_weight_N_m3 == pytest.approx(1700.0 * 9.81)


def test_grid_phases_move_the_grid_and_report_the_mean_and_spread():
    run, calls = _fake(11.0, 15.0, per_offset=4.0)
    res = strip_footing(30.0, "rough", grid_phases=2, run=run)
    assert calls["offsets"] == [0.0, 0.5]
    assert [p[1] for p in res.phases] == pytest.approx([11.0, 13.0])
    assert res.N_gamma_mpm == pytest.approx(12.0)
    rec = res.record()
    assert rec["grid_phases"] == 2 and rec["surface_offsets"] == [0.0, 0.5]
    assert rec["N_gamma_phase_spread"] == pytest.approx(2.0)
    one = strip_footing(30.0, "rough", run=_fake(11.0, 15.0)[0])
    assert "grid_phases" not in one.record() and len(one.phases) == 1
    with pytest.raises(InputError, match="grid_phases"):
        strip_footing(30.0, "rough", grid_phases=3, run=run)  # 2 points per cell: phases 1 or 2


def test_the_footing_plot_draws_every_grid_phase_and_the_bounds():
    import matplotlib

    matplotlib.use("Agg")
    from terradyn.plotting.studies import plot_footing

    run, _ = _fake(11.0, 15.0, per_offset=4.0)
    two = plot_footing(strip_footing(30.0, "smooth", grid_phases=2, run=run))
    labels = [ln.get_label() for ln in two.axes[0].get_lines()]
    assert sum("grid offset" in lab for lab in labels) == 2  # one curve per phase, each named
    assert any("offset 0.5 cell" in lab and "13" in lab for lab in labels)
    assert any("associated Mohr-Coulomb" in lab for lab in labels)
    assert any("isochoric" in lab for lab in labels)
    assert any("MPM cone" in lab for lab in labels)  # a smooth base has the cone's bound
    one = plot_footing(strip_footing(30.0, "smooth", run=_fake(11.0, 15.0)[0]))
    labels = [ln.get_label() for ln in one.axes[0].get_lines()]
    assert not any("grid offset" in lab for lab in labels) and any(lab.startswith("MPM") for lab in labels)
