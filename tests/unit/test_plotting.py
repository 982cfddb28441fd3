"""RFT plots: alpha maps, force versus depth, traction arrows (structure of the figures)."""

from __future__ import annotations

import numpy as np
import pytest

from terradyn import materials
from terradyn.plotting import plot_alpha_map, plot_alpha_maps
from terradyn.rft import li2013_alpha_material


@pytest.fixture(autouse=True)
def _close_figures():
    import matplotlib.pyplot as plt

    yield
    plt.close("all")


def _alpha_grid(step: float = 15.0):
    deg = np.arange(-90.0, 90.0 + 1e-9, step)
    bb, gg = np.meshgrid(np.radians(deg), np.radians(deg), indexing="ij")
    ax_, az_ = li2013_alpha_material(bb, gg, materials.get("LPS"))
    return bb, gg, ax_, az_


def _norm_centre(mesh) -> float:
    return 0.5 * (mesh.norm.vmin + mesh.norm.vmax)


def test_alpha_maps_share_a_zero_centred_scale_in_n_per_cm3():
    bb, gg, ax_, az_ = _alpha_grid()
    fig = plot_alpha_maps(bb, gg, ax_, az_, title="RFT alpha map, LPS")
    panels = [a for a in fig.axes if a.get_label() != "<colorbar>"]
    bars = [a for a in fig.axes if a.get_label() == "<colorbar>"]
    assert len(panels) == 2 and len(bars) == 1
    assert [a.get_title() for a in panels] == [r"$\alpha_z$", r"$\alpha_x$"]
    for a in panels:
        mesh = a.collections[0]
        assert _norm_centre(mesh) == pytest.approx(0.0, abs=1e-12)
        # one scale for both, reaching the largest |alpha| in N/cm^3
        assert mesh.norm.vmax == pytest.approx(max(np.abs(ax_).max(), np.abs(az_).max()) / 1e6)
        assert "[deg]" in a.get_xlabel() and r"\beta" in a.get_xlabel()
        assert set(np.round(a.get_xticks())) <= set(np.arange(-90, 91, 30))
    assert "[deg]" in panels[0].get_ylabel() and r"\gamma" in panels[0].get_ylabel()
    assert "N/cm$^3$" in bars[0].get_ylabel() and "10$^{-6}$" in bars[0].get_ylabel()
    assert fig.get_layout_engine() is not None  # constrained layout: no overlapping labels
    fig.canvas.draw()
    boxes = [a.get_tightbbox() for a in panels]
    assert not boxes[0].overlaps(boxes[1])


def test_single_alpha_map_is_centred_even_when_all_positive():
    bb, gg, _, az_ = _alpha_grid(30.0)
    positive = np.abs(az_) + 1.0
    ax = plot_alpha_map(bb, gg, positive, label=r"$\alpha_z$")
    mesh = ax.collections[0]
    assert mesh.norm.vmin == pytest.approx(-mesh.norm.vmax)
    bar = next(a for a in ax.figure.axes if a.get_label() == "<colorbar>")
    assert "N/cm$^3$" in bar.get_ylabel()
