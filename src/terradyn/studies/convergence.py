"""Grid convergence of MPM results: one case at three or more resolutions, the observed order and a
Richardson estimate of the converged value with an error band.

The estimates (Roache's grid convergence index for unequal refinement ratios, Celik et al. 2008, and a
least-squares limit over four or more resolutions) are general numerics, :mod:`terradyn.numerics`,
re-exported here; this module runs the MPM cases (intrusion, wheel, drag) at each cell size.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import InputError, check_positive
from ..numerics import (  # noqa: F401 - re-exported: the convergence study's public names
    FORMAL_ORDER,
    LeastSquaresLimit,
    RichardsonEstimate,
    least_squares_limit,
    richardson,
)

__all__ = [
    "ConvergenceResult",
    "RichardsonEstimate",
    "converge",
    "converge_drag",
    "converge_intrusion",
    "converge_wheel",
    "least_squares_limit",
    "richardson",
]


@dataclass(frozen=True)
class ConvergenceResult:
    """Results of one case at several cell sizes, and the Richardson estimate of each quantity."""

    cell_sizes: tuple[float, ...]
    values: Mapping[str, tuple[float, ...]]
    estimates: Mapping[str, RichardsonEstimate]
    wall_s: tuple[float, ...]
    metadata: Mapping[str, Any] = field(default_factory=dict)
    #: least-squares limits over every resolution (four or more cell sizes; else empty)
    fits: Mapping[str, LeastSquaresLimit] = field(default_factory=dict)
    #: with grid phases: each quantity's value at each phase, per resolution (``values`` hold the means)
    phase_values: Mapping[str, tuple[tuple[float, ...], ...]] = field(default_factory=dict)

    def runs(self) -> list[dict[str, Any]]:
        """One record per resolution: cell size [m], every quantity, wall time [s]."""
        rows = []
        for i, h in enumerate(self.cell_sizes):
            row: dict[str, Any] = {"cell_size_m": h}
            row.update({q: v[i] for q, v in self.values.items()})
            for q, phases in self.phase_values.items():
                row[f"{q}_phase_spread"] = max(phases[i]) - min(phases[i])
            row["wall_s"] = self.wall_s[i]
            rows.append(row)
        return rows

    def summary(self) -> list[dict[str, Any]]:
        """One record per quantity: finest value, observed order, extrapolated value, error band; with
        four or more resolutions also the least-squares limit (``ls_*``)."""
        out = []
        for q, est in self.estimates.items():
            fit = self.fits.get(q)
            ls = {}
            if fit is not None:
                ls = {
                    "ls_extrapolated": fit.extrapolated,
                    "ls_standard_error": fit.standard_error,
                    "ls_residual_sd": fit.residual_sd,
                    "relative_error_finest_ls": fit.relative_error,
                }
            out.append(
                {
                    "quantity": q,
                    "finest": est.finest,
                    "finest_cell_size_m": min(self.cell_sizes),
                    "observed_order": est.order,
                    "extrapolated": est.extrapolated,
                    "error_band": est.error_band,
                    "relative_error_finest": est.relative_error,
                    "monotone": est.monotone,
                    "note": est.note,
                    **ls,
                }
            )
        return out


def converge(
    run: Callable[..., Mapping[str, float]],
    cell_sizes: Sequence[float],
    quantities: Sequence[str],
    *,
    progress: Callable[[int, int], None] | None = None,
    metadata: Mapping[str, Any] | None = None,
    grid_phases: int = 1,
) -> ConvergenceResult:
    """Run ``run(cell_size)`` (returning a summary mapping) at each cell size, coarsest first, and
    estimate the converged value of each of ``quantities``. With ``grid_phases`` n > 1 each cell size
    runs n times, ``run(cell_size, surface_offset)`` with the grid moved by k / n of a cell against
    the bed's surface, and the estimates use the phases' mean (``phase_values`` keeps each phase's):
    an MPM force rings as a body crosses node lines, so one phase per cell size samples that ringing
    at a different point of its period at every resolution."""
    sizes = sorted({check_positive("cell_sizes", h) for h in cell_sizes}, reverse=True)
    if len(sizes) < 3:
        raise InputError("cell_sizes", list(cell_sizes), "three or more distinct cell sizes [m]")
    if not quantities:
        raise InputError("quantities", list(quantities), "one or more result names")
    if not isinstance(grid_phases, int) or grid_phases < 1:
        raise InputError("grid_phases", grid_phases, "an integer >= 1")
    values: dict[str, list[float]] = {q: [] for q in quantities}
    phases: dict[str, list[tuple[float, ...]]] = {q: [] for q in quantities}
    wall = []
    for i, h in enumerate(sizes):
        t0 = time.perf_counter()
        runs = []
        for k in range(grid_phases):
            if progress is not None:
                progress(i * grid_phases + k, len(sizes) * grid_phases)
            runs.append(run(h) if grid_phases == 1 else run(h, k / grid_phases))
        wall.append(time.perf_counter() - t0)
        for q in quantities:
            for summary in runs:
                if q not in summary:
                    raise InputError("quantities", q, f"a result of the case ({', '.join(summary)})")
            per_phase = tuple(float(summary[q]) for summary in runs)
            phases[q].append(per_phase)
            values[q].append(float(np.mean(per_phase)))
    if progress is not None:
        progress(len(sizes) * grid_phases, len(sizes) * grid_phases)
    estimates = {q: richardson(sizes, v) for q, v in values.items()}
    fits = {q: least_squares_limit(sizes, v) for q, v in values.items()} if len(sizes) >= 4 else {}
    meta = {**dict(metadata or {}), **({"grid_phases": grid_phases} if grid_phases > 1 else {})}
    per_phase_values = {q: tuple(v) for q, v in phases.items()} if grid_phases > 1 else {}
    return ConvergenceResult(tuple(sizes), {q: tuple(v) for q, v in values.items()}, estimates, tuple(wall),
                             meta, fits, per_phase_values)  # fmt: skip


def _resolution(run_options: dict[str, Any]) -> Any:
    """The case's :class:`~terradyn.mpm.Resolution` from ``resolution=`` and the flat resolution
    keywords in ``run_options`` (removed from it); its cell size is left to ``cell_sizes``."""
    from ..mpm.specs import LEGACY, Resolution, apply_legacy

    if "cell_size" in run_options:
        raise InputError("cell_size", run_options["cell_size"], "cell_sizes instead (three or more)")
    base = run_options.pop("resolution", Resolution())
    flat = {k: run_options.pop(k) for k in list(run_options) if LEGACY.get(k, ("",))[0] == "resolution"}
    base = apply_legacy("converge", flat, {"resolution": base})[0]["resolution"]
    if base.cell_size is not None:
        raise InputError("cell_size", base.cell_size, "cell_sizes instead (three or more)")
    return base


def _phase_bed(run_options: dict[str, Any], grid_phases: int, ppc: int) -> Any:
    """The case's :class:`~terradyn.mpm.Bed` (taken out of ``run_options``) when grid phases move its
    grid, else ``None``; the phases must divide the points per cell (each moves the grid by a whole
    number of point rows)."""
    from ..mpm.specs import Bed

    if grid_phases == 1:
        return None
    if not isinstance(grid_phases, int) or grid_phases < 1:
        raise InputError("grid_phases", grid_phases, "an integer >= 1")
    if any(k in run_options for k in ("bed_depth", "bed_width", "bed_length", "packing", "walls")):
        raise InputError("grid_phases", grid_phases, "bed settings given as bed=Bed(...) with grid phases")
    if ppc % grid_phases:
        raise InputError(
            "grid_phases", grid_phases, f"a divisor of the points per cell along an axis ({ppc})"
        )
    bed = run_options.pop("bed", Bed())
    if bed.surface_offset:
        raise InputError("bed.surface_offset", bed.surface_offset, "0 with grid phases (they set it)")
    return bed


def _case_run(
    run_case: Callable[..., Any], body: Any, material: Any, run_options: dict[str, Any], grid_phases: int
) -> Callable[..., Mapping[str, float]]:
    """``run(cell_size, surface_offset=0)`` -> the summary of ``run_case(body, material, ...)`` with the
    case's resolution at that cell size and, with grid phases, its bed at that surface offset."""
    base = _resolution(run_options)
    bed = _phase_bed(run_options, grid_phases, base.particles_per_cell)

    def run(h: float, offset: float = 0.0) -> Mapping[str, float]:
        beds = {} if bed is None else {"bed": bed.replace(surface_offset=offset)}
        return run_case(body, material, resolution=base.replace(cell_size=h), **beds, **run_options).summary

    return run


def converge_intrusion(
    body: Any,
    material: Any,
    *,
    cell_sizes: Sequence[float],
    quantities: Sequence[str] = ("force_z_N", "force_x_N"),
    progress: Callable[[int, int], None] | None = None,
    grid_phases: int = 1,
    **run_options: Any,
) -> ConvergenceResult:
    """:func:`terradyn.mpm.run_intrusion` of ``body`` at each cell size; other options (specs such as
    ``bed=`` and ``resolution=``, kinematics, flat keywords) as there; ``grid_phases`` as in
    :func:`converge` (it must divide the resolution's points per cell)."""
    from ..mpm import run_intrusion

    run = _case_run(run_intrusion, body, material, run_options, grid_phases)

    return converge(run, cell_sizes, quantities, progress=progress, metadata={"case": "intrusion"},
                    grid_phases=grid_phases)  # fmt: skip


def converge_wheel(
    wheel: Any,
    material: Any,
    *,
    cell_sizes: Sequence[float],
    quantities: Sequence[str] = ("sinkage_m", "drawbar_pull_N", "drive_torque_Nm"),
    progress: Callable[[int, int], None] | None = None,
    grid_phases: int = 1,
    **run_options: Any,
) -> ConvergenceResult:
    """:func:`terradyn.mpm.run_wheel` of ``wheel`` at each cell size; other options (specs such as
    ``bed=``, ``resolution=``, ``drive=``, the wheel's commands, flat keywords) as there;
    ``grid_phases`` as in :func:`converge`."""
    from ..mpm import run_wheel

    run = _case_run(run_wheel, wheel, material, run_options, grid_phases)

    return converge(run, cell_sizes, quantities, progress=progress, metadata={"case": "wheel"},
                    grid_phases=grid_phases)  # fmt: skip


def converge_drag(
    body: Any,
    material: Any,
    *,
    cell_sizes: Sequence[float],
    quantities: Sequence[str] = ("drag_N", "lift_N"),
    progress: Callable[[int, int], None] | None = None,
    grid_phases: int = 1,
    **run_options: Any,
) -> ConvergenceResult:
    """:func:`terradyn.mpm.run_drag` of ``body`` (buried at ``depth=``, dragged ``distance=``) at each
    cell size; other options (specs such as ``bed=``, ``resolution=``, ``stroke=``, flat keywords)
    as there; ``grid_phases`` as in :func:`converge`."""
    from ..mpm import run_drag

    run = _case_run(run_drag, body, material, run_options, grid_phases)

    return converge(run, cell_sizes, quantities, progress=progress, metadata={"case": "drag"},
                    grid_phases=grid_phases)  # fmt: skip
