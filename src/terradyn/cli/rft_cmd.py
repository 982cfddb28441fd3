"""``terradyn rft``: the RFT force law itself."""

from __future__ import annotations

import math

import numpy as np
import typer

from .. import materials
from ..errors import InputError, check_finite
from ..rft import li2013_alpha_material
from ._common import OutputFormat, emit, save_figure
from .options import FORMAT, MATERIAL, OUT, PLOT, out_file, plot_file

app = typer.Typer(
    help="Granular resistive force theory (Li et al. 2013 law).", no_args_is_help=True, rich_markup_mode=None
)


@app.command("alpha")
def alpha(
    material: str = MATERIAL,
    beta: float | None = typer.Option(None, "--beta", help="Element orientation beta [deg]."),
    gamma: float | None = typer.Option(None, "--gamma", help="Direction of motion gamma [deg]."),
    grid: bool = typer.Option(False, "--grid", help="Tabulate the whole alpha map instead."),
    step: float = typer.Option(5.0, "--step", help="Grid step [deg] for --grid."),
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    plot: str | None = PLOT,
) -> None:
    """Stress per depth (alpha_x, alpha_z) [N/m^3] at one (beta, gamma), or the whole map (--grid)."""
    out_path, plot_path = out_file("--out", out), plot_file("--plot", plot)
    mat = materials.get(material)
    if not grid:
        if beta is None or gamma is None:
            raise InputError("--beta/--gamma", (beta, gamma), "both angles in degrees, or --grid")
        if plot_path is not None:
            raise InputError("--plot", str(plot), "only with --grid")
        b = math.radians(check_finite("--beta", beta))
        g = math.radians(check_finite("--gamma", gamma))
        ax, az = li2013_alpha_material(b, g, mat)
        emit({"alpha_x_N_per_m3": float(ax), "alpha_z_N_per_m3": float(az)}, fmt, out_path)
        return
    if not (0.25 <= check_finite("--step", step) <= 45.0):
        raise InputError("--step", step, "a grid step in [0.25, 45] degrees")
    grid_deg = np.arange(-90.0, 90.0 + 1e-9, step)
    bb, gg = np.meshgrid(np.radians(grid_deg), np.radians(grid_deg), indexing="ij")
    map_x, map_z = li2013_alpha_material(bb, gg, mat)
    rows = [
        {
            "beta_deg": float(bi),
            "gamma_deg": float(gi),
            "alpha_x_N_per_m3": float(axi),
            "alpha_z_N_per_m3": float(azi),
        }
        for bi, gi, axi, azi in zip(
            np.degrees(bb).ravel(), np.degrees(gg).ravel(), map_x.ravel(), map_z.ravel(), strict=True
        )
    ]
    if plot_path is not None:
        from ..plotting import plot_alpha_maps

        fig = plot_alpha_maps(bb, gg, map_x, map_z, title=f"RFT alpha map, {mat.name}")
        save_figure(fig, plot_path)
    emit(rows, fmt, out_path, title=f"alpha map, {mat.name}")
