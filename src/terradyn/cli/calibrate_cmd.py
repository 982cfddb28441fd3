"""``terradyn calibrate``: fit material parameters to measurements and write a material TOML."""

from __future__ import annotations

from pathlib import Path

import typer

from ..errors import InputError
from ._common import OutputFormat, emit

app = typer.Typer(help="Fit RFT or Bekker parameters to measurements.", no_args_is_help=True)


def register(root: typer.Typer) -> None:
    root.add_typer(app, name="calibrate")


@app.command("rft")
def calibrate_rft(
    data: Path = typer.Argument(..., help="CSV: depth_m, force_z_N [, force_x_N, angle_deg, direction_deg]."),
    plate_length: float = typer.Option(..., "--plate-length", help="Plate length [m]."),
    plate_width: float = typer.Option(..., "--plate-width", help="Plate width [m]."),
    full: bool = typer.Option(False, "--full", help="Fit all nine coefficients, not only zeta."),
    name: str = typer.Option("calibrated", "--name", help="Name of the new material."),
    material_out: Path | None = typer.Option(None, "--material-out", help="Write a material TOML."),
    fmt: OutputFormat = typer.Option(OutputFormat.table, "--format", help="Output format."),
    out: Path | None = typer.Option(None, "--out", help="Also write the report to this file."),
) -> None:
    """Fit the RFT scale zeta (or the full alpha fit) to plate force-depth data."""
    from ..rft.calibration import fit_rft, read_plate_force_csv, write_rft_material_toml

    if material_out is not None and material_out.suffix != ".toml":
        raise InputError("--material-out", str(material_out), "a path ending in .toml")
    fit = fit_rft(read_plate_force_csv(data), plate_length=plate_length, plate_width=plate_width, full=full)
    rec = {
        "zeta_N_per_m3": fit.zeta,
        "r_squared": fit.r_squared,
        "rms_residual_N": fit.rms_residual_N,
        "values_fitted": fit.point_count,
        "full": fit.full,
    }
    if fit.full:
        for key, value in zip(fit.rft.coefficients.names(), fit.rft.coefficients.as_array(), strict=True):
            rec[f"{key}_N_per_m3"] = float(value) * fit.rft.scale
    if material_out is not None:
        write_rft_material_toml(material_out, name, fit, source=data.name)
    emit(rec, fmt, out)
