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

__all__ = ["force_slip_sweep", "force_slip_sweep_3d"]

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
    slip_definition: str = "classic"


def _run_task(task: _Task) -> tuple[list[tuple[Any, ...]], list[str]]:
    """All loads x slips of one (medium, model): rows of values and failure messages."""
    model = task.factory(task.material)
    rows, failures = [], []
    for load in task.loads:
        for slip in task.slips:
            try:
                r = wheel_steady(
                    task.body, model, load, slip, omega=task.omega, phase_count=task.phase_count,
                    slip_definition=task.slip_definition,
                )  # fmt: skip
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
    slip_definition: str = "classic",
) -> TableResult:
    """Steady solves over media x models x loads x slips (``slip_definition``: classic or bounded).

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
            slip_definition,
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


@dataclass(frozen=True)
class _Task3D:
    mesh: Any
    medium: Any
    medium_name: str
    load: float
    slip_angle: float
    slips: tuple[float, ...]
    options: tuple[tuple[str, Any], ...]


_VALUES_3D = (*_VALUES, "side_force_N", "aligning_moment_Nm")


def _run_task_3d(task: _Task3D) -> tuple[list[tuple[Any, ...]], list[str]]:
    """All slips of one (medium, load, slip angle) in 3D RFT: rows of values and failure messages."""
    from .steady3d import wheel_steady_3d

    rows, failures = [], []
    for slip in task.slips:
        try:
            r = wheel_steady_3d(
                task.mesh, task.medium, task.load, slip, slip_angle=task.slip_angle, **dict(task.options)
            )
            vals: tuple[Any, ...] = (True, *(getattr(r, k) for k in _VALUES_3D))
        except SolverError as exc:
            failures.append(
                f"{task.medium_name}/rft3d/W={task.load:g}/s={slip:g}/"
                f"angle={np.degrees(task.slip_angle):g} deg: {exc}"
            )
            vals = (False, *([0.0] * len(_VALUES_3D)))
        angle_deg = float(f"{np.degrees(task.slip_angle):.12g}")  # 30, not 29.999999999999996
        rows.append((task.medium_name, "rft3d", task.load, float(slip), angle_deg, *vals))
    return rows, failures


def force_slip_sweep_3d(
    mesh: Any,
    media: Sequence[Material | float],
    loads: Sequence[float] | np.ndarray,
    slips: Sequence[float] | np.ndarray,
    slip_angles: Sequence[float] | np.ndarray = (0.0,),
    *,
    omega: float = 1.0,
    phase_count: int = 1,
    period: float | None = None,
    slip_definition: str = "classic",
    on_point: Callable[[int], None] | None = None,
    scheduler: str = "serial",
    workers: int | None = None,
) -> TableResult:
    """3D-RFT steady solves of a wheel mesh over media x loads x slips x slip angles [rad].

    Media are Materials or 3D-RFT scales xi [N/m^3]. The columns are those of :func:`force_slip_sweep`
    (material, model = "rft3d", load_N, slip, solved, sinkage_m, drawbar_pull_N, drive_torque_Nm,
    power_W, tractive_efficiency, entry_angle_rad) plus slip_angle_deg, side_force_N and
    aligning_moment_Nm, so the two tables stack. Failed points as there (``solved = False``, zeros,
    reasons in ``metadata["failures"]``). Each (medium, load, slip angle) is one task of
    :func:`terradyn.parallel.map_items`.
    """
    options = (
        ("omega", omega), ("phase_count", phase_count), ("period", period),
        ("slip_definition", slip_definition),
    )  # fmt: skip
    tasks = [
        _Task3D(
            mesh,
            medium,
            medium.name if isinstance(medium, Material) else f"xi={float(medium):g}",
            float(load),
            float(angle),
            tuple(float(v) for v in slips),
            options,
        )
        for medium in media
        for load in loads
        for angle in slip_angles
    ]
    per_task = len(slips)

    def done(n: int) -> None:
        if on_point is not None:
            on_point(n * per_task)

    results = map_items(_run_task_3d, tasks, scheduler=scheduler, workers=workers, on_done=done)
    rows = [row for task_rows, _ in results for row in task_rows]
    failures = [f for _, task_failures in results for f in task_failures]
    names = ("material", "model", "load_N", "slip", "slip_angle_deg", "solved", *_VALUES_3D)
    cols = {k: np.asarray([row[i] for row in rows]) for i, k in enumerate(names)}
    meta = {
        "body": f"mesh of {getattr(mesh, 'facet_count', 0)} facets", "omega_rad_s": omega,
        "slip_definition": slip_definition, "failures": failures,
    }  # fmt: skip
    return TableResult(cols, meta)
