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


@app.command("bekker")
def calibrate_bekker(
    plates: Path = typer.Option(..., "--plates", help="CSV: plate_width_m, sinkage_m, pressure_Pa."),
    shear: Path | None = typer.Option(
        None, "--shear", help="CSV: normal_stress_Pa, shear_displacement_m, shear_stress_Pa."
    ),
    name: str = typer.Option("calibrated", "--name", help="Name of the new material."),
    material_out: Path | None = typer.Option(
        None, "--material-out", help="Write a material TOML (needs --shear)."
    ),
    fmt: OutputFormat = typer.Option(OutputFormat.table, "--format", help="Output format."),
    out: Path | None = typer.Option(None, "--out", help="Also write the report to this file."),
) -> None:
    """Fit k_c, k_phi, n to plate-sinkage tests (two or more widths) and c, phi, K to shear tests."""
    import math

    from ..terramechanics import (
        combine_fits,
        fit_bekker,
        fit_shear,
        read_plate_sinkage_csv,
        read_shear_csv,
        write_material_toml,
    )

    if material_out is not None and (shear is None or material_out.suffix != ".toml"):
        raise InputError("--material-out", str(material_out), "a .toml path, together with --shear")
    pfit = fit_bekker(read_plate_sinkage_csv(plates))
    rec: dict[str, object] = {
        "k_c_N_per_m_n1": pfit.k_c,
        "k_phi_N_per_m_n2": pfit.k_phi,
        "n": pfit.n,
        "pressure_r_squared": pfit.r_squared,
        "pressure_rms_residual_Pa": pfit.rms_residual,
        "plate_widths": len(pfit.plate_widths),
    }
    if shear is not None:
        sfit = fit_shear(read_shear_csv(shear))
        rec.update(
            {
                "cohesion_Pa": sfit.cohesion,
                "friction_angle_deg": math.degrees(sfit.friction_angle),
                "shear_modulus_m": sfit.shear_modulus,
                "shear_r_squared": sfit.r_squared,
                "shear_rms_residual_Pa": sfit.rms_residual,
            }
        )
        if material_out is not None:
            notes = (
                f"Bekker and Janosi-Hanamoto parameters fitted by terradyn calibrate bekker to "
                f"{plates.name} (R^2 = {pfit.r_squared:.4f}) and {shear.name} (R^2 = {sfit.r_squared:.4f})."
            )
            write_material_toml(
                material_out,
                name,
                bekker=combine_fits(pfit, sfit),
                description="Bekker fit to plate-sinkage and shear tests",
                notes=notes,
            )
    emit(rec, fmt, out)
