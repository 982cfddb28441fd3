"""3D RFT (Agarwal, Goldman & Kamrin 2023): the pointwise law, the sum over meshes and its kernels."""

import itertools
import math

import numpy as np
import pytest
from scipy import integrate

from terradyn import materials
from terradyn.errors import InputError
from terradyn.geometry3d import (
    Pose3D,
    TriangleMesh,
    Twist3D,
    box,
    cone,
    plate,
    rotation_from_rpy,
    sphere,
    wheel_cylinder,
    wheel_grousered,
)
from terradyn.materials import from_dict
from terradyn.rft.rft3d import (
    AGARWAL2023_TERMS,
    Agarwal2023Fit,
    RFT3DModel,
    agarwal2023_alpha,
    agarwal2023_alpha_local,
    agarwal2023_coefficients,
    agarwal2023_fits,
    agarwal2023_xi,
    agarwal2023_xi_material,
    rft3d_facet_forces,
    rft3d_facet_tractions,
    rft3d_wrench,
    rft3d_wrench_many,
)

MS = materials.get("MS")
XI = 1.0e6
WHEEL = wheel_grousered(
    0.1, 0.06, grouser_count=8, grouser_height=0.012, grouser_thickness=0.006,
    circumferential_resolution=96, axial_resolution=4,
)  # fmt: skip


