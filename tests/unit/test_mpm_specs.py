"""MPM run specs: validation messages, the legacy keywords, frozen/hashable specs, CLI flag names."""

from __future__ import annotations

import dataclasses
import inspect
import json
import math
import pickle
import re

import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.geometry import Plate, WheelCircular
from terradyn.mpm import (
    Bed,
    BedPacking,
    Drive,
    MPMTerrain,
    Outputs,
    Resolution,
    Stroke,
    Walls,
    run_intrusion,
    run_wheel,
)
from terradyn.mpm.bodies import ContactScheme
from terradyn.mpm.specs import LEGACY, MODEL_OVERRIDES

MS = materials.get("MS")
PLATE = Plate(0.04, 0.02)
WHEEL = WheelCircular(0.05, 0.05)


@pytest.mark.parametrize(
    ("spec", "changes", "field"),
    [
        (Bed, dict(packing="loose"), "packing"),
        (Bed, dict(density=-1.0), "bed_density"),
        (Bed, dict(walls="sticky"), "walls"),
        (Bed, dict(gravity=0.0), "gravity"),
        (Bed, dict(depth=0.0), "bed_depth"),
        (Bed, dict(width=-0.1), "bed_width"),
        (Bed, dict(settle_time=-1.0), "settle_time"),
        (Resolution, dict(cell_size=0.0), "cell_size"),
        (Resolution, dict(cell_size=math.nan), "cell_size"),
        (Resolution, dict(particles_per_cell=5), "particles_per_cell"),
        (Resolution, dict(particles_per_cell=2.5), "particles_per_cell"),
        (Resolution, dict(cfl=0.9), "cfl"),
        (Resolution, dict(contact="glue"), "contact"),
        (Resolution, dict(min_cells_across=1), "min_cells_across"),
        (Resolution, dict(flip=1.5), "flip"),
        (Resolution, dict(flip=math.nan), "flip"),
        (Outputs, dict(record_interval=-1.0), "record_interval"),
        (Outputs, dict(record_spacing=0.0), "record_spacing"),
        (Outputs, dict(record_spacing=0.01, record_interval=0.1), "record_spacing"),
        (Outputs, dict(snapshot_spacing=0.01, snapshot_interval=0.1), "snapshot_spacing"),
        (Outputs, dict(snapshot_dir=3), "snapshot_dir"),
        (Outputs, dict(checkpoint_interval=0.0), "checkpoint_interval"),
        (Outputs, dict(resume=True), "resume"),
        (Outputs, dict(progress="bar"), "progress"),
        (Outputs, dict(frame_count=3000), "frame_count"),
        (Outputs, dict(frame_count=True), "frame_count"),
        (Stroke, dict(averaging_window=0.0), "averaging_window"),
        (Drive, dict(sink_time=-0.1), "sink_time"),
        (Drive, dict(duration=0.0), "duration"),
        (Drive, dict(average_fraction=0.01), "average_fraction"),
    ],
)
def test_each_field_is_checked_and_named(spec, changes, field):
    with pytest.raises(InputError) as err:
        spec(**changes)
    assert err.value.field == field
    assert str(err.value).startswith(f"{field} = ")


def test_specs_coerce_their_inputs():
    bed = Bed(packing="unconsolidated", walls="no-slip")
    assert bed.packing is BedPacking.UNCONSOLIDATED and bed.walls == Walls.coerce("no-slip")
    res = Resolution(contact="cover", particles_per_cell=3.0, min_cells_across=4.0)
    assert res.contact is ContactScheme.COVER and res.particles_per_cell == 3 and res.min_cells_across == 4
    out = Outputs(checkpoint_path="run.npz", resume=True, snapshot_dir="snaps")
    assert out.checkpoint_path is not None and out.checkpoint_path.name == "run.npz"
    assert out.snapshot_dir is not None and out.snapshot_dir.name == "snaps"


def test_specs_are_frozen_hashable_and_read_back_from_their_repr():
    specs = [
        Bed(packing="unconsolidated", depth=0.2, settle_time=0.0),
        Resolution(cell_size=0.005, contact="cover"),
        Outputs(checkpoint_path="a.npz", resume=True, frame_count=10),
        Stroke(0.004),
        Drive(duration=1.5, average_fraction=0.3),
    ]
    names = {"Bed": Bed, "Resolution": Resolution, "Outputs": Outputs, "Stroke": Stroke, "Drive": Drive}
    for spec in specs:
        with pytest.raises(dataclasses.FrozenInstanceError):
            spec.cell_size = 1.0  # type: ignore[misc, attr-defined]
        assert eval(repr(spec), names) == spec  # the repr is what one would type
        assert hash(spec) == hash(eval(repr(spec), names))
        assert pickle.loads(pickle.dumps(spec)) == spec  # specs travel to worker processes
    assert repr(Bed()) == "Bed()" and repr(Resolution(cell_size=0.01)) == "Resolution(cell_size=0.01)"
    assert len({Bed(), Bed(), Bed(walls="free-slip"), Bed(depth=0.1)}) == 2  # free-slip is the default
    assert Resolution(cell_size=0.01).replace(cfl=0.2) == Resolution(cell_size=0.01, cfl=0.2)
    with pytest.raises(InputError, match="cfl"):
        Resolution().replace(cfl=2.0)


