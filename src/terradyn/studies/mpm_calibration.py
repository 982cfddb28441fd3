"""Calibrate the MPM continuum to a user's plate test: the friction coefficient from force-depth data.

A plate pushed into a cohesionless bed resists in proportion to the bed's shear strength: at fixed
geometry and density the force-depth curve of the Dunatunga-Kamrin continuum rises monotonically with
the internal friction coefficient mu_s, and the softened Young's modulus changes it little (docs/mpm.md).
So one plate test fixes mu_s. :func:`fit_mpm_friction` runs the same intrusion in MPM at trial values
of mu_s and solves ``k(mu_s) = 1`` for the least-squares scale between data and model,

    k = sum(F_data F_mpm) / sum(F_mpm^2),

by the Illinois variant of regula falsi in ln mu_s (k rises with mu_s). The data are the CSV of
``terradyn calibrate rft`` (depth_m, force_z_N [, force_x_N, angle_deg, direction_deg]); each distinct
(angle, direction) is one MPM run per trial. A bed at rest stays elastic only above
mu_s = sqrt(3)(1 - 2 nu)/(1 + nu): a fit that needs less raises the Poisson ratio to keep that margin,
and says so.

What a plate test cannot fix: the body-grain friction (needs a shear or drag test with force_x), the
rate dependence mu(I) (needs several speeds) and the stiffness (quasi-static forces barely depend on
it); those stay at the base medium's values.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import InputError, SolverError, check_length, check_positive
from ..materials import Material

if TYPE_CHECKING:
    from ..geometry import Plate
    from ..mpm.specs import Bed, Resolution

__all__ = ["MPMFrictionFit", "fit_mpm_friction", "poisson_ratio_for_stability"]

#: a fitted mu_s keeps this factor above the bed-stability limit
STABILITY_MARGIN = 1.05


def poisson_ratio_for_stability(friction_coefficient: float, margin: float = STABILITY_MARGIN) -> float:
    """The Poisson ratio nu at which sqrt(3)(1 - 2 nu)/(1 + nu) = mu_s / margin (a resting bed is then
    elastic with that margin)."""
    r = check_positive("friction_coefficient", friction_coefficient) / margin
    return max(0.0, (math.sqrt(3.0) - r) / (2.0 * math.sqrt(3.0) + r))


@dataclass(frozen=True)
class MPMFrictionFit:
    """Result of :func:`fit_mpm_friction`.

    ``friction_coefficient`` mu_s [-] and the plane-strain friction angle asin(mu_s) [rad] it stands
    for; ``poisson_ratio`` used (raised only if the stability margin required it); ``scale`` the final
    least-squares data/model scale (1 at an exact fit); ``rms_residual_N`` [N] and ``r_squared`` of the
    fitted curve; ``trials`` (mu_s, scale) of every MPM evaluation; ``material`` the base medium with
    the fitted continuum; ``cell_size`` [m] of the runs."""

    friction_coefficient: float
    friction_angle: float
    poisson_ratio: float
    scale: float
    rms_residual_N: float
    r_squared: float
    trials: tuple[tuple[float, float], ...]
    material: Material
    cell_size: float | None
    converged: bool
    #: the MPM force [N] at the fitted mu_s at each data row (not scaled by ``scale``)
    predicted_force_z_N: np.ndarray | None = None

    def record(self) -> dict[str, Any]:
        return {
            "friction_coefficient": self.friction_coefficient,
            "friction_angle_deg": math.degrees(self.friction_angle),
            "poisson_ratio": self.poisson_ratio,
            "scale_data_over_model": self.scale,
            "rms_residual_N": self.rms_residual_N,
            "r_squared": self.r_squared,
            "mpm_trials": len(self.trials),
            "cell_size_m": self.cell_size,
            "converged": self.converged,
        }


def _groups(data: Any) -> list[tuple[float, float, np.ndarray]]:
    """(angle [rad], direction [rad], row indices) of each distinct plate orientation and motion."""
    angle = np.radians(np.asarray(data.angle_deg, dtype=float))
    direction = np.radians(np.asarray(data.direction_deg, dtype=float))
    keys = sorted({(round(a, 9), round(d, 9)) for a, d in zip(angle, direction, strict=True)})
    return [
        (a, d, np.flatnonzero((np.round(angle, 9) == a) & (np.round(direction, 9) == d))) for a, d in keys
    ]


@dataclass(frozen=True)
class _PlateRun:
    """The MPM plate test the fit repeats: ``run`` (:func:`terradyn.mpm.run_intrusion` or a stand-in),
    the plate, the base medium, ``speed`` [m/s] and the bed and resolution specs."""

    run: Callable[..., Any]
    plate: Plate
    material: Material
    speed: float
    bed: Bed
    resolution: Resolution


@dataclass(eq=False)
class _ScaleAt:
    """k(mu_s), the least-squares data/model scale of the plate ``force`` [N] at ``depth`` [m] (rows
    grouped by orientation, :func:`_groups`); keeps every (mu_s, k) in ``trials``."""

    plate_run: _PlateRun
    depth: np.ndarray
    force: np.ndarray
    groups: list[tuple[float, float, np.ndarray]]
    max_trials: int
    progress: Callable[[int, int], None] | None
    trials: list[tuple[float, float]] = field(default_factory=list)

    def predicted(self, mu: float) -> np.ndarray:
        """The MPM force [N] at each data row at friction ``mu``: one run per orientation, interpolated
        to the data's depths (the Poisson ratio raised if stability needs it)."""
        p, depth = self.plate_run, self.depth
        base = p.material.continuum
        assert base is not None
        nu = max(base.poisson_ratio, poisson_ratio_for_stability(mu))
        predicted = np.zeros_like(self.force)
        for angle, direction, rows in self.groups:
            res = p.run(
                p.plate, p.material, depth=float(depth[rows].max()), angle=angle, direction=direction,
                speed=p.speed, bed=p.bed, resolution=p.resolution, friction_coefficient=mu, poisson_ratio=nu,
            )  # fmt: skip
            df = res.to_dataframe()
            order = np.argsort(df["depth_m"].to_numpy())
            d_run = df["depth_m"].to_numpy()[order]
            f_run = df["force_z_N"].to_numpy()[order]
            if depth[rows].max() > d_run.max() + 1e-9:
                raise SolverError(
                    f"the MPM run reached {d_run.max():.4g} m, short of the data's {depth[rows].max():.4g} m"
                )
            predicted[rows] = np.interp(depth[rows], d_run, f_run)
        return predicted

    def __call__(self, mu: float) -> tuple[np.ndarray, float]:
        """The predicted forces [N] at ``mu`` and their scale k (a trial, reported to ``progress``)."""
        predicted = self.predicted(mu)
        denom = float(predicted @ predicted)
        if denom <= 0:
            raise SolverError(f"the MPM plate carries no force at mu_s = {mu:.4g}")
        k = float(self.force @ predicted) / denom
        self.trials.append((mu, k))
        if self.progress is not None:
            self.progress(len(self.trials), self.max_trials)
        return predicted, k


