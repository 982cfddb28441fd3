"""Reading materials from TOML files and the registry of shipped media."""

from __future__ import annotations

import math
import tomllib
from functools import cache
from importlib import resources
from pathlib import Path
from typing import Any

from ..errors import InputError
from ._material import (
    BekkerParameters,
    ContinuumParameters,
    DEMParameters,
    LiCoefficients,
    Material,
    Provenance,
    RFTParameters,
)

__all__ = ["available", "from_dict", "get", "load"]

_SECTIONS = {"meta", "rft", "bekker", "density", "continuum", "friction", "drft", "dem"}
_META_KEYS = {"name", "description", "citation", "doi", "table", "notes"}
_RFT_KEYS = {"coefficients", "zeta_N_per_cm3", "zeta_N_per_m3", "scale_N_per_m3", "notes"}
_BEKKER_KEYS = {
    "k_c_N_per_m_n1",
    "k_phi_N_per_m_n2",
    "n",
    "cohesion_Pa",
    "friction_angle_deg",
    "shear_modulus_m",
    "notes",
}
_DENSITY_KEYS = {"grain_kg_m3", "bulk_kg_m3", "critical_kg_m3", "notes"}
_CONTINUUM_KEYS = {
    "youngs_modulus_Pa",
    "poisson_ratio",
    "friction_coefficient",
    "friction_coefficient_2",
    "inertial_number_0",
    "grain_diameter_m",
    "surface_friction",
    "notes",
}
_FRICTION_KEYS = {"internal_friction_angle_deg", "surface_friction", "notes"}
_DRFT_KEYS = {"lambda", "notes"}
#: [dem] key -> DEMParameters field
_DEM_FIELDS = {
    "grain_diameter_m": "grain_diameter",
    "diameter_spread": "diameter_spread",
    "grain_density_kg_m3": "grain_density",
    "youngs_modulus_Pa": "youngs_modulus",
    "poisson_ratio": "poisson_ratio",
    "friction": "friction",
    "rolling_friction": "rolling_friction",
    "restitution": "restitution",
    "wall_friction": "wall_friction",
}


def _check_keys(section: str, table: Any, allowed: set[str], where: str) -> dict[str, Any]:
    if not isinstance(table, dict):
        raise InputError(f"{where}[{section}]", table, "a TOML table")
    for key in table:
        if key not in allowed:
            raise InputError(f"{where}[{section}].{key}", table[key], f"one of {sorted(allowed)}")
    return table


def _number(table: dict[str, Any], key: str, section: str, where: str) -> float:
    if key not in table:
        raise InputError(f"{where}[{section}].{key}", None, "a number (the key is required)")
    value = table[key]
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise InputError(f"{where}[{section}].{key}", value, "a number")
    return float(value)


def _coefficients(value: Any, where: str) -> LiCoefficients:
    if value == "generic":
        return LiCoefficients.generic()
    if isinstance(value, dict):
        names = LiCoefficients.names()
        _check_keys("rft.coefficients", value, set(names), where)
        missing = [n for n in names if n not in value]
        if missing:
            raise InputError(f"{where}[rft.coefficients]", sorted(value), f"all of {list(names)}")
        return LiCoefficients(**{n: _number(value, n, "rft.coefficients", where) for n in names})
    raise InputError(f"{where}[rft].coefficients", value, '"generic" or a table of the nine coefficients')


def _rft(table: dict[str, Any], where: str) -> RFTParameters:
    _check_keys("rft", table, _RFT_KEYS, where)
    coeffs = _coefficients(table.get("coefficients", "generic"), where)
    given = [k for k in ("zeta_N_per_cm3", "zeta_N_per_m3", "scale_N_per_m3") if k in table]
    if len(given) != 1:
        raise InputError(
            f"{where}[rft]",
            given,
            "exactly one of zeta_N_per_cm3, zeta_N_per_m3, scale_N_per_m3",
        )
    key = given[0]
    value = _number(table, key, "rft", where)
    if key == "scale_N_per_m3":
        return RFTParameters(coeffs, value)
    zeta = value * 1.0e6 if key == "zeta_N_per_cm3" else value
    if zeta <= 0:
        raise InputError(f"{where}[rft].{key}", value, "a number > 0")
    return RFTParameters(coeffs, zeta / coeffs.alpha_z_plate_down())


def _dem(table: Any, where: str) -> DEMParameters:
    d = _check_keys("dem", table, {*_DEM_FIELDS, "notes"}, where)
    values = {name: _number(d, key, "dem", where) for key, name in _DEM_FIELDS.items()}
    return DEMParameters(**values, notes=str(d.get("notes", "")))


