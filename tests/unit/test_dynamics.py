"""Free-body wheel dynamics: steady limit, time-step convergence, energy, initial state, inputs."""

import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.geometry import WheelCircular, WheelGrousered
from terradyn.kinematics import Pose2D
from terradyn.locomotion import wheel_self_propelled, wheel_steady
from terradyn.locomotion.dynamics import WheelDynamicsResult, simulate_wheel, stable_time_step
from terradyn.rft import RFTModel
from terradyn.rft.drft import DRFTModel

MS = materials.get("MS")
WHEEL = WheelCircular(0.13, 0.16)
LOAD = 130.0
MASS = LOAD / 9.81


@pytest.fixture(scope="module")
def steady():
    return wheel_self_propelled(WHEEL, MS, LOAD)


@pytest.fixture(scope="module")
def rolling():
    return simulate_wheel(WHEEL, MS, mass=MASS, omega=5.0, duration=6.0, dt=1e-3, output_every=2)


def test_dynamic_steady_state_matches_self_propelled_solve(rolling, steady):
    s = rolling.steady_summary()
    assert s["revolutions"] >= 2
    assert s["slip"] == pytest.approx(steady.slip, abs=1e-3)
    assert s["sinkage_m"] == pytest.approx(steady.sinkage_m, rel=2e-3)
    assert s["drive_torque_Nm"] == pytest.approx(steady.drive_torque_Nm, rel=3e-3)
    assert s["vertical_force_N"] == pytest.approx(LOAD, rel=1e-3)
    assert abs(s["drawbar_pull_N"]) < 1e-2 * LOAD
    assert rolling.stats["failed_steps"] == 0


def test_drawbar_load_steady_state():
    steady = wheel_self_propelled(WHEEL, MS, LOAD, drawbar_load=15.0)
    r = simulate_wheel(WHEEL, MS, mass=MASS, omega=5.0, duration=5.0, dt=1e-3, drawbar_load=15.0)
    s = r.steady_summary()
    assert s["slip"] == pytest.approx(steady.slip, abs=2e-3)
    assert s["drawbar_pull_N"] == pytest.approx(15.0, abs=0.5)


def test_steady_state_independent_of_initial_velocity_and_ramp(rolling):
    ref = rolling.steady_summary()
    for kwargs in (
        {"initial_velocity": 0.6},
        {"initial_velocity": (0.2, -0.1)},
        {"omega_initial": 0.0, "ramp": 10.0},
    ):
        r = simulate_wheel(WHEEL, MS, mass=MASS, omega=5.0, duration=6.0, dt=1e-3, **kwargs)
        s = r.steady_summary()
        assert s["slip"] == pytest.approx(ref["slip"], abs=1e-3)
        assert s["sinkage_m"] == pytest.approx(ref["sinkage_m"], rel=2e-3)


def test_ramp_and_step_profiles():
    r = simulate_wheel(
        WHEEL, MS, mass=MASS, omega=4.0, omega_initial=1.0, ramp=6.0, step_time=0.2, duration=1.0, dt=1e-3
    )
    expect = np.where(r.t < 0.2, 1.0, np.minimum(4.0, 1.0 + 6.0 * (r.t - 0.2)))
    np.testing.assert_allclose(r.omega[1:], expect[1:], atol=1e-12)
    step = simulate_wheel(
        WHEEL, MS, mass=MASS, omega=3.0, omega_initial=0.5, step_time=0.3, duration=0.5, dt=1e-3
    )
    assert np.all(step.omega[step.t < 0.3 - 1e-9] == 0.5) and np.all(step.omega[step.t > 0.3 + 1e-9] == 3.0)


def test_torque_driven_wheel_reaches_the_steady_slip_of_that_torque_and_load():
    # With RFT a steady state under a torque needs the matching drawbar load (rate independence
    # leaves the speed free); the slip and sinkage are those of the quasi-static solve.
    target = wheel_self_propelled(WHEEL, MS, LOAD, drawbar_load=20.0)
    r = simulate_wheel(
        WHEEL,
        MS,
        mass=MASS,
        inertia=0.05,
        torque=target.drive_torque_Nm,
        omega_initial=4.0,
        drawbar_load=20.0,
        duration=4.0,
        dt=1e-3,
    )
    s = r.steady_summary()
    assert np.all(r.torque == target.drive_torque_Nm)
    assert s["slip"] == pytest.approx(target.slip, abs=0.01)
    assert s["sinkage_m"] == pytest.approx(target.sinkage_m, rel=0.01)
    free = wheel_steady(WHEEL, MS, LOAD, 0.3)
    assert free.drive_torque_Nm > 0


def _drop(dt):
    return simulate_wheel(
        WHEEL,
        MS,
        mass=MASS,
        omega=0.0,
        duration=0.4,
        dt=dt,
        initial_pose=Pose2D(0.0, 0.14, 0.0),
        initial_velocity=(0.0, -0.5),
    )


