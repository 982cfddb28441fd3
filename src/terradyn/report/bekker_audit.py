"""The shipped media's Bekker parameters checked against their source, unit by unit (thesis ch. 3, 6).

Source: the material table of Agarwal et al. (2019) (the thesis's Table 6.1 lists the same media), as
printed: k_c in "kN/m^(n+1)" and k_phi in "kN/m^(n+2)" for every column. The columns cannot all be in
kN: read that way the MS pressure at 2 cm sinkage under a 0.16 m wide wheel is about 1500 times the
RFT plate pressure zeta z of the same sand, measured independently in the same paper. This module
settles each column's unit by that independent check: for n = 1 the Bekker law p = (k_c/b + k_phi) z
and RFT's horizontal plate law p = zeta z describe the same plate-sinkage test, so the reading whose
pressure is nearest zeta z (ratio nearest 1 on a log scale at the wheel width b = 0.16 m and z = 2 cm)
is taken. No reading reconciles the poppy-seed columns (LPS, CPS): their nearer reading (N) is still
16.5 times stiffer than RFT at b = 0.16 m and negative for plates narrower than 3.1 cm, so they are
flagged, not changed: terradyn ships the source values in the nearer reading and says so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

__all__ = ["PRINTED", "PrintedBekker", "audit", "reading_ratio"]

#: wheel width [m] of the rigid wheel of the paper (the Bekker b of a wheel is its width)
WHEEL_WIDTH = 0.16
#: narrowest plate of the RFT calibration (Li et al. 2013: 3.81 cm x 2.54 cm) [m]
RFT_PLATE_WIDTH = 0.0254
#: sinkage at which the pressures are compared [m]
SINKAGE = 0.02


@dataclass(frozen=True)
class PrintedBekker:
    """One column of the source table, as printed (numbers and units untouched)."""

    medium: str
    k_c_printed: float  # printed unit kN/m^(n+1)
    k_phi_printed: float  # printed unit kN/m^(n+2)
    n: float
    zeta_N_per_cm3: float  # "RFT constant", used in N/cm^3


#: Agarwal et al. (2019), material table (arXiv:1901.10667), values as printed
PRINTED: tuple[PrintedBekker, ...] = (
    PrintedBekker("MS", -2.05e4, 3.13e6, 1.0, 2.02),
    PrintedBekker("MMS", 846.0, 6708.0, 1.4, 3.05),
    PrintedBekker("LPS", -2.06e5, 7.07e6, 1.0, 0.35),
    PrintedBekker("CPS", -3.24e5, 1.11e7, 1.0, 0.55),
)


def reading_ratio(col: PrintedBekker, factor: float, width: float, sinkage: float = SINKAGE) -> float:
    """Bekker pressure / RFT plate pressure at ``sinkage`` [m] for a plate of ``width`` [m] when the
    printed k_c, k_phi are multiplied by ``factor`` (1: read as N, 1000: read as kN) to give N."""
    k = factor * (col.k_c_printed / width + col.k_phi_printed)
    return k * sinkage**col.n / (col.zeta_N_per_cm3 * 1e6 * sinkage)


def audit() -> list[dict[str, Any]]:
    """One row per medium: both readings' pressure ratios, the settled reading, whether it is
    consistent (ratio in [0.5, 2] at the wheel width), and the shipped values it implies [SI]."""
    rows = []
    for col in PRINTED:
        ratios = {f: reading_ratio(col, f, WHEEL_WIDTH) for f in (1.0, 1000.0)}
        factor = min(ratios, key=lambda f: abs(math.log(ratios[f])) if ratios[f] > 0 else math.inf)
        crossing = -factor * col.k_c_printed / (factor * col.k_phi_printed - col.zeta_N_per_cm3 * 1e6)
        rows.append(
            {
                "medium": col.medium,
                "n": col.n,
                "ratio_if_N": ratios[1.0],
                "ratio_if_kN": ratios[1000.0],
                "reading": "N" if factor == 1.0 else "kN",
                "ratio_at_rft_plate": reading_ratio(col, factor, RFT_PLATE_WIDTH),
                "consistent": 0.5 <= ratios[factor] <= 2.0,
                "k_c_N_per_m_n1": factor * col.k_c_printed,
                "k_phi_N_per_m_n2": factor * col.k_phi_printed,
                "width_matching_rft_m": crossing if col.n == 1.0 and crossing > 0 else None,
            }
        )
    return rows