def test_every_legacy_keyword_is_one_spec_field_of_the_functions():
    specs = {"bed": Bed, "resolution": Resolution, "outputs": Outputs, "stroke": Stroke, "drive": Drive}
    for name, (arg, field) in LEGACY.items():
        assert field in {f.name for f in dataclasses.fields(specs[arg])}, name
        # the message of that field keeps the keyword's name (bed_length is bed_width's twin)
        assert specs[arg].message_name(field) in (name, "bed_width"), name
    for fn, own in ((run_intrusion, "stroke"), (run_wheel, "drive")):
        params = inspect.signature(fn).parameters
        assert {"bed", "resolution", "outputs", own} <= set(params)
        assert params["outputs"].default == Outputs() and params["bed"].default == Bed()
    assert set(MODEL_OVERRIDES).isdisjoint(LEGACY)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (
            lambda: run_intrusion(PLATE, MS, depth=0.01, cell_sise=0.01),
            "unexpected keyword argument 'cell_sise'",
        ),
        (
            lambda: run_intrusion(PLATE, MS, depth=0.01, bed_length=0.3),
            "unexpected keyword argument 'bed_length'",
        ),
        (
            lambda: run_intrusion(PLATE, MS, depth=0.01, duration=1.0),
            "unexpected keyword argument 'duration'",
        ),
        (lambda: run_wheel(WHEEL, MS, load=10.0, omega=1.0, bed_width=0.3), "'bed_width'"),
        (lambda: run_wheel(WHEEL, MS, load=10.0, omega=1.0, averaging_window=0.01), "'averaging_window'"),
        (
            lambda: MPMTerrain(MS, bed_width=0.2, bed_depth=0.1, cell_size=0.01, frame_count=3),
            "'frame_count'",
        ),
        (
            lambda: run_intrusion(PLATE, MS, depth=0.01, resolution=Resolution(cell_size=0.01), cfl=0.2),
            "'cfl' beside resolution=Resolution(cell_size=0.01)",
        ),
    ],
)
def test_unknown_or_doubled_keywords_are_a_type_error(call, message):
    with pytest.raises(TypeError, match=re.escape(message)):
        call()


def test_bad_legacy_values_name_the_keyword_written():
    with pytest.raises(InputError) as err:
        run_wheel(WHEEL, MS, load=10.0, omega=1.0, bed_length=-0.3)
    assert err.value.field == "bed_length"
    with pytest.raises(InputError) as err:
        run_intrusion(PLATE, MS, depth=0.01, bed_width=-0.3)
    assert err.value.field == "bed_width"
    with pytest.raises(InputError, match="record_interval"):  # a wheel has no single travel speed
        run_wheel(WHEEL, MS, load=10.0, omega=1.0, sink_time=0.0, duration=0.01, record_spacing=0.001)
    with pytest.raises(InputError) as err:
        MPMTerrain(MS, bed=Bed(depth=0.1), resolution=Resolution(cell_size=0.01))
    assert err.value.field == "bed_width"
    with pytest.raises(InputError, match="resolution"):
        run_intrusion(PLATE, MS, depth=0.01, resolution=0.01)  # type: ignore[arg-type]


def _same(a, b):
    assert a.summary == b.summary  # to the bit
    assert a.series.keys() == b.series.keys()
    for k in a.series:
        assert np.array_equal(a.series[k], b.series[k]), k
    assert a.metadata["steps"] == b.metadata["steps"] and a.metadata["particles"] == b.metadata["particles"]


def test_legacy_keywords_give_the_same_intrusion_as_specs():
    kw = dict(depth=0.01, speed=0.2, angle=0.3, direction=1.2, friction_coefficient=0.6)
    flat = run_intrusion(PLATE, MS, **kw, cell_size=0.01, min_cells_across=4, bed_width=0.2, bed_depth=0.08,
                         packing="unconsolidated", settle_time=0.01, record_spacing=0.002,
                         averaging_window=0.004)  # fmt: skip
    spec = run_intrusion(
        PLATE,
        MS,
        **kw,
        bed=Bed(packing="unconsolidated", width=0.2, depth=0.08, settle_time=0.01),
        resolution=Resolution(cell_size=0.01, min_cells_across=4),
        outputs=Outputs(record_spacing=0.002),
        stroke=Stroke(averaging_window=0.004),
    )
    _same(flat, spec)
    # the bed snaps outwards to whole cells (BedGrid): 0.2 m asked, at most one more cell each side
    assert 0.2 <= spec.metadata["bed_width_m"] <= 0.22 + 1e-12 and spec.summary["force_z_N"] > 0


#: the inputs a wheel checkpoint is keyed on (checkpoints written before the specs must still resume)
WHEEL_KEYS = {"run", "load", "omega", "slip", "drive_torque", "drawbar_load", "max_omega", "inertia",
              "duration", "sink_time", "settle_time", "bed_length", "bed_depth", "frame_count", "body",
              "model", "cell_size", "cfl", "gravity", "packing", "bed_density", "particles_per_cell",
              "walls", "contact", "derived"}  # fmt: skip