def _rotation_taking_minus_z_to(n: np.ndarray) -> np.ndarray:
    """A rotation whose third column is -n (so a body normal -z lands on n)."""
    c = -n / np.linalg.norm(n)
    helper = np.array([1.0, 0.0, 0.0]) if abs(c[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    a = np.cross(helper, c)
    a /= np.linalg.norm(a)
    return np.column_stack((a, np.cross(c, a), c))


def test_coefficient_table_shape_and_the_disputed_entry():
    c = agarwal2023_coefficients()
    assert c.shape == (3, 20) and len(AGARWAL2023_TERMS) == 20
    assert AGARWAL2023_TERMS[15] == "x2 x3^2"
    assert c[2, 15] == -0.02730
    alt = agarwal2023_coefficients(Agarwal2023Fit.ALTERNATIVE)
    assert alt[2, 15] == -0.20770
    np.testing.assert_array_equal(np.delete(alt.ravel(), 55), np.delete(c.ravel(), 55))
    with pytest.raises(InputError, match="fit"):
        agarwal2023_coefficients("paper")


def test_horizontal_plate_pushed_down_alpha_z():
    # beta = 0, gamma = pi/2: x1 = x2 = x3 = 1, alpha_z = -(f1 + f2 + f3) = -(sum of all 60 coefficients).
    a_r, a_t, a_z = agarwal2023_alpha_local(0.0, math.pi / 2, 0.0)
    assert a_z == pytest.approx(0.87574, abs=1e-12)
    assert abs(a_r) < 1e-12 and a_t == 0.0
    assert agarwal2023_alpha_local(0.0, math.pi / 2, 0.0, fit="alternative")[2] == pytest.approx(
        1.05614, abs=1e-12
    )
    # The same through a plate mesh at depth d: F_z = xi * 0.87574 * d * area.
    p = plate(0.08, 0.05, facet_size=0.01)
    for depth in (0.02, 0.05):
        w = rft3d_wrench(p, XI, Pose3D.from_rpy(0.0, 0.0, -depth), Twist3D.from_components(vz=-0.3))
        np.testing.assert_allclose(w.force, [0.0, 0.0, XI * 0.87574 * depth * 0.08 * 0.05], atol=1e-9)


def test_media_scaling_of_medium_sand_matches_plate_value():
    xi = agarwal2023_xi_material(MS)
    mu = math.tan(math.radians(34.0))
    assert xi == pytest.approx(1560.0 * 9.81 * (894 * mu**3 - 386 * mu**2 + 89 * mu), rel=1e-12)
    # xi * alpha_z(plate down) against the plane-RFT plate value zeta = 2.02 N/cm^3 of MS: within 6 %.
    assert xi * 0.87574 / MS.zeta == pytest.approx(1.0, abs=0.06)
    assert agarwal2023_xi(1500.0, 0.6, g=1.62) < agarwal2023_xi(1500.0, 0.6)


def test_media_scaling_errors_name_the_field():
    with pytest.raises(InputError, match="friction_coefficient"):
        agarwal2023_xi(1500.0, 0.0)
    with pytest.raises(InputError, match="critical_density"):
        agarwal2023_xi(-1.0, 0.5)
    bare = materials.get("poppy-lp").with_changes(critical_density=None)
    with pytest.raises(InputError, match="critical_density"):
        agarwal2023_xi_material(bare)


@pytest.mark.parametrize(
    ("beta", "gamma", "psi"),
    [(0.0, math.pi / 2, 0.0), (0.4, 0.9, 0.0), (-0.7, 0.3, 0.5), (1.2, -0.4, -1.1), (0.3, -1.2, 1.4),
     (-1.3, 1.5, 0.2), (0.0, 0.05, 0.0), (0.9, 0.0, -0.6)],
)  # fmt: skip
def test_tilted_plate_matches_the_tabulated_fit(beta, gamma, psi):
    # Local frame r = +x, theta = +y: n = (sin b cos psi, sin b sin psi, -cos b), v = (cos g, 0, -sin g).
    n = np.array([math.sin(beta) * math.cos(psi), math.sin(beta) * math.sin(psi), -math.cos(beta)])
    v = np.array([math.cos(gamma), 0.0, -math.sin(gamma)])
    pose = Pose3D(np.array([0.3, -0.2, -0.1]), _rotation_taking_minus_z_to(n))
    p = plate(0.04, 0.03, facet_size=0.01)
    w = rft3d_wrench(p, XI, pose, Twist3D(0.2 * v, np.zeros(3)))
    expected = np.array(agarwal2023_alpha_local(beta, gamma, psi)) * XI * 0.1 * 0.04 * 0.03
    np.testing.assert_allclose(w.force, expected, rtol=1e-9, atol=1e-9)


def test_plate_sliding_in_its_own_plane_has_no_leading_face():
    # n . v = 0 on both faces: the leading-edge rule (strict n . v > 0, as in the plane law) loads neither.
    p = plate(0.04, 0.03, facet_size=0.01)
    w = rft3d_wrench(p, XI, Pose3D.from_rpy(z=-0.1), Twist3D.from_components(vx=0.2))
    assert np.all(w.force == 0.0)
    assert agarwal2023_alpha_local(0.0, 0.0, 0.0)[0] < 0.0  # the fit itself has a drag there


def test_fit_values_against_hand_sums():
    # f_i(1, 1, 1) is the row sum; f_i(0, 0, 0) the constant.
    c = agarwal2023_coefficients()
    f = agarwal2023_fits(1.0, 1.0, 1.0)
    np.testing.assert_allclose(f, c.sum(axis=1), rtol=1e-12)
    np.testing.assert_allclose(agarwal2023_fits(0.0, 0.0, 0.0), c[:, 0], rtol=1e-12)


def test_upward_facets_use_their_plate_normal():
    # Top of a buried box pulled straight up = horizontal plate (normal down) pulled up:
    # x = (-1, 1, -1), alpha_z = -f1 + f2 - f3 (small and downward with the default fit).
    f1, f2, f3 = agarwal2023_fits(-1.0, 1.0, -1.0)
    expected = -f1 + f2 - f3
    assert -0.1 < expected < 0.0
    alpha = agarwal2023_alpha(np.array([[0.0, 0.0, 1.0]]), np.array([[0.0, 0.0, 0.5]]))
    np.testing.assert_allclose(alpha, [[0.0, 0.0, expected]], atol=1e-12)
    b = box(0.04, 0.04, 0.02, facet_size=0.01)
    w = rft3d_wrench(b, XI, Pose3D.from_rpy(0, 0, -0.1), Twist3D.from_components(vz=0.2))
    top_depth = 0.1 - 0.01
    assert w.force[2] == pytest.approx(XI * expected * top_depth * 0.04 * 0.04, rel=1e-9)
    # The alternative coefficient pushes up instead (the evidence against it in the module notes).
    alt = agarwal2023_alpha(np.array([[0.0, 0.0, 1.0]]), np.array([[0.0, 0.0, 0.5]]), fit="alternative")
    assert alt[0, 2] > 0.0


def test_leading_edge_rule_and_its_switch():
    n = np.array([[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]])
    v = np.array([[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    lead = agarwal2023_alpha(n, v)
    assert np.all(lead[1] == 0.0) and np.any(lead[0] != 0.0)
    both = agarwal2023_alpha(n, v, leading_edge=False)
    assert np.any(both[1] != 0.0)
    np.testing.assert_array_equal(both[0], lead[0])


def test_friction_cap():
    rng = np.random.default_rng(3)
    n = rng.normal(size=(200, 3))
    n /= np.linalg.norm(n, axis=1)[:, None]
    v = rng.normal(size=(200, 3))
    free = agarwal2023_alpha(n, v)
    np.testing.assert_array_equal(agarwal2023_alpha(n, v, surface_friction=math.inf), free)
    for mu in (0.0, 0.3):
        capped = agarwal2023_alpha(n, v, surface_friction=mu)
        a_n = np.einsum("ij,ij->i", capped, n)
        tangential = np.linalg.norm(capped - a_n[:, None] * n, axis=1)
        assert np.all(tangential <= mu * np.abs(a_n) + 1e-12)
        np.testing.assert_allclose(a_n, np.einsum("ij,ij->i", free, n), atol=1e-14)
    np.testing.assert_allclose(agarwal2023_alpha(n, v, surface_friction=10.0)[:5], free[:5])


def test_rest_and_degenerate_facets_carry_nothing():
    n = np.array([[0.0, 0.0, -1.0], [0.0, 0.0, 0.0], [0.0, 0.0, -1.0]])
    v = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 0.0, -1.0]])
    for leading in (True, False):
        a = agarwal2023_alpha(n, v, leading_edge=leading)
        assert np.all(a[:2] == 0.0) and np.all(np.isfinite(a)) and a[2, 2] > 0
    # A mesh with a zero-area facet (repeated vertex) next to a real one.
    mesh = TriangleMesh(
        np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0.0]]), np.array([[0, 2, 1], [1, 1, 3]])
    )
    assert mesh.areas[1] == 0.0 and np.all(mesh.normals[1] == 0.0)
    for backend in ("numpy", "numba"):
        w = rft3d_wrench(mesh, XI, Pose3D.from_rpy(z=-0.2), Twist3D.from_components(vz=-1), backend=backend)
        assert np.all(np.isfinite(w.as_array()))
        assert w.force[2] == pytest.approx(XI * 0.87574 * 0.2 * 0.5, rel=1e-12)


