"""The 3D wheel path: CAD mesh import (units, axle, centre, checks), slip angle to 90 deg, slip
definitions, prescribed sinkage, the 3D-RFT scale from a plane calibration, and culling."""

from __future__ import annotations

import math

import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.geometry3d import (
    Pose3D,
    TriangleMesh,
    Twist3D,
    box,
    fit_wheel_mesh,
    plate,
    wheel_cylinder,
    wheel_from_mesh,
    wheel_grousered,
)
from terradyn.geometry3d.visibility import _visible_facets_reference, visible_facets
from terradyn.kinematics import slip_convert
from terradyn.locomotion.steady3d import (
    wheel_at_sinkage_3d,
    wheel_contact_directions,
    wheel_contact_mesh,
    wheel_steady_3d,
    xi_from_zeta,
)

R, W = 0.0625, 0.06  # the 125 mm x 60 mm wheel of single-wheel rigs
MS = materials.get("MS")
# file axes of a CAD export with the axle along z: body = ROT_Z @ file
ROT_Z = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])


@pytest.fixture(scope="module")
def wheel():
    return wheel_cylinder(R, W, circumferential_resolution=120, axial_resolution=4, radial_resolution=2)


@pytest.fixture(scope="module")
def lugged():
    return wheel_grousered(
        R, W, grouser_count=5, grouser_height=0.008, grouser_thickness=0.004,
        circumferential_resolution=120, axial_resolution=2, radial_resolution=1,
    )  # fmt: skip


def _cad(mesh: TriangleMesh, offset=(5.0, 7.0, 3.0)) -> TriangleMesh:
    """The mesh as a CAD file would hold it: millimetres, axle along z, origin at a corner + offset."""
    v = (mesh.vertices @ ROT_Z) * 1000.0
    return TriangleMesh(v - v.min(axis=0) + np.asarray(offset), mesh.faces)


def test_mesh_path_recovers_the_primitive_from_its_mm_stl(tmp_path, wheel):
    pytest.importorskip("trimesh")
    from terradyn.geometry3d import load_wheel_mesh, save_mesh

    path = save_mesh(_cad(wheel), tmp_path / "wheel_mm_z.stl")
    placed, fit = load_wheel_mesh(path, units="mm", axle="z")
    assert fit.radius_m == pytest.approx(R, rel=1e-6) and fit.width_m == pytest.approx(W, rel=1e-6)
    ref = wheel_steady_3d(wheel, MS, 20.0, 0.3, slip_angle=math.radians(20.0))
    got = wheel_steady_3d(placed, MS, 20.0, 0.3, slip_angle=math.radians(20.0))
    for key in ("sinkage_m", "drawbar_pull_N", "side_force_N", "drive_torque_Nm", "aligning_moment_Nm"):
        assert getattr(got, key) == pytest.approx(getattr(ref, key), rel=1e-5, abs=1e-9), key
    assert got.nominal_radius_m == pytest.approx(R, rel=1e-6)


def test_centring_is_exact_for_an_odd_lug_count(lugged):
    placed, fit = wheel_from_mesh(_cad(lugged), units="mm", axle="z")
    assert np.max(np.abs(placed.vertices - lugged.vertices)) < 1e-12
    assert fit.roundness == pytest.approx(0.008 / (R + 0.008), rel=0.05)  # grouser tips vs rim


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({}, "mesh_units"),  # millimetres read as metres: a 70 m wheel
        ({"units": "mm"}, "axle"),  # axle along z read as y: not round
        ({"units": "mm", "axle": "x"}, "axle"),
        ({"units": "mm", "axle": "z", "center": (0.0, 0.0, 0.0)}, "center"),  # the corner as axle
        ({"units": "km"}, "mesh_units"),
        ({"units": "mm", "axle": "w"}, "axle"),
    ],
)
def test_implausible_wheels_are_refused_naming_the_flag(wheel, kwargs, field):
    with pytest.raises(InputError) as info:
        wheel_from_mesh(_cad(wheel), **kwargs)
    assert info.value.field == field


