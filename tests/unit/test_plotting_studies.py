"""Figures of the optimisation and the high-speed study, built from small real runs."""

from __future__ import annotations

import math

import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.plotting.studies import plot_high_speed, plot_optimization


@pytest.fixture(autouse=True)
def _close_figures():
    import matplotlib.pyplot as plt

    yield
    plt.close("all")


def _panels(fig):
    return [a for a in fig.axes if a.get_label() != "<colorbar>"]


def test_optimization_figure_trace_and_map_in_display_units():
    from terradyn.optimize import optimize_flapped_wheel

    res = optimize_flapped_wheel(
        materials.get("CPS"), hub_radius=0.05, width=0.05, load=10.0, max_iterations=2, population=3,
        phase_count=4,
    )  # fmt: skip
    fig = plot_optimization(res, ["flap_count", "flap_angle"], "velocity")
    trace, objective = _panels(fig)
    assert trace.get_xlabel() == "generation [-]" and "[-]" in trace.get_ylabel()
    assert objective.get_xlabel() == "flap count [-]" and objective.get_ylabel() == "flap angle [deg]"
    assert trace.get_legend() is not None and objective.get_legend() is not None
    bar = next(a for a in fig.axes if a.get_label() == "<colorbar>")
    assert "V / (\\omega R_{out})" in bar.get_ylabel()
    (best,) = [ln for ln in objective.lines if ln.get_label() == "best"]
    assert best.get_ydata()[0] == pytest.approx(math.degrees(res.best["flap_angle"]))
    with pytest.raises(InputError, match="names"):
        plot_optimization(res, ["flap_count", "flap_count"], "velocity")


def test_high_speed_figure_one_panel_per_quantity_with_onset():
    from terradyn.studies.high_speed import high_speed_sweep

    res = high_speed_sweep(reduced=True)
    fig = plot_high_speed(res)
    axes = _panels(fig)
    assert len(axes) == 3
    assert all(a.get_xlabel().endswith("[-]") and a.get_ylabel().endswith("[-]") for a in axes)
    labels = axes[0].get_legend_handles_labels()[1]
    assert {"RFT", "DRFT"} <= set(labels)
    onset = res.onsets["drft"]["omega_onset_normalised"]
    if onset is not None:
        assert "DRFT slip onset" in labels
        assert any(np.allclose(ln.get_xdata(), onset) for ln in axes[1].lines)
