"""Flapped-wheel design optimisation with an interior optimum (thesis ch. 7).

The normalised speed V / (omega R_out) of a self-propelled flapped wheel (quasi-static RFT) rises
monotonically with the flap count over 2-12 flaps in the shipped media (the wheel tends to a circle of
radius R_out), so maximising it only finds a bound; the cost of transport P / (W V) varies by only
about 10 % with the flap count along its valley (CPS, 10 N, flap angle 0), so the count is weakly
determined and is held fixed here. The cost of transport of the default wheel (hub radius 5 cm,
width 5 cm, 8 flaps, 10 N) on closely packed poppy seeds (CPS) has its minimum, about 0.30, inside the
box of flap length / hub radius in [0.1, 0.8] and flap angle in [-75, 75] deg: short flaps slip, long
ones dig, and leaning the flaps (the flap angle of :class:`terradyn.geometry.WheelFlapped`) trades the
two. The minimum lies in a shallow diagonal valley (longer flaps want more lean; about 0.301-0.304
from L / r = 0.21 at 40 deg to 0.27 at 55 deg) and a second, higher valley (about 0.31) reaches the
75 deg bound. This study finds the minimum by differential evolution
(:func:`terradyn.optimize.optimize`), maps the objective on a grid over the same bounds, and reports
how far inside them the optimum lies and the lowest value on the bounds.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from pydantic import Field

from .. import materials
from ..errors import SolverError
from ..materials import Material
from ._base import StudyEntry, StudyOutput, _Params

if TYPE_CHECKING:
    from ..optimize import OptimizationResult

__all__ = ["FlappedOptimisationParams", "OptimisationStudy", "flapped_optimisation"]


@dataclass
class OptimisationStudy:
    """Result: the figure (objective map), settings, metrics and findings as (text, verdict)."""

    figure: Any
    settings: dict[str, Any]
    metrics: dict[str, Any]
    findings: list[tuple[str, str]] = field(default_factory=list)
    grid: dict[str, np.ndarray] = field(default_factory=dict)


@dataclass(frozen=True)
class _FlappedWheel:
    """The wheel whose cost of transport is minimised: medium, hub radius [m], width [m], load [N],
    flap count and the phases of a revolution each evaluation averages over."""

    material: Material
    hub_radius: float
    width: float
    load: float
    flap_count: int
    phase_count: int

    def cost_of_transport(self, p: dict[str, float]) -> float:
        """P / (W V) [-] at ``p["flap_length_ratio"]`` (flap length / hub radius) and
        ``p["flap_angle_deg"]`` [deg] (quasi-static RFT, self-propelled)."""
        from ..optimize import flapped_wheel_performance

        perf = flapped_wheel_performance(
            self.material,
            hub_radius=self.hub_radius,
            width=self.width,
            flap_count=int(self.flap_count),
            flap_length=p["flap_length_ratio"] * self.hub_radius,
            flap_angle=math.radians(p["flap_angle_deg"]),
            load=self.load,
            phase_count=self.phase_count,
        )
        return perf["cost_of_transport"]


@dataclass(frozen=True, eq=False)
class _ObjectiveMap:
    """The cost of transport on a grid: ``cost[i, j]`` at ``ratios[i]`` (flap length / hub radius) and
    ``angles[j]`` [deg], NaN where the wheel found no steady state."""

    ratios: np.ndarray
    angles: np.ndarray
    cost: np.ndarray

    def lowest(self) -> tuple[float, float, float]:
        """The map's lowest cost and the ratio and angle [deg] where it is."""
        k = np.unravel_index(np.nanargmin(self.cost), self.cost.shape)
        return float(self.cost[k]), self.ratios[k[0]], self.angles[k[1]]

    def lowest_on_bounds(self) -> float:
        """The lowest cost on the map's edges (the bounds of the search)."""
        grid = self.cost
        return float(np.nanmin(np.concatenate([grid[0], grid[-1], grid[:, 0], grid[:, -1]])))


def _objective_map(
    cost: Callable[[dict[str, float]], float],
    length_ratios: tuple[float, float],
    angles_deg: tuple[float, float],
    quick: bool,
) -> _ObjectiveMap:
    """``cost`` on a grid over the bounds (7 x 6 points quick, else 15 x 13)."""
    ratios = np.linspace(length_ratios[0], length_ratios[1], 7 if quick else 15)
    angles = np.linspace(angles_deg[0], angles_deg[1], 6 if quick else 13)
    grid = np.full((ratios.size, angles.size), np.nan)
    for i, r in enumerate(ratios):
        for j, a in enumerate(angles):
            try:
                grid[i, j] = cost({"flap_length_ratio": float(r), "flap_angle_deg": float(a)})
            except SolverError:
                pass
    return _ObjectiveMap(ratios, angles, grid)


