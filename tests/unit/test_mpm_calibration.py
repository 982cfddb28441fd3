"""Fitting the MPM friction coefficient to plate force-depth data."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError, SolverError
from terradyn.rft.calibration import PlateData
from terradyn.studies.mpm_calibration import fit_mpm_friction, poisson_ratio_for_stability


def _data(depths, forces, angle=0.0, direction=90.0):
    n = len(depths)
    return PlateData(np.asarray(depths, float), np.asarray(forces, float), None, np.full(n, angle),
                     np.full(n, direction))  # fmt: skip


class _Model:
    """A stand-in for run_intrusion: F = c mu^2.4 depth (monotone in mu, like a bearing factor)."""

    def __init__(self, c=3000.0):
        self.c = c
        self.calls = []

    def __call__(self, body, material, *, depth, friction_coefficient, poisson_ratio, **kw):
        self.calls.append((friction_coefficient, poisson_ratio))
        d = np.linspace(0.0, depth * 1.2, 60)
        f = self.c * friction_coefficient**2.4 * d
        import pandas as pd

        return SimpleNamespace(to_dataframe=lambda: pd.DataFrame({"depth_m": d, "force_z_N": f}))


@pytest.mark.parametrize("mu_true", [0.5, 0.7, 1.1])
def test_fit_recovers_the_friction_of_a_monotone_model(mu_true):
    model = _Model()
    depths = [0.01, 0.02, 0.03, 0.04]
    data = _data(depths, [model.c * mu_true**2.4 * d for d in depths])
    fit = fit_mpm_friction(data, materials.get("MS"), plate_length=0.04, plate_width=0.02, run=model,
                           tolerance=1e-4)  # fmt: skip
    assert fit.converged
    assert fit.friction_coefficient == pytest.approx(mu_true, rel=1e-3)
    assert fit.r_squared > 0.999999
    assert len(fit.trials) <= 8
    assert fit.material.continuum.friction_coefficient == fit.friction_coefficient
    assert fit.material.continuum.friction_coefficient_2 >= fit.friction_coefficient
    assert fit.friction_angle == pytest.approx(math.asin(min(mu_true, 1.0)), rel=1e-3)


def test_weak_medium_raises_poisson_ratio_to_keep_the_bed_stable():
    model = _Model()
    data = _data([0.02, 0.04], [model.c * 0.3**2.4 * d for d in (0.02, 0.04)])
    fit = fit_mpm_friction(data, materials.get("MS"), plate_length=0.04, plate_width=0.02, run=model,
                           tolerance=1e-4)  # fmt: skip
    assert fit.friction_coefficient == pytest.approx(0.3, rel=1e-3)
    nu = fit.poisson_ratio
    assert nu > materials.get("MS").continuum.poisson_ratio
    assert math.sqrt(3) * (1 - 2 * nu) / (1 + nu) == pytest.approx(0.3 / 1.05, rel=1e-9)
    assert poisson_ratio_for_stability(0.3) == pytest.approx(nu)


def test_unreachable_data_and_bad_input_are_clear():
    model = _Model()
    data = _data([0.02], [1e9])
    with pytest.raises(SolverError, match="no mu_s"):
        fit_mpm_friction(data, materials.get("MS"), plate_length=0.04, plate_width=0.02, run=model)
    with pytest.raises(InputError, match="depth"):
        fit_mpm_friction(_data([-0.01], [1.0]), materials.get("MS"), plate_length=0.04, plate_width=0.02,
                         run=model)  # fmt: skip
    with pytest.raises(InputError, match="plate_length"):
        fit_mpm_friction(_data([0.01], [1.0]), materials.get("MS"), plate_length=0.0, plate_width=0.02,
                         run=model)  # fmt: skip


def test_each_orientation_is_one_run_per_trial():
    model = _Model()
    d = np.array([0.02, 0.04, 0.02, 0.04])
    data = PlateData(d, model.c * 0.6**2.4 * d, None, np.array([0.0, 0.0, 30.0, 30.0]), np.full(4, 90.0))
    fit = fit_mpm_friction(data, materials.get("MS"), plate_length=0.04, plate_width=0.02, run=model,
                           tolerance=1e-4)  # fmt: skip
    assert len(model.calls) == 2 * len(fit.trials)


@pytest.mark.slow
def test_fit_recovers_the_friction_of_mpm_generated_data():
    """Data made by MPM at mu_s = 0.65 (coarse bed); the fit starts from MS's 0.559 and finds 0.65."""
    from terradyn.geometry import Plate
    from terradyn.mpm import run_intrusion

    ms = materials.get("MS")
    res = run_intrusion(Plate(0.06, 0.02), ms, depth=0.04, cell_size=0.01, friction_coefficient=0.65)
    df = res.to_dataframe()
    depths = np.array([0.015, 0.02, 0.025, 0.03, 0.035, 0.04])
    forces = np.interp(depths, df["depth_m"].to_numpy(), df["force_z_N"].to_numpy())
    fit = fit_mpm_friction(_data(depths, forces), ms, plate_length=0.06, plate_width=0.02, cell_size=0.01,
                           tolerance=0.005)  # fmt: skip
    assert fit.converged
    assert fit.friction_coefficient == pytest.approx(0.65, rel=0.03)
