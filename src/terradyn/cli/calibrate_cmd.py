"""``terradyn calibrate``: fit material parameters to measurements and write a material TOML."""

from __future__ import annotations

import dataclasses
from typing import Any

import typer

from ..errors import InputError
from ._common import OutputFormat, emit
from .options import FORMAT, MATERIAL, OUT, input_file, out_file, with_flags

app = typer.Typer(
    help="Fit RFT, Bekker or MPM parameters to measurements.", no_args_is_help=True, rich_markup_mode=None
)


def _dem_flags() -> Any:
    from .dem_cmd import DEM_CALIBRATION_FLAGS

    return with_flags("dem", DEM_CALIBRATION_FLAGS)


@app.command("rft")
@_dem_flags()
def calibrate_rft(
    data: str | None = typer.Argument(
        None, help="CSV: depth_m, force_z_N [, force_x_N, angle_deg, direction_deg] (or --from-dem)."
    ),
    length: float = typer.Option(..., "--length", help="Plate length [m]."),
    width: float = typer.Option(..., "--width", help="Plate width (out of plane) [m]."),
    full: bool = typer.Option(False, "--full", help="Fit all nine coefficients, not only zeta."),
    name: str = typer.Option("calibrated", "--name", help="Name of the new material."),
    material_out: str | None = typer.Option(None, "--material-out", help="Write a material TOML (.toml)."),
    from_dem: str | None = typer.Option(
        None, "--from-dem", help="Medium (name or TOML) to run DEM virtual plate tests in instead of DATA."
    ),
    dem: dict[str, Any] = {},  # the --dem-* flags of the virtual plate test (DEM_CALIBRATION_FLAGS)  # noqa: B006
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
) -> None:
    """Fit the RFT scale zeta (or the full alpha fit) to plate force-depth data or DEM plate tests."""
    from ..rft.calibration import fit_rft, read_plate_force_csv, write_rft_material_toml

    if from_dem is not None or data is None:
        from .dem_cmd import calibrate_from_dem

        return calibrate_from_dem(data, from_dem, length=length, width=width, full=full, name=name,
                                  material_out=material_out, fmt=fmt, out=out, **dem)  # fmt: skip
    data_path = input_file("DATA", data)
    assert data_path is not None
    toml_path = out_file("--material-out", material_out, (".toml",))
    out_path = out_file("--out", out)
    if not name.strip():
        raise InputError("--name", name, "a non-empty material name")
    fit = fit_rft(read_plate_force_csv(data_path), plate_length=length, plate_width=width, full=full)
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
    if toml_path is not None:
        write_rft_material_toml(toml_path, name, fit, source=data_path.name)
    emit(rec, fmt, out_path)


