"""Unit conversions used at the boundaries (CLI, TOML). The library itself is SI throughout."""

from __future__ import annotations

import math

__all__ = ["G_EARTH", "N_PER_CM3", "deg", "to_deg"]

#: Standard gravity [m/s^2].
G_EARTH = 9.81
#: One N/cm^3 expressed in N/m^3.
N_PER_CM3 = 1.0e6


def deg(value_deg: float) -> float:
    """Degrees to radians."""
    return math.radians(value_deg)


def to_deg(value_rad: float) -> float:
    """Radians to degrees."""
    return math.degrees(value_rad)
