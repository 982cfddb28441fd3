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


def test_force_slip_row_has_units_and_one_legend_for_loads_and_models():
    from terradyn.plotting import new_force_slip_figure, plot_force_slip
    from terradyn.studies.wheels import wheel_force_slip

    t = wheel_force_slip(media=["MS"], loads=[80.0, 130.0], slips=[0.1, 0.4], models=["rft", "wong-reece"])
    fig, axes = new_force_slip_figure(1)
    row = plot_force_slip(t.columns, material="MS", axes=axes[0])
    assert [ax.get_ylabel() for ax in row] == ["drawbar pull [N]", "drive torque [N m]", "sinkage [mm]"]
    assert all(ax.get_xlabel() == "slip [-]" for ax in row)
    labels = [txt.get_text() for txt in row[0].get_legend().get_texts()]
    assert labels == ["W = 80 N", "W = 130 N", "RFT", "Wong-Reece"]
    assert row[1].get_legend() is None and row[2].get_legend() is None
    assert len(row[0].lines) >= 4  # 2 loads x 2 models (plus the zero line)
    assert fig.get_layout_engine() is not None


def test_body_tractions_arrows_key_in_newtons_and_surface():
    import math

    from terradyn.geometry import Plate
    from terradyn.kinematics import Pose2D, Twist2D, to_world
    from terradyn.plotting import plot_body_tractions
    from terradyn.rft import rft_element_forces

    plate = Plate(0.05, 0.02)
    pose = Pose2D(0.0, -0.03, math.radians(30.0))
    el = rft_element_forces(plate, materials.get("MS"), pose, Twist2D(0.0, -1.0, 0.0))
    outline = [to_world(np.asarray(p), pose) for p in plate.outline()]
    ax = plot_body_tractions(outline, el.positions, el.forces, title="RFT, MS")
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("x [m]", "z [m]") and ax.get_aspect() == 1.0
    assert any(ln.get_label() == "free surface" for ln in ax.lines)
    (quiver,) = [c for c in ax.collections if c.__class__.__name__ == "Quiver"]
    assert 1 <= len(quiver.U) <= 24 + 1
    # the arrows add up to the body's force, at one length scale
    keys = [a for a in ax.artists if a.__class__.__name__ == "QuiverKey"]
    assert keys and keys[0].text.get_text().startswith("RFT force") and " N per " in keys[0].text.get_text()
    drawn = np.array([quiver.U.sum(), quiver.V.sum()])
    total = el.forces.sum(axis=0)
    cos = drawn @ total / (np.linalg.norm(drawn) * np.linalg.norm(total))
    assert cos == pytest.approx(1.0, abs=1e-9)


def test_force_depth_labels_and_legend():
    from terradyn.plotting import plot_force_depth

    depth = np.linspace(0.0, 0.05, 4)
    ax = plot_force_depth(depth, {"F_x": depth * 10, "F_z": depth * 100}, title="t")
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("depth [mm]", "force [N]")
    np.testing.assert_allclose(ax.lines[0].get_xdata(), depth * 1e3)
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["F_x", "F_z"]