def from_dict(data: dict[str, Any], *, source: str = "<dict>") -> Material:
    """Build a :class:`Material` from the parsed content of a material TOML file."""
    where = source
    for section in data:
        if section not in _SECTIONS:
            raise InputError(f"{where}[{section}]", "...", f"one of the sections {sorted(_SECTIONS)}")
    meta = _check_keys("meta", data.get("meta", {}), _META_KEYS, where)
    if "name" not in meta:
        raise InputError(f"{where}[meta].name", None, "a material name")
    rft = _rft(data["rft"], where) if "rft" in data else None
    bekker = None
    if "bekker" in data:
        b = _check_keys("bekker", data["bekker"], _BEKKER_KEYS, where)
        bekker = BekkerParameters(
            k_c=_number(b, "k_c_N_per_m_n1", "bekker", where),
            k_phi=_number(b, "k_phi_N_per_m_n2", "bekker", where),
            n=_number(b, "n", "bekker", where),
            cohesion=_number(b, "cohesion_Pa", "bekker", where),
            friction_angle=math.radians(_number(b, "friction_angle_deg", "bekker", where)),
            shear_modulus=_number(b, "shear_modulus_m", "bekker", where),
        )
    density = _check_keys("density", data.get("density", {}), _DENSITY_KEYS, where)
    continuum = None
    if "continuum" in data:
        c = _check_keys("continuum", data["continuum"], _CONTINUUM_KEYS, where)
        mu_s = _number(c, "friction_coefficient", "continuum", where)
        continuum = ContinuumParameters(
            youngs_modulus=_number(c, "youngs_modulus_Pa", "continuum", where),
            poisson_ratio=_number(c, "poisson_ratio", "continuum", where),
            friction_coefficient=mu_s,
            friction_coefficient_2=(
                _number(c, "friction_coefficient_2", "continuum", where)
                if "friction_coefficient_2" in c
                else mu_s
            ),
            inertial_number_0=(
                _number(c, "inertial_number_0", "continuum", where) if "inertial_number_0" in c else 0.278
            ),
            grain_diameter=(
                _number(c, "grain_diameter_m", "continuum", where) if "grain_diameter_m" in c else 1e-3
            ),
            surface_friction=(
                _number(c, "surface_friction", "continuum", where) if "surface_friction" in c else 0.4
            ),
        )
    dem = _dem(data["dem"], where) if "dem" in data else None
    friction = _check_keys("friction", data.get("friction", {}), _FRICTION_KEYS, where)
    drft = _check_keys("drft", data.get("drft", {}), _DRFT_KEYS, where)

    def opt(table: dict[str, Any], key: str, section: str) -> float | None:
        return _number(table, key, section, where) if key in table else None

    phi_deg = opt(friction, "internal_friction_angle_deg", "friction")
    return Material(
        name=str(meta["name"]),
        description=str(meta.get("description", "")),
        rft=rft,
        bekker=bekker,
        continuum=continuum,
        grain_density=opt(density, "grain_kg_m3", "density"),
        bulk_density=opt(density, "bulk_kg_m3", "density"),
        critical_density=opt(density, "critical_kg_m3", "density"),
        internal_friction_angle=math.radians(phi_deg) if phi_deg is not None else None,
        drft_lambda=opt(drft, "lambda", "drft"),
        surface_friction=opt(friction, "surface_friction", "friction"),
        dem=dem,
        provenance=Provenance(
            citation=str(meta.get("citation", "")),
            doi=str(meta.get("doi", "")),
            table=str(meta.get("table", "")),
            notes=str(meta.get("notes", "")),
        ),
    )


def load(path: str | Path) -> Material:
    """Read a material TOML file (the format of the shipped ``data/*.toml``)."""
    p = Path(path)
    if not p.is_file():
        raise InputError("material file", str(path), "an existing TOML file")
    try:
        data = tomllib.loads(p.read_text(encoding="utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise InputError("material file", str(path), "valid TOML", str(exc)) from None
    return from_dict(data, source=p.name)


@cache
def _shipped() -> dict[str, Material]:
    out: dict[str, Material] = {}
    for entry in resources.files("terradyn.materials").joinpath("data").iterdir():
        if entry.name.endswith(".toml"):
            data = tomllib.loads(entry.read_text(encoding="utf-8"))
            mat = from_dict(data, source=entry.name)
            out[mat.name.lower()] = mat
    return out


def available() -> list[str]:
    """Names of the shipped media, sorted."""
    return sorted(m.name for m in _shipped().values())


def get(name: str | Material) -> Material:
    """A shipped medium by name (case-insensitive), or a path to a TOML file, or a Material as is."""
    if isinstance(name, Material):
        return name
    if not isinstance(name, str):
        raise InputError("material", name, "a material name or a TOML file path")
    shipped = _shipped()
    key = name.strip().lower()
    if key in shipped:
        return shipped[key]
    if key.endswith(".toml"):
        return load(name)
    raise InputError("material", name, f"one of {available()} or a path to a .toml file")
