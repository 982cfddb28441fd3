"""Wheel-simulation plots: the time series and the animation frames (rotation marker, labels)."""

from __future__ import annotations

import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.geometry import WheelCircular
from terradyn.locomotion.dynamics import simulate_wheel
from terradyn.plotting.animation import animate_body, plot_body_frame, plot_time_series


@pytest.fixture(autouse=True)
def _close_figures():
    import matplotlib.pyplot as plt

    yield
    plt.close("all")


@pytest.fixture(scope="module")
def run():
    body = WheelCircular(0.13, 0.16)
    mat = materials.get("CPS")
    res = simulate_wheel(body, mat, mass=8.0, omega=2.0, duration=0.6, output_every=10)
    return body, mat, res


def test_time_series_has_units_on_every_axis(run):
    axes = plot_time_series(run[2])
    assert axes.shape == (3, 2)
    ylabels = [ax.get_ylabel() for ax in axes.ravel()]
    for unit in ("[m/s]", "[rad/s]", "[-]", "[mm]", "[N]", "[N m]"):
        assert any(unit in lab for lab in ylabels), unit
    assert all("[" in lab and "]" in lab for lab in ylabels)
    assert [ax.get_xlabel() for ax in axes[-1]] == ["time [s]", "time [s]"]
    assert all(ax.get_legend() is not None for ax in axes.ravel())


def _marker(ax):
    (line,) = [ln for ln in ax.lines if ln.get_gid() == "rotation-marker"]
    return np.column_stack(line.get_data())


def test_body_frame_labels_surface_and_turning_marker(run):
    body, mat, res = run
    i0, i1 = 0, len(res.t) - 1
    ax0 = plot_body_frame(body, mat, res, i0)
    ax1 = plot_body_frame(body, mat, res, i1)
    assert (ax0.get_xlabel(), ax0.get_ylabel()) == ("x [m]", "z [m]")
    assert ax0.get_aspect() == 1.0
    assert any(ln.get_label() == "free surface" for ln in ax0.lines)
    assert any(t.get_text().startswith("t = ") and t.get_text().endswith(" s") for t in ax1.texts)
    m0, m1 = _marker(ax0), _marker(ax1)
    # the spoke starts at the axle and turns by the wheel angle between the two rows
    np.testing.assert_allclose(m1[0], [res.x[i1], res.z[i1]], atol=1e-12)
    d0, d1 = m0[1] - m0[0], m1[1] - m1[0]
    turned = np.arctan2(d0[0] * d1[1] - d0[1] * d1[0], d0 @ d1)  # counter-clockwise angle in view
    expected = -(res.theta[i1] - res.theta[i0])  # theta about +y turns clockwise in view
    assert abs(res.theta[i1] - res.theta[i0]) > 0.1
    assert np.angle(np.exp(1j * (turned - expected))) == pytest.approx(0.0, abs=1e-9)
    assert ax1.collections  # traction arrows of the loaded elements
    with pytest.raises(InputError, match="index"):
        plot_body_frame(body, mat, res, len(res.t))


def test_animate_body_writes_a_gif(run, tmp_path):
    body, mat, res = run
    path = animate_body(body, mat, res, tmp_path / "w.gif", frames=3, fps=5)
    assert path.read_bytes()[:3] == b"GIF"
    assert [p.name for p in tmp_path.iterdir()] == ["w.gif"]