def test_energy_balance_of_a_dropped_wheel():
    errors = []
    for dt in (1e-3, 5e-4, 2.5e-4):
        r = _drop(dt)
        assert r.stats["stuck_steps"] > 0 and abs(r.vz[-1]) == 0.0  # settled
        assert r.fz[-1] == pytest.approx(LOAD, rel=1e-9)
        energy = 0.5 * MASS * (r.vx**2 + r.vz**2) + MASS * 9.81 * r.z
        power = r.fx * r.vx + r.fz * r.vz
        work = float(np.sum(0.5 * (power[1:] + power[:-1]) * np.diff(r.t)))  # trapezoid of F . v
        loss = energy[-1] - energy[0]
        assert loss < 0
        errors.append(abs(work - loss) / abs(loss))
        # bookkeeping: backward Euler dissipates exactly (m/2)|dv|^2 per step
        dissipated = 0.5 * MASS * np.sum(np.diff(r.vx) ** 2 + np.diff(r.vz) ** 2)
        assert r.soil_work[-1] - loss == pytest.approx(dissipated, rel=2e-3)
    assert errors[-1] < 0.01
    assert 1.6 < errors[0] / errors[1] < 2.5 and 1.6 < errors[1] / errors[2] < 2.5  # first order


def test_time_step_convergence_is_first_order():
    sink = [_drop(dt).sinkage[-1] for dt in (1e-3, 5e-4, 2.5e-4)]
    d1, d2 = sink[1] - sink[0], sink[2] - sink[1]
    assert d1 > 0 and d2 > 0
    assert 1.6 < d1 / d2 < 2.5
    assert abs(d2) / sink[2] < 0.01


def test_grousered_wheel_dynamics_rft_and_drft():
    wheel = WheelGrousered(0.1, 0.05, 15, 0.006, 0.004)
    elements = wheel.discretize_counts(14, 8)
    poppy = materials.get("poppy-cp")
    common = dict(mass=4.0, omega=3.0, duration=3.0, elements=elements)
    rft = simulate_wheel(wheel, poppy, model="rft", **common).steady_summary()
    drft_lo = simulate_wheel(wheel, poppy, model=DRFTModel(poppy), **common).steady_summary()
    assert 0 < rft["slip"] < 1 and rft["sinkage_m"] > 0
    assert drft_lo["slip"] >= rft["slip"] - 0.01
    fast = simulate_wheel(wheel, poppy, model="drft", **{**common, "omega": 12.0, "duration": 2.0})
    assert fast.steady_summary()["slip"] > drft_lo["slip"] + 0.05
    assert fast.model == "drft" and fast.metadata["structural_correction"]


def test_outputs(tmp_path, rolling):
    assert isinstance(rolling, WheelDynamicsResult)
    df = rolling.to_dataframe()
    for col in (
        "time_s",
        "x_m",
        "z_m",
        "theta_rad",
        "vx_m_s",
        "vz_m_s",
        "omega_rad_s",
        "force_x_N",
        "force_z_N",
        "drive_torque_Nm",
        "slip",
        "sinkage_m",
        "power_W",
    ):
        assert col in df.columns
    assert len(df) == len(rolling) == 3001
    np.testing.assert_allclose(rolling.power, rolling.torque * rolling.omega)
    ds = rolling.to_xarray()
    assert ds["sinkage_m"].shape == (3001,)
    path = rolling.save(tmp_path / "run.nc")
    import xarray as xr

    with xr.open_dataset(path, engine=rolling.netcdf_engine()) as back:
        np.testing.assert_allclose(back["slip"].values, rolling.slip)
    rolling.save(tmp_path / "run.csv")
    with pytest.raises(InputError):
        rolling.save(tmp_path / "run.txt")
    with pytest.raises(dataclasses_frozen_error()):
        rolling.mass = 3.0


def dataclasses_frozen_error():
    import dataclasses

    return dataclasses.FrozenInstanceError


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"dt": 0.0}, "dt"),
        ({"dt": -1e-3}, "dt"),
        ({"dt": 0.5}, "dt"),
        ({"mass": -1.0}, "mass"),
        ({"mass": 0.0}, "mass"),
        ({"inertia": -0.1}, "inertia"),
        ({"duration": 0.0}, "duration"),
        ({"omega": None}, "omega/torque"),
        ({"torque": 2.0}, "omega/torque"),
        ({"model": "mpm"}, "model"),
        ({"model": RFTModel(materials.get("CPS"))}, "model"),
        ({"ramp": -1.0}, "ramp"),
        ({"output_every": 0}, "output_every"),
        ({"gravity": 0.0}, "gravity"),
        ({"tolerance": 0.1}, "tolerance"),
        ({"initial_velocity": (1.0, 2.0, 3.0)}, "initial_velocity"),
    ],
)
def test_bad_input(kwargs, field):
    args = {"mass": MASS, "omega": 2.0, "duration": 0.1, "dt": 1e-3, **kwargs}
    with pytest.raises(InputError) as exc:
        simulate_wheel(WHEEL, MS, **args)
    assert exc.value.field == field


