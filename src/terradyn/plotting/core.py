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
    "plot_sweep_forces",
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
    ax.grid(True, alpha=0.35)
    ax.legend()
    return ax


def plot_sweep_forces(rows: list[dict[str, float]], *, title: str = "") -> Any:
    """Vertical and horizontal force [N] against depth of a sweep's rows (keys ``depth_m``,
    ``angle_deg``, ``direction_deg``, ``force_z_N``, ``force_x_N``): one line per (angle, direction),
    depths sorted. Returns the figure."""
    fig, axes = new_figure(1, 2, figsize=(10.0, 4.2), sharex=True)
    groups: dict[tuple[float, float], list[dict[str, float]]] = {}
    for r in rows:
        groups.setdefault((r["angle_deg"], r["direction_deg"]), []).append(r)
    for (angle, direction), members in sorted(groups.items()):
        members = sorted(members, key=lambda r: r["depth_m"])
        depth = np.array([r["depth_m"] for r in members]) * 1e3
        label = f"angle {angle:g}°, direction {direction:g}°"
        for ax, key in ((axes[0, 0], "force_z_N"), (axes[0, 1], "force_x_N")):
            ax.plot(depth, [r[key] for r in members], marker="o", ms=4, label=label)
    for ax, name in ((axes[0, 0], "vertical force F$_z$ [N]"), (axes[0, 1], "horizontal force F$_x$ [N]")):
        ax.set_xlabel("depth of the reference point [mm]")
        ax.set_ylabel(name)
        ax.axhline(0.0, color="0.6", lw=0.8)
        ax.grid(True, alpha=0.35)
    axes[0, 0].legend(fontsize=8)
    if title:
        fig.suptitle(title)
    return fig


def plot_body_tractions(
    outline: list[np.ndarray],
    positions: np.ndarray,
    forces: np.ndarray,
    *,
    surface_level: float = 0.0,
    ax: Any = None,
    title: str = "",
) -> Any:
    """A body outline (world polygons [m]) with per-element force arrows [N] and the free surface.

    Neighbouring elements are summed in runs of k so at most ~24 arrows are drawn (the key says k). The
    arrows share one length scale (the largest is drawn a quarter of the body size long), shown by a key
    arrow in newtons; the bed below ``surface_level`` [m] is shaded. Returns the axes.
    """
    ax = new_axes(ax)
    pts = np.vstack([np.asarray(p) for p in outline]) if outline else np.asarray(positions)
    size = float(np.ptp(pts, axis=0).max()) if len(pts) else 1.0
    for poly in outline:
        closed = np.vstack((poly, poly[:1]))
        ax.fill(closed[:, 0], closed[:, 1], facecolor="0.88", edgecolor="k", lw=1.0, zorder=2)
    forces = np.asarray(forces, dtype=float).reshape(-1, 2)
    active = np.hypot(forces[:, 0], forces[:, 1]) > 0
    pos, total, k = bin_arrows(np.asarray(positions, dtype=float).reshape(-1, 2)[active], forces[active])
    if len(total):
        peak = float(np.hypot(total[:, 0], total[:, 1]).max())
        metres_per_newton = 0.25 * size / peak
        f = total * metres_per_newton
        q = ax.quiver(
            pos[:, 0],
            pos[:, 1],
            f[:, 0],
            f[:, 1],
            color="tab:red",
            angles="xy",
            scale_units="xy",
            scale=1,
            width=0.004,
            zorder=3,
        )
        key = _nice(0.5 * peak)
        ax.quiverkey(
            q,
            0.82,
            0.06,
            key * metres_per_newton,
            f"RFT force, {key:g} N per {'element' if k == 1 else f'{k} elements'}",
            labelpos="N",
            coordinates="axes",
            fontproperties={"size": 8},
        )
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    pad = 0.35 * size
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(min(lo[1], surface_level) - pad, max(hi[1], surface_level) + pad)
    ax.axhspan(ax.get_ylim()[0] - size, surface_level, color="tan", alpha=0.35, lw=0, zorder=0)
    ax.axhline(surface_level, color="saddlebrown", lw=1.2, label="free surface", zorder=1)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    ax.legend(loc="upper right", fontsize=8)
    if title:
        ax.set_title(title)
    return ax


def bin_arrows(
    positions: np.ndarray, forces: np.ndarray, max_arrows: int = 24
) -> tuple[np.ndarray, np.ndarray, int]:
    """Consecutive elements in runs of ``k`` (so at most ~``max_arrows`` arrows): mean position [m] and
    summed force [N] of each run, and ``k`` (1 when there are few elements)."""
    k = max(1, int(np.ceil(len(forces) / max_arrows)))
    if len(forces) == 0:
        return np.zeros((0, 2)), np.zeros((0, 2)), k
    groups = np.arange(len(forces)) // k
    count = np.bincount(groups).astype(float)
    mean_pos = np.column_stack([np.bincount(groups, weights=positions[:, j]) / count for j in (0, 1)])
    total = np.column_stack([np.bincount(groups, weights=forces[:, j]) for j in (0, 1)])
    return mean_pos, total, k


def _nice(value: float) -> float:
    """1, 2 or 5 times a power of ten, at most ``value`` (> 0)."""
    exp = np.floor(np.log10(value))
    for m in (5.0, 2.0, 1.0):
        if m * 10**exp <= value:
            return float(m * 10**exp)
    return float(10**exp)  # pragma: no cover - m = 1 always fits
