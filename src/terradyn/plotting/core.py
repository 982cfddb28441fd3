"""Plots of RFT results (alpha maps, force versus depth, traction arrows)."""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["new_axes", "plot_alpha_map", "plot_body_tractions", "plot_force_depth"]


def new_axes(ax: Any = None, *, figsize: tuple[float, float] = (6.0, 4.5)) -> Any:
    """The given axes, or new ones on a non-interactive figure."""
    if ax is not None:
        return ax
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    _, ax = plt.subplots(figsize=figsize)
    return ax


def plot_alpha_map(
    beta: np.ndarray, gamma: np.ndarray, alpha: np.ndarray, *, label: str, ax: Any = None
) -> Any:
    """Heat map of one alpha component [N/m^3] over beta and gamma grids [rad] (2D arrays)."""
    ax = new_axes(ax)
    mesh = ax.pcolormesh(np.degrees(beta), np.degrees(gamma), alpha / 1e6, shading="auto", cmap="RdBu_r")
    ax.figure.colorbar(mesh, ax=ax, label=f"{label} [N/cm$^3$]")
    ax.set_xlabel(r"$\beta$ [deg]")
    ax.set_ylabel(r"$\gamma$ [deg]")
    ax.set_title(label)
    return ax


def plot_force_depth(
    depth: np.ndarray, forces: dict[str, np.ndarray], *, ax: Any = None, title: str = ""
) -> Any:
    """Force components [N] versus depth [m], one line per entry of ``forces``."""
    ax = new_axes(ax)
    for name, values in forces.items():
        ax.plot(np.asarray(depth) * 1e3, values, marker="o", ms=3, label=name)
    ax.set_xlabel("depth [mm]")
    ax.set_ylabel("force [N]")
    ax.axhline(0.0, color="0.6", lw=0.8)
    if title:
        ax.set_title(title)
    ax.legend()
    return ax


def plot_body_tractions(
    outline: list[np.ndarray],
    positions: np.ndarray,
    forces: np.ndarray,
    *,
    surface_level: float = 0.0,
    ax: Any = None,
    title: str = "",
) -> Any:
    """A body outline (world polygons [m]) with per-element force arrows and the free surface."""
    ax = new_axes(ax)
    for poly in outline:
        closed = np.vstack((poly, poly[:1]))
        ax.plot(closed[:, 0], closed[:, 1], color="k", lw=1.0)
    active = np.hypot(forces[:, 0], forces[:, 1]) > 0
    if np.any(active):
        ax.quiver(
            positions[active, 0],
            positions[active, 1],
            forces[active, 0],
            forces[active, 1],
            color="tab:red",
            angles="xy",
            width=0.004,
        )
    ax.axhline(surface_level, color="tab:brown", lw=1.2)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    if title:
        ax.set_title(title)
    return ax
