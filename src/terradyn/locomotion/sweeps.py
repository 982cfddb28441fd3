"""Sweeps of steady wheel solves over slips, loads, media and terrain models."""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import SolverError
from ..geometry import Body
from ..materials import Material
from ..parallel import map_items
from ..results import TableResult
from ..terrain import TerrainModel
from .steady import wheel_steady

__all__ = ["force_slip_sweep"]

ModelFactory = Callable[[Material], TerrainModel]
_VALUES = (
    "sinkage_m",
    "drawbar_pull_N",
    "drive_torque_Nm",
    "power_W",
    "tractive_efficiency",
    "entry_angle_rad",
)


@dataclass(frozen=True)
class _Task:
    body: Body
    material: Material
    model_name: str
    factory: Any
    loads: tuple[float, ...]
    slips: tuple[float, ...]
    omega: float
    phase_count: int


def _run_task(task: _Task) -> tuple[list[tuple[Any, ...]], list[str]]:
    """All loads x slips of one (medium, model): rows of values and failure messages."""
    model = task.factory(task.material)
    rows, failures = [], []
    for load in task.loads:
        for slip in task.slips:
            try:
                r = wheel_steady(task.body, model, load, slip, omega=task.omega, phase_count=task.phase_count)
                vals = (
                    True,
                    r.sinkage_m,
                    r.drawbar_pull_N,
                    r.drive_torque_Nm,
                    r.power_W,
                    r.tractive_efficiency,
                    r.entry_angle_rad,
                )
            except SolverError as exc:
                failures.append(f"{task.material.name}/{task.model_name}/W={load:g}/s={slip:g}: {exc}")
                vals = (False, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
            rows.append((task.material.name, task.model_name, float(load), float(slip), *vals))
    return rows, failures


def force_slip_sweep(
    body: Body,
    media: Sequence[Material],
    models: Mapping[str, ModelFactory],
    loads: Sequence[float] | np.ndarray,
    slips: Sequence[float] | np.ndarray,
    *,
    omega: float = 1.0,
    phase_count: int = 16,
    on_point: Callable[[int], None] | None = None,
    scheduler: str = "serial",
    workers: int | None = None,
) -> TableResult:
    """Steady solves over media x models x loads x slips.

    ``models`` maps a model name to a factory ``material -> terrain model`` (a
    :class:`~terradyn.locomotion.models.ModelSpec` is one, and is picklable for ``scheduler`` other than
    ``"serial"``; see :func:`terradyn.parallel.map_items`). A point the model cannot solve (e.g. the
    load is more than the medium carries) is kept with ``solved = False`` and zeros, and its reason in
    ``metadata["failures"]``.
    """
    tasks = [
        _Task(
            body,
            mat,
            name,
            factory,
            tuple(float(v) for v in loads),
            tuple(float(v) for v in slips),
            omega,
            phase_count,
        )
        for mat in media
        for name, factory in models.items()
    ]
    per_task = len(loads) * len(slips)

    def done(n: int) -> None:
        if on_point is not None:
            on_point(n * per_task)

    results = map_items(_run_task, tasks, scheduler=scheduler, workers=workers, on_done=done)
    rows = [row for task_rows, _ in results for row in task_rows]
    failures = [f for _, task_failures in results for f in task_failures]
    names = ("material", "model", "load_N", "slip", "solved", *_VALUES)
    cols = {k: np.asarray([row[i] for row in rows]) for i, k in enumerate(names)}
    return TableResult(cols, {"body": repr(body), "omega_rad_s": omega, "failures": failures})