def _metrics(
    res: OptimizationResult,
    objective_map: _ObjectiveMap,
    length_ratios: tuple[float, float],
    angles_deg: tuple[float, float],
) -> dict[str, Any]:
    """The optimum, how far inside the bounds it lies (fractions of each range) and the map's lows."""
    best_r, best_a = res.best["flap_length_ratio"], res.best["flap_angle_deg"]
    span_r, span_a = length_ratios[1] - length_ratios[0], angles_deg[1] - angles_deg[0]
    margin_r = min(best_r - length_ratios[0], length_ratios[1] - best_r) / span_r
    margin_a = min(best_a - angles_deg[0], angles_deg[1] - best_a) / span_a
    return {
        "best_flap_length_ratio": best_r,
        "best_flap_angle_deg": best_a,
        "best_cost_of_transport": res.best_value,
        "grid_min_cost_of_transport": objective_map.lowest()[0],
        "interior": margin_r > 0.05 and margin_a > 0.05,
        "bounds_min_cost_of_transport": objective_map.lowest_on_bounds(),
        "margin_length": margin_r,
        "margin_angle": margin_a,
        "evaluations": len(res.evaluations),
    }


def _findings(
    res: OptimizationResult, objective_map: _ObjectiveMap, metrics: dict[str, Any]
) -> list[tuple[str, str]]:
    """(text, verdict): the optimum lies inside the bounds, matches the map's lowest value and is below
    the lowest value on the bounds."""
    best_r, best_a = metrics["best_flap_length_ratio"], metrics["best_flap_angle_deg"]
    margin_r, margin_a, interior = metrics["margin_length"], metrics["margin_angle"], metrics["interior"]
    grid_best, grid_best_r, grid_best_a = objective_map.lowest()
    edge_best = metrics["bounds_min_cost_of_transport"]
    beats = res.best_value <= grid_best + 1e-9
    return [
        (
            f"optimum L / r = {best_r:.3f}, flap angle {best_a:.1f} deg, "
            f"cost of transport {res.best_value:.4f} "
            f"({'inside' if interior else 'ON'} the bounds: {margin_r:.0%} of the length range and "
            f"{margin_a:.0%} of the angle range from the nearest bound)",
            "agrees" if interior else "disagrees",
        ),
        (
            f"the map's lowest value {grid_best:.4f} at L / r = {grid_best_r:.3f}, {grid_best_a:.1f} deg "
            f"(differential evolution {'matches or beats' if beats else 'is above'} it)",
            "agrees" if res.best_value <= grid_best * 1.02 else "disagrees",
        ),
        (
            f"lowest value on the bounds of the map {edge_best:.4f}, "
            f"{edge_best / res.best_value - 1:+.1%} above the optimum",
            "agrees" if edge_best > res.best_value else "disagrees",
        ),
    ]


def _plot_map(
    res: OptimizationResult,
    objective_map: _ObjectiveMap,
    wheel: _FlappedWheel,
    length_ratios: tuple[float, float],
    angles_deg: tuple[float, float],
) -> Any:
    """The objective map with the evaluations of the search, its optimum and the bounds."""
    import matplotlib.pyplot as plt

    best_r, best_a = res.best["flap_length_ratio"], res.best["flap_angle_deg"]
    span_r, span_a = length_ratios[1] - length_ratios[0], angles_deg[1] - angles_deg[0]
    fig, ax = plt.subplots(figsize=(7, 4.8), layout="constrained")
    mesh = ax.pcolormesh(
        objective_map.angles, objective_map.ratios, objective_map.cost, shading="nearest", cmap="viridis_r"
    )
    fig.colorbar(mesh, ax=ax, label="cost of transport P / (W V) [-]")
    ev = res.evaluations.columns
    ok = ev["feasible"].astype(bool)
    ax.scatter(
        ev["flap_angle_deg"][ok], ev["flap_length_ratio"][ok], s=6, c="w", alpha=0.5, label="evaluations"
    )
    ax.plot([best_a], [best_r], "r*", ms=16, label=f"optimum: L / r = {best_r:.2f}, {best_a:.0f} deg")
    ax.add_patch(
        plt.Rectangle(
            (angles_deg[0], length_ratios[0]),
            span_a,
            span_r,
            fill=False,
            ec="k",
            ls="--",
            lw=1.2,
            label="bounds",
        )
    )
    ax.set_xlabel("flap angle [deg]")
    ax.set_ylabel("flap length / hub radius [-]")
    ax.set_title(
        f"{wheel.flap_count}-flap wheel on {wheel.material.name}, {wheel.load:g} N: "
        "cost of transport (RFT, quasi-static)"
    )
    ax.legend(fontsize=7, loc="upper left")
    return fig


