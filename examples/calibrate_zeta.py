"""Recover the RFT scale of a medium from noisy plate force-depth data.

Run: python examples/calibrate_zeta.py
"""

from __future__ import annotations

import numpy as np

from terradyn import materials
from terradyn.geometry import Plate
from terradyn.rft.calibration import PlateData, fit_rft
from terradyn.studies.intrusion import intrusion_forces


def main() -> dict[str, float]:
    truth = materials.get("MMS")
    depths = np.linspace(0.01, 0.08, 12)
    clean = intrusion_forces(Plate(0.04, 0.02), truth, depths).columns["force_z_N"]
    noisy = clean * (1 + np.random.default_rng(42).normal(0, 0.03, clean.size))
    data = PlateData(depths, noisy, None, np.zeros_like(depths), np.full_like(depths, 90.0))
    fit = fit_rft(data, plate_length=0.04, plate_width=0.02)
    print(
        f"fitted zeta = {fit.zeta / 1e6:.3f} N/cm^3 (true {truth.zeta / 1e6:.3f}), R^2 = {fit.r_squared:.4f}"
    )
    assert abs(fit.zeta / truth.zeta - 1) < 0.03
    return {"zeta": fit.zeta}


if __name__ == "__main__":
    main()
