"""Write a :class:`Material` as a material TOML file (the format :func:`terradyn.materials.load` reads)."""

from __future__ import annotations

import math
from pathlib import Path

from ._material import LiCoefficients, Material

__all__ = ["material_to_toml", "write_material"]


def _q(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", " ") + '"'


def _f(value: float) -> str:
    return repr(float(value))


def material_to_toml(material: Material) -> str:
    """Every parameter of ``material`` as TOML text; ``load`` of it gives back an equal material."""
    m = material
    p = m.provenance
    lines = ["[meta]", f"name = {_q(m.name)}", f"description = {_q(m.description)}"]
    meta = (("citation", p.citation), ("doi", p.doi), ("table", p.table), ("notes", p.notes))
    lines += [f"{key} = {_q(value)}" for key, value in meta if value]
    if m.rft is not None:
        lines += ["", "[rft]", f"scale_N_per_m3 = {_f(m.rft.scale)}"]
        generic = LiCoefficients.generic().as_array()
        own = m.rft.coefficients.as_array()
        if all(a == b for a, b in zip(own, generic, strict=True)):
            lines.append('coefficients = "generic"')
        else:
            lines.append("[rft.coefficients]")
            lines += [f"{k} = {_f(v)}" for k, v in zip(LiCoefficients.names(), own, strict=True)]
    if m.bekker is not None:
        b = m.bekker
        lines += [
            "", "[bekker]", f"k_c_N_per_m_n1 = {_f(b.k_c)}", f"k_phi_N_per_m_n2 = {_f(b.k_phi)}",
            f"n = {_f(b.n)}", f"cohesion_Pa = {_f(b.cohesion)}",
            f"friction_angle_deg = {_f(math.degrees(b.friction_angle))}",
            f"shear_modulus_m = {_f(b.shear_modulus)}",
        ]  # fmt: skip
    density = [(k, v) for k, v in (("grain_kg_m3", m.grain_density), ("bulk_kg_m3", m.bulk_density),
                                   ("critical_kg_m3", m.critical_density)) if v is not None]  # fmt: skip
    if density:
        lines += ["", "[density]"] + [f"{k} = {_f(v)}" for k, v in density]
    friction = []
    if m.internal_friction_angle is not None:
        friction.append(f"internal_friction_angle_deg = {_f(math.degrees(m.internal_friction_angle))}")
    if m.surface_friction is not None:
        friction.append(f"surface_friction = {_f(m.surface_friction)}")
    if friction:
        lines += ["", "[friction]", *friction]
    if m.drft_lambda is not None:
        lines += ["", "[drft]", f"lambda = {_f(m.drft_lambda)}"]
    if m.continuum is not None:
        c = m.continuum
        lines += [
            "", "[continuum]", f"youngs_modulus_Pa = {_f(c.youngs_modulus)}",
            f"poisson_ratio = {_f(c.poisson_ratio)}",
            f"friction_coefficient = {_f(c.friction_coefficient)}",
            f"friction_coefficient_2 = {_f(c.friction_coefficient_2)}",
            f"inertial_number_0 = {_f(c.inertial_number_0)}", f"grain_diameter_m = {_f(c.grain_diameter)}",
            f"surface_friction = {_f(c.surface_friction)}",
        ]  # fmt: skip
    if m.dem is not None:
        d = m.dem
        lines += [
            "", "[dem]", f"grain_diameter_m = {_f(d.grain_diameter)}",
            f"diameter_spread = {_f(d.diameter_spread)}",
            f"grain_density_kg_m3 = {_f(d.grain_density)}", f"youngs_modulus_Pa = {_f(d.youngs_modulus)}",
            f"poisson_ratio = {_f(d.poisson_ratio)}", f"friction = {_f(d.friction)}",
            f"rolling_friction = {_f(d.rolling_friction)}", f"restitution = {_f(d.restitution)}",
            f"wall_friction = {_f(d.wall_friction)}",
        ]  # fmt: skip
        if d.notes:
            lines.append(f"notes = {_q(d.notes)}")
    return "\n".join(lines) + "\n"


def write_material(path: str | Path, material: Material) -> Path:
    """Write ``material`` to ``path`` (.toml) atomically (through :mod:`terradyn.io`)."""
    from ..errors import InputError
    from ..io import atomic_write_text

    p = Path(path)
    if p.suffix != ".toml":
        raise InputError("path", str(path), "a path ending in .toml")
    return atomic_write_text(p, material_to_toml(material))
