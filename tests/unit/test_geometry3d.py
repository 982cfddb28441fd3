"""Triangle meshes, primitives, mesh files and 3D kinematics."""

import math
import sys

import numpy as np
import pytest

from terradyn.errors import InputError
from terradyn.geometry3d import (
    Pose3D,
    TriangleMesh,
    Twist3D,
    Wrench3D,
    box,
    cone,
    load_mesh,
    plate,
    resample,
    rotation_from_rpy,
    rpy_from_rotation,
    save_mesh,
    sphere,
    wheel_cylinder,
    wheel_grousered,
)
from terradyn.kinematics import Pose2D, Twist2D, point_velocities, to_world

GROUSERED = wheel_grousered(
    0.1, 0.05, grouser_count=10, grouser_height=0.01, grouser_thickness=0.005, circumferential_resolution=120
)


def _mirror_set(points: np.ndarray) -> bool:
    """True if the point set is unchanged (exactly) by y -> -y."""
    a = np.unique(points, axis=0)
    b = np.unique(points * np.array([1.0, -1.0, 1.0]), axis=0)
    return a.shape == b.shape and bool(np.all(a == b))


@pytest.mark.parametrize(
    ("mesh", "volume", "area", "rtol"),
    [
        (box(0.3, 0.2, 0.1, facet_size=0.05), 0.006, 2 * (0.06 + 0.03 + 0.02), 1e-12),
        (wheel_cylinder(0.1, 0.05), math.pi * 0.01 * 0.05,
         2 * math.pi * 0.1 * 0.05 + 2 * math.pi * 0.01, 1e-3),
        (sphere(0.1, subdivisions=4), 4 / 3 * math.pi * 1e-3, 4 * math.pi * 0.01, 3e-3),
        (cone(0.05, 0.1, circumferential_resolution=128), math.pi * 0.05**2 * 0.1 / 3,
         math.pi * 0.05 * (0.05 + math.hypot(0.05, 0.1)), 1e-3),
    ],
)  # fmt: skip
def test_primitives_are_closed_outward_and_measure_right(mesh, volume, area, rtol):
    assert mesh.is_closed()
    assert mesh.volume == pytest.approx(volume, rel=rtol)
    assert mesh.area == pytest.approx(area, rel=rtol)
    # Outward: normals point away from the centroid of the body on average.
    assert np.einsum("ij,ij->i", mesh.normals, mesh.centroids - mesh.centroids.mean(axis=0)).mean() > 0
    np.testing.assert_allclose(np.linalg.norm(mesh.normals, axis=1), 1.0, rtol=1e-12)


@pytest.mark.parametrize(
    "mesh",
    [GROUSERED, wheel_cylinder(0.1, 0.05, axial_resolution=3), box(0.3, 0.2, 0.1),
     sphere(0.1, subdivisions=2), cone(0.05, 0.1, circumferential_resolution=30),
     plate(0.2, 0.1, facet_size=0.03)],
)  # fmt: skip
def test_primitives_are_exactly_mirror_symmetric_about_xz(mesh):
    assert _mirror_set(mesh.vertices)
    flip = np.array([1.0, -1.0, 1.0, 1.0, 1.0, -1.0, 1.0])
    rows = np.round(np.hstack((mesh.centroids, mesh.areas[:, None], mesh.normals)), 12) + 0.0
    a = rows[np.lexsort(rows.T)]
    b = np.round(rows * flip, 12) + 0.0
    np.testing.assert_array_equal(a, b[np.lexsort(b.T)])


