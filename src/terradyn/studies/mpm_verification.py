"""MPM against plasticity theory, no RFT involved: the rigid strip footing on weighted sand.

A rigid strip footing of width B is pushed into a cohesionless bed of unit weight gamma = rho g. Rigid-
plastic theory gives the collapse pressure of a surface footing as q_u = 0.5 gamma B N_gamma(phi) with a
bearing factor from the method of characteristics (exact values for associated flow: Martin 2005; for
isochoric, non-associated flow there is no exact solution; the associated value is an upper bound on
it, and finite-element values exist in Frydman & Burd 1997 and Loukidis & Salgado 2009, not retrieved
here, see :mod:`terradyn.plasticity.references`). The MPM continuum (Dunatunga-Kamrin, isochoric,
mu_s = sin phi in plane strain) is a non-associated Mohr-Coulomb material of friction angle phi and
dilatancy 0, so its N_gamma is compared with the non-associated value.

How N_gamma is read from an MPM run: the footing moves down at constant speed; the bearing pressure
q(s) = F_z / (B w) is recorded against settlement s. An elastic-plastic bed has no sharp collapse, and
once the mechanism has formed the footing is embedded by s, which adds a surcharge term that grows
linearly, q ~ q_u + gamma N_q s. So the collapse pressure q_u is the intercept at s = 0 of a straight
line fitted to q(s) over s/B in [0.5, 1.5] x ``settlement_ratio`` (default 0.1, i.e. 0.05-0.15 B, after
the elastic part and before deep embedment), and

    N_gamma_mpm = 2 q_u / (gamma B).

The slope of that line over gamma is reported beside N_q of the reduced angle phi* (tan phi* = sin phi,
Davis 1968, the isochoric equivalent) as a check that the linear part is the embedment term. The
settlement must span a few cells: the default cell size is B/20.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from enum import Enum
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import InputError, SolverError, check_length, check_positive, check_range

if TYPE_CHECKING:
    from ..mpm.specs import Bed, Resolution

__all__ = ["FootingBase", "StripFootingResult", "strip_footing"]


class FootingBase(str, Enum):
    """Footing-soil interface: ``rough`` (no slip) or ``smooth`` (frictionless)."""

    rough = "rough"
    smooth = "smooth"


#: body-grain friction standing for a rough base (sticking: far above tan(phi) = 0.67 of 34 deg sand;
#: the largest the MPM model accepts)
ROUGH_FRICTION = 2.0


@dataclass(frozen=True)
class StripFootingResult:
    """One MPM strip-footing run and its bearing factor.

    ``N_gamma_mpm`` [-] = 2 q_u / (gamma B) from the intercept q_u, with ``N_gamma_stderr`` its standard
    error (least squares, the residuals' lag-1 autocorrelation shrinking the sample to its effective
    size: the pressure rings as the base crosses cells), ``N_gamma_raw`` = 2 q / (gamma B)
    at the reading settlement ``settlement_m`` (pressure ``pressure_Pa``), ``embedment_slope`` the
    fitted dq/ds over gamma [-] and ``N_q_reduced`` N_q(phi*) to compare it with, ``unit_weight_N_m3`` gamma,
    ``reference`` (dict from :func:`terradyn.plasticity.strip_footing_reference`, or empty when that
    package has no value), ``curve`` (settlement [m], pressure [Pa]) of the whole run (the first grid
    phase's); ``particles_per_cell`` and ``volumetric`` the discretisation
    (:class:`terradyn.mpm.specs.Resolution`); ``phases`` each grid phase's surface offset, intercept
    and curve (the readings above are then the phases' means, ``N_gamma_stderr`` that of the mean)."""

    friction_angle_deg: float
    base: FootingBase
    width_m: float
    cell_size_m: float
    N_gamma_mpm: float
    N_gamma_raw: float
    N_gamma_stderr: float
    pressure_Pa: float
    settlement_m: float
    embedment_slope: float
    N_q_reduced: float
    unit_weight_N_m3: float
    reference: dict[str, Any]
    curve: tuple[np.ndarray, np.ndarray]
    final_particles: dict[str, np.ndarray] | None = None
    final_segments: np.ndarray | None = None
    particles_per_cell: int = 2
    volumetric: str = "point"
    flip: float = 0.0
    #: one (surface offset [cells], N_gamma intercept, (s, q) curve) per grid phase
    phases: tuple[tuple[float, float, tuple[np.ndarray, np.ndarray]], ...] = ()

    def record(self) -> dict[str, Any]:
        rec: dict[str, Any] = {
            "N_gamma_mpm": self.N_gamma_mpm,
            "N_gamma_reference": self.reference.get("N_gamma_reference"),
            "reference": self.reference.get("reference", ""),
            "N_gamma_mpm_stderr": self.N_gamma_stderr,
            "N_gamma_raw": self.N_gamma_raw,
            "friction_angle_deg": self.friction_angle_deg,
            "base": self.base.value,
            "width_m": self.width_m,
            "cell_size_m": self.cell_size_m,
            "particles_per_cell": self.particles_per_cell,
            "volumetric": self.volumetric,
            "flip": self.flip,
            "pressure_Pa": self.pressure_Pa,
            "settlement_m": self.settlement_m,
            "embedment_slope": self.embedment_slope,
            "N_q_reduced": self.N_q_reduced,
        }
        if len(self.phases) > 1:
            values = [p[1] for p in self.phases]
            rec["grid_phases"] = len(self.phases)
            rec["surface_offsets"] = [p[0] for p in self.phases]
            rec["N_gamma_phase_values"] = values
            rec["N_gamma_phase_spread"] = max(values) - min(values)
        ref = rec["N_gamma_reference"]
        rec["reference_kind"] = self.reference.get("reference_kind")
        rec["N_gamma_reference_band"] = self.reference.get("N_gamma_fe_band")
        if ref:
            rec["ratio_mpm_to_reference"] = self.N_gamma_mpm / float(ref)
            # the target: within 10 % of the non-associated value
            rec["within_10_percent_of_reference"] = abs(self.N_gamma_mpm / float(ref) - 1.0) <= 0.1
        if "N_gamma_associated" in self.reference:
            rec["N_gamma_associated"] = self.reference["N_gamma_associated"]
        # the rigorous bracket of a psi = 0 value (Radenkovic's theorems), None where unknown
        lower = self.reference.get("N_gamma_lower_bound")
        upper = self.reference.get("N_gamma_upper_bound")
        rec["N_gamma_lower_bound"], rec["N_gamma_upper_bound"] = lower, upper
        rec["within_bounds"] = (
            None
            if lower is None and upper is None
            else (lower is None or self.N_gamma_mpm >= lower) and (upper is None or self.N_gamma_mpm <= upper)
        )
        return rec


def _read(res: Any, width: float, out_of_plane: float, settlement: float, gamma: float) -> tuple[Any, ...]:
    """``(N_gamma intercept, N_gamma raw, its standard error, pressure at the reading [Pa], embedment
    slope / gamma [-], (s [m], q [Pa]) curve)`` of one footing run of ``width`` B [m]."""
    df = res.to_dataframe()
    s = df["depth_m"].to_numpy()
    q = df["force_z_N"].to_numpy() / (width * out_of_plane)
    touching = s > 0
    if not np.any(touching):
        raise SolverError("the footing never reached the bed")
    fit = (s >= 0.5 * settlement) & (s <= 1.5 * settlement)
    if np.count_nonzero(fit) < 4:
        raise SolverError(f"too few records between {0.5 * settlement:.4g} and {1.5 * settlement:.4g} m")
    slope, intercept = np.polyfit(s[fit], q[fit], 1)
    q_stderr = _intercept_stderr(s[fit], q[fit], float(slope), float(intercept))
    near = np.abs(s - settlement) <= 0.1 * settlement
    q_read = float(q[near].mean()) if np.any(near) else float(intercept + slope * settlement)
    to_n = 2.0 / (gamma * width)
    return (
        to_n * float(intercept),
        to_n * q_read,
        to_n * q_stderr,
        q_read,
        float(slope) / gamma,
        (s[touching], q[touching]),
    )


def _reference(phi_deg: float, base: FootingBase) -> dict[str, Any]:
    try:
        from ..plasticity import strip_footing_reference
    except ImportError:  # pragma: no cover - the theory package is part of terradyn
        return {}
    try:
        return dict(strip_footing_reference(phi_deg, base.value))
    except InputError:
        return {}


def _nq_reduced(phi: float) -> float:
    """Reissner's N_q at the Davis (1968) isochoric angle tan phi* = sin phi."""
    from ..plasticity import davis1968_reduced_friction_angle, reissner1924_nq

    return float(reissner1924_nq(davis1968_reduced_friction_angle(phi)))


def _intercept_stderr(s: np.ndarray, q: np.ndarray, slope: float, intercept: float) -> float:
    """Standard error of a least-squares line's intercept with serially correlated residuals: the
    ordinary formula with the sample shrunk to n (1 - r) / (1 + r), r the residuals' lag-1
    autocorrelation (clipped to [0, 0.95])."""
    n = len(s)
    res = q - (intercept + slope * s)
    rho = 0.0
    if n > 3 and np.std(res[:-1]) > 0 and np.std(res[1:]) > 0:
        rho = float(np.clip(np.corrcoef(res[:-1], res[1:])[0, 1], 0.0, 0.95))
    sxx = float(np.sum((s - s.mean()) ** 2))
    sigma2 = float(np.sum(res**2)) / max(1, n - 2)
    var = sigma2 * (1.0 / n + s.mean() ** 2 / sxx) * (1.0 + rho) / (1.0 - rho)
    return math.sqrt(var)


@dataclass(frozen=True)
class _FootingRun:
    """The MPM footing run every grid phase repeats: ``run`` (:func:`terradyn.mpm.run_intrusion` or a
    stand-in), the medium, the base, footing width B [m], cell size [m], reading settlement [m],
    speed [m/s], bed and resolution specs, and the continuum's mu_s and Poisson ratio."""

    run: Callable[..., Any]
    material: Any
    base: FootingBase
    width: float
    cell_size: float
    settlement: float
    speed: float
    bed: Bed
    resolution: Resolution
    friction_coefficient: float
    poisson_ratio: float


def _check_grid_phases(grid_phases: int, resolution: Resolution) -> None:
    """One :class:`InputError` line unless ``grid_phases`` divides the points per cell along an axis."""
    ppc = resolution.particles_per_cell
    if not isinstance(grid_phases, int) or grid_phases < 1 or ppc % grid_phases != 0:
        raise InputError(
            "grid_phases",
            grid_phases,
            f"a divisor of the points per cell along an axis ({ppc})",
            "each phase moves the grid by a whole number of point rows",
        )


def _unit_weight(mat: Any, bed: Bed) -> float:
    """gamma = rho g [N/m^3] of the bed as it is made (a consolidated bed: 1.02 critical density by
    default), or of the density the bed is given."""
    from ..mpm.model import resolve_model
    from ..mpm.solver import initial_density

    model = resolve_model(mat)
    rho = (
        bed.density
        if bed.density is not None
        else initial_density(model.bulk_density, model.critical_density, bed.packing)
    )
    return rho * bed.gravity


def _phase_reading(
    footing: _FootingRun,
    k: int,
    grid_phases: int,
    gamma: float,
    progress: Callable[[float, float], None] | None,
) -> tuple[Any, ...]:
    """Grid phase ``k`` of ``grid_phases`` (the grid moved by k / n of a cell against the surface):
    ``(surface offset, run result, *reading)`` with the reading of :func:`_read`; its progress is its
    share of the whole."""
    from ..geometry import Plate
    from ..mpm.specs import Outputs, Stroke

    b, h, settlement = footing.width, footing.cell_size, footing.settlement
    out_of_plane = 0.01
    offset = (footing.bed.surface_offset + k / grid_phases) % 1.0
    phase_progress = None
    if progress is not None:

        def phase_progress(done: float, total: float) -> None:
            progress(k * total + done, grid_phases * total)

    res = footing.run(
        Plate(length=b, width=out_of_plane),
        footing.material,
        depth=1.5 * settlement,
        speed=footing.speed,
        bed=footing.bed.replace(surface_offset=offset),
        resolution=footing.resolution.replace(cell_size=h),
        outputs=Outputs(record_spacing=min(0.25 * h, 0.02 * settlement), progress=phase_progress),
        stroke=Stroke(averaging_window=0.2 * settlement),
        friction_coefficient=footing.friction_coefficient,
        poisson_ratio=footing.poisson_ratio,
        surface_friction=ROUGH_FRICTION if footing.base is FootingBase.rough else 0.0,
    )
    return (offset, res, *_read(res, b, out_of_plane, settlement, gamma))


def _footing_result(
    footing: _FootingRun, readings: list[tuple[Any, ...]], phi_deg: float, gamma: float
) -> StripFootingResult:
    """The phases' mean readings (the first phase's curve and final state) and the references."""
    first = readings[0]
    res = first[1]
    n_phase = [r[2] for r in readings]
    stderr = math.sqrt(sum(r[4] ** 2 for r in readings)) / len(readings)
    resolution = footing.resolution
    return StripFootingResult(
        friction_angle_deg=phi_deg,
        base=footing.base,
        width_m=footing.width,
        cell_size_m=footing.cell_size,
        N_gamma_mpm=float(np.mean(n_phase)),
        N_gamma_raw=float(np.mean([r[3] for r in readings])),
        N_gamma_stderr=stderr,
        pressure_Pa=float(np.mean([r[5] for r in readings])),
        settlement_m=footing.settlement,
        embedment_slope=float(np.mean([r[6] for r in readings])),
        N_q_reduced=_nq_reduced(math.radians(phi_deg)),
        unit_weight_N_m3=gamma,
        reference=_reference(phi_deg, footing.base),
        curve=first[7],
        phases=tuple((r[0], r[2], r[7]) for r in readings),
        final_particles=getattr(res, "final_particles", None),
        final_segments=None if getattr(res, "final_frame", None) is None else res.final_frame["segments"],
        particles_per_cell=resolution.particles_per_cell,
        volumetric=resolution.volumetric,
        flip=resolution.flip,
    )


def strip_footing(
    friction_angle_deg: float,
    base: FootingBase | str = FootingBase.rough,
    *,
    material: Any = "MS",
    width: float = 0.04,
    cell_size: float | None = None,
    settlement_ratio: float = 0.1,
    speed: float = 0.02,
    bed: Bed | None = None,
    resolution: Resolution | None = None,
    grid_phases: int = 1,
    progress: Callable[[float, float], None] | None = None,
    run: Callable[..., Any] | None = None,
) -> StripFootingResult:
    """Bearing factor N_gamma of a rigid strip footing of ``width`` B [m] on a bed of ``material`` whose
    continuum friction is set to sin(``friction_angle_deg``) (plane strain); ``base`` rough or smooth.
    ``cell_size`` [m] (default B/20; or ``resolution.cell_size``), ``speed`` [m/s],
    ``settlement_ratio`` s/B of the reading; ``bed`` and ``resolution`` (:mod:`terradyn.mpm.specs`)
    as in :func:`terradyn.mpm.run_intrusion`. ``grid_phases`` n > 1 repeats the run with the grid moved
    against the surface by k / n of a cell (``Bed.surface_offset``, k = 0..n-1; n must divide
    ``particles_per_cell``) and reports the mean reading with the phases' values and spread: the
    pressure steps up each time the base crosses a node line, so the reading depends on where the grid
    lies (docs/mpm.md). ``run`` replaces :func:`terradyn.mpm.run_intrusion` (tests)."""
    from .. import materials
    from ..mpm.specs import Bed, Resolution

    bed = Bed() if bed is None else bed
    resolution = Resolution() if resolution is None else resolution
    if cell_size is not None and resolution.cell_size is not None:
        raise InputError("cell_size", cell_size, "None when resolution.cell_size is given", "give one")
    cell_size = resolution.cell_size if cell_size is None else cell_size

    phi_deg = check_range("friction_angle_deg", friction_angle_deg, 20.0, 45.0, unit="deg")
    try:
        base = FootingBase(base)
    except ValueError:
        raise InputError("base", base, "'rough' or 'smooth'") from None
    mat = materials.get(material) if isinstance(material, str) else material
    if mat.continuum is None or mat.bulk_density is None:
        raise InputError("material", mat.name, "a medium with a [continuum] table and a bulk density")
    b = check_length("width", width)
    h = b / 20.0 if cell_size is None else check_positive("cell_size", cell_size)
    ratio = check_range("settlement_ratio", settlement_ratio, 0.005, 0.5)
    phi = math.radians(phi_deg)
    mu = math.sin(phi)
    from .mpm_calibration import poisson_ratio_for_stability

    nu = max(mat.continuum.poisson_ratio, poisson_ratio_for_stability(mu))
    if run is None:
        from ..mpm import run_intrusion

        run = run_intrusion
    settlement = ratio * b
    if settlement < 2.0 * h:
        raise InputError(
            "cell_size",
            h,
            f"at most {settlement / 2:.4g} m",
            "the reading settlement must span two cells or more",
        )
    _check_grid_phases(grid_phases, resolution)
    gamma = _unit_weight(mat, bed)
    footing = _FootingRun(run, mat, base, b, h, settlement, speed, bed, resolution, mu, nu)
    readings = [_phase_reading(footing, k, grid_phases, gamma, progress) for k in range(grid_phases)]
    return _footing_result(footing, readings, phi_deg, gamma)
