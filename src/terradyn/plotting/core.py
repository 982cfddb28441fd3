"""Plots of RFT results (alpha maps, force versus depth, traction arrows)."""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = [
    "new_axes",
    "new_figure",
    "plot_alpha_map",
    "plot_alpha_maps",
    "plot_body_tractions",
    "plot_force_depth",
]


def new_axes(ax: Any = None, *, figsize: tuple[float, float] = (6.0, 4.5)) -> Any:
    """The given axes, or new ones on a non-interactive figure with constrained layout."""
    if ax is not None:
        return ax
    _, axes = new_figure(1, 1, figsize=figsize)
    return axes[0, 0]


def new_figure(
    nrows: int,
    ncols: int,
    *,
    figsize: tuple[float, float],
    sharex: bool = False,
    sharey: bool = False,
) -> tuple[Any, Any]:
    """A figure and its 2D array of axes, laid out by matplotlib's constrained layout (no overlaps)."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(
        nrows, ncols, figsize=figsize, sharex=sharex, sharey=sharey, squeeze=False, layout="constrained"
    )
    return fig, axes


# The library holds alpha in N/m^3; plots show the literature's N/cm^3 and say how they were converted.
_ALPHA_UNIT_NOTE = "[N/cm$^3$]\n(= N/m$^3$ $\\times$ 10$^{-6}$)"
_ANGLE_TICKS = np.arange(-180.0, 181.0, 30.0)


def _symmetric_limit(*arrays: np.ndarray) -> float:
    """Largest |value| over the finite entries (1 when all are zero or none are finite)."""
    finite = [np.abs(a[np.isfinite(a)]) for a in map(np.asarray, arrays)]
    hi = max((float(f.max()) for f in finite if f.size), default=0.0)
    return hi if hi > 0 else 1.0


def plot_alpha_map(
    beta: np.ndarray,
    gamma: np.ndarray,
    alpha: np.ndarray,
    *,
    label: str,
    ax: Any = None,
    limit: float | None = None,
    colorbar: bool = True,
    xlabel: str = r"$\beta$ [deg]",
    ylabel: str = r"$\gamma$ [deg]",
) -> Any:
    """Heat map of one alpha component [N/m^3] over beta and gamma grids [rad] (2D arrays).

    Shown in N/cm^3 (the literature's unit) on a diverging colour map centred on zero: blue pulls, red
    pushes, white is no stress. ``limit`` [N/m^3] is the half-range of the colour scale (default: the
    largest |alpha|); pass the same one to several maps to compare them. ``colorbar=False`` leaves the
    colour bar to the caller (it can use ``ax.collections[0]``). Returns the axes.
    """
    from matplotlib.colors import CenteredNorm

    ax = new_axes(ax)
    half = (_symmetric_limit(alpha) if limit is None else float(limit)) / 1e6
    mesh = ax.pcolormesh(
        np.degrees(beta),
        np.degrees(gamma),
        np.asarray(alpha) / 1e6,
        shading="auto",
        cmap="RdBu_r",
        norm=CenteredNorm(vcenter=0.0, halfrange=half),
    )
    if colorbar:
        ax.figure.colorbar(mesh, ax=ax, label=f"{label} {_ALPHA_UNIT_NOTE}")
    _degree_axes(ax, np.degrees(beta), np.degrees(gamma))
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(label)
    return ax


def _degree_axes(ax: Any, xdeg: np.ndarray, ydeg: np.ndarray) -> None:
    """Ticks every 30 degrees within the data range, square cells."""
    for values, setter in ((xdeg, ax.set_xticks), (ydeg, ax.set_yticks)):
        lo, hi = float(np.min(values)), float(np.max(values))
        setter(_ANGLE_TICKS[(_ANGLE_TICKS >= lo - 1e-9) & (_ANGLE_TICKS <= hi + 1e-9)])
    ax.set_aspect("equal")


def plot_alpha_maps(
    beta: np.ndarray,
    gamma: np.ndarray,
    alpha_x: np.ndarray,
    alpha_z: np.ndarray,
    *,
    title: str = "",
    xlabel: str = r"$\beta$ [deg]",
    ylabel: str = r"$\gamma$ [deg]",
) -> Any:
    """alpha_z and alpha_x [N/m^3] over beta and gamma grids [rad] side by side; returns the Figure.

    Both panels share one colour scale centred on zero (the two components compare directly, as in
    Li et al. 2013, fig. 2) and one colour bar in N/cm^3.
    """
    fig, axes = new_figure(1, 2, figsize=(10.5, 4.6), sharey=True)
    limit = _symmetric_limit(alpha_x, alpha_z)
    for ax, values, name in zip(axes[0], (alpha_z, alpha_x), (r"$\alpha_z$", r"$\alpha_x$"), strict=True):
        plot_alpha_map(
            beta, gamma, values, label=name, ax=ax, limit=limit, colorbar=False, xlabel=xlabel, ylabel=ylabel
        )
    axes[0, 1].set_ylabel("")
    fig.colorbar(axes[0, 0].collections[0], ax=axes[0, :], label=rf"$\alpha$ {_ALPHA_UNIT_NOTE}", shrink=0.9)
    if title:
        fig.suptitle(title)
    return fig


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
