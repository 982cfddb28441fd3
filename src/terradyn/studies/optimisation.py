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
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from pydantic import Field

from .. import materials
from ..errors import SolverError
from ._base import StudyEntry, StudyOutput, _Params

__all__ = ["FlappedOptimisationParams", "OptimisationStudy", "flapped_optimisation"]


@dataclass
class OptimisationStudy:
    """Result: the figure (objective map), settings, metrics and findings as (text, verdict)."""

    figure: Any
    settings: dict[str, Any]
    metrics: dict[str, Any]
    findings: list[tuple[str, str]] = field(default_factory=list)
    grid: dict[str, np.ndarray] = field(default_factory=dict)


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
    import matplotlib.pyplot as plt

    from ..optimize import Bound, flapped_wheel_performance, optimize

    mat = materials.get(material)
    phases = 12 if quick else 24

    def cost(p: dict[str, float]) -> float:
        perf = flapped_wheel_performance(
            mat,
            hub_radius=hub_radius,
            width=width,
            flap_count=int(flap_count),
            flap_length=p["flap_length_ratio"] * hub_radius,
            flap_angle=math.radians(p["flap_angle_deg"]),
            load=load,
            phase_count=phases,
        )
        return perf["cost_of_transport"]

    bounds = [Bound("flap_length_ratio", *length_ratios), Bound("flap_angle_deg", *angles_deg)]
    res = optimize(
        cost,
        bounds,
        maximize=False,
        seed=seed,
        max_iterations=6 if quick else 25,
        population=5 if quick else 10,
    )
    ratios = np.linspace(length_ratios[0], length_ratios[1], 7 if quick else 15)
    angles = np.linspace(angles_deg[0], angles_deg[1], 6 if quick else 13)
    grid = np.full((ratios.size, angles.size), np.nan)
    for i, r in enumerate(ratios):
        for j, a in enumerate(angles):
            try:
                grid[i, j] = cost({"flap_length_ratio": float(r), "flap_angle_deg": float(a)})
            except SolverError:
                pass
    best_r, best_a = res.best["flap_length_ratio"], res.best["flap_angle_deg"]
    span_r, span_a = length_ratios[1] - length_ratios[0], angles_deg[1] - angles_deg[0]
    margin_r = min(best_r - length_ratios[0], length_ratios[1] - best_r) / span_r
    margin_a = min(best_a - angles_deg[0], angles_deg[1] - best_a) / span_a
    interior = margin_r > 0.05 and margin_a > 0.05
    k = np.unravel_index(np.nanargmin(grid), grid.shape)
    grid_best = float(grid[k])
    edge = np.concatenate([grid[0], grid[-1], grid[:, 0], grid[:, -1]])
    edge_best = float(np.nanmin(edge))

    fig, ax = plt.subplots(figsize=(7, 4.8), layout="constrained")
    mesh = ax.pcolormesh(angles, ratios, grid, shading="nearest", cmap="viridis_r")
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
    ax.set_title(f"{flap_count}-flap wheel on {mat.name}, {load:g} N: cost of transport (RFT, quasi-static)")
    ax.legend(fontsize=7, loc="upper left")
    metrics = {
        "best_flap_length_ratio": best_r,
        "best_flap_angle_deg": best_a,
        "best_cost_of_transport": res.best_value,
        "grid_min_cost_of_transport": grid_best,
        "interior": interior,
        "bounds_min_cost_of_transport": edge_best,
        "margin_length": margin_r,
        "margin_angle": margin_a,
        "evaluations": len(res.evaluations),
    }
    beats = res.best_value <= grid_best + 1e-9
    findings = [
        (
            f"optimum L / r = {best_r:.3f}, flap angle {best_a:.1f} deg, "
            f"cost of transport {res.best_value:.4f} "
            f"({'inside' if interior else 'ON'} the bounds: {margin_r:.0%} of the length range and "
            f"{margin_a:.0%} of the angle range from the nearest bound)",
            "agrees" if interior else "disagrees",
        ),
        (
            f"the map's lowest value {grid_best:.4f} at L / r = {ratios[k[0]]:.3f}, {angles[k[1]]:.1f} deg "
            f"(differential evolution {'matches or beats' if beats else 'is above'} it)",
            "agrees" if res.best_value <= grid_best * 1.02 else "disagrees",
        ),
        (
            f"lowest value on the bounds of the map {edge_best:.4f}, "
            f"{edge_best / res.best_value - 1:+.1%} above the optimum",
            "agrees" if edge_best > res.best_value else "disagrees",
        ),
    ]
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
    return OptimisationStudy(
        fig, settings, metrics, findings, {"ratios": ratios, "angles": angles, "cost": grid}
    )


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
