"""Particle field plots and animations of MPM frames (synthetic frames: no solver run)."""

from __future__ import annotations

import numpy as np
import pytest

from terradyn.errors import InputError
from terradyn.mpm.bodies import body_segments_world
from terradyn.plotting.mpm import animate_frames, plot_fields


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
