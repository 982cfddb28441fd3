"""Wheel force-slip studies (thesis chapter 6.1; Agarwal et al. 2019)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from pydantic import Field

from .. import materials
from ..geometry import WheelCircular
from ..locomotion import force_slip_sweep
from ..locomotion.models import ModelSpec
from ..results import TableResult
from ._base import StudyEntry, StudyOutput, _Params

__all__ = ["WheelForceSlipParams", "summarise_force_slip", "wheel_force_slip"]


def wheel_force_slip(
    *,
    media: Sequence[str] = ("MS", "MMS", "LPS", "CPS"),
    loads: Sequence[float] = (80.0, 130.0, 150.0, 190.0),
    slips: Sequence[float] | np.ndarray = tuple(np.round(np.linspace(-0.7, 0.7, 15), 10)),
    models: Sequence[str] = ("rft", "wong-reece"),
    radius: float = 0.13,
    width: float = 0.16,
    scheduler: str = "serial",
) -> TableResult:
    """Drawbar pull, drive torque and sinkage versus slip of the rigid wheel of Agarwal et al. 2019.

    Defaults: the 0.26 m diameter x 0.16 m wheel on MS, MMS, LPS and CPS at 80-190 N, slip -0.7 to
    0.7, RFT and Wong-Reece side by side (the thesis Fig. 6-8 analogue).
    """
    wheel = WheelCircular(radius, width)
    specs = {name: ModelSpec(name) for name in models}
    mats = [materials.get(m) for m in media]
    return force_slip_sweep(wheel, mats, specs, loads, slips, scheduler=scheduler)


def summarise_force_slip(
    table: TableResult, *, radius: float = 0.13, width: float = 0.16
) -> list[dict[str, Any]]:
    """Per medium, model and load: the free-rolling slip (solved, DP = 0), and DP and sinkage at s = 0.3."""
    from ..errors import SolverError
    from ..locomotion import wheel_self_propelled

    c = table.columns
    wheel = WheelCircular(radius, width)
    out: list[dict[str, Any]] = []
    keys = dict.fromkeys(zip(c["material"].tolist(), c["model"].tolist(), c["load_N"].tolist(), strict=True))
    for mat, model, load in keys:
        m = (c["material"] == mat) & (c["model"] == model) & (c["load_N"] == load) & c["solved"].astype(bool)
        row: dict[str, Any] = {"material": mat, "model": model, "load_N": load, "solved_points": int(m.sum())}
        try:
            row["free_rolling_slip"] = wheel_self_propelled(
                wheel, ModelSpec(model)(materials.get(mat)), load
            ).slip
        except SolverError:
            row["free_rolling_slip"] = "none"
        if np.any(m):
            k = np.nonzero(m)[0][int(np.argmin(np.abs(c["slip"][m] - 0.3)))]
            row.update(
                {
                    "slip": float(c["slip"][k]),
                    "drawbar_pull_N": float(c["drawbar_pull_N"][k]),
                    "drive_torque_Nm": float(c["drive_torque_Nm"][k]),
                    "sinkage_m": float(c["sinkage_m"][k]),
                }
            )
        out.append(row)
    return out


class WheelForceSlipParams(_Params):
    media: list[str] = Field(default_factory=lambda: ["MS", "MMS", "LPS", "CPS"])
    loads_N: list[float] = Field(default_factory=lambda: [80.0, 130.0, 150.0, 190.0])
    slip_min: float = Field(-0.7, ge=-1, le=1)
    slip_max: float = Field(0.7, ge=-1, le=1)
    slip_count: int = Field(15, ge=2, le=1001)
    models: list[str] = Field(default_factory=lambda: ["rft", "wong-reece"])
    radius_m: float = Field(0.13, gt=0)
    width_m: float = Field(0.16, gt=0)


def _run(p: WheelForceSlipParams) -> StudyOutput:
    from ..plotting import new_force_slip_figure, plot_force_slip

    slips = np.round(np.linspace(p.slip_min, p.slip_max, 5 if p.quick else p.slip_count), 10)
    t = wheel_force_slip(
        media=p.media, loads=p.loads_N, slips=slips, models=p.models, radius=p.radius_m, width=p.width_m
    )
    fig, axes = new_force_slip_figure(len(p.media))
    for row, name in zip(axes, [materials.get(m).name for m in p.media], strict=True):
        plot_force_slip(t.columns, material=name, axes=row)
    fig.suptitle(f"Rigid wheel {2 * p.radius_m:g} m x {p.width_m:g} m: RFT (solid) and Wong-Reece (dashed)")
    return StudyOutput(
        {"wheel_force_slip": t},
        {"wheel_force_slip": fig},
        summarise_force_slip(t, radius=p.radius_m, width=p.width_m),
    )


def study_entries() -> tuple[StudyEntry, ...]:
    """The studies this module provides (:mod:`terradyn.studies.registry` lists them)."""
    return (
        (
            "wheel-force-slip",
            WheelForceSlipParams,
            _run,
            "force-slip and sinkage-slip of the 0.26 m wheel, RFT vs Wong-Reece, four media",
        ),
    )
