"""High-speed grousered wheel on poppy seeds (thesis ch. 8): slip onset with dynamic RFT."""

import math

import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.studies.high_speed import (
    HighSpeedWheel,
    high_speed_initial_conditions,
    high_speed_onset_sensitivity,
    high_speed_sweep,
    slip_onset,
)


@pytest.fixture(scope="module")
def reduced():
    return high_speed_sweep(reduced=True)


def test_reduced_sweep_shows_the_slip_rise_with_drft_only(reduced):
    df = reduced.table.to_dataframe()
    rft, drft = df[df.model == "rft"], df[df.model == "drft"]
    assert len(rft) == len(drft) == 6
    # quasi-static RFT: slip independent of omega until body inertia matters (omega sqrt(l/g) > 1.5)
    low = rft[rft.omega_normalised <= 1.1]
    assert np.ptp(low.slip) < 0.01
    assert reduced.onsets["rft"]["omega_onset_rad_s"] is None
    # DRFT: the low-speed limit is RFT, then slip and sinkage rise and the speed plateaus
    assert drft.slip.iloc[0] == pytest.approx(rft.slip.iloc[0], abs=0.01)
    assert np.all(np.diff(drft.slip) > 0) and np.all(np.diff(drft.sinkage_m) > 0)
    assert drft.slip.iloc[-1] > drft.slip.iloc[0] + 0.2
    v, w = drft.velocity_normalised.to_numpy(), drft.omega_normalised.to_numpy()
    low_slope = (v[2] - v[0]) / (w[2] - w[0])
    high_slope = (v[-1] - v[-3]) / (w[-1] - w[-3])
    assert high_slope < 0.5 * low_slope  # V / sqrt(g l) levels off at high spin
    on = reduced.onset
    assert set(on) >= {"omega_onset_rad_s", "omega_onset_normalised"}
    assert 0.3 < on["omega_onset_normalised"] < 1.0
    assert on["omega_onset_rad_s"] == pytest.approx(on["omega_onset_normalised"] * math.sqrt(9.81 / 0.212))
    assert on["froude_onset"] == pytest.approx(0.5 * on["omega_onset_normalised"] ** 2)
    assert reduced.table.metadata["onsets"]["drft"] == on


def test_onset_is_invariant_under_gravity_scaling():
    # zeta ~ rho_c g: at the same mass, the dimensionless onset does not move, omega_c ~ sqrt(g)
    hat = [0.15, 0.5, 0.8, 1.1]
    table = high_speed_onset_sensitivity(variations={"gravity": (3.71,)}, omega_normalised=hat, reduced=True)
    df = table.to_dataframe()
    ref, moon = df.iloc[0], df.iloc[1]
    assert moon.omega_onset_normalised == pytest.approx(ref.omega_onset_normalised, rel=1e-3)
    assert moon.omega_onset_rad_s == pytest.approx(ref.omega_onset_rad_s * math.sqrt(3.71 / 9.81), rel=1e-3)
    assert moon.low_speed_slip == pytest.approx(ref.low_speed_slip, abs=1e-3)


def test_slip_onset_definition():
    w = np.array([1.0, 2.0, 3.0, 4.0])
    on = slip_onset(
        w, [0.2, 0.21, 0.3, 0.5], [0.05, 0.05, 0.06, 0.07], outer_diameter=0.2, gravity=10.0, slip_margin=0.05
    )
    assert on["omega_onset_rad_s"] == pytest.approx(2.0 + 0.04 / 0.09)
    assert on["omega_steepest_rad_s"] == pytest.approx(3.5)
    assert on["drop_to_sinkage_onset"] == pytest.approx(0.1**2 * on["omega_onset_rad_s"] ** 2 / (10 * 0.05))
    flat = slip_onset(w, [0.2] * 4, [0.05] * 4, outer_diameter=0.2)
    assert flat["omega_onset_rad_s"] is None and flat["omega_steepest_rad_s"] is None
    with pytest.raises(InputError):
        slip_onset([2.0, 1.0], [0.1, 0.2], [0.1, 0.1], outer_diameter=0.2)


def test_bad_inputs():
    no_density = materials.get("MS").with_changes(critical_density=None)
    for kwargs, field in (
        ({"models": ("mpm",)}, "models"),
        ({"omegas": [3.0, 1.0]}, "omegas"),
        ({"gravity": -1.0}, "gravity"),
        ({"material": no_density}, "material"),
    ):
        with pytest.raises(InputError) as exc:
            high_speed_sweep(reduced=True, **kwargs)
        assert exc.value.field == field
    with pytest.raises(InputError) as exc:
        HighSpeedWheel(grouser_count=0)
    assert exc.value.field == "grouser_count"
    with pytest.raises(InputError):
        high_speed_onset_sensitivity(variations={"friction": (1.0,)})


@pytest.mark.slow
def test_full_high_speed_study():
    full = high_speed_sweep()
    on = full.onset
    assert 0.3 < on["omega_onset_normalised"] < 1.0
    sens = high_speed_onset_sensitivity().to_dataframe().set_index(["parameter", "value"])
    ref = sens.iloc[0]
    # heavier wheel: deeper, so a larger spin is needed before the surface drop matters
    assert sens.loc[("mass_ratio", 12.0)].omega_onset_normalised > ref.omega_onset_normalised
    assert sens.loc[("mass_ratio", 3.0)].omega_onset_normalised < ref.omega_onset_normalised
    # the structural drop at onset scales with the low-speed sinkage (within a factor 2)
    ratios = sens.drop_to_sinkage_onset.to_numpy()
    assert np.all(ratios > 0) and ratios.max() / ratios.min() < 2.0
    ic = high_speed_initial_conditions().to_dataframe()
    for _, group in ic.groupby("omega_normalised"):
        assert np.ptp(group.slip) < 0.01
