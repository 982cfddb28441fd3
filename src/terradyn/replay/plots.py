"""Figures of a replay: parity (predicted vs measured, error bars, 1:1 line) and residuals vs slip or
slip angle. Each takes the per-run records of :class:`~terradyn.replay.ReplayResult` and returns the
figure (matplotlib is imported here, when a figure is asked for)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from .table import QUANTITIES

__all__ = ["plot_parity", "plot_residuals"]

_LABELS = {
    "drawbar_pull_N": ("drawbar pull", "N", 1.0),
    "drive_torque_Nm": ("drive torque", "N m", 1.0),
    "sinkage_m": ("sinkage", "mm", 1e3),
    "side_force_N": ("side force", "N", 1.0),
}
_COLOURS = {"calibration": "tab:blue", "held-out": "tab:orange", "all": "tab:blue"}


def _present(runs: Sequence[dict[str, Any]]) -> list[str]:
    return [q for q in QUANTITIES if any(r.get(f"residual_{q}") is not None for r in runs)]


def _grid(count: int, title: str) -> tuple[Any, list[Any]]:
    import matplotlib.pyplot as plt

    cols = min(2, max(1, count))
    rows = (max(1, count) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(5.2 * cols, 4.4 * rows), squeeze=False)
    flat = list(axes.ravel())
    for ax in flat[count:]:
        ax.set_visible(False)
    fig.suptitle(title)
    return fig, flat[:count]


def _series(runs: Sequence[dict[str, Any]], q: str, key: str) -> dict[str, tuple[np.ndarray, ...]]:
    """Per set: (x, measured, predicted, residual, std) arrays of the runs with a residual of ``q``."""
    out: dict[str, tuple[np.ndarray, ...]] = {}
    for name in ("calibration", "held-out", "all"):
        rs = [r for r in runs if r["set"] == name and r.get(f"residual_{q}") is not None]
        if not rs:
            continue
        out[name] = tuple(
            np.array([float(r.get(k) or 0.0) for r in rs])
            for k in (key, f"measured_{q}", f"predicted_{q}", f"residual_{q}", f"std_{q}")
        )
    return out


def plot_parity(runs: Sequence[dict[str, Any]], *, title: str = "replay: predicted vs measured") -> Any:
    """Predicted vs measured per quantity, measured standard deviations as error bars, 1:1 line."""
    quantities = _present(runs)
    fig, axes = _grid(len(quantities), title)
    for ax, q in zip(axes, quantities, strict=True):
        name, unit, f = _LABELS[q]
        lo, hi = np.inf, -np.inf
        for set_name, (_, m, p, _, sd) in _series(runs, q, "slip").items():
            ax.errorbar(
                m * f, p * f, xerr=sd * f if np.any(sd > 0) else None, fmt="o", ms=4, capsize=2,
                color=_COLOURS[set_name], label=f"{set_name} runs ({m.size})",
            )  # fmt: skip
            lo, hi = (
                min(lo, float(np.min(m * f)), float(np.min(p * f))),
                max(hi, float(np.max(m * f)), float(np.max(p * f))),
            )
        pad = 0.05 * (hi - lo) if hi > lo else 1.0
        ax.plot([lo - pad, hi + pad], [lo - pad, hi + pad], "k--", lw=1, label="1:1")
        ax.set_xlabel(f"measured {name} [{unit}]")
        ax.set_ylabel(f"predicted {name} [{unit}]")
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def plot_residuals(runs: Sequence[dict[str, Any]], *, against: str = "slip", title: str | None = None) -> Any:
    """Residual (predicted - measured) per quantity against ``slip`` [-] or ``slip_angle_deg`` [deg]."""
    quantities = _present(runs)
    xlabel = "slip (omega r - V) / max(omega r, V) [-]" if against == "slip" else "slip angle [deg]"
    fig, axes = _grid(
        len(quantities), title or f"replay: residuals vs {xlabel.split(' [')[0].split(' (')[0]}"
    )
    for ax, q in zip(axes, quantities, strict=True):
        name, unit, f = _LABELS[q]
        for set_name, (x, _, _, r, sd) in _series(runs, q, against).items():
            ax.errorbar(
                x, r * f, yerr=sd * f if np.any(sd > 0) else None, fmt="o", ms=4, capsize=2,
                color=_COLOURS[set_name], label=f"{set_name} runs ({x.size})",
            )  # fmt: skip
        ax.axhline(0.0, color="k", lw=1, ls="--", label="zero residual")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(f"{name} residual, predicted - measured [{unit}]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    return fig
