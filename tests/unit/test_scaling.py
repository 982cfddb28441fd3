import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.geometry import Plate, WheelCircular
from terradyn.locomotion import wheel_self_propelled, wheel_steady
from terradyn.scaling import ScaleFactors, WheelTest, dimensionless_groups, scale_body, scale_test

CPS = materials.get("CPS")


def test_scale_body_scales_lengths_only():
    w = scale_body(WheelCircular(0.1, 0.05), 2.0)
    assert (w.radius, w.width) == (0.2, 0.1)
    p = scale_body(Plate(0.05, 0.02, thickness=0.001), 3.0)
    assert p.length == pytest.approx(0.15) and p.thickness == pytest.approx(0.003)


@pytest.mark.parametrize(
    "factors",
    [
        ScaleFactors(length=2.0),
        ScaleFactors(gravity=1.62 / 9.81),
        ScaleFactors(length=0.5, gravity=3.71 / 9.81, density=1.3),
    ],
)
def test_scaled_steady_states_are_identical_in_dimensionless_form(factors):
    base = WheelTest(WheelCircular(0.1, 0.05), CPS, mass=3.0, omega=2.0)
    new = scale_test(base, factors)
    assert new.load == pytest.approx(base.load * factors.force)
    a = wheel_steady(base.body, base.material, base.load, 0.3, omega=base.omega)
    b = wheel_steady(new.body, new.material, new.load, 0.3, omega=new.omega)
    assert b.sinkage_m / factors.length == pytest.approx(a.sinkage_m, rel=1e-6)
    assert b.drawbar_pull_N / factors.force == pytest.approx(a.drawbar_pull_N, rel=1e-5)
    assert b.drive_torque_Nm / factors.torque == pytest.approx(a.drive_torque_Nm, rel=1e-5)
    assert b.power_W / factors.power == pytest.approx(a.power_W, rel=1e-5)
    fa = wheel_self_propelled(base.body, base.material, base.load)
    fb = wheel_self_propelled(new.body, new.material, new.load)
    assert fb.slip == pytest.approx(fa.slip, abs=1e-6)


def test_groups_and_errors():
    g = dimensionless_groups(
        length=0.212,
        mass=6 * 638 * 0.212**2 * 0.05,
        gravity=9.81,
        critical_density=638,
        width=0.05,
        omega=6.8,
        velocity=1.44,
    )
    assert g["mass_ratio"] == pytest.approx(6.0)
    assert g["omega_hat"] == pytest.approx(6.8 * (0.212 / 9.81) ** 0.5)
    with pytest.raises(InputError, match="cohesion"):
        scale_test(
            WheelTest(WheelCircular(0.1, 0.05), materials.get("MS"), 3.0, 1.0), ScaleFactors(gravity=0.5)
        )
    with pytest.raises(InputError, match=r"scale\.length"):
        ScaleFactors(length=0)


@pytest.mark.parametrize("factors", [ScaleFactors(length=2.0), ScaleFactors(gravity=1.62 / 9.81)])
def test_scaled_simulations_have_identical_dimensionless_trajectories(factors):
    import numpy as np

    from terradyn.locomotion import simulate_wheel

    base = WheelTest(WheelCircular(0.1, 0.05), CPS, mass=3.0, omega=3.0)
    new = scale_test(base, factors)
    dt = 1e-3
    runs = []
    for test, step in ((base, dt), (new, dt * factors.time)):
        runs.append(
            simulate_wheel(
                test.body,
                test.material,
                mass=test.mass,
                omega=test.omega,
                gravity=test.gravity,
                duration=2.0 * (step / dt),
                dt=step,
                output_every=10,
            )
        )
    a, b = runs
    L = factors.length
    np.testing.assert_allclose(b.t / factors.time, a.t, rtol=1e-9)
    np.testing.assert_allclose(b.x / L, a.x, atol=1e-6 * 0.1)
    np.testing.assert_allclose(b.z / L, a.z, atol=1e-6 * 0.1)
    np.testing.assert_allclose(b.vx / factors.velocity, a.vx, atol=1e-5 * float(np.abs(a.vx).max()))
    np.testing.assert_allclose(b.slip, a.slip, atol=1e-5)
    np.testing.assert_allclose(b.fz / factors.force, a.fz, atol=1e-5 * float(np.abs(a.fz).max()))
