"""MPM as a stateful terrain model (init/step) and the model-agnostic coupled driver.

Coarse grids (1 cm cells) keep these in the default suite; the physics of the solver itself is
checked in test_mpm_validation.py.
"""

from __future__ import annotations

import numpy as np
import pytest

from mpm_reference import MODEL
from terradyn import materials
from terradyn.errors import InputError
from terradyn.geometry import Plate, WheelCircular
from terradyn.kinematics import Pose2D, Twist2D
from terradyn.locomotion import simulate_coupled, wheel_steady
from terradyn.mpm import MPMTerrain, run_intrusion
from terradyn.rft import RFTModel
from terradyn.terrain import StatefulTerrainModel, Stateless

H = 0.01


def _plate_through_terrain(terrain: MPMTerrain, plate: Plate, z0: float, z_end: float, v: float, dt: float):
    pose = Pose2D(0.0, z0)
    terrain.init(plate, pose)
    rows = []
    while pose.z > z_end:
        w = terrain.step(pose, Twist2D(0.0, -v, 0.0), dt)
        rows.append((-(pose.z - 0.5 * v * dt), w.fx, w.fz, w.torque_y))
        pose = Pose2D(0.0, pose.z - v * dt)
    return np.array(rows)


def test_stepping_the_terrain_reproduces_the_prescribed_intrusion_run():
    """Same bed, same motion: init/step and run_intrusion give the same force at depth (< 2 %)."""
    plate = Plate(0.06, 0.02, thickness=3 * H)
    depth, v = 0.06, 0.1
    # a fixed bed (whole cells; the size the sizing rule gave before its Prandtl-mechanism margins):
    # this test is about init/step against run_intrusion, not the bed rule
    ref = run_intrusion(plate, MODEL, depth=depth, cell_size=H, speed=v, bed_width=0.47, bed_depth=0.25)
    md = ref.metadata
    terrain = MPMTerrain(
        MODEL, bed_width=md["bed_width_m"], bed_depth=md["bed_depth_m"], cell_size=H, max_speed=v
    )
    assert isinstance(terrain, StatefulTerrainModel)
    rows = _plate_through_terrain(terrain, plate, 0.02, -(depth + 0.03), v, 2e-3)
    window = ref.summary["averaging_window_m"]
    sel = np.abs(rows[:, 0] - depth) <= 0.5 * window
    assert rows[sel, 2].mean() == pytest.approx(ref.summary["force_z_N"], rel=0.02)
    # symmetric plate pushed straight down: no net side force or torque (relative to the lift)
    assert abs(rows[sel, 1].mean()) < 0.02 * rows[sel, 2].mean()
    assert abs(rows[sel, 3].mean()) < 0.02 * rows[sel, 2].mean() * 0.03
    assert terrain.time == pytest.approx(len(rows) * 2e-3)


def test_torque_reference_point_shifts_with_the_force():
    plate = Plate(0.06, 0.02, thickness=H)
    terrain = MPMTerrain(MODEL, bed_width=0.4, bed_depth=0.15, cell_size=H, max_speed=0.1, settle_time=0.02)
    pose = Pose2D(0.0, -0.02)
    terrain.init(plate, pose)
    w0 = terrain.step(pose, Twist2D(0.0, -0.05, 0.0), 1e-3)
    terrain2 = MPMTerrain(MODEL, bed_width=0.4, bed_depth=0.15, cell_size=H, max_speed=0.1, settle_time=0.02)
    terrain2.init(plate, pose)
    w1 = terrain2.step(pose, Twist2D(0.0, -0.05, 0.0), 1e-3, about=(0.1, 0.0))
    assert w1.fx == pytest.approx(w0.fx) and w1.fz == pytest.approx(w0.fz)
    # tau_a = tau_o + (o_z - a_z) f_x - (o_x - a_x) f_z with o the body origin at ``pose``
    expected = w0.torque_y + (pose.z - 0.0) * w0.fx - (pose.x - 0.1) * w0.fz
    assert w1.torque_y == pytest.approx(expected, rel=1e-6, abs=1e-9)


def test_save_and_restore_continue_identically(tmp_path):
    plate = Plate(0.06, 0.02, thickness=H)
    kw = dict(bed_width=0.4, bed_depth=0.15, cell_size=H, max_speed=0.1, settle_time=0.02)
    terrain = MPMTerrain(MODEL, **kw)
    pose = Pose2D(0.0, 0.0)
    terrain.init(plate, pose)
    tw = Twist2D(0.0, -0.05, 0.0)
    for _ in range(5):
        terrain.step(pose, tw, 2e-3)
        pose = Pose2D(0.0, pose.z - 1e-4)
    path = terrain.save(tmp_path / "bed.npz")
    after = [terrain.step(Pose2D(0.0, pose.z - k * 1e-4), tw, 2e-3).fz for k in range(3)]
    other = MPMTerrain(MODEL, **kw)
    other.restore(plate, path)
    assert other.time == pytest.approx(0.01)
    again = [other.step(Pose2D(0.0, pose.z - k * 1e-4), tw, 2e-3).fz for k in range(3)]
    np.testing.assert_allclose(again, after, rtol=1e-9)
    with pytest.raises(InputError, match="checkpoint"):
        MPMTerrain(MODEL, **{**kw, "cell_size": 0.0125}).restore(plate, path)


