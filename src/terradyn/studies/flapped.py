"""Flapped (non-circular) wheel locomotion (thesis chapters 6.2 and 7)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from pydantic import Field

from .. import materials
from ..errors import SolverError
from ..optimize import flapped_wheel_performance
from ..results import TableResult
from ._base import StudyEntry, StudyOutput, _Params

__all__ = ["FlappedParams", "flapped_wheel_sweep"]


def flapped_wheel_sweep(
    *,
    media: Sequence[str] = ("CPS",),
    hub_radius: float = 0.05,
    width: float = 0.05,
    flap_counts: Sequence[int] = (3, 4, 6, 8),
    flap_length_ratios: Sequence[float] = (0.25, 0.5, 1.0),
    flap_angles: Sequence[float] = (0.0,),
    loads: Sequence[float] = (10.0,),
    phase_count: int = 24,
) -> TableResult:
    """Normalised forward speed V / (omega R_out) of self-propelled flapped wheels over their design.

    Each row is one design x load x medium: flap count, flap length / hub radius, flap angle [rad],
    load [N], and the quasi-static RFT performance (see
    :func:`terradyn.optimize.flapped_wheel_performance`); designs that cannot carry the load have
    ``solved = False``.
    """
    keys = (
        "material",
        "flap_count",
        "flap_length_ratio",
        "flap_angle_rad",
        "load_N",
        "solved",
        "velocity_normalised",
        "slip",
        "sinkage_m",
        "cost_of_transport",
    )
    rows: dict[str, list] = {k: [] for k in keys}
    for name in media:
        mat = materials.get(name)
        for count in flap_counts:
            for ratio in flap_length_ratios:
                for angle in flap_angles:
                    for load in loads:
                        try:
                            perf = flapped_wheel_performance(
                                mat,
                                hub_radius=hub_radius,
                                width=width,
                                flap_count=int(count),
                                flap_length=ratio * hub_radius,
                                flap_angle=angle,
                                load=load,
                                phase_count=phase_count,
                            )
                            vals = (
                                True,
                                perf["velocity_normalised"],
                                perf["slip"],
                                perf["sinkage_m"],
                                perf["cost_of_transport"],
                            )
                        except SolverError:
                            vals = (False, 0.0, 0.0, 0.0, 0.0)
                        for k, v in zip(keys, (mat.name, int(count), ratio, angle, load, *vals), strict=True):
                            rows[k].append(v)
    return TableResult(
        {k: np.asarray(v) for k, v in rows.items()},
        {"model": "rft (quasi-static, period-averaged)", "hub_radius_m": hub_radius},
    )


class FlappedParams(_Params):
    material: str = "CPS"
    media: list[str] = Field(default_factory=lambda: ["CPS", "MS"])
    hub_radius_m: float = Field(0.05, gt=0)
    width_m: float = Field(0.05, gt=0)
    flap_counts: list[int] = Field(default_factory=lambda: [2, 3, 4, 6, 8, 12])
    flap_length_ratios: list[float] = Field(default_factory=lambda: [0.25, 0.5, 0.75, 1.0, 1.5])
    flap_angles_deg: list[float] = Field(default_factory=lambda: [0.0])
    loads_N: list[float] = Field(default_factory=lambda: [5.0, 10.0])


def _run(p: FlappedParams) -> StudyOutput:
    import matplotlib.pyplot as plt

    counts = p.flap_counts[:2] if p.quick else p.flap_counts
    ratios = p.flap_length_ratios[:2] if p.quick else p.flap_length_ratios
    t = flapped_wheel_sweep(
        media=p.media,
        hub_radius=p.hub_radius_m,
        width=p.width_m,
        flap_counts=counts,
        flap_length_ratios=ratios,
        flap_angles=[math.radians(a) for a in p.flap_angles_deg],
        loads=p.loads_N,
        phase_count=8 if p.quick else 24,
    )
    c = t.columns
    from matplotlib.ticker import MaxNLocator

    fig, axes = plt.subplots(
        1, len(p.media), figsize=(5.5 * len(p.media), 4), squeeze=False, layout="constrained"
    )
    summary = []
    for ax, name in zip(axes[0], p.media, strict=True):
        mat = materials.get(name).name
        for ratio in ratios:
            for load in p.loads_N:
                m = (
                    (c["material"] == mat)
                    & np.isclose(c["flap_length_ratio"], ratio)
                    & (c["load_N"] == load)
                    & c["solved"].astype(bool)
                    & np.isclose(c["flap_angle_rad"], math.radians(p.flap_angles_deg[0]))
                )
                if np.any(m):
                    ax.plot(
                        c["flap_count"][m],
                        c["velocity_normalised"][m],
                        marker="o",
                        label=f"L / r = {ratio:g}, W = {load:g} N",
                    )
        ax.set_xlabel("flap count [-]")
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
        ax.set_ylabel(r"normalised speed $V / (\omega R_{out})$ [-]")
        ax.set_title(f"flapped wheel, {mat} (L: flap length, r: hub radius)")
        ax.grid(True, alpha=0.35)
        ax.legend(fontsize=7)
        m = (c["material"] == mat) & c["solved"].astype(bool)
        if np.any(m):
            k = np.nonzero(m)[0][int(np.argmax(c["velocity_normalised"][m]))]
            summary.append(
                {
                    "material": mat,
                    "best_flap_count": int(c["flap_count"][k]),
                    "best_flap_length_ratio": float(c["flap_length_ratio"][k]),
                    "load_N": float(c["load_N"][k]),
                    "velocity_normalised": float(c["velocity_normalised"][k]),
                }
            )
    return StudyOutput({"flapped_wheels": t}, {"flapped_wheels": fig}, summary)


def study_entries() -> tuple[StudyEntry, ...]:
    """The studies this module provides (:mod:`terradyn.studies.registry` lists them)."""
    return (
        (
            "flapped-wheels",
            FlappedParams,
            _run,
            "normalised speed of flapped wheels vs flap count, length, angle, load, medium",
        ),
    )