@app.command("bekker")
def calibrate_bekker(
    plates: str = typer.Option(..., "--plates", help="CSV: plate_width_m, sinkage_m, pressure_Pa."),
    shear: str | None = typer.Option(
        None, "--shear", help="CSV: normal_stress_Pa, shear_displacement_m, shear_stress_Pa."
    ),
    name: str = typer.Option("calibrated", "--name", help="Name of the new material."),
    material_out: str | None = typer.Option(
        None, "--material-out", help="Write a material TOML (.toml; needs --shear)."
    ),
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
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

    plates_path = input_file("--plates", plates)
    shear_path = input_file("--shear", shear)
    assert plates_path is not None
    toml_path = out_file("--material-out", material_out, (".toml",))
    out_path = out_file("--out", out)
    if toml_path is not None and shear_path is None:
        raise InputError("--material-out", material_out, "a .toml path, together with --shear")
    if not name.strip():
        raise InputError("--name", name, "a non-empty material name")
    pfit = fit_bekker(read_plate_sinkage_csv(plates_path))
    rec: dict[str, object] = {
        "k_c_N_per_m_n1": pfit.k_c,
        "k_phi_N_per_m_n2": pfit.k_phi,
        "n": pfit.n,
        "pressure_r_squared": pfit.r_squared,
        "pressure_rms_residual_Pa": pfit.rms_residual,
        "plate_widths": len(pfit.plate_widths),
    }
    if shear_path is not None:
        sfit = fit_shear(read_shear_csv(shear_path))
        rec.update(
            {
                "cohesion_Pa": sfit.cohesion,
                "friction_angle_deg": math.degrees(sfit.friction_angle),
                "shear_modulus_m": sfit.shear_modulus,
                "shear_r_squared": sfit.r_squared,
                "shear_rms_residual_Pa": sfit.rms_residual,
            }
        )
        if toml_path is not None:
            notes = (
                f"Bekker and Janosi-Hanamoto parameters fitted by terradyn calibrate bekker to "
                f"{plates_path.name} (R^2 = {pfit.r_squared:.4f}) and {shear_path.name} "
                f"(R^2 = {sfit.r_squared:.4f})."
            )
            write_material_toml(
                toml_path,
                name,
                bekker=combine_fits(pfit, sfit),
                description="Bekker fit to plate-sinkage and shear tests",
                notes=notes,
            )
    emit(rec, fmt, out_path)


@app.command("mpm")
def calibrate_mpm(
    data: str = typer.Argument(..., help="CSV: depth_m, force_z_N [, force_x_N, angle_deg, direction_deg]."),
    length: float = typer.Option(..., "--length", help="Plate length [m]."),
    width: float = typer.Option(..., "--width", help="Plate width (out of plane) [m]."),
    material: str = MATERIAL,
    cell_size: float | None = typer.Option(None, "--cell-size", help="MPM grid cell size [m] of the fit."),
    speed: float = typer.Option(0.05, "--speed", help="Intrusion speed [m/s] of the MPM runs."),
    tolerance: float = typer.Option(0.01, "--tolerance", help="Accepted |data/model scale - 1| [-]."),
    name: str = typer.Option("calibrated", "--name", help="Name of the new material."),
    material_out: str | None = typer.Option(None, "--material-out", help="Write a material TOML (.toml)."),
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
) -> None:
    """Fit the MPM continuum friction mu_s to plate force-depth data (the CSV of 'calibrate rft')."""
    from .. import materials
    from ..rft.calibration import read_plate_force_csv
    from ..studies.mpm_calibration import fit_mpm_friction
    from ._common import fraction_progress

    data_path = input_file("DATA", data)
    assert data_path is not None
    toml_path = out_file("--material-out", material_out, (".toml",))
    out_path = out_file("--out", out)
    if not name.strip():
        raise InputError("--name", name, "a non-empty material name")
    if not 0 < tolerance < 0.5:
        raise InputError("--tolerance", tolerance, "a number in (0, 0.5)")
    base = materials.get(material)
    plate_data = read_plate_force_csv(data_path)
    with fraction_progress("fitting mu_s with MPM", "trials") as update:
        fit = fit_mpm_friction(
            plate_data, base, plate_length=length, plate_width=width, cell_size=cell_size, speed=speed,
            tolerance=tolerance, progress=lambda done, total: update(done, done / total),
        )  # fmt: skip
    if toml_path is not None:
        from ..materials import write_material

        notes = (
            f"MPM continuum friction fitted by terradyn calibrate mpm to {data_path.name}: "
            f"mu_s = {fit.friction_coefficient:.4g} (data/model scale {fit.scale:.4f}, "
            f"R^2 = {fit.r_squared:.4f}, "
            f"{len(fit.trials)} MPM runs per orientation at cell size {cell_size or 'default'}); other "
            f"parameters from {base.name}."
        )
        fitted = fit.material.with_changes(
            name=name, provenance=dataclasses.replace(base.provenance, notes=notes, table="")
        )
        write_material(toml_path, fitted)
    emit(fit.record(), fmt, out_path)
