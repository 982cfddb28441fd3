"""Forced-slip MPM wheels settle: the drawbar pull reaches a steady value during the drive (read from
its time series, not from a cut-off window) and rises with slip, and so does the sinkage.

The 0.13 m x 0.16 m wheel on MS under 130 N at 11 mm cells (diameter / 24; the default is / 32, see
docs/mpm.md for the resolution study), 4 rad of drive. Slow: three runs. (At 16 mm cells the pull at
slip 0.5 still drifted by 1.7 N between the last two quarters of a 4.5 rad drive.)
"""

from __future__ import annotations

import pytest

from terradyn import materials
from terradyn.geometry import WheelCircular
from terradyn.mpm import run_wheel


@pytest.mark.slow
def test_forced_slip_pull_is_steady_and_rises_with_slip():
    wheel, ms = WheelCircular(0.13, 0.16), materials.get("MS")
    pulls, sinkages = [], []
    for slip in (0.1, 0.3, 0.5):
        res = run_wheel(wheel, ms, load=130.0, omega=1.0, slip=slip, cell_size=0.011, duration=4.0)
        drive = res.series["phase"] == "drive"
        pull = res.series["drawbar_pull_N"][drive]
        quarter = len(pull) // 4
        # steady: the means of the last two quarters of the drive agree within 1 % of the load
        assert abs(pull[-quarter:].mean() - pull[-2 * quarter : -quarter].mean()) < 1.3, slip
        pulls.append(res.summary["drawbar_pull_N"])
        sinkages.append(res.summary["sinkage_m"])
    assert pulls[0] < pulls[1] < pulls[2], pulls
    assert sinkages[0] < sinkages[1] < sinkages[2], sinkages
