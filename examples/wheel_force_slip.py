"""Drawbar pull and sinkage of a rigid wheel in medium sand versus slip, and its free-rolling slip.

Run: python examples/wheel_force_slip.py
"""

from __future__ import annotations

import numpy as np

from terradyn import materials
from terradyn.geometry import WheelCircular
from terradyn.locomotion import wheel_self_propelled, wheel_steady


def main() -> dict[str, float]:
    ms = materials.get("MS")
    wheel = WheelCircular(radius=0.13, width=0.16)
    slips = np.linspace(-0.5, 0.7, 7)
    pulls = []
    for s in slips:
        r = wheel_steady(wheel, ms, load=130.0, slip=float(s))
        pulls.append(r.drawbar_pull_N)
        print(
            f"s = {s:+.2f}: sinkage {r.sinkage_m * 1e3:5.1f} mm, DP {r.drawbar_pull_N:+7.2f} N, "
            f"torque {r.drive_torque_Nm:+6.2f} N m"
        )
    free = wheel_self_propelled(wheel, ms, load=130.0)
    print(f"free-rolling slip: {free.slip:.4f}")
    assert np.all(np.diff(pulls) > 0)  # more slip, more pull
    assert pulls[0] < 0 < pulls[-1]
    assert 0 < free.slip < 0.3
    return {"free_rolling_slip": free.slip}


if __name__ == "__main__":
    main()