def test_legacy_keywords_give_the_same_wheel_as_specs(tmp_path):
    kw = dict(load=20.0, omega=2.0, slip=0.2)
    ckpt = tmp_path / "wheel.npz"
    flat = run_wheel(WHEEL, MS, **kw, cell_size=0.1 / 8, duration=0.05, sink_time=0.01, settle_time=0.01,
                     bed_length=0.4, record_interval=0.005, average_fraction=0.4,
                     checkpoint_path=ckpt)  # fmt: skip
    bed = Bed(settle_time=0.01, width=0.4)
    resolution = Resolution(cell_size=0.1 / 8)
    drive = Drive(duration=0.05, sink_time=0.01, average_fraction=0.4)
    spec = run_wheel(WHEEL, MS, **kw, bed=bed, resolution=resolution, outputs=Outputs(record_interval=0.005),
                     drive=drive)  # fmt: skip
    _same(flat, spec)
    assert spec.metadata["bed_width_m"] == 0.4
    with np.load(ckpt) as data:
        assert set(json.loads(str(data["__inputs__"]))) == WHEEL_KEYS
    again = Outputs(record_interval=0.005, checkpoint_path=ckpt, resume=True)
    resumed = run_wheel(WHEEL, MS, **kw, bed=bed, resolution=resolution, drive=drive, outputs=again)
    assert resumed.summary == flat.summary  # the flat run's checkpoint is the spec run's


def test_terrain_takes_specs_or_the_old_keywords():
    flat = MPMTerrain(MS, bed_width=0.2, bed_depth=0.1, cell_size=0.01, packing="unconsolidated", cfl=0.2)
    spec = MPMTerrain(
        MS,
        bed=Bed(width=0.2, depth=0.1, packing="unconsolidated"),
        resolution=Resolution(cell_size=0.01, cfl=0.2),
    )
    assert flat.grid == spec.grid and flat.dt == spec.dt and flat.bed == spec.bed
    assert flat._inputs(None, None) == spec._inputs(None, None)  # the checkpoint key


PLATE_ARGS = ("plate", "--length", "0.06", "--depth", "0.02")
WHEEL_ARGS = ("--load", "10", "--omega", "1")
SIZES = ("--cell-sizes", "0.01,0.008,0.006")


@pytest.mark.parametrize(
    ("args", "flag"),
    [
        (("intrude", *PLATE_ARGS, "--packing", "loose"), "--packing"),
        (("intrude", *PLATE_ARGS, "--walls", "sticky"), "--walls"),
        (("intrude", *PLATE_ARGS, "--contact", "glue"), "--contact"),
        (("intrude", *PLATE_ARGS, "--particles-per-cell", "7"), "--particles-per-cell"),
        (("intrude", *PLATE_ARGS, "--cell-size", "-0.01"), "--cell-size"),
        (("intrude", *PLATE_ARGS, "--checkpoint-interval", "0"), "--checkpoint-interval"),
        (("wheel", *WHEEL_ARGS, "--duration", "-1"), "--duration"),
        (("wheel", *WHEEL_ARGS, "--particles-per-cell", "0"), "--particles-per-cell"),
        (("wheel", *WHEEL_ARGS, "--contact", "glue"), "--contact"),
        (("converge", "intrude", *PLATE_ARGS, *SIZES, "--walls", "sticky"), "--walls"),
        (("converge", "wheel", *WHEEL_ARGS, *SIZES, "--particles-per-cell", "9"), "--particles-per-cell"),
        (("converge", "wheel", *WHEEL_ARGS, *SIZES, "--packing", "loose"), "--packing"),
        (("verify", "strip-footing", "--phi", "30", "--cell-size", "-0.001"), "--cell-size"),
        (("verify", "strip-footing", "--phi", "30", "--contact", "glue"), "--contact"),
        (("intrude", *PLATE_ARGS, "--flip", "2"), "--flip"),
        (("wheel", *WHEEL_ARGS, "--flip", "-0.5"), "--flip"),
        (("verify", "strip-footing", "--phi", "30", "--flip", "1.01"), "--flip"),
        (("wheel", *WHEEL_ARGS, "--spin-up", "-1"), "--spin-up"),
        (("wheel", *WHEEL_ARGS, "--duration", "1", "--spin-up", "0.8"), "--spin-up"),
        (("wheel", *WHEEL_ARGS, "--slip", "0.2", "--initial-speed", "0.1"), "--initial-speed"),
        (("converge", "wheel", *WHEEL_ARGS, *SIZES, "--spin-up", "-1"), "--spin-up"),
    ],
)
def test_cli_names_the_flag_of_a_bad_spec_field(run_cli, args, flag):
    """Every CLI flag that feeds a spec field names itself when the spec refuses its value."""
    code, _, err = run_cli("mpm", *args)
    assert code == 1, err
    assert err.startswith(f"terradyn: error: {flag} = "), err
