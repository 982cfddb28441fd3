"""Wheels A, B and C of the thesis (Table 6.2) and the closest wheels that are publicly documented.

What is public: Agarwal et al. (2019) test "three different wheel types" in forced slip; their wheel
table is not in any text terradyn could read (the rendering of the paper's material table ends with
the number 260, which starts the wheel table: very probably wheel A's diameter in mm). The thesis's
Table 6.2 was not available either. So terradyn defines the closest documented wheels and says where
each number comes from:

* **A**: rigid smooth wheel, diameter 0.26 m (the "260" above), width 0.16 m (the MIT single-wheel
  test-bed wheel of the public Wong-Reece and RFT reproductions of the paper; secondary source), the
  wheel of every terradyn wheel default.
* **B**: the grousered wheel of Agarwal, Karsai, Goldman & Kamrin (Sci. Adv. 2021) on poppy seeds:
  outer diameter 212 mm and 15 lugs (published); lug height 18 mm, thickness 4 mm and width 50 mm are
  terradyn assumptions (see :mod:`terradyn.studies.high_speed`), modelled with effective lugs.
* **C**: no public description was found. terradyn's stand-in is the closest documented wheel it can
  build without inventing a number: wheel B's rim without its lugs, a rigid smooth cylinder of B's
  published outer diameter (212 mm) and assumed width (50 mm), at B's loads. B and C then differ only
  by the lugs, and C is the smooth rim that docs/mpm.md studies at rest, under slip and at a fixed
  depth. It is a stand-in, not the thesis's wheel C: the report says so wherever C appears.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

__all__ = ["WHEELS", "WheelDefinition", "wheel_body"]


@dataclass(frozen=True)
class WheelDefinition:
    """A wheel of Table 6.2 as terradyn defines it (None fields: not defined)."""

    name: str
    kind: str
    outer_diameter_m: float | None
    width_m: float | None
    grousers: int | None
    loads_N: tuple[float, ...]
    source: str


_A = WheelDefinition(
    "A",
    "rigid smooth",
    0.26,
    0.16,
    0,
    (80.0, 130.0, 150.0, 190.0),
    "diameter: Agarwal et al. 2019 wheel table (first number, as rendered); width and loads: public "
    "reproductions of that paper (secondary)",
)
_B = WheelDefinition(
    "B",
    "rigid grousered (effective lugs)",
    0.212,
    0.05,
    15,
    (42.0, 84.0),
    "outer diameter and lug count: Agarwal et al. 2021 (Sci. Adv. 7, eabe0631); lug size, width: "
    "terradyn assumptions; 84 N = mass ratio 6 on poppy seeds (rho_c = 638 kg/m^3), 42 N half of it",
)
#: C is B without its lugs: every other field is B's
_C = replace(
    _B,
    name="C",
    kind="rigid smooth (stand-in: wheel B without lugs)",
    grousers=0,
    source="not public: terradyn's stand-in is B's rim without lugs; outer diameter as B (Agarwal et al. "
    "2021), width and loads as B (terradyn assumptions)",
)

WHEELS: tuple[WheelDefinition, ...] = (_A, _B, _C)


def wheel_body(name: str) -> Any:
    """The terradyn body of wheel ``name`` (A, B or C; C is the smooth stand-in of the module doc)."""
    from ..errors import InputError
    from ..geometry import WheelCircular
    from .high_speed import HighSpeedWheel

    if name == "A":
        return WheelCircular(0.13, 0.16)
    if name == "B":
        return HighSpeedWheel().body()
    if name == "C":
        spec = WHEELS[2]
        return WheelCircular(0.5 * float(spec.outer_diameter_m), float(spec.width_m))  # type: ignore[arg-type]
    raise InputError("wheel", name, "A, B or C")
