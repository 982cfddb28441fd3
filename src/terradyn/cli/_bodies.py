"""Build a body from CLI flags: one table says which size flags each shape takes."""

from __future__ import annotations

import math
from enum import Enum
from typing import Any

import typer

from .. import geometry
from ..errors import InputError
from .options import DEFAULT_BODY_WIDTH

__all__ = ["BODY_FLAGS", "BodyKind", "BodyOptions", "build_body"]


class BodyKind(str, Enum):
    plate = "plate"
    cylinder = "cylinder"
    square = "square"
    half_cylinder = "half-cylinder"
    wedge = "wedge"
    wheel = "wheel"
    grousered = "grousered"
    flapped = "flapped"
    c_leg = "c-leg"
    polygon = "polygon"


# shape -> (constructor name in terradyn.geometry, {flag: keyword}), required flags have no default.
BODY_FLAGS: dict[BodyKind, tuple[str, dict[str, str]]] = {
    BodyKind.plate: ("Plate", {"length": "length", "thickness": "thickness"}),
    BodyKind.cylinder: ("Cylinder", {"radius": "radius"}),
    BodyKind.square: ("Square", {"side": "side"}),
    BodyKind.half_cylinder: ("HalfCylinder", {"radius": "radius"}),
    BodyKind.wedge: ("Wedge", {"base": "base", "height": "height", "tip_offset": "tip_offset"}),
    BodyKind.wheel: ("WheelCircular", {"radius": "radius"}),
    BodyKind.grousered: (
        "WheelGrousered",
        {
            "radius": "radius",
            "grouser_count": "grouser_count",
            "grouser_height": "grouser_height",
            "grouser_thickness": "grouser_thickness",
        },
    ),
    BodyKind.flapped: (
        "WheelFlapped",
        {
            "hub_radius": "hub_radius",
            "flap_count": "flap_count",
            "flap_length": "flap_length",
            "flap_angle": "flap_angle",
            "thickness": "flap_thickness",
        },
    ),
    BodyKind.c_leg: ("CLeg", {"radius": "radius", "thickness": "thickness"}),
    BodyKind.polygon: ("Polygon", {"points_file": "path"}),
}
_OPTIONAL = {"thickness", "tip_offset"}


class BodyOptions:
    """Typer options of every size flag (all optional; the shape decides which apply)."""

    length = typer.Option(None, "--length", help="Plate length [m].")
    width = typer.Option(DEFAULT_BODY_WIDTH, "--width", help="Out-of-plane width of the body [m].")
    thickness = typer.Option(None, "--thickness", help="Plate/flap/C-leg thickness [m].")
    radius = typer.Option(None, "--radius", help="Radius [m] (cylinder, wheel rim, C-leg).")
    side = typer.Option(None, "--side", help="Square side [m].")
    base = typer.Option(None, "--base", help="Wedge base (top) length [m].")
    height = typer.Option(None, "--height", help="Wedge height [m].")
    tip_offset = typer.Option(None, "--tip-offset", help="Wedge tip offset from centre [m].")
    grouser_count = typer.Option(None, "--grouser-count", help="Number of grousers.")
    grouser_height = typer.Option(None, "--grouser-height", help="Grouser height [m].")
    grouser_thickness = typer.Option(None, "--grouser-thickness", help="Grouser thickness [m].")
    hub_radius = typer.Option(None, "--hub-radius", help="Flapped-wheel hub radius [m].")
    flap_count = typer.Option(None, "--flap-count", help="Number of flaps.")
    flap_length = typer.Option(None, "--flap-length", help="Flap length [m].")
    flap_angle = typer.Option(None, "--flap-angle", help="Flap angle from radial [deg].")
    points_file = typer.Option(None, "--points-file", help="Polygon vertices (CSV x,z or JSON) [m].")


def _declared(names: tuple[str, ...], **overrides: Any) -> dict[str, tuple[Any, Any]]:
    ints = {"grouser_count", "flap_count"}
    out: dict[str, tuple[Any, Any]] = {}
    for name in names:
        ann: Any = str | None if name == "points_file" else int | None if name in ints else float | None
        out[name] = (ann, overrides.get(name, getattr(BodyOptions, name)))
    return out


#: every size flag of an intruder body (``terradyn intrude``, ``terradyn mpm intrude``)
BODY_SIZE_FLAGS = _declared(
    ("length", "thickness", "radius", "side", "base", "height", "tip_offset", "grouser_count",
     "grouser_height", "grouser_thickness", "hub_radius", "flap_count", "flap_length", "flap_angle",
     "points_file"),
)  # fmt: skip


def build_body(kind: BodyKind, width: float, **flags: Any) -> geometry.Body:
    """The body of shape ``kind`` from its size flags; a flag the shape does not take is an error."""
    ctor_name, accepted = BODY_FLAGS[kind]
    given = {k: v for k, v in flags.items() if v is not None}
    for key in given:
        if key not in accepted:
            allowed = ", ".join(f"--{a.replace('_', '-')}" for a in accepted) or "none"
            raise InputError(f"--{key.replace('_', '-')}", given[key], f"a flag of {kind.value} ({allowed})")
    kwargs: dict[str, Any] = {}
    for flag, keyword in accepted.items():
        if flag in given:
            value = given[flag]
            kwargs[keyword] = math.radians(value) if flag == "flap_angle" else value
        elif flag not in _OPTIONAL and not (kind is BodyKind.flapped and flag == "flap_angle"):
            raise InputError(f"--{flag.replace('_', '-')}", None, f"a value (required for {kind.value})")
    ctor = getattr(geometry, ctor_name, None)
    if ctor is None:
        raise InputError("BODY", kind.value, "a shape this build of terradyn provides")
    if kind is BodyKind.polygon:
        from .options import input_file

        return ctor.from_file(input_file("--points-file", kwargs.pop("path")), width, center=False)
    return ctor(width=width, **kwargs)
