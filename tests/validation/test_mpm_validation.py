"""Physics checks of the MPM solver: geostatic column, weight on a bed, plate intrusion, bearing capacity.

Short versions (coarse grids) run by default; ``-m slow`` runs the finer ones. Figures quoted in the
issue note come from these tests. The friction coefficient is mu_s = 0.5 = sin(30 deg).
"""

from __future__ import annotations

import numpy as np
import pytest

from mpm_reference import BULK_DENSITY, MODEL
from terradyn.geometry import Plate
from terradyn.mpm import run_intrusion, run_wheel
from terradyn.mpm.bodies import BodyState
from terradyn.mpm.solver import BedGrid, Phase, Runner, make_bed, stable_time_step

RHO, G = BULK_DENSITY, 9.81
# N_gamma at phi = 30 deg (continuum.md section 7.1): exact smooth (Martin) ... Vesic. The measured
# factor averages settlements s = 0.05-0.15 B, whose surcharge gamma s N_q adds 2 (s / B) N_q = 3.7
# (N_q = 18.4 at 30 deg, mean s / B = 0.1) to the upper bound. Measured with the two-field contact:
# 28.2 / 24.1 / 23.0 at 10 / 5 / 2.5 mm cells (converging from above; the legacy contact gave
# 16.3 / 20.7 from below).
N_GAMMA_RANGE = (7.65, 22.40 + 2 * 0.1 * 18.4)