def _states():
    yield WHEEL, Pose3D.from_rpy(0.01, 0.0, 0.05, pitch=0.3), Twist3D.from_components(0.1, 0.0, -0.02, wy=1.4)
    yield (
        sphere(0.05, subdivisions=3),
        Pose3D.from_rpy(0, 0, -0.02, roll=0.3, yaw=1.0),
        Twist3D.from_components(0.1, 0.05, -0.1, wx=0.5, wz=-2.0),
    )
    yield (
        box(0.1, 0.06, 0.04),
        Pose3D.from_rpy(0.2, -0.1, -0.03, roll=-0.4, pitch=0.7, yaw=2.0),
        Twist3D.from_components(-0.2, 0.1, 0.05, wx=1.0, wy=-1.0, wz=0.3),
    )


@pytest.mark.parametrize("leading", [True, False])
@pytest.mark.parametrize("friction", [None, 0.4])
@pytest.mark.parametrize("fit", list(Agarwal2023Fit))
def test_numba_kernels_equal_numpy_reference(leading, friction, fit):
    opts = {"leading_edge": leading, "surface_friction": friction, "fit": fit, "about": [0.05, -0.02, 0.1]}
    for mesh, pose, twist in _states():
        ref = rft3d_wrench(mesh, MS, pose, twist, backend="numpy", **opts).as_array()
        scale = np.abs(ref).max()
        assert scale > 0
        for parallel in (False, True):
            got = rft3d_wrench(mesh, MS, pose, twist, parallel=parallel, **opts).as_array()
            np.testing.assert_allclose(got, ref, rtol=1e-9, atol=1e-11 * scale)
        many = rft3d_wrench_many(
            mesh, MS, np.array([pose.position] * 2), np.array([pose.rotation] * 2),
            np.array([twist.linear] * 2), np.array([twist.angular] * 2), about=np.array([opts["about"]] * 2),
            leading_edge=leading, surface_friction=friction, fit=fit,
        )  # fmt: skip
        np.testing.assert_allclose(many, np.vstack([ref, ref]), rtol=1e-9, atol=1e-11 * scale)


def test_facet_tractions_numba_equals_numpy():
    rng = np.random.default_rng(7)
    c = rng.uniform(-0.1, 0.05, size=(500, 3))
    n = rng.normal(size=(500, 3))
    v = rng.normal(size=(500, 3))
    n[:50, 2] = 0.0  # vertical facets
    v[50:100, :2] = 0.0  # vertical motion
    v[100:110] = 0.0  # at rest
    for opts in ({}, {"leading_edge": False, "surface_friction": 0.2}):
        a = rft3d_facet_tractions(c, n, v, xi=XI, surface_level=0.01, backend="numpy", **opts)
        b = rft3d_facet_tractions(c, n, v, xi=XI, surface_level=0.01, **opts)
        np.testing.assert_allclose(b, a, rtol=1e-10, atol=1e-6)
        assert np.all(a[c[:, 2] >= 0.01] == 0.0)


