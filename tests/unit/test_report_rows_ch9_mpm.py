"""The chapter 9 MPM rows (superposition, plowing, lift and drag, Fig. 9-9): registered, and their quick
forms build in the report with their figures named and the run's numbers in the findings."""

import math

import numpy as np
import pytest

from terradyn.report import reproduce
from terradyn.report.registry import item, rows_of
from terradyn.report.rows.common import fluctuations

ROWS = {
    "ch9-superposition": ("ch9_intrusion:superposition_mpm", "superposition_mpm"),
    "ch9-plowing": ("ch9_drag:plowing_mpm", "plowing_mpm"),
    "ch9-lift-drag": ("ch9_drag:lift_drag_mpm", "lift_drag_mpm"),
    "fig-9-9": ("ch9_drag:cylinder_fields_mpm", "fig_9_9_fields"),
}


def test_rows_are_registered():
    for key, (name, _) in ROWS.items():
        assert dict(rows_of(item(key)))["mpm"] == f"terradyn.report.rows.{name}"


def test_fluctuations_tell_a_periodic_signal_from_noise():
    d = np.linspace(0.0, 0.1, 401)
    periodic = fluctuations(d, 2.0 + 0.2 * np.sin(2 * math.pi * d / 0.01) + 0.5 * d)
    assert periodic["mean_N"] == pytest.approx(2.025, rel=1e-3)
    assert periodic["relative_std"] == pytest.approx(0.2 / math.sqrt(2) / 2.025, rel=0.02)
    assert periodic["peak_lag_m"] == pytest.approx(0.01, rel=0.03)
    assert periodic["peak_height"] > 0.9
    noise = fluctuations(d, 2.0 + 0.2 * np.random.default_rng(1).standard_normal(d.size))
    assert noise["peak_height"] < 0.3


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    folder = tmp_path_factory.mktemp("ch9_report")
    return folder, reproduce(folder, quick=True, only=list(ROWS))


def test_quick_rows_build_and_name_their_figures(report):
    folder, run = report
    assert run.failures == []
    html = (folder / "report.html").read_text(encoding="utf-8")
    for key, (_, figure) in ROWS.items():
        r = run.results[(key, "mpm")]
        assert r["status"] == "ran"
        assert list(r["figures"]) == [figure]
        assert f"{figure}.png" in html or figure in html
        assert f"id='{key}'" in html
        assert r["findings"] and any(ch.isdigit() for f in r["findings"] for ch in f["text"])


def test_superposition_numbers_are_the_runs(report):
    _, run = report
    r = run.results[("ch9-superposition", "mpm")]
    rows = r["tables"]["superposition"]
    assert all(x["rft_ratio"] == pytest.approx(1.0, abs=1e-12) for x in rows)  # RFT superposes exactly
    assert all(math.isfinite(x["mpm_ratio"]) and x["mpm_ratio"] > 0 for x in rows)
    texts = " ".join(f["text"] for f in r["findings"])
    assert f"{rows[0]['mpm_ratio']:.3f}" in texts and f"{rows[-1]['mpm_ratio']:.3f}" in texts


def test_lift_drag_and_plowing_numbers_are_the_runs(report):
    _, run = report
    rows = run.results[("ch9-lift-drag", "mpm")]["tables"]["lift_drag"]
    assert all(x["drag_N"] > 0 for x in rows)
    texts = " ".join(f["text"] for f in run.results[("ch9-lift-drag", "mpm")]["findings"])
    for x in rows:
        assert f"{x['drag_N']:.2f}" in texts if x["body"] == "cylinder" else f"{x['drag_N']:.3f} N" in texts
    plow = run.results[("ch9-plowing", "mpm")]
    loose, dense = plow["tables"]["plowing"][0], plow["tables"]["plowing"][-1]
    assert dense["packing_fraction"] > loose["packing_fraction"]
    texts = " ".join(f["text"] for f in plow["findings"])
    assert f"{dense['drag_mean_N']:.2f} N" in texts and f"{loose['drag_relative_std']:.3f}" in texts