def _solve_unit_scale(
    model_at: _ScaleAt, mu0: float, bounds: tuple[float, float], tolerance: float
) -> tuple[float, np.ndarray, float, bool]:
    """mu_s with k(mu_s) = 1 within ``tolerance``, starting at ``mu0`` in ``bounds``: bracket, then
    Illinois regula falsi in ln mu_s. Returns mu_s, its predicted forces [N], k and convergence."""
    low, high = bounds
    max_trials, trials = model_at.max_trials, model_at.trials
    best_mu, (best_pred, best_k) = mu0, model_at(mu0)
    converged = abs(best_k - 1.0) <= tolerance
    if converged:
        return best_mu, best_pred, best_k, converged
    # bracket: k rises with mu_s; step by the data/model ratio (force roughly ~ mu_s^2)
    a, ka = mu0, best_k
    b = min(max(mu0 * best_k**0.5, low), high)
    pb, kb = model_at(b)
    while (ka - 1.0) * (kb - 1.0) > 0 and len(trials) < max_trials:
        if b in (low, high):
            raise SolverError(
                f"no mu_s in [{low:g}, {high:g}] fits the data: the data/model scale is {kb:.3g} "
                f"at mu_s = {b:.4g}"
            )
        a, ka = b, kb
        b = min(max(b * kb**0.5, low), high)
        pb, kb = model_at(b)
    best_mu, best_pred, best_k = b, pb, kb
    ga, gb = math.log(ka), math.log(kb)
    la, lb = math.log(a), math.log(b)
    while abs(best_k - 1.0) > tolerance and len(trials) < max_trials:
        lc = lb - gb * (lb - la) / (gb - ga)
        pc, kc = model_at(math.exp(lc))
        gc = math.log(kc)
        best_mu, best_pred, best_k = math.exp(lc), pc, kc
        if gc * gb < 0:
            la, ga = lb, gb
        else:
            ga *= 0.5  # Illinois: halve the value at the end that stays
        lb, gb = lc, gc
    return best_mu, best_pred, best_k, abs(best_k - 1.0) <= tolerance


