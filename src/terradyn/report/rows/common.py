"""What the rows of several chapters share: verdicts, studies, the MPM intrusion run and its settings,
the wheel force-slip axes and the drag fluctuation measure.

Nothing here registers a row; the rows are named in :data:`terradyn.report.rows.ROWS`.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..outputs import Finding

__all__ = [
    "DEM_QUICK_NOTE",
    "DILATANCY_K",
    "GRAVISH_TRANSITION",
    "INTRUSION_FULL",
    "INTRUSION_QUICK",
    "MEDIA",
    "MPM_MATERIAL",
    "PLOW_IMMERSED",
    "PLOW_LENGTH",
    "STROKE_QUICK_NOTE",
    "TRAVEL_QUICK_NOTE",
    "IntrusionSetting",
    "RunSetting",
    "bed_outgrown_findings",
    "fluctuations",
    "force_slip_axes",
    "intrude",
    "intrusion_setting",
    "study",
    "verdict",
]

#: the four media of the thesis's wheel chapters
MEDIA = ("MS", "MMS", "LPS", "CPS")
#: the medium of the MPM intrusion and drag rows
MPM_MATERIAL = "MS"
#: dilatancy constant of the MPM packing and plowing rows; not calibrated to any medium (see docs/mpm.md
#: "Dilatancy")
DILATANCY_K = 4.0
#: packing fraction near which Gravish et al. (2010) see the drag change from smooth to fluctuating
GRAVISH_TRANSITION = 0.605
#: the plowing plate of the MPM and DEM rows: 35 mm long, 5 mm of it above the surface (30 mm immersed);
#: its centre is at 12.5 mm
PLOW_LENGTH, PLOW_IMMERSED = 0.035, 0.03

#: the quick form of the MPM rows that push a plate (chapter 4)
STROKE_QUICK_NOTE = "quick form: coarse cells, doubled speed, short stroke, small bed; not converged"
#: the quick form of the MPM rows of superposition and the drag runs (chapter 9)
TRAVEL_QUICK_NOTE = "quick form: coarse cells, doubled speed, short travel, small bed; not converged"
#: the quick form of the DEM rows
DEM_QUICK_NOTE = "quick form: a plate a few grains long, a few hundred grains; not converged"


def verdict(ok: bool) -> str:
    """The verdict of a finding whose check ``ok`` passed or failed."""
    return "agrees" if ok else "disagrees"


def study(name: str, quick: bool, **overrides: Any) -> Any:
    """The result of the registered study ``name`` (:func:`terradyn.studies.registry.run_study`)."""
    from ...studies.registry import run_study

    return run_study(name, quick=quick, overrides=overrides)[1]


def bed_outgrown_findings(runs: dict[str, dict[str, Any]]) -> list[Finding]:
    """One finding naming the wheel runs (label -> run metadata) that outgrew their bed
    (:func:`~terradyn.mpm.wheel_runs.bed_limits`), or none when none did."""
    from ...mpm.wheel_runs import bed_limits

    parts = [f"{label}: {text}" for label, meta in runs.items() for text, _, _ in bed_limits(meta)]
    if not parts:
        return []
    return [
        Finding(
            "bed outgrown, so these readings depend on the bed's size (docs/mpm.md, sections on the floor "
            "under a wheel that sinks and on the bow wave): " + "; ".join(parts),
            "info",
        )
    ]


@dataclass(frozen=True)
class IntrusionSetting:
    """Resolution, stroke and bed of an intrusion row: cell size [m], speed [m/s], minimum cells across,
    averaging window [m] (None: the run's default), bed width and depth [m] (None: the sizing rule)."""

    cell_size: float
    speed: float
    min_cells: int
    window: float | None = None
    bed_width: float | None = None
    bed_depth: float | None = None

    def as_dict(self) -> dict[str, Any]:
        return {
            "cell_size_m": self.cell_size,
            "speed_m_s": self.speed,
            "min_cells_across": self.min_cells,
            "averaging_window_m": self.window or "default",
            "bed_m": "sized by the intrusion rule"
            if self.bed_width is None
            else f"{self.bed_width:g} x {self.bed_depth:g} (smaller than the sizing rule)",
        }


#: quick: 12.5 mm cells (3.2 across the 40 mm plate), 0.1 m/s, a 10 mm averaging window and a small
#: bed (a smoke form); full: 5 mm cells, 0.05 m/s and the default bed and window (docs/mpm.md tables)
INTRUSION_QUICK = IntrusionSetting(0.0125, 0.1, 3, window=0.01, bed_width=0.3, bed_depth=0.125)
INTRUSION_FULL = IntrusionSetting(0.005, 0.05, 6)


def intrusion_setting(quick: bool) -> IntrusionSetting:
    """The setting of the chapter 9 intrusion rows (packing, wedges) in the quick or the full form."""
    return INTRUSION_QUICK if quick else INTRUSION_FULL


@functools.lru_cache(maxsize=64)
def intrude(
    body: Any,
    depth: float,
    setting: IntrusionSetting,
    *,
    material: str = MPM_MATERIAL,
    packing: str = "consolidated",
    dilatancy: float = 0.0,
    angle_deg: float = 0.0,
    direction_deg: float = 90.0,
) -> tuple[dict[str, np.ndarray], dict[str, float]]:
    """One MPM intrusion (:func:`terradyn.mpm.run_intrusion`) of ``body`` to ``depth`` [m] in
    ``material``: along ``direction_deg`` [deg below +x] with the body at ``angle_deg`` [deg], into a
    bed of ``packing`` with dilatancy constant ``dilatancy`` [-]; the series (depth, forces) and the
    summary. The defaults are :func:`~terradyn.mpm.run_intrusion`'s own (straight down, no tilt, a
    consolidated bed, the medium without dilatancy). Cached in-process: rows run serially share a run."""
    from ... import materials
    from ...mpm.runs import run_intrusion
    from ...mpm.specs import Bed, Resolution, Stroke

    res = run_intrusion(
        body,
        materials.get(material),
        depth=depth,
        angle=math.radians(angle_deg),
        direction=math.radians(direction_deg),
        speed=setting.speed,
        bed=Bed(packing=packing, width=setting.bed_width, depth=setting.bed_depth),
        resolution=Resolution(cell_size=setting.cell_size, min_cells_across=setting.min_cells),
        stroke=Stroke(averaging_window=setting.window),
        dilatancy=dilatancy,
    )
    series = {k: np.asarray(res.series[k]) for k in ("depth_m", "force_x_N", "force_z_N")}
    return series, dict(res.summary)


@dataclass(frozen=True)
class RunSetting:
    """Resolution and travel of a row: cell size [m], speed [m/s], distance [m], fewest cells across,
    bed length and depth [m] (None: the run's sizing rule), intrusion averaging window [m]."""

    cell_size: float
    speed: float
    distance: float
    min_cells: int
    bed_width: float | None = None
    bed_depth: float | None = None
    window: float | None = None

    def as_dict(self) -> dict[str, Any]:
        return {
            "cell_size_m": self.cell_size,
            "speed_m_s": self.speed,
            "distance_m": self.distance,
            "min_cells_across": self.min_cells,
            "bed_m": "sized by the run's rule"
            if self.bed_width is None
            else f"{self.bed_width:g} x {self.bed_depth:g} (smaller than the sizing rule)",
        }


def force_slip_axes(
    axes: Any,
    rows: list[dict[str, Any]],
    media: Sequence[str],
    *,
    rft_label: str = "RFT",
    title: str = "",
    legend: bool = True,
) -> None:
    """Drawbar pull, drive torque and sinkage against slip on three ``axes``: MPM solid, RFT dashed,
    one colour per medium of ``media``; ``rows`` hold ``material``, ``slip`` and the ``*_mpm_*`` /
    ``*_rft_*`` values of the wheel rows. ``legend``: one legend for the figure, below the axes (the
    figure needs constrained layout), so it never covers a curve."""
    quantities = (("drawbar_pull", "N", 1.0), ("drive_torque", "Nm", 1.0), ("sinkage", "m", 1e3))
    for k, name in enumerate(media):
        sel = [r for r in rows if r["material"] == name]
        slips = [r["slip"] for r in sel]
        for ax, (key, unit, scale) in zip(axes, quantities, strict=True):
            for model, style, label in (("mpm", "o-", "MPM"), ("rft", "s--", rft_label)):
                values = [r[f"{key}_{model}_{unit}"] * scale for r in sel]
                ax.plot(slips, values, style, color=f"C{k}", label=f"{name} {label}")
    for ax, ylabel in zip(axes, ("drawbar pull [N]", "drive torque [N m]", "sinkage [mm]"), strict=True):
        if title:
            ax.set_title(f"{title}: {ylabel.split(' [')[0]}")
        ax.set_xlabel("slip [-]")
        ax.set_ylabel(ylabel)
        ax.grid(True, alpha=0.35)
    if legend:
        handles, labels = axes[0].get_legend_handles_labels()
        ncols = min(len(labels), 8)
        axes[0].figure.legend(handles, labels, loc="outside lower center", ncols=ncols, fontsize=8)


def fluctuations(distance: np.ndarray, force: np.ndarray) -> dict[str, float]:
    """Character of a force signal over travel: mean [N], std / mean [-] of the linearly detrended
    signal, and the first peak of its autocorrelation after the first zero crossing: its lag [m]
    (the period of a periodic signal) and height [-] (near 1: periodic; near 0 or none: irregular).
    ``peak_lag_m`` is NaN-free: 0 with height 0 when there is no peak."""
    d, f = np.asarray(distance, dtype=float), np.asarray(force, dtype=float)
    mean = float(f.mean())
    resid = f - np.polyval(np.polyfit(d, f, 1), d) if len(f) > 2 else f - mean
    rel = float(resid.std() / abs(mean)) if mean != 0 else 0.0
    lag, height = 0.0, 0.0
    if len(resid) > 8 and resid.std() > 0:
        r = resid - resid.mean()
        # unbiased estimate: each lag's sum over its own number of pairs
        ac = np.correlate(r, r, mode="full")[len(r) - 1 :] / (r @ r) * len(r) / np.arange(len(r), 0, -1)
        neg = np.flatnonzero(ac < 0.0)
        if len(neg):
            tail = ac[neg[0] : len(ac) // 2]
            if len(tail) > 2:
                k = int(np.argmax(tail))
                if 0 < k < len(tail) - 1:
                    step = float(np.mean(np.diff(d)))
                    lag, height = (neg[0] + k) * step, float(tail[k])
    return {"mean_N": mean, "relative_std": rel, "peak_lag_m": lag, "peak_height": height}
