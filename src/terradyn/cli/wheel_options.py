"""The wheel shapes and their size flags, declared once for every command that builds a wheel
(``wheel steady|self-propelled|sweep|simulate|compare``, ``mpm wheel``)."""

from __future__ import annotations

from enum import Enum
from typing import Any

from ..geometry import Body
from ._bodies import BodyKind, _declared, build_body
from .options import WHEEL_RADIUS, with_flags

__all__ = ["WHEEL_SIZE_FLAGS", "WheelShape", "shape_flags", "wheel_body", "wheel_flags"]


class WheelShape(str, Enum):
    circular = "circular"
    grousered = "grousered"
    flapped = "flapped"
    c_leg = "c-leg"
    polygon = "polygon"


_SHAPE_TO_BODY = {
    WheelShape.circular: BodyKind.wheel,
    WheelShape.grousered: BodyKind.grousered,
    WheelShape.flapped: BodyKind.flapped,
    WheelShape.c_leg: BodyKind.c_leg,
    WheelShape.polygon: BodyKind.polygon,
}


#: the size flags of every wheel shape, declared once for all wheel commands
WHEEL_SIZE_FLAGS = _declared(
    ("radius", "thickness", "grouser_count", "grouser_height", "grouser_thickness", "hub_radius",
     "flap_count", "flap_length", "flap_angle", "points_file"),
    radius=WHEEL_RADIUS,
)  # fmt: skip
wheel_flags = with_flags("sizes", WHEEL_SIZE_FLAGS)


def wheel_body(shape: WheelShape, width: float, flags: dict[str, Any]) -> Body:
    """The plane wheel of ``shape`` and width [m] from its size flags."""
    return build_body(_SHAPE_TO_BODY[shape], width, **flags)


def shape_flags(shape: WheelShape, values: dict[str, Any]) -> dict[str, Any]:
    """The size flags that apply to ``shape`` (the default --radius is the circular and grousered
    wheels' only)."""
    keys = (
        "radius",
        "thickness",
        "grouser_count",
        "grouser_height",
        "grouser_thickness",
        "hub_radius",
        "flap_count",
        "flap_length",
        "flap_angle",
        "points_file",
    )
    flags = {k: values[k] for k in keys}
    if shape in (WheelShape.flapped, WheelShape.polygon):
        flags["radius"] = None  # the default --radius belongs to circular and grousered wheels
    return flags
