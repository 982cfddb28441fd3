"""The MPM strip footing with its base as a grid boundary condition: the continuum without the contact.

:func:`terradyn.studies.mpm_verification.strip_footing` pushes a rigid plate through the grains with the
body contact; its reading carries the contact's errors (the pressure steps each time the base crosses a
node line, docs/mpm.md) on top of the continuum's. This case removes the contact: the grid nodes under
the footing (``|x| <= B/2`` on the surface node line and the node line above it) take the footing's
velocity, as the finite-element footing (:func:`terradyn.plasticity.fe_footing.fe_strip_footing`)
prescribes its footing nodes. By default the grid follows the footing down, so the footing nodes stay
on its base and the grains move through the grid (``follow=False`` keeps the grid still: the base then
stays on the surface node line while the grains move away from it, so only settlements well under a
cell read right); the settlement is small, like the FE's, and the reading is the plateau of the
bearing pressure, not an intercept.

The MPM run is :func:`terradyn.mpm.run_node_footing`; this module picks the continuum and reads the
bearing factor from its pressure curve. Everything else is the MPM of the intrusion runs: the bed of
:func:`terradyn.mpm.solver.make_bed`
(geostatic stress, K0 = nu / (1 - nu)), its damped settling (:func:`terradyn.mpm.model.default_settle_time`),
the Dunatunga-Kamrin continuum with mu_s = mu_2 = sin(phi) (rate independent, isochoric), the point or
patch-averaged volumetric update, quadratic B-splines and free-slip walls. A symmetry plane at x = 0
(``v_x = 0`` on the nodes of the left wall) halves the grid.

Loading: the footing velocity rises from 0 to ``speed`` over a half-cosine ramp of
``ramp_crossings`` P-wave transits of the bed depth (a sudden start sends a stress wave of about
rho c v, 2 kPa at 0.02 m/s, as large as the collapse pressure), then stays constant to the
settlement ``settlement_ratio`` x B. The bearing pressure is the vertical impulse the footing nodes
take from the grid per step, over the loaded half-width; N_gamma is 2 q / (gamma B) averaged over the
last quarter of the settlement.

Status (docs/mpm.md, "Footing as a grid boundary condition" and "Loading rate"): the continuum's own
check against the FE reference. The reading depends on the loading rate, as the FE's does: at B/10
(34 deg smooth) 22.1 / 19.0 / 17.2 / 15.9 at 0.01 / 0.0025 / 0.000625 / 0.00016 m/s, and a footing
held after a fast push loses load (22.1 to 11.6) where one held after a slow push keeps it (15.9 to
16.2); pushed slowly the MPM reads 2-3 % below the slow FE at the same cell size (16.45-16.49). At the
default 0.01 m/s, 34 deg smooth reads 22.1 / 18.6 / 14.4 at B/10 / B/20 / B/40 (6 B x 3 B) and 12.0
at B/80 (4 B x 2 B). :func:`footing_loading_rate` runs both models over a range of rates.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import InputError, check_length, check_range

__all__ = [
    "LoadingRateStudy",
    "NodeFooting",
    "NodeFootingConvergence",
    "footing_loading_rate",
    "node_footing_convergence",
    "node_strip_footing",
    "plateau_measures",
]

#: a reading is a plateau when its two halves differ by at most this fraction of it (``N_gamma_drift``)
PLATEAU_DRIFT = 0.10
#: ... and no earlier window of the same length (from a quarter of the settlement on) averages more than
#: this multiple of it (``N_gamma_peak_ratio``). Measured on the stop-28/29 node-footing curves (APIC and
#: FLIP 0.99, B/20-B/80): every case with a plateau has a ratio of 0.999-1.001 and a drift of -0.01 to
#: 0.09; 34 deg rough with FLIP 0.99 at B/80, which peaks early and falls by a third, 1.26 and 0.125.
PLATEAU_PEAK_RATIO = 1.05


def plateau_measures(settlement: np.ndarray, value: np.ndarray) -> tuple[float, float]:
    """(drift, peak ratio) of a reading taken as the mean of ``value`` over the last quarter of the
    ``settlement`` range: the mean of the quarter's second half minus its first half, over the reading;
    and the largest mean over windows a quarter of the range long starting between a quarter and three
    quarters of it, over the reading (1 when the reading is the curve's highest stretch)."""
    s = np.asarray(settlement, dtype=float)
    v = np.asarray(value, dtype=float)
    top = float(np.max(s))
    tail = v[s >= 0.75 * top]
    reading = float(np.mean(tail))
    if not (reading > 0.0) or len(tail) < 2:
        return math.nan, math.nan
    half = len(tail) // 2
    drift = (float(np.mean(tail[half:])) - float(np.mean(tail[:half]))) / reading
    peak = reading
    for start in np.linspace(0.25 * top, 0.75 * top, 41):
        window = v[(s >= start) & (s < start + 0.25 * top)]
        if len(window):
            peak = max(peak, float(np.mean(window)))
    return drift, peak / reading


@dataclass(frozen=True)
class NodeFooting:
    """One node-footing run: ``N_gamma`` (mean of 2 q / (gamma B) over the last quarter of the
    settlement), ``N_gamma_spread`` (max - min there), ``curve`` (settlement [m], pressure [Pa]) per
    recorded row, and the discretisation."""

    friction_angle_deg: float
    base: str
    width_m: float
    cell_size_m: float
    domain_m: tuple[float, float]
    symmetric: bool
    volumetric: str
    particles_per_cell: int
    speed_m_s: float
    settlement_m: float
    unit_weight_N_m3: float
    N_gamma: float
    N_gamma_spread: float
    curve: tuple[np.ndarray, np.ndarray]
    particles: int
    steps: int
    wall_s: float
    #: 2 q / (gamma B) while the footing is held still after the push (``hold_time``): the mean over
    #: the hold's last quarter, and (time since the push ended [s], pressure [Pa]) per recorded row
    N_gamma_held: float | None = None
    held_curve: tuple[np.ndarray, np.ndarray] | None = None
    #: duration of the push, start-up ramp included [s]
    push_time_s: float = 0.0
    #: FLIP fraction of the particle velocity update (0: the solver's APIC)
    flip: float = 0.0
    #: local damping alpha at the free nodes (0: none)
    local_damping: float = 0.0
    #: the reading's plateau measures (:func:`plateau_measures`)
    N_gamma_drift: float = 0.0
    N_gamma_peak_ratio: float = 1.0

    @property
    def plateau(self) -> bool:
        """Whether the reading is a plateau (:data:`PLATEAU_DRIFT`, :data:`PLATEAU_PEAK_RATIO`); a curve
        that peaked earlier and fell, or still climbs steeply, gives no collapse load."""
        return abs(self.N_gamma_drift) <= PLATEAU_DRIFT and self.N_gamma_peak_ratio <= PLATEAU_PEAK_RATIO

    def record(self) -> dict[str, Any]:
        held = {} if self.N_gamma_held is None else {"N_gamma_held": self.N_gamma_held}
        return {
            "friction_angle_deg": self.friction_angle_deg,
            "base": self.base,
            "width_m": self.width_m,
            "cell_size_m": self.cell_size_m,
            "cells_per_width": self.width_m / self.cell_size_m,
            "domain_m": list(self.domain_m),
            "symmetric": self.symmetric,
            "volumetric": self.volumetric,
            "particles_per_cell": self.particles_per_cell,
            "flip": self.flip,
            "local_damping": self.local_damping,
            "speed_m_s": self.speed_m_s,
            "settlement_m": self.settlement_m,
            "N_gamma": self.N_gamma,
            "N_gamma_spread": self.N_gamma_spread,
            "N_gamma_drift": self.N_gamma_drift,
            "N_gamma_peak_ratio": self.N_gamma_peak_ratio,
            "plateau": self.plateau,
            "particles": self.particles,
            "steps": self.steps,
            "wall_s": self.wall_s,
            "push_time_s": self.push_time_s,
            **held,
        }


def node_strip_footing(
    friction_angle_deg: float,
    base: str = "smooth",
    *,
    material: Any = "MS",
    width: float = 0.04,
    cell_size: float | None = None,
    domain_widths: tuple[float, float] = (6.0, 3.0),
    symmetric: bool = True,
    settlement_ratio: float = 0.02,
    speed: float = 0.01,
    ramp_crossings: float = 10.0,
    volumetric: str = "patch",
    particles_per_cell: int = 2,
    cfl: float = 0.3,
    follow: bool = True,
    base_rows: int = 2,
    hold_time: float = 0.0,
    flip: float = 0.0,
    local_damping: float = 0.0,
    progress: Callable[[float, float], None] | None = None,
) -> NodeFooting:
    """N_gamma of a rigid strip footing of ``width`` B [m] whose base is the grid nodes under it.

    ``friction_angle_deg`` phi (continuum mu_s = sin phi), ``base`` ``"smooth"`` (v_x free at the
    footing nodes) or ``"rough"`` (v_x = 0). ``cell_size`` [m] (default B/20, B/2 a whole number of
    cells); ``domain_widths`` (half-width from the footing centre, depth) in B, by default the FE
    reference's 6 B x 3 B (at B/20 the 34 deg rough footing reads 24.3 / 26.4 / 26.5 in 4 x 2 /
    6 x 3 / 8 x 4, the smooth one 18.9 / 18.6 / 18.4); ``symmetric`` grids only x >= 0 with a
    symmetry plane at x = 0 (else both halves). Loading as in the module docstring: ``speed`` [m/s]
    after a ramp of ``ramp_crossings`` wave transits, to ``settlement_ratio`` x B; ``cfl`` as in
    :class:`terradyn.mpm.specs.Resolution` (at coarse cells the reading depends on ``speed / cfl``,
    docs/mpm.md). ``follow`` moves the grid down with the footing (else the grid stays and the
    footing nodes are the surface node line and the ``base_rows - 1`` lines above it).
    ``volumetric`` ``"point"`` or ``"patch"`` and ``particles_per_cell`` as in
    :class:`terradyn.mpm.specs.Resolution`. ``hold_time`` [s] then holds the footing still
    (``N_gamma_held``, ``held_curve``). ``flip`` in [0, 1] blends the particle velocity update from
    the solver's APIC (0) towards FLIP (1), a diagnostic of the transfer's numerical dissipation
    (docs/mpm.md, "What the rate error is"); positions and affine matrices stay APIC's.
    ``local_damping`` alpha in [0, 0.95] adds the local damping of quasi-static explicit codes at the
    free nodes (:func:`terradyn.mpm.run_node_footing`); a diagnostic: it does not stop
    pure FLIP's creep and adds a speed-dependent excess (docs/mpm.md, "The creep is not ringing").
    ``progress(done, total)`` gets the steps done. The MPM run is
    :func:`terradyn.mpm.run_node_footing`; this function picks the continuum for phi and reads
    N_gamma from its pressure curve.
    """
    from ..mpm import FootingPush, NodeFootingCase, Resolution, run_node_footing

    phi_deg = check_range("friction_angle_deg", friction_angle_deg, 20.0, 45.0, unit="deg")
    case = NodeFootingCase(width=width, base=base, domain_widths=domain_widths, symmetric=symmetric,
                           follow=follow, base_rows=base_rows)  # fmt: skip
    resolution = Resolution(cell_size=cell_size, particles_per_cell=particles_per_cell, cfl=cfl,
                            volumetric=volumetric, flip=flip)  # fmt: skip
    push = FootingPush(speed=speed, ramp_crossings=ramp_crossings, settlement_ratio=settlement_ratio,
                       hold_time=hold_time)  # fmt: skip
    local_damping = check_range("local_damping", local_damping, 0.0, 0.95)
    model = _footing_model(material, phi_deg)
    run = run_node_footing(model, case, resolution=resolution, push=push, local_damping=local_damping,
                           progress=progress)  # fmt: skip
    b = case.width
    settlement = push.settlement_ratio * b
    gamma = run.unit_weight_N_m3
    q = run.pressure_Pa
    n_gamma = 2.0 * q / (gamma * b)
    tail = n_gamma[run.settlement_m >= 0.75 * settlement]
    drift, peak_ratio = plateau_measures(run.settlement_m, n_gamma)
    held_n = 2.0 * run.held_pressure_Pa / (gamma * b)
    return NodeFooting(
        friction_angle_deg=phi_deg,
        base=base,
        width_m=b,
        cell_size_m=run.cell_size_m,
        domain_m=run.domain_m,
        symmetric=symmetric,
        volumetric=volumetric,
        particles_per_cell=particles_per_cell,
        speed_m_s=float(speed),
        settlement_m=settlement,
        unit_weight_N_m3=gamma,
        N_gamma=float(np.mean(tail)),
        N_gamma_spread=float(np.max(tail) - np.min(tail)),
        curve=(run.settlement_m, q),
        particles=run.particles,
        steps=run.steps,
        wall_s=run.wall_s,
        N_gamma_held=float(np.mean(held_n[int(0.75 * len(held_n)) :])) if len(held_n) else None,
        held_curve=(run.held_time_s, run.held_pressure_Pa) if len(held_n) else None,
        push_time_s=run.push_time_s,
        flip=resolution.flip,
        local_damping=local_damping,
        N_gamma_drift=drift,
        N_gamma_peak_ratio=peak_ratio,
    )


def _footing_model(material: Any, phi_deg: float) -> Any:
    """The continuum of the node footing: ``material``'s (a name or a Material with a [continuum]
    table and a bulk density) with mu_s = mu_2 = sin(phi) and the Poisson ratio raised, if need be, to
    keep the bed stable (:func:`terradyn.studies.mpm_calibration.poisson_ratio_for_stability`)."""
    from .. import materials
    from ..mpm.model import resolve_model
    from .mpm_calibration import poisson_ratio_for_stability

    mat = materials.get(material) if isinstance(material, str) else material
    if mat.continuum is None or mat.bulk_density is None:
        raise InputError("material", mat.name, "a medium with a [continuum] table and a bulk density")
    mu = math.sin(math.radians(phi_deg))
    nu = max(mat.continuum.poisson_ratio, poisson_ratio_for_stability(mu))
    return resolve_model(mat, friction_coefficient=mu, poisson_ratio=nu)


@dataclass(frozen=True)
class NodeFootingConvergence:
    """:func:`node_strip_footing` at several cell sizes with the Richardson estimate, and the isochoric
    reference of the case (:func:`terradyn.plasticity.strip_footing_reference`; empty if none)."""

    runs: tuple[NodeFooting, ...]
    estimate: Any  # terradyn.studies.convergence.RichardsonEstimate
    reference: dict[str, Any] = field(default_factory=dict)

    def record(self) -> dict[str, Any]:
        """JSON-ready: every run, the estimate, and the finest reading (and the extrapolated value,
        when there is one) against the reference; ``within_10_percent_of_reference`` holds when the
        finest reading is within 10 % of it and its error band is under 10 % of it."""
        rec: dict[str, Any] = {"runs": [r.record() for r in self.runs], **self.estimate.record("N_gamma")}
        ref = self.reference.get("N_gamma_reference")
        rec["N_gamma_reference"] = ref
        rec["reference"] = self.reference.get("reference", "")
        rec["reference_kind"] = self.reference.get("reference_kind")
        rec["N_gamma_reference_band"] = self.reference.get("N_gamma_fe_band")
        if ref:
            finest = self.runs[-1].N_gamma
            rec["ratio_finest_to_reference"] = finest / float(ref)
            # the target asks for a converged reading: the finest within 10 % of the reference
            # and its own error band (Richardson, or the spread of the three finest) under 10 % of it
            # and a reading that is a plateau (a curve that peaked and fell gives no collapse load)
            rec["within_10_percent_of_reference"] = (
                abs(finest / float(ref) - 1.0) <= 0.1
                and self.estimate.error_band <= 0.1 * float(ref)
                and self.runs[-1].plateau
            )
            extrapolated = self.estimate.extrapolated
            rec["ratio_extrapolated_to_reference"] = (
                None if extrapolated is None else extrapolated / float(ref)
            )
        return rec


def node_footing_convergence(
    friction_angle_deg: float,
    base: str = "smooth",
    *,
    cells_per_width: Sequence[int] = (10, 20, 40),
    width: float = 0.04,
    progress: Callable[[float, float], None] | None = None,
    **kwargs: Any,
) -> NodeFootingConvergence:
    """:func:`node_strip_footing` at B / n for each n of ``cells_per_width`` (three or more distinct
    even integers) and the Richardson estimate of the three finest. ``progress(done, total)`` after
    each run, work counted as n^3 (cells x steps)."""
    from .convergence import richardson

    ns = tuple(cells_per_width)
    if (
        len(ns) < 3
        or len(set(ns)) != len(ns)
        or not all(isinstance(n, int) and 4 <= n <= 400 and n % 2 == 0 for n in ns)
    ):
        raise InputError("cells_per_width", list(ns), "three or more distinct even integers in [4, 400]")
    ns = tuple(sorted(ns))
    cost = [float(n) ** 3 for n in ns]
    runs = []
    done = 0.0
    for n, c in zip(ns, cost, strict=True):
        runs.append(node_strip_footing(friction_angle_deg, base, width=width, cell_size=width / n, **kwargs))
        done += c
        if progress is not None:
            progress(done, sum(cost))
    est = richardson([r.cell_size_m for r in runs[-3:]], [r.N_gamma for r in runs[-3:]])
    return NodeFootingConvergence(runs=tuple(runs), estimate=est, reference=_reference(runs[0]))


def _reference(run: NodeFooting) -> dict[str, Any]:
    """The isochoric reference of the run's case, empty when the theory package has none for it."""
    from ..plasticity import strip_footing_reference

    try:
        return dict(strip_footing_reference(run.friction_angle_deg, run.base))
    except InputError:
        return {}


@dataclass(frozen=True)
class LoadingRateStudy:
    """The node footing and the FE footing of the same case at one cell size, each pushed at several
    rates and held still afterwards (:func:`footing_loading_rate`); the MPM runs for each FLIP fraction
    of the velocity update in turn (``NodeFooting.flip``)."""

    friction_angle_deg: float
    base: str
    width_m: float
    cell_size_m: float
    mpm: tuple[NodeFooting, ...]
    #: (damping, FE runs in the order of the crossings)
    fe: tuple[tuple[float, tuple[Any, ...]], ...]

    def record(self) -> dict[str, Any]:
        """JSON-ready: one row per run, then the slowest push of each model, pushing and held, and the
        MPM's slowest reading over the mean of the FE's slowest ones."""
        rows: list[dict[str, Any]] = [
            {"model": "mpm", "speed_m_s": r.speed_m_s, "flip": r.flip, "push_time_s": r.push_time_s,
             "N_gamma": r.N_gamma, "N_gamma_held": r.N_gamma_held, "wall_s": r.wall_s}
            for r in self.mpm
        ]  # fmt: skip
        for damping, runs in self.fe:
            rows += [
                {"model": "fe", "damping": damping, "push_time_s": r.push_time_s, "N_gamma": r.N_gamma,
                 "N_gamma_held": r.N_gamma_held}
                for r in runs
            ]  # fmt: skip
        # the first FLIP fraction's slowest push (APIC with the default fractions)
        slow_mpm = max((r for r in self.mpm if r.flip == self.mpm[0].flip), key=lambda r: r.push_time_s)
        slow_fe = [max(runs, key=lambda r: r.push_time_s) for _, runs in self.fe]
        fe_mean = float(np.mean([r.N_gamma for r in slow_fe]))
        return {
            "friction_angle_deg": self.friction_angle_deg,
            "base": self.base,
            "width_m": self.width_m,
            "cell_size_m": self.cell_size_m,
            "cells_per_width": self.width_m / self.cell_size_m,
            "runs": rows,
            "mpm_slowest_N_gamma": slow_mpm.N_gamma,
            "mpm_slowest_N_gamma_held": slow_mpm.N_gamma_held,
            "fe_slowest_N_gamma": [r.N_gamma for r in slow_fe],
            "fe_slowest_N_gamma_held": [r.N_gamma_held for r in slow_fe],
            "ratio_mpm_to_fe_slowest": slow_mpm.N_gamma / fe_mean,
        }


def footing_loading_rate(
    friction_angle_deg: float,
    base: str = "smooth",
    *,
    cells_per_width: int = 10,
    width: float = 0.04,
    speeds: Sequence[float] = (0.01, 0.0025, 0.000625, 0.00015625),
    crossings: Sequence[float] = (100.0, 200.0, 800.0, 1600.0),
    dampings: Sequence[float] = (0.8, 0.5),
    hold_time: float = 0.05,
    hold_crossings: float = 50.0,
    flips: Sequence[float] = (0.0,),
    progress: Callable[[float, float], None] | None = None,
) -> LoadingRateStudy:
    """How the loading rate sets the reading: the MPM node footing (:func:`node_strip_footing`, medium
    MS, its moduli and unit weight) at each of ``speeds`` [m/s] and the FE footing
    (:func:`terradyn.plasticity.fe_footing.fe_strip_footing`, the same cone and moduli) over each of
    ``crossings`` wave crossings with each local damping of ``dampings``, both at the cell size
    B / ``cells_per_width`` and both held still after the push (``hold_time`` [s], ``hold_crossings``).
    The MPM speeds are run for each FLIP fraction of ``flips`` (0: the solver's APIC; see
    :func:`node_strip_footing`). Both materials are rate independent; a reading that moves with the
    rate, or a held load below the pushing one, is the discretisation's. ``progress(done, total)``
    after each run."""
    from ..plasticity.fe_footing import fe_strip_footing

    n = cells_per_width
    if not (isinstance(n, int) and 4 <= n <= 400 and n % 2 == 0):
        raise InputError("cells_per_width", n, "an even integer in [4, 400]")
    speeds = _numbers("speeds", speeds, "one or more speeds > 0 [m/s]", lambda v: v > 0.0)
    crossings = _numbers("crossings", crossings, "one or more numbers > 0", lambda v: v > 0.0)
    dampings = _numbers("dampings", dampings, "one or more numbers in [0, 1)", lambda v: 0.0 <= v < 1.0)
    flips = _numbers("flips", flips, "one or more numbers in [0, 1]", lambda v: 0.0 <= v <= 1.0)
    # checked before the MPM runs, so a bad FE setting does not waste them
    check_range("hold_crossings", hold_crossings, 0.0, 1e4)
    check_range("hold_time", hold_time, 0.0, 10.0, unit="s")
    if base not in ("smooth", "rough"):
        raise InputError("base", base, "'smooth' or 'rough'")
    b = check_length("width", width)
    mu = math.sin(math.radians(check_range("friction_angle_deg", friction_angle_deg, 20.0, 45.0, unit="deg")))
    total = float(len(speeds) * len(flips) + len(crossings) * len(dampings))
    done = 0.0

    def step() -> None:
        nonlocal done
        done += 1.0
        if progress is not None:
            progress(done, total)

    mpm = []
    for f in flips:
        for v in speeds:
            mpm.append(node_strip_footing(friction_angle_deg, base, width=b, cell_size=b / n, speed=v,
                                          hold_time=hold_time, flip=f))  # fmt: skip
            step()
    fe = []
    for d in dampings:
        runs = []
        for c in crossings:
            runs.append(fe_strip_footing(mu, base=base, width=b, elements_per_half_width=n // 2, damping=d,
                                         crossings=c, hold_crossings=hold_crossings))  # fmt: skip
            step()
        fe.append((float(d), tuple(runs)))
    return LoadingRateStudy(float(friction_angle_deg), base, b, b / n, tuple(mpm), tuple(fe))


def _numbers(
    name: str, values: Sequence[float], allowed: str, accept: Callable[[float], bool]
) -> tuple[float, ...]:
    """``values`` as floats, one or more, each a finite number that ``accept`` takes; else an
    InputError naming ``name``."""
    vals = tuple(values)
    ok = bool(vals) and all(
        isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and accept(float(v))
        for v in vals
    )
    if not ok:
        raise InputError(name, list(vals), allowed)
    return tuple(float(v) for v in vals)