@pytest.mark.parametrize(
    "mesh",
    [WHEEL, wheel_cylinder(0.08, 0.05, circumferential_resolution=64, axial_resolution=3),
     box(0.1, 0.05, 0.04), sphere(0.05, subdivisions=2), cone(0.03, 0.06, circumferential_resolution=24)],
)  # fmt: skip
@pytest.mark.parametrize("leading", [True, False])
def test_mirror_symmetric_body_moving_straight_has_no_side_force_roll_or_yaw(mesh, leading):
    # Symmetric about the x-z plane, moving in it and spinning about y: F_y = M_x = M_z = 0.
    pose = Pose3D.from_rpy(0.0, 0.0, 0.03 if mesh.bounds[0, 2] < -0.05 else -0.03, pitch=0.37)
    twist = Twist3D.from_components(0.12, 0.0, -0.04, wy=1.9)
    for friction in (None, 0.3):
        w = rft3d_wrench(
            mesh, MS, pose, twist, leading_edge=leading, surface_friction=friction, about=[0.0, 0.0, 0.0]
        )
        f = np.abs(w.force).max()
        assert f > 0
        assert abs(w.force[1]) < 1e-12 * f
        assert abs(w.moment[0]) < 1e-12 * f and abs(w.moment[2]) < 1e-12 * f