def test_terrain_rejects_bad_use():
    plate = Plate(0.06, 0.02)
    terrain = MPMTerrain(MODEL, bed_width=0.3, bed_depth=0.1, cell_size=H, max_speed=0.1, settle_time=0.0)
    with pytest.raises(InputError, match="init"):
        terrain.step(Pose2D(0, 0), Twist2D(), 1e-3)
    with pytest.raises(InputError, match="stateful"):
        terrain.wrench(plate, Pose2D(0, 0), Twist2D())
    with pytest.raises(InputError, match="pose"):
        terrain.init(plate, Pose2D(0.2, 0.0))  # outside the bed
    terrain.init(plate, Pose2D(0.0, 0.03))
    with pytest.raises(InputError, match="max_speed"):
        terrain.step(Pose2D(0, 0.03), Twist2D(0.0, -1.0, 0.0), 1e-3)
    with pytest.raises(InputError, match="dt"):
        terrain.step(Pose2D(0, 0.03), Twist2D(), 0.0)
    with pytest.raises(InputError, match="bed_width"):
        MPMTerrain(MODEL, bed_width=-1.0, bed_depth=0.1, cell_size=H)
    with pytest.raises(InputError, match="material"):
        MPMTerrain("sand", bed_width=0.3, bed_depth=0.1, cell_size=H)


@pytest.mark.parametrize("name", ["rft", "drft", "wong-reece"])
def test_coupled_driver_on_stateless_models_reproduces_the_steady_solve(name):
    """The generic driver with a stateless model settles on that model's implicit steady solution."""
    from terradyn.locomotion.models import ModelSpec

    model = ModelSpec(name)(materials.get("MS"))
    wheel = WheelCircular(0.1, 0.1)
    ref = wheel_steady(wheel, model, 50.0, 0.2, omega=1.0)
    res = simulate_coupled(
        wheel,
        Stateless(model),
        load=50.0,
        pose=Pose2D(0.0, 0.1),
        duration=2.0,
        dt=1e-3,
        omega=1.0,
        vx=0.08,
    )
    s = res.summary
    assert s["force_z_N"] == pytest.approx(50.0, rel=0.01)  # Wong-Reece leaves an undamped bounce
    assert s["sinkage_m"] == pytest.approx(ref.sinkage_m, rel=0.04)
    assert s["force_x_N"] == pytest.approx(ref.drawbar_pull_N, rel=0.04)
    assert s["drive_torque_Nm"] == pytest.approx(ref.drive_torque_Nm, rel=0.02)
    assert s["slip"] == pytest.approx(0.2)


def test_material_means_rft_in_the_coupled_driver():
    mat = materials.get("MS")
    wheel = WheelCircular(0.1, 0.1)
    kw = dict(load=50.0, pose=Pose2D(0.0, 0.1), duration=0.2, dt=1e-3, omega=1.0, vx=0.08)
    a = simulate_coupled(wheel, mat, **kw).summary
    b = simulate_coupled(wheel, Stateless(RFTModel(mat)), **kw).summary
    assert a == b


def test_coupled_driver_on_mpm_block_comes_to_rest_carrying_its_weight():
    """A block dropped onto the MPM bed through the same driver ends at rest with F_z = load."""
    block = Plate(0.06, 0.05, thickness=0.02)
    terrain = MPMTerrain(MODEL, bed_width=0.3, bed_depth=0.08, cell_size=H, max_speed=0.5)
    load = 10.0
    res = simulate_coupled(block, terrain, load=load, pose=Pose2D(0.0, 0.0105), duration=0.25, dt=1e-3)
    s = res.summary
    assert s["force_z_N"] == pytest.approx(load, rel=0.02)
    assert abs(s["force_x_N"]) < 0.02 * load
    assert 0.0 < s["sinkage_m"] < 0.02
    # At rest: no drift, and only the elastic ringing of a mass on the soft bed (period about
    # 2 pi sqrt(m / k) = 30 ms for k ~ E; measured peak to peak 0.14 mm = 0.014 cells)
    assert abs(res.series["vz_m_s"][-60:].mean()) < 2e-3
    assert np.ptp(res.series["z_m"][-60:]) < 0.02 * H


def test_coupled_driver_rejects_bad_input():
    mat = materials.get("MS")
    wheel = WheelCircular(0.1, 0.1)
    with pytest.raises(InputError, match="terrain"):
        simulate_coupled(wheel, "sand", load=1.0, pose=Pose2D(0, 0.1), duration=1.0, dt=0.01)
    with pytest.raises(InputError, match="load"):
        simulate_coupled(wheel, mat, load=-1.0, pose=Pose2D(0, 0.1), duration=1.0, dt=0.01)
    with pytest.raises(InputError, match="dt"):
        simulate_coupled(wheel, mat, load=1.0, pose=Pose2D(0, 0.1), duration=1.0, dt=2.0)
