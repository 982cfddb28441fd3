"""Sweeps of steady wheel solves over slips, loads, media and terrain models."""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from ..errors import SolverError
from ..geometry import Body
from ..materials import Material
from ..results import TableResult
from ..terrain import TerrainModel
from .steady import wheel_steady

__all__ = ["force_slip_sweep"]

ModelFactory = Callable[[Material], TerrainModel]


def force_slip_sweep(
    body: Body,
    media: Sequence[Material],
    models: dict[str, ModelFactory],
    loads: Sequence[float],
    slips: Sequence[float],
    *,
    omega: float = 1.0,
    phase_count: int = 16,
    on_point: Callable[[int], None] | None = None,
) -> TableResult:
    """Steady solves over media x models x loads x slips.

    ``models`` maps a model name to a factory ``material -> terrain model``. A point the model cannot
    solve (e.g. the load is more than the medium carries) is kept with ``solved = False`` and zeros,
    and its reason in ``metadata["failures"]``.
    """
    cols: dict[str, list] = {
        k: []
        for k in (
            "material", "model", "load_N", "slip", "solved", "sinkage_m", "drawbar_pull_N",
            "drive_torque_Nm", "power_W", "tractive_efficiency", "entry_angle_rad",
        )
    }
    failures: list[str] = []
    for mat in media:
        for name, factory in models.items():
            model = factory(mat)
            for load in loads:
                for slip in slips:
                    try:
                        r = wheel_steady(body, model, load, slip, omega=omega, phase_count=phase_count)
                        vals = (True, r.sinkage_m, r.drawbar_pull_N, r.drive_torque_Nm, r.power_W,
                                r.tractive_efficiency, r.entry_angle_rad)
                    except SolverError as exc:
                        failures.append(f"{mat.name}/{name}/W={load:g}/s={slip:g}: {exc}")
                        vals = (False, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
                    for key, v in zip(
                        ("material", "model", "load_N", "slip"), (mat.name, name, float(load), float(slip)),
                        strict=True,
                    ):
                        cols[key].append(v)
                    for key, v in zip(list(cols)[4:], vals, strict=True):
                        cols[key].append(v)
                    if on_point is not None:
                        on_point(1)
    return TableResult(
        {k: np.asarray(v) for k, v in cols.items()},
        {"body": repr(body), "omega_rad_s": omega, "failures": failures},
    )