def test_linear_in_depth():
    p = plate(0.05, 0.05, facet_size=0.01)
    pose = [Pose3D.from_rpy(0.0, 0.0, -d, pitch=0.3, yaw=0.2) for d in (0.02, 0.04, 0.06)]
    twist = Twist3D.from_components(0.1, 0.03, -0.2)
    f = [rft3d_wrench(p, MS, q, twist).force for q in pose]
    np.testing.assert_allclose(f[1], 2 * f[0], rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(f[2], 3 * f[0], rtol=1e-10, atol=1e-12)
    # A fully buried body: F is affine in depth (equivalently in the surface level).
    s = sphere(0.03, subdivisions=2)
    pose0, twist = Pose3D.from_rpy(0.0, 0.0, -0.1), Twist3D.from_components(0.1, 0.0, -0.1, wy=2.0)
    g = [rft3d_wrench(s, MS, pose0, twist, surface_level=h).force for h in (0.0, 0.01, 0.02)]
    np.testing.assert_allclose(g[2] - g[1], g[1] - g[0], rtol=1e-9, atol=1e-12)
    # Half the xi, half the force.
    np.testing.assert_allclose(
        rft3d_wrench(s, 0.5 * XI, pose0, twist).as_array(), 0.5 * rft3d_wrench(s, XI, pose0, twist).as_array()
    )


def test_invariant_to_horizontal_translation_and_yaw():
    pose = Pose3D.from_rpy(0.0, 0.0, 0.04, pitch=0.5, roll=0.1)
    twist = Twist3D.from_components(0.1, 0.02, -0.03, wx=0.2, wy=1.5, wz=-0.4)
    base = rft3d_wrench(WHEEL, MS, pose, twist, about=[0.01, 0.02, 0.0])
    shift = np.array([1.3, -0.7, 0.0])
    moved = rft3d_wrench(
        WHEEL,
        MS,
        Pose3D(pose.position + shift, pose.rotation),
        twist,
        about=np.array([0.01, 0.02, 0.0]) + shift,
    )
    np.testing.assert_allclose(moved.as_array(), base.as_array(), rtol=1e-9, atol=1e-12)
    for yaw in (0.3, math.pi / 2, 2.5):
        rz = rotation_from_rpy(0.0, 0.0, yaw)
        turned = rft3d_wrench(
            WHEEL, MS, Pose3D(rz @ pose.position, rz @ pose.rotation),
            Twist3D(rz @ twist.linear, rz @ twist.angular), about=rz @ np.array([0.01, 0.02, 0.0]),
        )  # fmt: skip
        np.testing.assert_allclose(turned.force, rz @ base.force, rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(turned.moment, rz @ base.moment, rtol=1e-9, atol=1e-10)


def test_buried_sphere_converges_with_facet_size():
    # Sphere of radius R centred at depth 0.12 m pushed straight down; reference by quadrature of the law.
    radius, zc = 0.05, -0.12

    def integrand(theta: float) -> float:
        n = np.array([[math.sin(theta), 0.0, math.cos(theta)]])
        a_z = agarwal2023_alpha(n, np.array([[0.0, 0.0, -1.0]]))[0, 2]
        return a_z * -(zc + radius * math.cos(theta)) * 2.0 * math.pi * radius**2 * math.sin(theta)

    exact = integrate.quad(integrand, math.pi / 2, math.pi, epsabs=1e-14, epsrel=1e-12)[0]
    errors = []
    for level in (2, 3, 4, 5):
        w = rft3d_wrench(
            sphere(radius, subdivisions=level), 1.0, Pose3D.from_rpy(z=zc), Twist3D.from_components(vz=-1)
        )
        errors.append(abs(w.force[2] - exact) / exact)
    assert all(b < a for a, b in itertools.pairwise(errors))
    # Facet size halves per level: at least first order.
    assert math.log2(errors[1] / errors[3]) / 2 > 0.9
    assert errors[-1] < 0.005


def test_facet_forces_sum_to_the_wrench_and_tabulate():
    pose = Pose3D.from_rpy(0.0, 0.0, 0.05, pitch=0.2)
    twist = Twist3D.from_components(0.1, 0.0, 0.0, wy=1.2)
    ff = rft3d_facet_forces(WHEEL, MS, pose, twist)
    np.testing.assert_allclose(ff.forces.sum(axis=0), ff.wrench.force)
    assert ff.active.any() and not ff.active.all()
    assert np.all(ff.tractions[~ff.active] == 0.0)
    assert np.all(np.abs(ff.beta) <= math.pi / 2 + 1e-12) and np.all(np.abs(ff.psi) <= math.pi / 2 + 1e-12)
    df = ff.to_dataframe()
    assert len(df) == WHEEL.facet_count and "force_z_N" in df.columns


def test_model_from_material_with_surface_friction():
    data = {
        "meta": {"name": "sand3d"},
        "density": {"critical_kg_m3": 1500.0},
        "friction": {"internal_friction_angle_deg": 30.0, "surface_friction": 0.3},
    }
    sand = from_dict(data)
    assert sand.surface_friction == 0.3
    model = RFT3DModel.from_material(sand)
    assert model.surface_friction == 0.3 and model.xi == pytest.approx(agarwal2023_xi_material(sand))
    pose, twist = Pose3D.from_rpy(z=0.05, pitch=0.1), Twist3D.from_components(0.1, wy=1.5)
    direct = rft3d_wrench(WHEEL, sand, pose, twist)
    np.testing.assert_allclose(model.wrench(WHEEL, pose, twist).as_array(), direct.as_array())
    uncapped = rft3d_wrench(WHEEL, sand, pose, twist, surface_friction=math.inf)
    assert not np.allclose(uncapped.as_array(), direct.as_array())
    assert model.facet_forces(WHEEL, pose, twist).wrench.force == pytest.approx(direct.force)
    with pytest.raises(InputError, match="surface_friction"):
        from_dict({**data, "friction": {"surface_friction": -1.0}})


def test_input_errors():
    pose, twist = Pose3D.from_rpy(), Twist3D.from_components(vz=-1)
    with pytest.raises(InputError, match="medium"):
        rft3d_wrench(WHEEL, "sand", pose, twist)  # type: ignore[arg-type]
    with pytest.raises(InputError, match="xi"):
        rft3d_wrench(WHEEL, -1.0, pose, twist)
    with pytest.raises(InputError, match="mesh"):
        rft3d_wrench(np.zeros((3, 3)), XI, pose, twist)  # type: ignore[arg-type]
    with pytest.raises(InputError, match="backend"):
        rft3d_wrench(WHEEL, XI, pose, twist, backend="gpu")
    with pytest.raises(InputError, match="rotations"):
        rft3d_wrench_many(
            WHEEL, XI, np.zeros((2, 3)), np.zeros((3, 3, 3)), np.zeros((2, 3)), np.zeros((2, 3))
        )
    with pytest.raises(InputError, match="normals"):
        agarwal2023_alpha(np.zeros((2, 2)), np.zeros((2, 2)))
    with pytest.raises(InputError, match="surface_friction"):
        rft3d_wrench(WHEEL, XI, pose, twist, surface_friction=-0.1)
