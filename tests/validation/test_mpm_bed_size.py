"""Bed size and grid alignment: the bed snaps to the grid, so a body meets the same grid whatever the
bed size (checked without a run); and the measured wall/floor rule of :func:`terradyn.mpm.run_intrusion`
(:func:`terradyn.mpm.runs.mechanism_clearance`): moving the walls or the floor of the default bed 1.5
times further away changes the force by under 3 % (slow: three plate runs). Measured for the 60 mm
plate at 10 mm cells: 226.4 N default, -1.1 % wider, -0.1 % deeper.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mpm_reference import MODEL
from terradyn import materials
from terradyn.geometry import Plate
from terradyn.mpm import BedGrid, run_intrusion
from terradyn.mpm.solver import GRID_PAD, make_bed


def test_bed_grid_snaps_outwards_to_whole_cells():
    h = 0.01
    grid = BedGrid(0.4234, 0.2055, 0.03, h, -0.2117)
    assert grid.x_left == pytest.approx(-0.22, abs=1e-12)
    assert grid.x_right == pytest.approx(0.22, abs=1e-12)  # encloses -0.2117 + 0.4234 = 0.2117
    assert grid.depth == pytest.approx(0.21, abs=1e-12)
    x0, z0 = grid.origin
    # nodes on multiples of h, and the node line z = 0 is the free surface
    assert x0 / h == pytest.approx(round(x0 / h), abs=1e-9)
    assert (0.0 - z0) / h == pytest.approx(GRID_PAD + 21, abs=1e-9)
    particles = make_bed(MODEL, grid, particles_per_cell=2)
    assert particles.pos[:, 1].max() == pytest.approx(-h / 4, abs=1e-12)  # top row a quarter cell down
    assert particles.pos[:, 1].min() == pytest.approx(-grid.depth + h / 4, abs=1e-12)
    # an aligned box is left as it is
    same = BedGrid(0.42, 0.21, 0.03, h, -0.21)
    assert (same.width, same.depth, same.x_left) == (pytest.approx(0.42), pytest.approx(0.21), -0.21)


def test_a_surface_offset_moves_the_node_lines_below_the_surface_and_keeps_the_bed():
    """surface_offset = 0.5: the surface stays at z = 0 and the floor on a node line, the node lines
    sit half a cell below the surface, and the points keep their h / 2 rows up to the surface."""
    from terradyn.errors import InputError
    from terradyn.mpm.specs import Bed

    h = 0.01
    grid = BedGrid(0.42, 0.2, 0.03, h, -0.21, surface_offset=0.5)
    assert grid.depth == pytest.approx(0.205, abs=1e-12)
    _x0, z0 = grid.origin
    lines = z0 + h * (GRID_PAD + np.arange(30))  # node lines from the floor up
    assert lines[0] == pytest.approx(-grid.depth, abs=1e-12)
    assert np.min(np.abs(lines - (-0.5 * h))) == pytest.approx(0.0, abs=1e-12)
    assert np.min(np.abs(lines)) == pytest.approx(0.5 * h, abs=1e-12)  # no node line on the surface
    # idempotent: a grid rebuilt from its own depth (the moving window does) keeps it
    assert BedGrid(0.42, grid.depth, 0.03, h, -0.21, surface_offset=0.5).depth == pytest.approx(grid.depth)
    p = make_bed(MODEL, grid, particles_per_cell=2).pos[:, 1]
    rows = np.unique(np.round(p, 12))
    assert rows.max() == pytest.approx(-h / 4, abs=1e-12) and rows.min() == pytest.approx(-grid.depth + h / 4)
    assert np.allclose(np.diff(rows), h / 2)
    # offset 0 makes exactly the bed of before (the same points, bit for bit)
    old = make_bed(MODEL, BedGrid(0.42, 0.2, 0.03, h, -0.21), particles_per_cell=2).pos
    cz = (np.arange(20)[:, None] + np.array([0.25, 0.75])[None, :]).ravel() * h - 0.2
    assert np.array_equal(np.unique(old[:, 1]), np.unique(cz))
    with pytest.raises(InputError, match="surface_offset"):
        make_bed(MODEL, BedGrid(0.42, 0.2, 0.03, h, -0.21, surface_offset=0.25), particles_per_cell=2)
    with pytest.raises(InputError, match="surface_offset"):
        Bed(surface_offset=1.0)


@pytest.mark.slow
@pytest.mark.parametrize(("length", "cell_size"), [(0.06, 0.01)])
def test_walls_and_floor_beyond_the_default_rule_change_the_force_by_under_3_percent(length, cell_size):
    plate, ms = Plate(length, 0.1), materials.get("MS")
    base = run_intrusion(plate, ms, depth=0.04, cell_size=cell_size)
    width, depth = base.metadata["bed_width_m"], base.metadata["bed_depth_m"]
    f0 = base.summary["force_z_N"]
    assert math.isfinite(f0) and f0 > 0
    for w, d in [(1.5 * width, depth), (width, 1.5 * depth)]:
        f = run_intrusion(plate, ms, depth=0.04, cell_size=cell_size, bed_width=w, bed_depth=d)
        assert f.summary["force_z_N"] == pytest.approx(f0, rel=0.03), (w, d)