def _fitted_medium(material: Material, mu: float) -> Material:
    """``material`` with continuum friction ``mu`` (mu_2 keeps its step above mu_s) and the Poisson
    ratio the bed's stability needs."""
    base = material.continuum
    assert base is not None
    nu = max(base.poisson_ratio, poisson_ratio_for_stability(mu))
    mu2 = max(base.friction_coefficient_2 - base.friction_coefficient + mu, mu)
    return material.with_changes(
        continuum=dataclasses.replace(
            base, friction_coefficient=mu, friction_coefficient_2=mu2, poisson_ratio=nu
        )
    )


def fit_mpm_friction(
    data: Any,
    material: Material,
    *,
    plate_length: float,
    plate_width: float,
    cell_size: float | None = None,
    bounds: tuple[float, float] = (0.2, 1.5),
    tolerance: float = 0.01,
    max_trials: int = 10,
    speed: float = 0.05,
    bed: Bed | None = None,
    resolution: Resolution | None = None,
    progress: Callable[[int, int], None] | None = None,
    run: Callable[..., Any] | None = None,
) -> MPMFrictionFit:
    """Fit the continuum friction mu_s of ``material`` to plate force-depth ``data``.

    ``data`` is a :class:`terradyn.rft.calibration.PlateData` (see :func:`read_plate_force_csv`),
    ``plate_length``, ``plate_width`` [m] the plate; the MPM runs use ``cell_size`` [m] (default: the
    solver's, or ``resolution.cell_size``), ``speed`` [m/s], and the ``bed`` and ``resolution``
    specs (:mod:`terradyn.mpm.specs`) as in :func:`terradyn.mpm.run_intrusion`. Stops when the
    data/model scale is within ``tolerance`` of 1. ``run`` replaces :func:`terradyn.mpm.run_intrusion`
    (tests)."""
    from ..geometry import Plate
    from ..mpm.specs import Bed, Resolution

    bed = Bed() if bed is None else bed
    resolution = Resolution() if resolution is None else resolution
    if cell_size is not None:
        if resolution.cell_size is not None:
            raise InputError("cell_size", cell_size, "None when resolution.cell_size is given", "give one")
        resolution = resolution.replace(cell_size=cell_size)

    if material.continuum is None:
        raise InputError("material", material.name, "a medium with a [continuum] table (MPM parameters)")
    plate = Plate(
        length=check_length("plate_length", plate_length), width=check_length("plate_width", plate_width)
    )
    low, high = (check_positive("bounds", b) for b in bounds)
    if not low < high:
        raise InputError("bounds", bounds, "low < high")
    tolerance = check_positive("tolerance", tolerance)
    if run is None:
        from ..mpm import run_intrusion

        run = run_intrusion
    depth = np.asarray(data.depth_m, dtype=float)
    force = np.asarray(data.force_z_N, dtype=float)
    if np.any(depth <= 0):
        raise InputError("depth_m", float(depth.min()), "depths > 0 [m] (below the free surface)")
    if not np.any(np.abs(force) > 0):
        raise InputError("force_z_N", 0.0, "some non-zero forces")
    base = material.continuum
    plate_run = _PlateRun(run, plate, material, speed, bed, resolution)
    model_at = _ScaleAt(plate_run, depth, force, _groups(data), max_trials, progress)
    mu0 = min(max(base.friction_coefficient, low), high)
    best_mu, best_pred, best_k, converged = _solve_unit_scale(model_at, mu0, (low, high), tolerance)
    residual = force - best_pred
    ss_tot = float(np.sum((force - force.mean()) ** 2))
    r2 = 1.0 - float(residual @ residual) / ss_tot if ss_tot > 0 else 1.0
    return MPMFrictionFit(
        friction_coefficient=best_mu,
        friction_angle=math.asin(min(best_mu, 1.0)),
        poisson_ratio=max(base.poisson_ratio, poisson_ratio_for_stability(best_mu)),
        scale=best_k,
        rms_residual_N=float(np.sqrt(np.mean(residual**2))),
        r_squared=r2,
        trials=tuple(model_at.trials),
        material=_fitted_medium(material, best_mu),
        cell_size=resolution.cell_size,
        converged=converged,
        predicted_force_z_N=best_pred,
    )