def test_grousered_wheel_geometry():
    r, h, t, k = 0.1, 0.01, 0.005, 10
    mesh = GROUSERED
    assert mesh.is_closed()
    # Lug cross-section: its rectangle minus the circular segment it shares with the rim disc.
    lug = h * t - (r * r * math.asin(t / (2 * r)) - 0.5 * t * math.sqrt(r * r - t * t / 4))
    assert mesh.volume == pytest.approx(0.05 * (math.pi * r * r + k * lug), rel=2e-3)
    radial = np.hypot(mesh.vertices[:, 0], mesh.vertices[:, 2])
    assert radial.max() == pytest.approx(math.hypot(r + h, t / 2), rel=1e-12)
    # First lug points along -z.
    assert mesh.bounds[0, 2] == pytest.approx(-(r + h), rel=1e-12)
    with pytest.raises(InputError, match="grouser_thickness"):
        wheel_grousered(0.1, 0.05, grouser_count=100, grouser_height=0.01, grouser_thickness=0.01)


def test_plate_is_two_sided():
    p = plate(0.2, 0.1, facet_size=0.05)
    assert p.area == pytest.approx(2 * 0.02)
    up = p.normals[:, 2] > 0
    assert up.sum() == (~up).sum() and np.all(np.abs(p.normals[:, 2]) == 1.0)


def test_resample_bounds_edges_and_keeps_the_surface():
    mesh = sphere(0.1, subdivisions=1)
    fine = resample(mesh, 0.02)
    assert fine.edge_lengths().max() <= 0.02
    assert fine.is_closed()
    assert fine.volume == pytest.approx(mesh.volume, rel=1e-12)
    assert fine.area == pytest.approx(mesh.area, rel=1e-12)
    np.testing.assert_allclose((fine.centroids * fine.areas[:, None]).sum(0), 0.0, atol=1e-15)
    # Already fine enough: unchanged.
    assert resample(fine, 0.05).facet_count == fine.facet_count
    b = resample(box(1.0, 0.5, 0.2, facet_size=1.0), 0.1)
    assert b.edge_lengths().max() <= 0.1 and b.is_closed() and b.volume == pytest.approx(0.1)
    with pytest.raises(InputError, match="target_facet_size"):
        resample(mesh, 1e-7)
    with pytest.raises(InputError, match="target_facet_size"):
        resample(mesh, 0.0)


def test_mesh_validation():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0.0]])
    with pytest.raises(InputError, match=r"mesh\.vertices"):
        TriangleMesh(np.zeros((3, 2)), np.array([[0, 1, 2]]))
    with pytest.raises(InputError, match=r"mesh\.faces"):
        TriangleMesh(v, np.array([[0, 1, 3]]))
    with pytest.raises(InputError, match=r"mesh\.faces"):
        TriangleMesh(v, np.array([[0.0, 1.0, 2.0]]))
    with pytest.raises(InputError, match=r"mesh\.vertices"):
        TriangleMesh(np.array([[0, 0, 0], [1, 0, np.nan], [0, 1, 0.0]]), np.array([[0, 1, 2]]))
    m = TriangleMesh(v, np.array([[0, 1, 2]]))
    np.testing.assert_allclose(m.normals, [[0, 0, 1]])
    assert m.areas[0] == 0.5 and not m.is_closed()
    with pytest.raises(ValueError, match="read-only"):
        m.vertices[0, 0] = 1.0
    moved = m.transformed(Pose3D.from_rpy(1.0, 2.0, 3.0, roll=math.pi))
    np.testing.assert_allclose(moved.normals, [[0, 0, -1]], atol=1e-15)
    np.testing.assert_allclose(moved.centroids, [[1 + 1 / 3, 2 - 1 / 3, 3]], atol=1e-15)
    both = m.merged(m.translated([0, 0, 1]))
    assert both.facet_count == 2 and m.scaled(2.0).area == pytest.approx(2.0)


def test_load_mesh_errors_name_the_file(tmp_path):
    missing = tmp_path / "nowhere.stl"
    with pytest.raises(InputError, match=r"nowhere\.stl") as err:
        load_mesh(missing)
    assert "existing" in str(err.value)
    pytest.importorskip("trimesh")
    junk = tmp_path / "junk.stl"
    junk.write_text("this is not a mesh\n")
    with pytest.raises(InputError, match=r"junk\.stl"):
        load_mesh(junk)