def test_tiny_wheel_is_refused_and_a_given_centre_is_used(wheel):
    with pytest.raises(InputError) as info:
        wheel_from_mesh(wheel.scaled(1e-3))  # a 0.06 mm wheel
    assert info.value.field == "mesh_units"
    fit = fit_wheel_mesh(_cad(wheel).scaled(1e-3), axle="z")
    centre = np.array(fit.center_m) * 1e3 + np.array([1.0, 0.0, 0.0])  # 1 mm off the fitted axle
    placed, _ = wheel_from_mesh(_cad(wheel), units="mm", axle="z", center=centre)
    assert placed.vertices[:, 0].max() == pytest.approx(R - 1e-3, abs=1e-9)


def _sideways(mesh, angle_deg, rim=0.05, carriage=0.01):
    return wheel_steady_3d(
        mesh, MS, 20.0, slip_angle=math.radians(angle_deg), rim_speed=rim, carriage_speed=carriage,
        slip_definition="bounded",
    )  # fmt: skip


def test_ninety_degree_slip_angle_mirrors_and_is_the_limit(wheel):
    plus, minus = _sideways(wheel, 90.0), _sideways(wheel, -90.0)
    assert plus.vertical_force_N == pytest.approx(20.0, rel=1e-6)
    assert plus.lateral_velocity_m_s == pytest.approx(0.01) and plus.slip == pytest.approx(1.0)
    # mirror symmetry about the wheel plane: lateral force and moments flip, the rest is equal
    assert minus.side_force_N == pytest.approx(-plus.side_force_N, rel=1e-9)
    assert minus.aligning_moment_Nm == pytest.approx(-plus.aligning_moment_Nm, rel=1e-9)
    assert minus.overturning_moment_Nm == pytest.approx(-plus.overturning_moment_Nm, rel=1e-9)
    for key in ("sinkage_m", "drawbar_pull_N", "drive_torque_Nm"):
        assert getattr(minus, key) == pytest.approx(getattr(plus, key), rel=1e-9)
    # the soil resists the sideways motion: F_y opposes V_y, and carries a real share of the load
    assert plus.side_force_N < -0.1 * 20.0
    # 90 deg is the limit of the angles below it (no jump), and the side force grows towards it
    near = _sideways(wheel, 89.999)
    assert near.side_force_N == pytest.approx(plus.side_force_N, rel=1e-3)
    assert near.sinkage_m == pytest.approx(plus.sinkage_m, rel=1e-3)
    assert abs(_sideways(wheel, 30.0).side_force_N) < abs(plus.side_force_N)


def test_ninety_degrees_with_a_slip_names_slip_angle(wheel):
    with pytest.raises(InputError) as info:
        wheel_steady_3d(wheel, MS, 20.0, 0.3, slip_angle=math.pi / 2)
    assert info.value.field == "slip_angle" and "rim_speed" in str(info.value)
    with pytest.raises(InputError) as info:
        _sideways(wheel, 91.0)
    assert info.value.field == "slip_angle"


def test_3d_locked_wheel_speeds_and_bounded_slip_agree_and_are_continuous(wheel):
    locked = wheel_steady_3d(wheel, MS, 20.0, -1.0, slip_definition="bounded")
    assert locked.omega_rad_s == 0.0 and locked.slip == -1.0 and locked.drawbar_pull_N < 0.0
    by_speed = wheel_steady_3d(wheel, MS, 20.0, rim_speed=0.0, carriage_speed=0.01, slip_definition="bounded")
    assert by_speed.drawbar_pull_N == pytest.approx(locked.drawbar_pull_N, rel=1e-9)
    near = wheel_steady_3d(wheel, MS, 20.0, -0.999, slip_definition="bounded")
    assert near.drawbar_pull_N == pytest.approx(locked.drawbar_pull_N, rel=5e-3)
    classic = wheel_steady_3d(wheel, MS, 20.0, -0.6)
    bounded = wheel_steady_3d(
        wheel, MS, 20.0, slip_convert(-0.6, source="classic", target="bounded"), slip_definition="bounded"
    )
    assert bounded.drawbar_pull_N == pytest.approx(classic.drawbar_pull_N, rel=1e-9)
    with pytest.raises(InputError) as info:
        wheel_steady_3d(wheel, MS, 20.0, rim_speed=0.0, carriage_speed=0.01)  # classic: undefined
    assert info.value.field == "rim_speed"


