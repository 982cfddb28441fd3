"""Global design optimisation (differential evolution) and the flapped-wheel design problem.

:func:`optimize` maximises or minimises any objective of named, bounded parameters (integers allowed)
with scipy's differential evolution, recording a convergence trace and every evaluation.
:func:`optimize_flapped_wheel` applies it to a flapped wheel: maximise the normalised forward speed
V / (omega R_out) of the self-propelled wheel, or minimise its cost of transport P / (W V).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .errors import InputError, SolverError, check_length, check_positive
from .materials import Material
from .results import TableResult

__all__ = [
    "Bound",
    "OptimizationResult",
    "flapped_wheel_performance",
    "optimize",
    "optimize_flapped_wheel",
]


@dataclass(frozen=True)
class Bound:
    """A design parameter ``name`` in [low, high]; ``integer`` for counts."""

    name: str
    low: float
    high: float
    integer: bool = False

    def __post_init__(self) -> None:
        if not (math.isfinite(self.low) and math.isfinite(self.high) and self.low < self.high):
            raise InputError(f"bounds.{self.name}", (self.low, self.high), "finite low < high")


@dataclass(frozen=True)
class OptimizationResult:
    """Best design, its objective value, the convergence trace and every evaluation."""

    best: dict[str, float]
    best_value: float
    maximize: bool
    trace: list[float]
    evaluations: TableResult
    converged: bool
    message: str = ""
    extra: dict[str, Any] = field(default_factory=dict)


def optimize(
    objective: Callable[[dict[str, float]], float],
    bounds: Sequence[Bound],
    *,
    maximize: bool = True,
    seed: int = 0,
    max_iterations: int = 40,
    population: int = 12,
    tolerance: float = 1e-6,
    polish: bool = False,
    progress: Callable[[int, int], None] | None = None,
) -> OptimizationResult:
    """Global optimum of ``objective(params)`` over the box ``bounds`` by differential evolution.

    An objective that raises :class:`~terradyn.errors.SolverError` for a design (e.g. the wheel
    cannot carry the load) counts as the worst value. Deterministic for a given ``seed``.
    """
    from scipy.optimize import differential_evolution

    if not bounds:
        raise InputError("bounds", bounds, "at least one parameter")
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer) or not 0 <= seed < 2**32:
        raise InputError("seed", seed, "an integer in [0, 2^32 - 1]")
    if isinstance(max_iterations, bool) or not isinstance(max_iterations, int) or max_iterations < 1:
        raise InputError("max_iterations", max_iterations, "an integer >= 1")
    if isinstance(population, bool) or not isinstance(population, int) or population < 1:
        raise InputError("population", population, "an integer >= 1")
    names = [b.name for b in bounds]
    if len(set(names)) != len(names):
        raise InputError("bounds", names, "distinct parameter names")
    sign = -1.0 if maximize else 1.0
    history: dict[str, list[float]] = {n: [] for n in names}
    values: list[float] = []
    feasible: list[bool] = []
    worst = 1e30
    bad_inputs: list[InputError] = []

    def params_of(x: np.ndarray) -> dict[str, float]:
        return {b.name: (float(round(v)) if b.integer else float(v)) for b, v in zip(bounds, x, strict=True)}

    def f(x: np.ndarray) -> float:
        p = params_of(x)
        try:
            v = float(objective(p))
            ok = math.isfinite(v)
        except SolverError:
            v, ok = math.nan, False
        except InputError as exc:  # a design outside what the model takes: infeasible, remember why
            bad_inputs.append(exc)
            v, ok = math.nan, False
        for n in names:
            history[n].append(p[n])
        values.append(v if ok else math.nan)
        feasible.append(ok)
        return sign * v if ok else worst

    trace: list[float] = []

    def callback(intermediate_result: Any) -> None:
        trace.append(sign * float(intermediate_result.fun))
        if progress is not None:
            progress(len(trace), max_iterations)

    res = differential_evolution(
        f,
        [(b.low, b.high) for b in bounds],
        integrality=[b.integer for b in bounds],
        seed=seed,
        maxiter=max_iterations,
        popsize=population,
        tol=tolerance,
        polish=polish,
        callback=callback,
        updating="immediate",
    )
    if res.fun >= worst:
        if bad_inputs:
            raise bad_inputs[0]
        raise SolverError("no feasible design in the bounds: every evaluation failed")
    cols: dict[str, np.ndarray] = {n: np.asarray(history[n]) for n in names}
    cols["objective"] = np.nan_to_num(np.asarray(values), nan=0.0)
    cols["feasible"] = np.asarray(feasible)
    return OptimizationResult(
        best=params_of(res.x),
        best_value=sign * float(res.fun),
        maximize=maximize,
        trace=trace,
        evaluations=TableResult(cols, {"seed": seed}),
        converged=bool(res.success),
        message=str(res.message),
    )


def flapped_wheel_performance(
    material: Material,
    *,
    hub_radius: float,
    width: float,
    flap_count: int,
    flap_length: float,
    flap_angle: float,
    load: float,
    omega: float = 1.0,
    phase_count: int = 24,
    element_size: float | None = None,
    method: str = "steady",
    revolutions: float = 4.0,
) -> dict[str, float]:
    """Self-propelled performance of a flapped wheel with RFT.

    ``method="steady"`` (default, fast): quasi-static, period-averaged forces (below).
    ``method="dynamic"``: a free-body simulation (mass = load / 9.81, spin ``omega``) over
    ``revolutions`` turns, averaged over the last whole revolution; it resolves the bobbing.

    Returns ``velocity_normalised`` = V / (omega R_out) = 1 - slip, ``slip``, ``sinkage_m``,
    ``cost_of_transport`` = P / (W V) (inf-free: SolverError when V <= 0) and ``outer_radius_m``.
    The wheel is held at the axle height where the period-averaged vertical force carries the load,
    so this is the mean behaviour of a wheel that does not bob; a free-body simulation resolves the
    bobbing.
    """
    from .geometry import WheelFlapped
    from .locomotion import wheel_self_propelled
    from .rft import RFTModel

    check_positive("load", load)
    wheel = WheelFlapped(
        hub_radius=hub_radius,
        width=width,
        flap_count=int(flap_count),
        flap_length=flap_length,
        flap_angle=flap_angle,
    )
    if method not in ("steady", "dynamic"):
        raise InputError("method", method, "'steady' or 'dynamic'")
    if method == "dynamic":
        from .locomotion.dynamics import simulate_wheel

        check_positive("omega", omega)
        check_positive("revolutions", revolutions)
        run = simulate_wheel(
            wheel,
            material,
            mass=load / 9.81,
            omega=omega,
            duration=revolutions * 2 * math.pi / omega,
            output_every=10,
            element_size=element_size,
        )
        summary = run.steady_summary(revolutions=1.0)
        speed = summary["forward_velocity_m_s"]
        if speed <= 0:
            raise SolverError("the wheel does not move forward")
        return {
            "velocity_normalised": speed / (omega * wheel.outer_radius),
            "slip": summary["slip"],
            "sinkage_m": summary["sinkage_m"],
            "cost_of_transport": summary["power_W"] / (load * speed),
            "outer_radius_m": wheel.outer_radius,
        }
    res = wheel_self_propelled(
        wheel, RFTModel(material, element_size=element_size), load, omega=omega, phase_count=phase_count
    )
    velocity = res.forward_velocity_m_s
    if velocity <= 0:
        raise SolverError("the wheel does not move forward")
    return {
        "velocity_normalised": 1.0 - res.slip,
        "slip": res.slip,
        "sinkage_m": res.sinkage_m,
        "cost_of_transport": res.power_W / (load * velocity),
        "outer_radius_m": wheel.outer_radius,
    }


def optimize_flapped_wheel(
    material: Material,
    *,
    hub_radius: float,
    width: float,
    load: float,
    flap_count: tuple[int, int] = (2, 12),
    flap_length_ratio: tuple[float, float] = (0.2, 1.5),
    flap_angle: tuple[float, float] = (-math.pi / 3, math.pi / 3),
    metric: str = "velocity",
    seed: int = 0,
    max_iterations: int = 15,
    population: int = 8,
    phase_count: int = 16,
    element_size: float | None = None,
    method: str = "steady",
    progress: Callable[[int, int], None] | None = None,
) -> OptimizationResult:
    """Best flap count, flap length / hub radius and flap angle [rad] of a flapped wheel.

    ``metric`` = "velocity" maximises V / (omega R_out); "cost-of-transport" minimises P / (W V).
    """
    if metric not in ("velocity", "cost-of-transport"):
        raise InputError("metric", metric, "'velocity' or 'cost-of-transport'")
    hub_radius = check_length("hub_radius", hub_radius)
    width = check_length("width", width)
    load = check_positive("load", load)
    if method not in ("steady", "dynamic"):
        raise InputError("method", method, "'steady' or 'dynamic'")
    for name, (low, high) in (("flap_length_ratio", flap_length_ratio), ("flap_angle", flap_angle)):
        if not (math.isfinite(low) and math.isfinite(high) and low < high):
            raise InputError(name, (low, high), "finite bounds with low < high")
    key = "velocity_normalised" if metric == "velocity" else "cost_of_transport"

    def objective(p: dict[str, float]) -> float:
        perf = flapped_wheel_performance(
            material,
            hub_radius=hub_radius,
            width=width,
            flap_count=int(p["flap_count"]),
            flap_length=p["flap_length_ratio"] * hub_radius,
            flap_angle=p["flap_angle"],
            load=load,
            phase_count=phase_count,
            element_size=element_size,
            method=method,
        )
        return perf[key]

    bounds = [
        Bound("flap_count", flap_count[0], flap_count[1], integer=True),
        Bound("flap_length_ratio", *flap_length_ratio),
        Bound("flap_angle", *flap_angle),
    ]
    return optimize(
        objective,
        bounds,
        maximize=(metric == "velocity"),
        seed=seed,
        max_iterations=max_iterations,
        population=population,
        progress=progress,
    )
