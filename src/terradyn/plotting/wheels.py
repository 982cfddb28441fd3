"""Force-slip and sinkage-slip plots of wheel sweeps."""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["plot_force_slip"]

_QUANTITIES = (
    ("drawbar_pull_N", "drawbar pull [N]"),
    ("drive_torque_Nm", "drive torque [N m]"),
    ("sinkage_m", "sinkage [mm]"),
)
_STYLES = {"rft": "-", "wong-reece": "--", "drft": ":"}
_NAMES = {"rft": "RFT", "wong-reece": "Wong-Reece", "drft": "DRFT"}


def plot_force_slip(columns: dict[str, np.ndarray], *, material: str, axes: Any = None) -> Any:
    """Drawbar pull, drive torque and sinkage versus slip for one medium (a row of three axes).

    ``columns`` are those of :func:`terradyn.locomotion.force_slip_sweep`; one colour per load, one
    line style per model (RFT solid, Wong-Reece dashed), explained by one legend in the first axes.
    Unsolved points are left out. Returns the axes.
    """
    from matplotlib.lines import Line2D

    if axes is None:
        _, grid = new_force_slip_figure(1)
        axes = grid[0]
    sel_mat = columns["material"] == material
    loads = sorted(set(columns["load_N"][sel_mat].tolist()))
    models = list(dict.fromkeys(columns["model"][sel_mat].tolist()))
    colours = [f"C{i}" for i in range(len(loads))]
    for ax, (key, label) in zip(axes, _QUANTITIES, strict=True):
        for load, colour in zip(loads, colours, strict=True):
            for model in models:
                m = sel_mat & (columns["load_N"] == load) & (columns["model"] == model)
                m &= columns["solved"].astype(bool)
                if not np.any(m):
                    continue
                order = np.argsort(columns["slip"][m])
                y = columns[key][m][order] * (1e3 if key == "sinkage_m" else 1.0)
                ax.plot(
                    columns["slip"][m][order],
                    y,
                    _STYLES.get(model, "-."),
                    color=colour,
                    marker="o",
                    ms=2.5,
                )
        ax.set_xlabel("slip [-]")
        ax.set_ylabel(label)
        ax.axhline(0.0, color="0.7", lw=0.8)
        ax.grid(True, alpha=0.35)
        ax.set_title(f"{material}: {label.split(' [')[0]}")
    handles = [
        Line2D([], [], color=c, marker="o", ms=2.5, label=f"W = {w:g} N")
        for w, c in zip(loads, colours, strict=True)
    ]
    handles += [Line2D([], [], color="k", ls=_STYLES.get(m, "-."), label=_NAMES.get(m, m)) for m in models]
    axes[0].legend(handles=handles, fontsize=7, ncols=2 if len(handles) > 5 else 1)
    return axes


def new_force_slip_figure(material_count: int) -> tuple[Any, Any]:
    """A figure with one row of three axes per medium (constrained layout: no overlapping titles;
    callers need no ``tight_layout``)."""
    from .core import new_figure

    return new_figure(material_count, 3, figsize=(14, 3.8 * material_count + 0.4))