def test_prescribed_sinkage_returns_the_load_state(wheel, lugged):
    for mesh, phases in ((wheel, 1), (lugged, 5)):
        loaded = wheel_steady_3d(mesh, MS, 20.0, 0.4, slip_angle=0.2, phase_count=phases)
        held = wheel_at_sinkage_3d(mesh, MS, loaded.sinkage_m, 0.4, slip_angle=0.2, phase_count=phases)
        assert held.load_N == pytest.approx(20.0, rel=1e-6)
        assert held.axle_height_m == pytest.approx(loaded.axle_height_m, abs=1e-9)
        for key in ("drawbar_pull_N", "side_force_N", "drive_torque_Nm"):
            assert getattr(held, key) == pytest.approx(getattr(loaded, key), rel=1e-5), key
    with pytest.raises(InputError) as info:
        wheel_at_sinkage_3d(wheel, MS, 0.07, 0.4)  # deeper than the axle at the surface
    assert info.value.field == "sinkage"


def test_prescribed_sinkage_2d():
    from terradyn.geometry import WheelCircular
    from terradyn.locomotion import wheel_steady
    from terradyn.locomotion.prescribed import wheel_at_sinkage

    body = WheelCircular(0.13, 0.16)
    loaded = wheel_steady(body, MS, 130.0, -0.3, slip_definition="bounded")
    held = wheel_at_sinkage(body, MS, loaded.sinkage_m, -0.3, slip_definition="bounded")
    assert held.load_N == pytest.approx(130.0, rel=1e-6)
    assert held.drawbar_pull_N == pytest.approx(loaded.drawbar_pull_N, rel=1e-6)


def test_xi_from_zeta_matches_the_plane_law_on_a_plate_pushed_down():
    from terradyn.geometry import Plate
    from terradyn.kinematics import Pose2D, Twist2D
    from terradyn.rft import RFTModel
    from terradyn.rft.rft3d import rft3d_wrench

    cal = MS.with_zeta(2.0e5)
    length, width, depth = 0.05, 0.02, 0.03
    plane = RFTModel(cal).wrench(Plate(length, width), Pose2D(0.0, -depth, 0.0), Twist2D(0.0, -0.01, 0.0))
    spatial = rft3d_wrench(
        plate(length, width), xi_from_zeta(cal.zeta), Pose3D(np.array([0.0, 0.0, -depth]), np.eye(3)),
        Twist3D(np.array([0.0, 0.0, -0.01]), np.zeros(3)),
    )  # fmt: skip
    assert plane.fz == pytest.approx(2.0e5 * depth * length * width, rel=1e-9)
    assert spatial.force[2] == pytest.approx(plane.fz, rel=1e-9)


def _hubbed(hub_radius):
    hub = wheel_cylinder(
        hub_radius, 0.04, circumferential_resolution=60, axial_resolution=2, radial_resolution=1
    )
    return hub


def test_culling_leaves_a_closed_outer_wheel_unchanged(wheel, lugged):
    for mesh, phases in ((wheel, 1), (lugged, 5)):
        for angle in (0.0, 0.35, math.pi / 2):
            culled = wheel_contact_mesh(mesh, slip_angle=angle)
            kw = {"slip_angle": angle, "phase_count": phases, "rim_speed": 0.05, "carriage_speed": 0.01,
                  "slip_definition": "bounded"}  # fmt: skip
            a = wheel_steady_3d(mesh, MS, 20.0, **kw)
            b = wheel_steady_3d(culled, MS, 20.0, **kw)
            for key in ("sinkage_m", "drawbar_pull_N", "side_force_N", "drive_torque_Nm"):
                assert getattr(b, key) == pytest.approx(getattr(a, key), rel=1e-12, abs=1e-15), (key, angle)


def test_culling_drops_an_enclosed_hub(wheel):
    hub = _hubbed(0.056)  # inside the tyre, but below the surface at this sinkage
    both = wheel.merged(hub)
    alone = wheel_steady_3d(wheel, MS, 60.0, 0.3, slip_angle=0.3)
    assert alone.sinkage_m > R - 0.056
    with_hub = wheel_steady_3d(both, MS, 60.0, 0.3, slip_angle=0.3)
    assert with_hub.sinkage_m < 0.97 * alone.sinkage_m  # the hidden hub carries load without culling
    culled = wheel_contact_mesh(both, slip_angle=0.3)
    assert culled.facet_count <= wheel.facet_count
    got = wheel_steady_3d(culled, MS, 60.0, 0.3, slip_angle=0.3)
    assert got.sinkage_m == pytest.approx(alone.sinkage_m, rel=1e-12)
    assert got.drawbar_pull_N == pytest.approx(alone.drawbar_pull_N, rel=1e-12)


