"""The steps of ``terradyn wheel sweep``: its grid of points, the plane and 3D sweeps, one table."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ..errors import InputError
from ._common import parse_float_list

__all__ = ["SweepGrid", "SweepRun", "plane_table", "spatial_table", "stack", "sweep_grid"]


@dataclass(frozen=True)
class SweepGrid:
    """The points of a sweep: loads [N], slips [-] and slip angles [deg] (3D models only)."""

    loads: list[float]
    slips: list[float]
    angles: list[float]


@dataclass(frozen=True)
class SweepRun:
    """How every point is solved: spin ``omega`` [rad/s], slip definition, Dask ``scheduler`` and
    ``workers``, and ``on_point`` called after each point (the progress bar)."""

    omega: float
    slip_definition: str
    scheduler: str
    workers: int | None
    on_point: Callable[..., Any]


def sweep_grid(load: str, slip: str, slip_angle: str) -> SweepGrid:
    """The --load, --slip and --slip-angle lists (each a comma list or start:stop:count), checked."""
    loads = parse_float_list("--load", load)
    slips = parse_float_list("--slip", slip)
    for s in slips:
        if not -1.0 <= s <= 1.0:
            raise InputError("--slip", slip, "slips in [-1, 1]")
    angles = parse_float_list("--slip-angle", slip_angle)
    for a in angles:
        if not abs(a) < 90.0:
            raise InputError(
                "--slip-angle", slip_angle, "angles in (-90, 90) [deg]",
                "at 90 deg give the speeds: wheel steady --rim-speed --carriage-speed",
            )  # fmt: skip
    return SweepGrid(loads, slips, angles)


def plane_table(
    body: Any, media: list[Any], factories: dict[str, Any], grid: SweepGrid, run: SweepRun, phase_count: int
) -> Any:
    """The sweep of the plane models (one factory each) over ``media`` and the grid's loads and slips."""
    from ..locomotion import force_slip_sweep

    return force_slip_sweep(
        body,
        media,
        factories,
        grid.loads,
        grid.slips,
        omega=run.omega,
        phase_count=phase_count,
        on_point=run.on_point,
        scheduler=run.scheduler,
        workers=run.workers,
        slip_definition=run.slip_definition,
    )


def spatial_table(
    wheel: Any, media: list[Any], grid: SweepGrid, run: SweepRun, phase_count: int, culling: bool
) -> Any:
    """The 3D-RFT sweep of ``wheel`` over ``media`` and the whole grid (``culling``: the wheel's
    contact mesh for the grid's slip angles first)."""
    from ..locomotion.sweeps import force_slip_sweep_3d

    if culling:
        from ..locomotion.steady3d import wheel_contact_mesh

        wheel = wheel_contact_mesh(wheel, slip_angle=[math.radians(a) for a in grid.angles])
    return force_slip_sweep_3d(
        wheel,
        media,
        grid.loads,
        grid.slips,
        [math.radians(a) for a in grid.angles],
        omega=run.omega,
        phase_count=phase_count,
        slip_definition=run.slip_definition,
        on_point=run.on_point,
        scheduler=run.scheduler,
        workers=run.workers,
    )


def stack(tables: list[Any]) -> Any:
    """One table from plane and 3D sweep tables (plane rows get slip angle, side force and moment 0)."""
    if len(tables) == 1:
        return tables[0]
    import numpy as np

    from ..results import TableResult

    names = list(tables[-1].columns)
    cols = {}
    for name in names:
        parts = []
        for t in tables:
            n = len(t)
            parts.append(t.columns[name] if name in t.columns else np.zeros(n))
        cols[name] = np.concatenate(parts)
    meta = dict(tables[0].metadata)
    meta["failures"] = [f for t in tables for f in t.metadata["failures"]]
    return TableResult(cols, meta)