def flapped_optimisation(
    *,
    material: str = "CPS",
    hub_radius: float = 0.05,
    width: float = 0.05,
    load: float = 10.0,
    flap_count: int = 8,
    length_ratios: tuple[float, float] = (0.1, 0.8),
    angles_deg: tuple[float, float] = (-75.0, 75.0),
    quick: bool = False,
    seed: int = 0,
) -> OptimisationStudy:
    """Minimise the cost of transport of a flapped wheel over (flap length / hub radius, flap angle).

    Parameters
    ----------
    material : medium name; hub_radius, width : [m]; load : [N]; flap_count : number of flaps
    length_ratios : bounds of flap length / hub radius [-]; angles_deg : bounds of the flap angle [deg]
    quick : coarser map, fewer phases and generations (the report's ``--quick`` form)
    seed : differential-evolution seed
    """
    from ..optimize import Bound, optimize

    mat = materials.get(material)
    phases = 12 if quick else 24
    wheel = _FlappedWheel(mat, hub_radius, width, load, flap_count, phases)
    bounds = [Bound("flap_length_ratio", *length_ratios), Bound("flap_angle_deg", *angles_deg)]
    res = optimize(
        wheel.cost_of_transport,
        bounds,
        maximize=False,
        seed=seed,
        max_iterations=6 if quick else 25,
        population=5 if quick else 10,
    )
    objective_map = _objective_map(wheel.cost_of_transport, length_ratios, angles_deg, quick)
    metrics = _metrics(res, objective_map, length_ratios, angles_deg)
    fig = _plot_map(res, objective_map, wheel, length_ratios, angles_deg)
    settings = {
        "material": mat.name,
        "hub_radius_m": hub_radius,
        "width_m": width,
        "load_N": load,
        "flap_count": flap_count,
        "length_ratios": list(length_ratios),
        "angles_deg": list(angles_deg),
        "phase_count": phases,
        "seed": seed,
        "objective": "minimise cost of transport",
    }
    grid = {"ratios": objective_map.ratios, "angles": objective_map.angles, "cost": objective_map.cost}
    return OptimisationStudy(fig, settings, metrics, _findings(res, objective_map, metrics), grid)


class FlappedOptimisationParams(_Params):
    material: str = "CPS"
    hub_radius_m: float = Field(0.05, gt=0)
    width_m: float = Field(0.05, gt=0)
    load_N: float = Field(10.0, gt=0)
    flap_count: int = Field(8, ge=2, le=64)
    length_ratio_min: float = Field(0.1, gt=0)
    length_ratio_max: float = Field(0.8, gt=0)
    angle_min_deg: float = Field(-75.0, ge=-85, le=85)
    angle_max_deg: float = Field(75.0, ge=-85, le=85)
    seed: int = Field(0, ge=0)


def _run(p: FlappedOptimisationParams) -> StudyOutput:
    from ..errors import InputError
    from ..results import TableResult

    if not p.length_ratio_min < p.length_ratio_max:
        raise InputError("parameters.length_ratio_min", p.length_ratio_min, "< length_ratio_max")
    if not p.angle_min_deg < p.angle_max_deg:
        raise InputError("parameters.angle_min_deg", p.angle_min_deg, "< angle_max_deg")
    res = flapped_optimisation(
        material=p.material,
        hub_radius=p.hub_radius_m,
        width=p.width_m,
        load=p.load_N,
        flap_count=p.flap_count,
        length_ratios=(p.length_ratio_min, p.length_ratio_max),
        angles_deg=(p.angle_min_deg, p.angle_max_deg),
        quick=p.quick,
        seed=p.seed,
    )
    g = res.grid
    rr, aa = np.meshgrid(g["ratios"], g["angles"], indexing="ij")
    cost = g["cost"].ravel()
    table = TableResult(
        {
            "flap_length_ratio": rr.ravel(),
            "flap_angle_deg": aa.ravel(),
            "solved": np.isfinite(cost),
            "cost_of_transport": np.nan_to_num(cost, nan=0.0),
        },
        {"study": "flapped-wheel optimisation map", **res.settings},
    )
    summary = [{k: v for k, v in res.metrics.items()}]
    return StudyOutput({"optimisation_map": table}, {"optimisation": res.figure}, summary)


def study_entries() -> tuple[StudyEntry, ...]:
    """The studies this module provides (:mod:`terradyn.studies.registry` lists them)."""
    return (
        (
            "flapped-optimisation",
            FlappedOptimisationParams,
            _run,
            "flapped wheel: cost of transport over flap length and angle, optimum inside the bounds (ch. 7)",
        ),
    )
