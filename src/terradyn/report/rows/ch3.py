"""Chapter 3 of the thesis reproduction report: classical terramechanics.

``ch3-pressure-sinkage``: Bekker pressure-sinkage of the four media beside the RFT plate law (one row
for both models). Each row is ``name(quick) -> ItemOutput``; every number in a finding is computed
here from the run (reference values carry their citation in the text).
"""

from __future__ import annotations

import numpy as np

from ... import materials
from ..outputs import Finding, ItemOutput
from .common import MEDIA, verdict

__all__ = ["pressure_sinkage_bekker"]


def pressure_sinkage_bekker(quick: bool) -> ItemOutput:
    """Bekker p(z) of the shipped media at the wheel width and at the RFT plate width, beside zeta z."""
    import matplotlib.pyplot as plt

    from ...terramechanics import bekker_pressure
    from ..bekker_audit import SINKAGE, WHEEL_WIDTH

    plate = 0.05  # a 5 cm plate: narrower ones have negative stiffness with the poppy-seed k_c
    z = np.linspace(0.0, 0.04, 9 if quick else 41)
    fig, axes = plt.subplots(1, 4, figsize=(16, 3.8), layout="constrained")
    out = ItemOutput(
        figures={"pressure_sinkage": fig}, settings={"sinkage_max_m": 0.04, "widths_m": [WHEEL_WIDTH, plate]}
    )
    for ax, name in zip(axes, MEDIA, strict=True):
        mat = materials.get(name)
        b = mat.require_bekker()
        for width, style in ((WHEEL_WIDTH, "-"), (plate, ":")):
            p = np.asarray(bekker_pressure(z, width, b.k_c, b.k_phi, b.n))
            ax.plot(z * 1e3, p / 1e3, style, color="C0", label=f"Bekker, b = {width * 100:g} cm")
        ax.plot(z * 1e3, mat.zeta * z / 1e3, "--", color="C1", label="RFT plate, zeta z")
        ax.set_xlabel("sinkage z [mm]")
        ax.set_ylabel("pressure p [kPa]")
        ax.set_title(name)
        ax.grid(True, alpha=0.35)
        ax.legend(fontsize=7)
        ratio = float(bekker_pressure(SINKAGE, WHEEL_WIDTH, b.k_c, b.k_phi, b.n)) / (mat.zeta * SINKAGE)
        out.metrics[f"{name}_bekker_over_rft"] = ratio
        out.findings.append(
            Finding(
                f"{name}: Bekker pressure at z = {SINKAGE * 1e3:g} mm, b = {WHEEL_WIDTH} m is {ratio:.3g} x "
                f"the "
                f"RFT plate pressure zeta z",
                verdict(0.5 <= ratio <= 2.0),
            )
        )
    fig.suptitle("Bekker pressure-sinkage (shipped parameters) and the RFT plate law")
    return out