def test_open_rim_hub_is_visible_sideways_only():
    """A hub inside a rim with no side walls is reachable along the axle, not across it."""
    rim_v = wheel_cylinder(R, W, circumferential_resolution=48, axial_resolution=2, radial_resolution=1)
    rim = TriangleMesh(rim_v.vertices, rim_v.faces[np.abs(rim_v.normals[:, 1]) < 0.5])  # tread only
    hub = _hubbed(0.03)
    both = rim.merged(hub)
    hub_faces = np.arange(rim.facet_count, both.facet_count)
    radial = np.abs(both.normals[hub_faces, 1]) < 0.5
    straight = visible_facets(both, wheel_contact_directions(0.0))
    assert not np.any(straight[hub_faces][radial])
    tilted = visible_facets(both, wheel_contact_directions(0.4))
    assert np.any(tilted[hub_faces])


def test_visibility_kernel_matches_the_reference():
    small = wheel_cylinder(0.06, 0.06, circumferential_resolution=16, axial_resolution=1, radial_resolution=1)
    small = small.merged(wheel_cylinder(0.03, 0.04, circumferential_resolution=8, axial_resolution=1))
    for angle in (0.0, 0.3, -1.2):
        d = wheel_contact_directions(angle, count=8)
        np.testing.assert_array_equal(visible_facets(small, d), _visible_facets_reference(small, d))


def test_numpy_stl_reader_matches_trimesh(tmp_path, lugged):
    trimesh = pytest.importorskip("trimesh")
    from terradyn.geometry3d import load_mesh, save_mesh
    from terradyn.geometry3d.mesh import _read_closed_stl

    binary = save_mesh(lugged, tmp_path / "lugged.stl")
    ascii_path = tmp_path / "lugged_ascii.stl"
    ascii_path.write_bytes(
        trimesh.Trimesh(lugged.vertices, lugged.faces, process=False).export(file_type="stl_ascii").encode()
    )
    ref = trimesh.load(str(binary), force="mesh", process=True)
    for path in (binary, ascii_path):
        fast = _read_closed_stl(path)
        assert fast is not None and fast.vertex_count == len(ref.vertices)
        assert fast.volume == pytest.approx(float(ref.volume), rel=1e-6) and fast.volume > 0
        assert load_mesh(path).facet_count == lugged.facet_count
    # reversed winding is flipped outward; an open mesh is left to trimesh (which refuses it)
    flipped = save_mesh(TriangleMesh(lugged.vertices, lugged.faces[:, ::-1]), tmp_path / "flipped.stl")
    assert load_mesh(flipped).volume == pytest.approx(lugged.volume, rel=1e-5)
    open_path = save_mesh(TriangleMesh(lugged.vertices, lugged.faces[1:]), tmp_path / "open.stl")
    assert _read_closed_stl(open_path) is None
    with pytest.raises(InputError):
        load_mesh(open_path)


def test_a_wheel_that_is_not_round_needs_its_axle():
    square = box(0.1, 0.05, 0.1, facet_size=0.005)  # a square "wheel" about body y, 0.1 m across
    assert fit_wheel_mesh(square).roundness == pytest.approx(1.0 - math.sqrt(0.5), abs=0.02)
    coarse = wheel_cylinder(R, W, circumferential_resolution=24, axial_resolution=1, radial_resolution=1)
    assert wheel_from_mesh(coarse)[1].roundness < 0.01  # a 24-gon: sectors without a vertex are skipped
    with pytest.raises(InputError) as info:
        wheel_from_mesh(square.translated((0.3, 0.0, 0.2)))
    assert info.value.field == "axle" and "--center" in str(info.value)
    placed, _ = wheel_from_mesh(square.translated((0.3, 0.0, 0.2)), center=(0.3, 0.0, 0.2))
    np.testing.assert_allclose(placed.vertices, square.vertices, atol=1e-15)
    with pytest.raises(InputError) as info:
        wheel_from_mesh(square.translated((0.3, 0.0, 0.2)), center=(0.3, 0.0, 0.15))  # half a side off
    assert info.value.field == "center"
