"""MPM kernels: numba equals the pure-NumPy reference; conservation of mass and momentum."""

from __future__ import annotations

import numpy as np
import pytest

from mpm_reference import KERNEL_H, KERNEL_ORIGIN, KERNEL_SHAPE, kernel_particles
from terradyn.mpm import _kernels as K
from terradyn.mpm._reference import (
    g2p_reference,
    grid_update_reference,
    p2g_reference,
    polygon_sdf_reference,
)
from terradyn.mpm.model import GranularModel

H = KERNEL_H
X0, Z0 = KERNEL_ORIGIN
SHAPE = KERNEL_SHAPE
MODEL = GranularModel(
    youngs_modulus=2e6,
    poisson_ratio=0.33,
    friction_coefficient=0.5,
    friction_coefficient_2=0.7,
    inertial_number_0=0.278,
    grain_diameter=1e-3,
    grain_density=2600.0,
    critical_density=1500.0,
    bulk_density=1560.0,
    surface_friction=0.4,
)
particles = kernel_particles


def run_p2g(pos, vel, aff, stress, mass, vol, dt):
    buf = np.zeros((3, *SHAPE, 3))  # three chunks to exercise the reduction
    K.p2g(pos, vel, aff, stress, mass, vol, X0, Z0, H, dt, buf)
    gm, gp = K.grid_totals(buf)
    return gm, gp, buf


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_p2g_equals_reference(seed):
    p = particles(seed)
    gm, gp, _ = run_p2g(*p, dt=1e-4)
    rm, rp = p2g_reference(*p, X0, Z0, H, 1e-4, SHAPE)
    np.testing.assert_allclose(gm, rm, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(gp, rp, rtol=1e-10, atol=1e-12)


def test_p2g_conserves_mass_and_momentum():
    pos, vel, aff, stress, mass, vol = particles(5)
    gm, gp, _ = run_p2g(pos, vel, aff, stress, mass, vol, dt=1e-4)
    assert gm.sum() == pytest.approx(mass.sum(), rel=1e-13)
    # affine terms and internal forces carry no net momentum (partition of unity, sum of gradients = 0)
    np.testing.assert_allclose(gp.sum(axis=(0, 1)), (mass[:, None] * vel).sum(axis=0), rtol=1e-10, atol=1e-12)


@pytest.mark.parametrize("walls", [(0, 0, 0), (1, 1, 1), (2, 2, 2), (0, 1, 2)])
def test_grid_update_equals_reference(walls):
    p = particles(3)
    gm, gp, buf = run_p2g(*p, dt=1e-4)
    kinds = np.array(walls, dtype=np.int64)
    mus = np.array([0.3, 0.3, 0.3])
    gv = np.zeros_like(gp)
    gm_out = np.zeros_like(gm)
    K.grid_update(buf, gm_out, gv, 1e-4, 9.81, 5.0, 3, kinds, mus)
    np.testing.assert_allclose(gm_out, gm, rtol=1e-14)
    ref = grid_update_reference(gm, gp, 1e-4, 9.81, 5.0, 3, kinds, mus)
    np.testing.assert_allclose(gv, ref, rtol=1e-12, atol=1e-14)


def test_g2p_equals_reference():
    pos, vel, aff, stress, mass, vol = particles(4)
    rng = np.random.default_rng(9)
    gv = rng.normal(0, 0.05, (*SHAPE, 2))
    bounds = np.array([X0 + 2 * H, X0 + 11 * H, Z0 + 2 * H, Z0 + 9 * H])
    mat = MODEL.as_kernel_array()
    ref = g2p_reference(pos, vel, aff, stress, mass, vol, gv, X0, Z0, H, 1e-4, bounds, mat)
    gdot = np.zeros(len(pos))
    gm = np.zeros_like(gv)
    node = np.zeros((*SHAPE, 3))
    node[..., 2] = 1e300  # no body: no band nodes
    geo = np.zeros((len(pos), 3))
    K.g2p(pos, vel, aff, stress, mass, vol, gdot, gv, gm, geo, node, X0, Z0, H, 1e-4, bounds, *mat)
    for got, want in zip((pos, vel, aff, stress, vol, gdot), ref, strict=True):
        np.testing.assert_allclose(got, want, rtol=1e-9, atol=1e-9)


def test_polygon_sdf_equals_reference():
    from terradyn.geometry import WheelCircular
    from terradyn.mpm.bodies import body_segments

    seg = body_segments(WheelCircular(0.1, 0.1), 0.01)
    pts = np.random.default_rng(1).uniform(-0.15, 0.15, (400, 2))
    got = np.array([K.polygon_sdf(x, z, seg)[0] for x, z in pts])
    np.testing.assert_allclose(got, polygon_sdf_reference(pts, seg), atol=1e-12)
    r = np.hypot(pts[:, 0], pts[:, 1])
    np.testing.assert_allclose(got, r - 0.1, atol=2e-4)  # polygon of half-cell chords
    # outward normal
    _, nx, nz = K.polygon_sdf(0.2, 0.0, seg)
    assert (nx, nz) == pytest.approx((1.0, 0.0), abs=1e-6)


def test_body_contact_blocks_approach_and_reports_reaction():
    from terradyn.geometry import Plate
    from terradyn.mpm.bodies import body_segments, effective_body

    seg = body_segments(effective_body(Plate(0.1, 0.1), H, "cover"), H)  # 3 cells thick
    gm = np.full(SHAPE, 0.01)
    gv = np.zeros((*SHAPE, 2))
    gv[..., 1] = 0.2  # grains moving up into a plate at rest
    pose = np.array([X0 + 7.37 * H, Z0 + 6.3 * H, 0.0])
    f = K.body_contact(gm, gv, X0, Z0, H, 1e-3, seg, pose, np.zeros(3), 0.08, 0.4)
    inside = np.array(
        [
            [K.polygon_sdf(X0 + i * H - pose[0], Z0 + j * H - pose[1], seg)[0] < 0 for j in range(SHAPE[1])]
            for i in range(SHAPE[0])
        ]
    )
    assert inside.sum() > 0
    # nodes in the lower half (normal -z) are stopped; the reaction pushes the body up
    assert f[1] > 0
    moved = gv[..., 1] != 0.2
    assert np.all(inside[moved])
    # reaction = momentum taken from the grains per unit time
    assert f[1] == pytest.approx(-(0.01 * (gv[..., 1] - 0.2) / 1e-3).sum())
    assert f[0] == pytest.approx(-(0.01 * gv[..., 0] / 1e-3).sum(), abs=1e-9)


def test_particle_mass_is_conserved_exactly_through_a_run():
    from terradyn.mpm.bodies import BodyState
    from terradyn.mpm.solver import BedGrid, Phase, Runner, make_bed, stable_time_step

    grid = BedGrid(0.06, 0.04, 0.01, 0.005)
    p = make_bed(MODEL, grid)
    m0 = p.mass.copy()
    dt = stable_time_step(MODEL, grid.cell_size)
    runner = Runner(MODEL, grid, p, BodyState.empty(), dt, [Phase("a", 200)], has_body=False)
    runner.run()
    assert np.array_equal(runner.particles.mass, m0)
    q = runner.particles
    buf = K.make_buffer(*grid.shape, len(q))
    K.p2g(q.pos, q.vel, q.aff, q.stress, q.mass, q.vol, *grid.origin, grid.cell_size, dt, buf)
    gm, _ = K.grid_totals(buf)
    assert gm.sum() == pytest.approx(m0.sum(), rel=1e-13)


def _rolling_wheel_runner(threads: int):
    """A bed of ~5400 particles (two blocks of body_particles) with a wheel rolling through it."""
    import numba

    from terradyn.geometry import WheelCircular
    from terradyn.mpm.bodies import BodyState, body_segments
    from terradyn.mpm.solver import BedGrid, Phase, Runner, make_bed, stable_time_step

    grid = BedGrid(0.2, 0.06, 0.03, 0.003, -0.1)
    body = BodyState(
        seg=body_segments(WheelCircular(0.03, 0.1), 0.003),
        pose=np.array([0.0, 0.024, 0.0]),
        twist=np.array([0.05, -0.05, -2.0]),
        free=np.zeros(3, dtype=np.bool_),
        mass=1.0,
        load=np.zeros(3),
        friction=0.4,
        width=0.1,
    )
    runner = Runner(MODEL, grid, make_bed(MODEL, grid), body, stable_time_step(MODEL, 0.003), [Phase("a", 1)])
    old = numba.get_num_threads()
    numba.set_num_threads(threads)
    try:
        runner.prepare()
    finally:
        numba.set_num_threads(old)
    return runner


def test_two_threads_give_the_one_thread_step_to_rounding():
    import numba

    if numba.config.NUMBA_NUM_THREADS < 2:
        pytest.skip("needs NUMBA_NUM_THREADS >= 2")
    runs = []
    for threads in (1, 2):
        runner = _rolling_wheel_runner(2)  # two p2g grid copies in both runs
        forces = np.zeros((40, 3))
        old = numba.get_num_threads()
        numba.set_num_threads(threads)
        try:
            runner._advance(40, 0.0, forces)
        finally:
            numba.set_num_threads(old)
        runs.append((runner.particles, forces))
    (p1, f1), (p2, f2) = runs
    assert np.abs(f1[:, 1]).max() > 0.0  # the wheel is in contact
    np.testing.assert_allclose(f2, f1, rtol=1e-9, atol=1e-9 * np.abs(f1).max())
    np.testing.assert_allclose(p2.pos, p1.pos, rtol=0, atol=1e-12)
    np.testing.assert_allclose(p2.stress, p1.stress, rtol=0, atol=1e-9 * np.abs(p1.stress).max())


def test_body_particles_blocks_list_the_near_particles_in_order():
    import numba

    runner = _rolling_wheel_runner(1)
    pos, b = runner.particles.pos, runner.body
    reach = b.reach + 4.5 * runner.grid.cell_size
    assert len(pos) > 4096  # more than one block
    r = np.hypot(pos[:, 0] - b.pose[0], pos[:, 1] - b.pose[1])
    want = np.flatnonzero(r * r <= reach * reach)
    old = numba.get_num_threads()
    for threads in {1, min(2, numba.config.NUMBA_NUM_THREADS)}:
        geo = np.full((len(pos), 3), 7.0)  # stale rows must be cleared
        near = np.zeros(len(pos), dtype=np.int64)
        numba.set_num_threads(threads)
        try:
            k = K.body_particles(pos, b.seg, b.pose, reach, geo, near)
        finally:
            numba.set_num_threads(old)
        np.testing.assert_array_equal(near[:k], want)
        far = np.setdiff1d(np.arange(len(pos)), want)
        assert np.all(geo[far] == 0.0)
        np.testing.assert_allclose(np.hypot(geo[want, 0], geo[want, 1]), 1.0, rtol=1e-12)


def test_runner_keeps_the_faster_thread_count_and_probes_the_other():
    from terradyn.mpm import solver

    runner = _rolling_wheel_runner(1)
    n = solver.PARALLEL_MIN_PARTICLES
    runner.particles = solver.ParticleState(
        *(np.zeros((n, *a.shape[1:])) for a in vars(runner.particles).values())
    )
    assert runner._thread_count(1) == 1
    picks = []
    for _ in range(2 + 2 * solver.THREAD_PROBE_EVERY):
        use = runner._thread_count(2)
        picks.append(use)
        runner._time_chunk(use, 1.0 if use == 1 else 2.0)  # two threads twice as slow
    assert picks[:3] == [2, 2, 1]  # warm-up chunk (not timed), then each count once
    later = picks[3:]
    assert later.count(1) > later.count(2) >= 1  # one thread kept, two threads tried again
    small = _rolling_wheel_runner(1)
    assert len(small.particles) < n and small._thread_count(2) == 1
