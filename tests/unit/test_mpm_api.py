"""terradyn.mpm public API: validation, results, snapshots, checkpoints/resume, instability errors."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from mpm_reference import MODEL
from terradyn import materials
from terradyn.errors import InputError
from terradyn.geometry import Plate, WheelCircular
from terradyn.mpm import (
    GranularModel,
    IntrusionResult,
    MPMInstabilityError,
    Walls,
    bed_stability_ratio,
    friction_coefficient_from_angle,
    read_snapshot,
    run_intrusion,
    run_wheel,
)

FAST = dict(cell_size=0.01, speed=0.2, bed_width=0.2, bed_depth=0.12, settle_time=0.02)


def test_friction_mapping_and_bed_stability():
    assert friction_coefficient_from_angle(math.radians(30.0)) == pytest.approx(0.5)
    assert bed_stability_ratio(0.3) == pytest.approx(0.533, abs=1e-3)
    with pytest.raises(InputError) as err:
        MODEL.with_changes(poisson_ratio=0.2).check_bed_stability()
    assert err.value.field == "friction_coefficient"


@pytest.mark.parametrize("name", ["MS", "MMS", "LPS", "CPS", "poppy-cp", "poppy-lp", "generic"])
def test_shipped_media_have_continuum_parameters(name):
    mat = materials.get(name)
    model = GranularModel.from_material(mat)
    model.check_bed_stability()
    assert 1e5 < model.youngs_modulus < 1e8  # softened, documented
    if mat.internal_friction_angle is not None:
        assert model.friction_coefficient == pytest.approx(math.sin(mat.internal_friction_angle), abs=1e-3)
    assert (
        GranularModel.from_material(mat, rate_dependent=True).friction_coefficient_2
        > model.friction_coefficient
    )


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        (dict(cell_size=0.05), "cell_size"),
        (dict(cell_size=-1.0), "cell_size"),
        (dict(depth=-0.1), "depth"),
        (dict(direction=0.0), "direction"),
        (dict(speed=0.0), "speed"),
        (dict(cfl=0.9), "cfl"),
        (dict(packing="fluffy"), "packing"),
        (dict(bed_density=1400.0), "bed_density"),
        (dict(bed_depth=0.06), "bed_depth"),
        (dict(walls="sticky"), "walls"),
    ],
)
def test_run_intrusion_validates_inputs(kwargs, field):
    args = dict(depth=0.02, **FAST)
    args.update(kwargs)
    with pytest.raises(InputError) as err:
        run_intrusion(Plate(0.08, 0.1), MODEL, **args)
    assert err.value.field == field


def test_run_wheel_validates_inputs():
    with pytest.raises(InputError) as err:
        run_wheel(WheelCircular(0.05, 0.1), MODEL, load=-1.0, omega=1.0, cell_size=0.01)
    assert err.value.field == "load"
    with pytest.raises(InputError) as err:
        run_wheel(WheelCircular(0.05, 0.1), MODEL, load=5.0, omega=1.0, slip=1.5, cell_size=0.01)
    assert err.value.field == "slip"
    with pytest.raises(InputError) as err:
        run_wheel("wheel", MODEL, load=5.0, omega=1.0)
    assert err.value.field == "body"


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"omega": 1.0, "slip": 0.2, "forward_speed": 0.05}, "slip"),
        ({"drive_torque": 1.0, "forward_speed": 0.05}, "forward_speed"),
        ({"omega": 0.0, "forward_speed": float("nan")}, "forward_speed"),
        ({"omega": 0.0, "forward_speed": 0.05, "drawbar_load": 1.0}, "drawbar_load"),
        ({"omega": 0.0, "forward_speed": 0.05, "initial_speed": 0.1}, "initial_speed"),
    ],
)
def test_a_towed_run_validates_its_forward_speed(kwargs, field):
    """A prescribed forward speed replaces the slip: any input that would also set it is refused."""
    with pytest.raises(InputError) as err:
        run_wheel(WheelCircular(0.05, 0.1), MODEL, load=5.0, cell_size=0.01, **kwargs)
    assert err.value.field == field


def test_intrusion_result_summary_snapshots_and_progress(tmp_path):
    calls = []
    res = run_intrusion(
        Plate(0.08, 0.1),
        MODEL,
        depth=0.02,
        **FAST,
        snapshot_dir=tmp_path / "snap",
        progress=lambda t, f: calls.append((t, f)),
    )
    assert isinstance(res, IntrusionResult)
    for key in ("force_x_N", "force_z_N", "torque_y_Nm"):
        assert math.isfinite(res.summary[key])
    assert res.summary["force_z_N"] > 0  # resists the downward push
    df = res.to_dataframe()
    assert {"time_s", "depth_m", "force_z_N", "torque_y_Nm"} <= set(df.columns)
    assert calls and calls[-1][1] == pytest.approx(1.0)
    assert all(b[0] >= a[0] for a, b in itertools.pairwise(calls))
    snaps = sorted((tmp_path / "snap").glob("particles_*.nc"))
    assert snaps
    ds = read_snapshot(snaps[-1])
    assert ds["pressure"].attrs["units"] == "Pa"
    assert ds.sizes["particle"] == res.metadata["particles"]
    assert not list((tmp_path / "snap").glob(".*"))  # no temporary files left behind


def test_checkpoint_resume_continues_a_killed_run(tmp_path):
    ckpt = tmp_path / "run.npz"
    ref = run_intrusion(Plate(0.08, 0.1), MODEL, depth=0.02, **FAST)

    class Kill(Exception):
        pass

    def killer(t, frac):
        if frac > 0.6:
            raise Kill

    with pytest.raises(Kill):
        run_intrusion(
            Plate(0.08, 0.1),
            MODEL,
            depth=0.02,
            **FAST,
            checkpoint_path=ckpt,
            checkpoint_interval=1e-9,
            progress=killer,
        )
    assert ckpt.exists()
    res = run_intrusion(Plate(0.08, 0.1), MODEL, depth=0.02, **FAST, checkpoint_path=ckpt, resume=True)
    assert res.metadata["steps"] == ref.metadata["steps"]
    # the resumed run reproduces the uninterrupted one (same arithmetic, parallel sums aside)
    np.testing.assert_allclose(res.series["force_z_N"], ref.series["force_z_N"], rtol=1e-6, atol=1e-6)
    with pytest.raises(InputError) as err:  # a checkpoint of other inputs is refused
        run_intrusion(Plate(0.08, 0.1), MODEL, depth=0.03, **FAST, checkpoint_path=ckpt, resume=True)
    assert err.value.field == "checkpoint_path"


def test_instability_stops_with_clear_error_and_keeps_checkpoint(tmp_path):
    from terradyn.mpm.bodies import BodyState
    from terradyn.mpm.solver import BedGrid, Phase, Runner, make_bed

    grid = BedGrid(0.1, 0.05, 0.01, 0.01)
    p = make_bed(MODEL, grid)
    ckpt = tmp_path / "c.npz"
    runner = Runner(
        MODEL,
        grid,
        p,
        BodyState.empty(),
        1e-3,
        [Phase("a", 50)],
        has_body=False,
        checkpoint_path=ckpt,
        fingerprint="x",
    )
    runner.save_checkpoint()
    before = ckpt.read_bytes()
    with pytest.raises(MPMInstabilityError, match=r"CFL|NaN|runaway"):
        runner.run()  # dt far above the stable step
    assert ckpt.read_bytes() == before


def test_walls_coercion():
    assert Walls.coerce("no-slip").bottom.code == 1
    assert Walls.coerce(None).left.code == 0
    with pytest.raises(InputError):
        Walls.coerce(3)


def test_shipped_medium_with_mu_of_i_runs_and_reports_finite_forces():
    res = run_intrusion(Plate(0.08, 0.1), materials.get("generic"), depth=0.02, rate_dependent=True, **FAST)
    assert res.summary["force_z_N"] > 0
    assert "friction_coefficient_2=0.778" in res.metadata["granular_model"]
    assert np.isfinite(res.to_dataframe()[["force_x_N", "force_z_N", "torque_y_Nm"]].to_numpy()).all()
