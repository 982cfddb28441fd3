"""Reading N_gamma from a strip-footing run: the intercept of the embedment line (stand-in solver)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.studies.mpm_verification import strip_footing


def _fake(n_gamma, slope, width=0.04, out_of_plane=0.01, noise=0.0, seed=0):
    gamma = materials.get("MS").bulk_density * 9.81
    calls = {}
    rng = np.random.default_rng(seed)

    def run(body, material, *, depth, **kw):
        calls.update(kw, depth=depth, length=body.length)
        s = np.linspace(-0.001, depth, 400)
        q_u = 0.5 * gamma * width * n_gamma
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
