"""Particle field plots and animations of MPM frames (synthetic frames: no solver run)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from terradyn.errors import InputError
from terradyn.mpm.bodies import body_segments_world
from terradyn.plotting.mpm import animate_frames, plot_fields


@pytest.fixture(autouse=True)
def _close_figures():
    import matplotlib.pyplot as plt

    yield
    plt.close("all")


def _frame(t: float) -> dict:
    rng = np.random.default_rng(0)
    x, z = rng.uniform(-0.1, 0.1, 500), rng.uniform(-0.1, 0.0, 500)
    seg = np.array([[-0.02, 0.0, 0.02, 0.0], [0.02, 0.0, 0.02, 0.01], [0.02, 0.01, -0.02, 0.0]])
    return {
        "time_s": np.array(t),
        "segments": body_segments_world(seg, np.array([0.0, 0.01 - t, 0.0])),
        "x": x,
        "z": z,
        "speed": np.abs(np.sin(10 * x + t)),
        "pressure": 1e3 * (-z),
    }


def test_body_segments_world_rotates_clockwise_about_y():
    seg = np.array([[1.0, 0.0, 0.0, 1.0]])
    w = body_segments_world(seg, np.array([2.0, 3.0, np.pi / 2]))
    # R(theta) = [[c, s], [-s, c]]: body +x goes to world -z, body +z to world +x
    np.testing.assert_allclose(w[0], [[2.0, 2.0], [3.0, 3.0]], atol=1e-12)


def test_plot_fields_has_one_panel_per_quantity():
    f = _frame(0.0)
    fig = plot_fields(
        f, segments=f["segments"], quantities=("speed", "pressure"), window=(-0.1, 0.1, -0.1, 0.02)
    )
    assert len([a for a in fig.axes if a.get_label() != "<colorbar>"]) == 2
    with pytest.raises(InputError, match="quantity"):
        plot_fields(f, quantities=("temperature",))


def test_animate_frames_writes_gif_atomically(tmp_path):
    path = animate_frames([_frame(0.0), _frame(0.01), _frame(0.02)], tmp_path / "a.gif", fps=5)
    assert path.read_bytes()[:3] == b"GIF"
    assert [p.name for p in tmp_path.iterdir()] == ["a.gif"]
    with pytest.raises(InputError, match="frames"):
        animate_frames([_frame(0.0)], tmp_path / "b.gif")
    with pytest.raises(InputError, match="gif"):
        animate_frames([_frame(0.0), _frame(0.1)], tmp_path / "b.avi")


@pytest.fixture(scope="module")
def mpm_runs():
    """A small real intrusion and a short forced-slip wheel run (a few seconds together)."""
    from mpm_reference import MODEL
    from terradyn.geometry import Plate, WheelCircular
    from terradyn.mpm import run_intrusion, run_wheel

    fast = dict(cell_size=0.01, bed_width=0.2, bed_depth=0.12, settle_time=0.02)
    intrusion = run_intrusion(Plate(0.08, 0.1), MODEL, depth=0.02, speed=0.2, **fast)
    wheel = run_wheel(
        WheelCircular(0.05, 0.05), MODEL, load=5.0, omega=2.0, slip=0.3, cell_size=0.01, duration=0.1
    )
    return intrusion, wheel


def test_mpm_wheel_history_has_one_panel_per_unit(mpm_runs):
    from terradyn.plotting.mpm import plot_mpm_history

    fig = plot_mpm_history(mpm_runs[1], kind="wheel", title="wheel")
    ylabels = [ax.get_ylabel() for ax in fig.axes]
    assert ylabels == ["force [N]", "torque [N m]", "sinkage [mm]", "slip [-]"]
    assert fig.axes[-1].get_xlabel() == "time [s]"
    assert all(ax.get_legend() is not None for ax in fig.axes)
    assert fig.axes[0].get_shared_x_axes().joined(fig.axes[0], fig.axes[-1])
    slip = fig.axes[3].lines[0].get_ydata()
    assert np.nanmax(np.abs(np.asarray(slip) - 0.3)) < 1e-6  # forced slip, radius recovered
    # no radius given, none in the metadata and no slip in the summary: the slip panel is left out
    bare = dataclasses.replace(mpm_runs[1], summary={"load_N": 5.0})
    assert len(plot_mpm_history(bare, kind="wheel").axes) == 3
    assert len(plot_mpm_history(bare, kind="wheel", radius=0.05).axes) == 4


def test_mpm_intrusion_history_plots_force_and_torque_versus_depth(mpm_runs):
    from terradyn.plotting.mpm import plot_mpm_history

    fig = plot_mpm_history(mpm_runs[0], kind="intrusion")
    assert [ax.get_ylabel() for ax in fig.axes] == ["force on body [N]", "torque [N m]"]
    assert "[mm]" in fig.axes[-1].get_xlabel()
    assert all(ax.get_legend() is not None for ax in fig.axes)
    depth_mm = fig.axes[0].lines[0].get_xdata()
    np.testing.assert_allclose(depth_mm, mpm_runs[0].series["depth_m"] * 1e3)
    with pytest.raises(InputError, match="kind"):
        plot_mpm_history(mpm_runs[0], kind="plate")
    with pytest.raises(InputError, match="result"):
        plot_mpm_history(mpm_runs[0], kind="wheel")


def test_plot_fields_window_is_cut_to_bed_and_body():
    f = _frame(0.0)
    fig = plot_fields(f, segments=f["segments"], quantities=("speed",), window=(-1.0, 1.0, -1.0, 1.0))
    (ax,) = [a for a in fig.axes if a.get_label() != "<colorbar>"]
    lo, hi = ax.get_xlim()
    assert -0.12 < lo < -0.1 and 0.1 < hi < 0.12  # particles span [-0.1, 0.1]
    assert ax.get_ylim()[1] >= float(np.asarray(f["segments"])[..., 1].max())
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("x [m]", "z [m]")
    bar = next(a for a in fig.axes if a.get_label() == "<colorbar>")
    assert bar.get_ylabel() == "|v| [m/s]"
