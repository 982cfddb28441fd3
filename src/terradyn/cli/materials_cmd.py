"""``terradyn materials``: list and show the shipped media."""

from __future__ import annotations

import math
from typing import Any

import typer

from .. import materials
from ._common import OutputFormat, emit
from .options import FORMAT, OUT, out_file

app = typer.Typer(help="Granular media and their parameters.", no_args_is_help=True, rich_markup_mode=None)


def material_record(mat: materials.Material) -> dict[str, Any]:
    rec: dict[str, Any] = {"name": mat.name, "description": mat.description}
    if mat.rft is not None:
        rec["rft_zeta_N_per_m3"] = mat.rft.zeta
        for key, value in zip(mat.rft.coefficients.names(), mat.rft.coefficients.as_array(), strict=True):
            rec[f"rft_{key}"] = float(value)
        rec["rft_scale_N_per_m3"] = mat.rft.scale
    if mat.bekker is not None:
        b = mat.bekker
        rec.update(
            {
                "bekker_k_c_N_per_m_n1": b.k_c,
                "bekker_k_phi_N_per_m_n2": b.k_phi,
                "bekker_n": b.n,
                "cohesion_Pa": b.cohesion,
                "friction_angle_deg": math.degrees(b.friction_angle),
                "shear_modulus_m": b.shear_modulus,
            }
        )
    if mat.continuum is not None:
        c = mat.continuum
        rec.update(
            {
                "youngs_modulus_Pa": c.youngs_modulus,
                "poisson_ratio": c.poisson_ratio,
                "friction_coefficient": c.friction_coefficient,
                "friction_coefficient_2": c.friction_coefficient_2,
                "surface_friction": c.surface_friction,
            }
        )
    for key in ("grain_density", "bulk_density", "critical_density"):
        value = getattr(mat, key)
        if value is not None:
            rec[f"{key}_kg_m3"] = value
    if mat.internal_friction_angle is not None:
        rec["internal_friction_angle_deg"] = math.degrees(mat.internal_friction_angle)
    if mat.drft_lambda is not None:
        rec["drft_lambda"] = mat.drft_lambda
    rec["citation"] = mat.provenance.citation
    rec["doi"] = mat.provenance.doi
    rec["notes"] = mat.provenance.notes
    return rec


@app.command("list")
def list_(
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
) -> None:
    """List the shipped media."""
    out_path = out_file("--out", out)
    rows = []
    for name in materials.available():
        m = materials.get(name)
        rows.append(
            {
                "name": m.name,
                "zeta_N_per_m3": m.rft.zeta if m.rft else None,
                "bekker": m.bekker is not None,
                "continuum": m.continuum is not None,
                "description": m.description,
            }
        )
    emit(rows, fmt, out_path, title="terradyn media")


@app.command("show")
def show(
    name: str = typer.Argument(..., help="Medium name or a path to a material TOML file."),
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
) -> None:
    """Show every parameter of one medium, with its source."""
    out_path = out_file("--out", out)
    rec = material_record(materials.get(name))
    if fmt is OutputFormat.table:
        emit([{"parameter": k, "value": v} for k, v in rec.items()], fmt, out_path, title=name)
    else:
        emit(rec, fmt, out_path)