def test_stable_time_step_limits():
    base = stable_time_step(WHEEL, MS, mass=MASS, omega_max=0.0)
    k_max = MS.zeta * 0.16 * 0.26
    assert base == pytest.approx(np.sqrt(MASS / k_max))
    # 360 rim facets: at most half a facet per step
    assert stable_time_step(WHEEL, MS, mass=MASS, omega_max=5.0) == pytest.approx(2 * np.pi / 360 / 2 / 5.0)
    grousered = WheelGrousered(0.1, 0.05, 15, 0.006, 0.004)
    coarse = grousered.discretize_counts(2, 1)  # facets larger than the pitch / 4: the pitch governs
    fast = stable_time_step(grousered, MS, mass=MASS, omega_max=20.0, elements=coarse)
    assert fast == pytest.approx(2 * np.pi / 15 / 8 / 20.0)


def test_compiled_steps_satisfy_backward_euler_with_the_numpy_force_law():
    # Independent check of the compiled loop: recompute the soil wrench of every sampled state with the
    # NumPy DRFT reference and verify q' = q + dt u' and M (u' - u) / dt = F(q', u') + G.
    poppy = materials.get("poppy-cp")
    wheel = WheelGrousered(0.1, 0.05, 15, 0.006, 0.004)
    model = DRFTModel(poppy)
    dt, mass = 5e-4, 4.0
    r = simulate_wheel(wheel, poppy, model=model, mass=mass, omega=8.0, duration=0.4, dt=dt, drawbar_load=2.0)
    np.testing.assert_allclose(np.diff(r.x), dt * r.vx[1:], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(np.diff(r.z), dt * r.vz[1:], rtol=1e-12, atol=1e-15)
    from terradyn.kinematics import Twist2D
    from terradyn.rft.drft import drft_wrench

    mg = mass * 9.81
    residuals = []
    matched = []
    for k in range(1, len(r), 3):
        w = drft_wrench(
            wheel,
            model,
            Pose2D(r.x[k], r.z[k], r.theta[k]),
            Twist2D(r.vx[k], r.vz[k], r.omega[k]),
            backend="numpy",
            leading_band=0.01,
        )
        # (an element entering at zero depth can move the split of the structural correction: rare)
        matched.append(
            np.allclose(
                [w.fx, w.fz, w.torque_y], [r.fx[k], r.fz[k], r.soil_torque[k]], rtol=1e-9, atol=1e-9 * mg
            )
        )
        res_x = mass * (r.vx[k] - r.vx[k - 1]) / dt - (w.fx - 2.0)
        res_z = mass * (r.vz[k] - r.vz[k - 1]) / dt - (w.fz - mg)
        residuals.append(max(abs(res_x), abs(res_z)) / mg)
    residuals = np.array(residuals)
    assert np.mean(matched) > 0.98
    assert np.mean(residuals < 2e-5) > 0.98
    assert residuals.max() < 0.05


def test_low_spin_steady_state_matches_self_propelled_solve():
    # At low spin the wheel follows the quasi-static path phase by phase; the 1-degree facets of the
    # default rim make it bob (+1.6 % slip), so use 4x finer elements, as a convergence check would.
    size = WHEEL.default_element_size / 4
    steady = wheel_self_propelled(WHEEL, RFTModel(MS, element_size=size), LOAD)
    r = simulate_wheel(
        WHEEL, MS, mass=MASS, omega=1.0, duration=25.0, dt=2e-3, element_size=size, output_every=5
    )
    s = r.steady_summary()
    assert s["slip"] == pytest.approx(steady.slip, abs=2e-4)
    assert s["sinkage_m"] == pytest.approx(steady.sinkage_m, rel=5e-4)
    assert s["drive_torque_Nm"] == pytest.approx(steady.drive_torque_Nm, rel=5e-4)


@pytest.mark.parametrize("omega", [2.0, 5.0])
def test_drft_dynamic_steady_state_matches_quasi_static_drft_solve(omega):
    # For a circular wheel the DRFT terms depend on omega and on the axle velocity only, so the
    # quasi-static self-propelled solve with the DRFT model is the steady state of the dynamics (up to
    # the smoothing of the structural split used for time stepping: ~0.5 % in sinkage).
    steady = wheel_self_propelled(WHEEL, DRFTModel(MS), LOAD, omega=omega)
    r = simulate_wheel(WHEEL, MS, model="drft", mass=MASS, omega=omega, duration=max(6.0, 60.0 / omega))
    s = r.steady_summary()
    assert s["slip"] == pytest.approx(steady.slip, abs=2e-3)
    assert s["sinkage_m"] == pytest.approx(steady.sinkage_m, rel=1e-2)
    assert s["drive_torque_Nm"] == pytest.approx(steady.drive_torque_Nm, rel=1e-2)
    assert steady.slip > wheel_self_propelled(WHEEL, MS, LOAD).slip + 0.05
