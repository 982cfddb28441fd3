"""Push a plate into medium sand at several angles; RFT force grows linearly with depth.

Run: python examples/plate_intrusion.py
"""

from __future__ import annotations

import math

import numpy as np

from terradyn import materials
from terradyn.geometry import Plate
from terradyn.studies.intrusion import intrusion_forces


def main() -> dict[str, float]:
    ms = materials.get("MS")
    plate = Plate(length=0.05, width=0.02)
    depths = np.linspace(0.03, 0.12, 10)
    slopes = {}
    for angle_deg in (0, 30, 60):
        t = intrusion_forces(plate, ms, depths, angle=math.radians(angle_deg), direction=math.pi / 2)
        slope, intercept = np.polyfit(depths, t.columns["force_z_N"], 1)
        slopes[f"{angle_deg} deg"] = slope
        # Fully buried: the force is proportional to depth (no offset).
        assert abs(intercept) < 1e-9 * slope
        print(f"plate at {angle_deg:2d} deg: dF_z/d(depth) = {slope:8.1f} N/m")
    # A tilted plate is weaker in vertical penetration than a flat one.
    assert slopes["0 deg"] > slopes["30 deg"] > slopes["60 deg"] > 0
    return slopes


if __name__ == "__main__":
    main()