def test_load_mesh_without_trimesh(tmp_path, monkeypatch):
    path = tmp_path / "a.stl"
    path.write_text("solid a\nendsolid a\n")
    monkeypatch.setitem(sys.modules, "trimesh", None)
    with pytest.raises(InputError, match=r"terradyn\[mesh\]"):
        load_mesh(path)


def test_stl_round_trip_and_repairs(tmp_path):
    trimesh = pytest.importorskip("trimesh")
    wheel = wheel_cylinder(0.1, 0.05, circumferential_resolution=48, axial_resolution=2)
    path = save_mesh(wheel, tmp_path / "wheel.stl")
    back = load_mesh(path)
    assert back.is_closed() and back.facet_count == wheel.facet_count
    assert back.volume == pytest.approx(wheel.volume, rel=1e-6)
    mm = load_mesh(path, scale=1e-3)
    assert mm.volume == pytest.approx(wheel.volume * 1e-9, rel=1e-6)
    # Inside-out file: repaired to outward normals.
    inverted = trimesh.Trimesh(np.array(wheel.vertices), np.array(wheel.faces)[:, ::-1], process=False)
    inverted.export(str(tmp_path / "inverted.stl"))
    assert load_mesh(tmp_path / "inverted.stl").volume == pytest.approx(wheel.volume, rel=1e-6)
    # Open mesh: refused unless allowed.
    b = box(0.1, 0.1, 0.1, facet_size=0.1)
    keep = b.normals[:, 2] < 0.5  # drop the top face
    trimesh.Trimesh(np.array(b.vertices), np.array(b.faces)[keep]).export(str(tmp_path / "open.stl"))
    with pytest.raises(InputError, match=r"open\.stl.*watertight"):
        load_mesh(tmp_path / "open.stl")
    assert load_mesh(tmp_path / "open.stl", allow_open=True).facet_count == int(keep.sum())


def test_rpy_round_trip_and_pitch_is_the_plane_theta():
    for roll, pitch, yaw in [(0.1, -0.4, 2.0), (-2.0, 1.2, -0.3), (0.0, math.pi / 2, 0.7)]:
        r = rotation_from_rpy(roll, pitch, yaw)
        np.testing.assert_allclose(r @ r.T, np.eye(3), atol=1e-15)
        np.testing.assert_allclose(rotation_from_rpy(*rpy_from_rotation(r)), r, atol=1e-12)
    pose2 = Pose2D(0.3, -0.1, 0.8)
    pts = np.array([[0.1, 0.2], [-0.3, 0.05]])
    pose3 = Pose3D.from_pose2d(pose2)
    got = pose3.to_world(np.column_stack((pts[:, 0], np.zeros(2), pts[:, 1])))
    np.testing.assert_allclose(got[:, [0, 2]], to_world(pts, pose2), atol=1e-15)
    twist2 = Twist2D(0.2, -0.1, 1.7)
    v3 = Twist3D.from_twist2d(twist2).point_velocities(np.column_stack((pts[:, 0], np.zeros(2), pts[:, 1])))
    np.testing.assert_allclose(v3[:, [0, 2]], point_velocities(pts, twist2), atol=1e-15)
    assert np.all(v3[:, 1] == 0.0)


def test_pose_and_wrench_validation():
    with pytest.raises(InputError, match="rotation"):
        Pose3D(np.zeros(3), np.diag([1.0, 1.0, -1.0]))
    with pytest.raises(InputError, match="position"):
        Pose3D(np.array([0.0, np.inf, 0.0]), np.eye(3))
    with pytest.raises(InputError, match="linear"):
        Twist3D(np.zeros(2), np.zeros(3))
    w = Wrench3D(np.array([1.0, 0.0, 2.0]), np.array([0.0, 3.0, 0.0]), np.zeros(3))
    moved = w.moved_to([1.0, 0.0, 0.0])
    np.testing.assert_allclose(moved.moment, [0.0, 3.0 + 2.0, 0.0])
    assert w.to_wrench2d().as_array().tolist() == [1.0, 2.0, 3.0]
    assert w.to_dict()["moment_y_Nm"] == 3.0