def settled_column(cell_size: float):
    grid = BedGrid(0.2, 0.1, 0.01, cell_size)
    p = make_bed(MODEL, grid)
    dt = stable_time_step(MODEL, cell_size)
    c = MODEL.wave_speed()
    n = round(40 * grid.depth / c / dt)
    runner = Runner(
        MODEL,
        grid,
        p,
        BodyState.empty(),
        dt,
        [Phase("settle", n, damping=c / grid.depth), Phase("rest", n // 2)],
        has_body=False,
    )
    runner.run()
    before = runner.particles.pos.copy()
    runner.phases.append(Phase("check", n // 2))
    runner.run()
    return grid, runner.particles, before


@pytest.mark.parametrize("cell_size", [0.005, pytest.param(0.0025, marks=pytest.mark.slow)])
def test_settled_column_is_geostatic_and_at_rest(cell_size):
    grid, p, before = settled_column(cell_size)
    h = grid.cell_size
    x, z = p.pos[:, 0], p.pos[:, 1]
    inner = (x > 3 * h) & (x < grid.width - 3 * h) & (z < -2 * h) & (z > -grid.depth + 3 * h)
    errors = []
    for zr in np.unique(np.round(z[inner], 9)):
        row = inner & (np.abs(z - zr) < 1e-9)
        expected = -RHO * G * (0.0 - zr)
        errors.append(abs(p.stress[row, 1].mean() / expected - 1.0))
    assert max(errors) < 0.03
    # at rest: no flow and no drift over the last stretch
    assert np.abs(p.vel).max() < 1e-4
    assert np.abs(p.pos - before).max() < 0.01 * h


def test_block_resting_on_bed_carries_its_weight():
    load = 10.0
    res = run_wheel(
        Plate(0.04, 0.1, thickness=0.02),
        MODEL,
        load=load,
        omega=0.0,
        cell_size=0.005,
        duration=0.2,
        sink_time=0.1,
        settle_time=0.05,
    )
    assert res.summary["force_z_N"] == pytest.approx(load, rel=0.02)
    assert abs(res.summary["drawbar_pull_N"]) < 0.02 * load
    # The elastic settlement (about q B / E = 0.1 mm) is below what grid contact resolves: the block
    # rests within a few hundredths of a cell of the particle surface (measured -0.02 mm at 5 mm cells
    # with the two-field contact, +0.1 mm with the legacy one).
    assert -0.05 * 0.005 < res.summary["sinkage_m"] < 0.01


_PLATE_RUNS: dict = {}


def plate_run(cell_size, length=0.04, width=1.0, depth=0.08, speed=0.2, bed=(0.5, 0.24)):
    """Plate (length B = 0.04 m) pushed straight down; the bed leaves about 6 B to each side wall."""
    key = (cell_size, length, width, depth, speed, bed)
    if key not in _PLATE_RUNS:  # shared between tests of one session
        _PLATE_RUNS[key] = run_intrusion(
            Plate(length, width),
            MODEL,
            depth=depth,
            cell_size=cell_size,
            speed=speed,
            bed_width=bed[0],
            bed_depth=bed[1],
            min_cells_across=4,
            settle_time=20 * bed[1] / MODEL.wave_speed(),
        )
    return _PLATE_RUNS[key]


def force_at(res, depths, half=0.005):
    d, f = res.series["depth_m"], res.series["force_z_N"]
    return np.array([f[np.abs(d - x) < half].mean() for x in depths])


def linear_fit(x, y):
    a, b = np.polyfit(x, y, 1)
    r2 = 1.0 - np.sum((y - (a * x + b)) ** 2) / np.sum((y - y.mean()) ** 2)
    return a, b, r2


@pytest.mark.parametrize(
    ("cell_size", "depths"),
    [(0.01, (0.02, 0.06)), pytest.param(0.005, (0.03, 0.07), marks=pytest.mark.slow)],
)
def test_plate_force_grows_linearly_with_depth(cell_size, depths):
    res = plate_run(cell_size)
    d = np.arange(depths[0], depths[1] + 1e-9, 0.01)  # after the initial transient (D >= B/2)
    f = force_at(res, d)
    slope, _, r2 = linear_fit(d, f)
    assert slope > 0
    # A zero-thickness plate's force rings more from cell crossing than the old three-cell plate did
    # (rms residual about the linear fit 5-9 % against 3-4 %, MS at 3.3-10 mm cells); at 1 cm cells
    # (4 across the plate) r^2 = 0.89 on these five depths, so the coarse form allows 0.85.
    assert r2 > (0.95 if cell_size < 0.01 else 0.85)
    # slope per unit width in units of rho g B (about 24 at mu_s = 0.5)
    k = slope / (RHO * G * 0.04)
    assert 10.0 < k < 40.0


def test_plate_force_is_proportional_to_out_of_plane_width():
    kw = dict(depth=0.02, cell_size=0.01, speed=0.2, bed_width=0.2, bed_depth=0.12, settle_time=0.02)
    f1 = run_intrusion(Plate(0.08, 0.1), MODEL, **kw).summary
    f2 = run_intrusion(Plate(0.08, 0.25), MODEL, **kw).summary
    assert f2["force_z_N"] == pytest.approx(2.5 * f1["force_z_N"], rel=1e-9)
    assert f2["torque_y_Nm"] == pytest.approx(2.5 * f1["torque_y_Nm"], rel=1e-6, abs=1e-9)


@pytest.mark.parametrize(
    ("cell_size", "lengths", "depth", "at"),
    [
        (0.01, (0.04, 0.08), 0.08, [0.05, 0.06]),
        pytest.param(0.005, (0.03, 0.06), 0.06, [0.05], marks=pytest.mark.slow),
    ],
)
def test_plate_force_scales_with_plate_length(cell_size, lengths, depth, at):
    """Doubling the plate breadth B more than doubles the force at a fixed depth D, short of
    quadrupling it: strip-footing theory F = B (gamma D N_q d_q + gamma B N_gamma / 2) gives a ratio of
    about 2.1-2.5 at phi = 30 deg for these sizes (coarse grids, whose plates are thickened to three
    cells, measure 1.6-1.75)."""
    f = [force_at(plate_run(cell_size, length=b, depth=depth), at) for b in lengths]
    ratio = f[1] / f[0]
    assert np.all((1.4 < ratio) & (ratio < 2.8))


def test_plate_force_converges_as_cell_size_is_halved():
    d = np.array([0.02, 0.03, 0.04])
    coarse, fine = (force_at(plate_run(h, depth=0.04, bed=(0.5, 0.2)), d) for h in (0.01, 0.005))
    assert np.all(np.abs(fine / coarse - 1.0) < 0.25)


@pytest.mark.slow
def test_plate_force_converges_further_at_quarter_cells():
    d = np.array([0.03, 0.04, 0.05])
    f = [force_at(plate_run(h, depth=0.06), d) for h in (0.01, 0.005, 0.0025)]
    assert np.all(np.abs(f[2] / f[1] - 1.0) < 0.15)


def bearing_factor(cell_size, breadth=0.04, speed=0.1, bed=(0.44, 0.1)):
    """N_gamma = q / (rho g B / 2) of a rough surface footing, averaged over settlement 0.05-0.15 B."""
    res = run_intrusion(
        Plate(breadth, 1.0),
        MODEL,
        depth=0.005,
        cell_size=cell_size,
        speed=speed,
        surface_friction=1.0,
        bed_width=bed[0],
        bed_depth=bed[1],
        min_cells_across=4,
        settle_time=20 * bed[1] / MODEL.wave_speed(),
    )
    settlement = -res.series["z_m"]  # the MPM plate has zero thickness (two-field contact)
    sel = (settlement > 0.05 * breadth) & (settlement < 0.15 * breadth)
    q = res.series["force_z_N"][sel].mean() / breadth
    return q / (0.5 * RHO * G * breadth)


def test_strip_footing_bearing_capacity_in_published_range():
    n_gamma = bearing_factor(0.005)
    assert N_GAMMA_RANGE[0] < n_gamma < N_GAMMA_RANGE[1]


@pytest.mark.slow
def test_bearing_capacity_converges_with_cell_size():
    n = [bearing_factor(h) for h in (0.01, 0.005, 0.0025)]
    assert all(N_GAMMA_RANGE[0] < v < N_GAMMA_RANGE[1] for v in n[1:])
    assert abs(n[2] / n[1] - 1.0) < 0.2


def wheel_run(slip, duration=0.5, **kw):
    from terradyn.geometry import WheelCircular

    kw = {"omega": 2.0, **kw}
    return run_wheel(
        WheelCircular(0.05, 0.05),
        MODEL,
        load=5.0,
        slip=slip,
        cell_size=0.01,
        duration=duration,
        sink_time=0.15,
        settle_time=0.05,
        **kw,
    )


def test_torque_driven_wheel_balances_the_applied_torque():
    """Free spin under a drive torque: the soil's resisting torque settles on the applied one."""
    res = wheel_run(None, duration=1.0, omega=None, drive_torque=0.05)
    s = res.summary
    assert s["drive_torque_Nm"] == pytest.approx(0.05, rel=0.05)
    assert s["force_z_N"] == pytest.approx(5.0, rel=0.05)
    assert s["omega_rad_s"] > 0 and 0.0 < s["slip"] < 1.0
    assert res.metadata["mode"] == "torque-driven"


def test_towed_load_is_carried_as_drawbar_pull():
    """Self-propelled at a fixed spin with a horizontal load on the axle: the pull equals the load."""
    s = wheel_run(None, duration=1.0, drawbar_load=0.5).summary
    assert s["drawbar_pull_N"] == pytest.approx(0.5, rel=0.1)
    assert s["slip"] > 0.5  # pulling a load at omega = 2 rad/s needs much more slip than free rolling


def test_wheel_that_spins_away_stops_with_a_clear_error():
    from terradyn.mpm import MPMInstabilityError

    with pytest.raises(MPMInstabilityError, match="runs away"):
        wheel_run(None, duration=0.3, omega=None, drive_torque=5.0, max_omega=3.0)


@pytest.mark.parametrize(
    ("kw", "field"),
    [
        ({"omega": 1.0, "drive_torque": 0.1}, "omega"),
        ({"omega": None}, "omega"),
        ({"omega": None, "drive_torque": 0.1, "slip": 0.2}, "slip"),
        ({"slip": 0.2, "drawbar_load": 1.0}, "drawbar_load"),
        ({"omega": None, "drive_torque": 0.1, "max_omega": 0.0}, "max_omega"),
    ],
)
def test_wheel_control_modes_are_validated(kw, field):
    from terradyn.errors import InputError
    from terradyn.geometry import WheelCircular

    kw = {"omega": 2.0, **kw}
    with pytest.raises(InputError, match=field):
        run_wheel(WheelCircular(0.05, 0.05), MODEL, load=5.0, cell_size=0.01, **kw)


def test_wheel_forced_slip_orders_drawbar_pull_and_torque():
    drive, skid = wheel_run(0.3).summary, wheel_run(-0.3).summary
    for s in (drive, skid):
        assert s["force_z_N"] == pytest.approx(5.0, rel=0.05)  # vertical equilibrium under the load
        assert 0.0 < s["sinkage_m"] < 0.05
    assert drive["drawbar_pull_N"] > skid["drawbar_pull_N"]
    assert skid["drawbar_pull_N"] < 0  # a skidding wheel is braked
    assert drive["drive_torque_Nm"] > skid["drive_torque_Nm"] > -0.5
    assert drive["slip"] == pytest.approx(0.3)


@pytest.mark.slow
def test_self_propelled_wheel_finds_zero_drawbar_pull():
    s = wheel_run(None, duration=1.0).summary
    assert abs(s["drawbar_pull_N"]) < 0.1 * 5.0
    assert 0.0 < s["slip"] < 1.0
    assert s["drive_torque_Nm"] > 0


def test_unconsolidated_bed_compacts_and_resists_less():
    kw = dict(depth=0.03, cell_size=0.01, speed=0.2, bed_width=0.4, bed_depth=0.16, min_cells_across=4)
    dense = run_intrusion(Plate(0.04, 1.0), MODEL, packing="consolidated", **kw)
    loose = run_intrusion(Plate(0.04, 1.0), MODEL, packing="unconsolidated", **kw)
    fp = loose.final_particles
    deep_far = (np.abs(fp["x"]) > 0.12) & (fp["z"] < -0.06)
    # settling under gravity compacted the loose bed to the critical density at depth
    assert np.mean(fp["density"][deep_far] >= MODEL.critical_density) > 0.95
    assert loose.summary["force_z_N"] < dense.summary["force_z_N"]
