"""The grid contact against two exact statements: Coulomb's law on a sliding interface, and a resting
body that leaves the grains under it as dense as the bed.

A flat-bottomed sled (0.12 m base, ski tips, 0.05 m wide) on poppy-cp under 10 N, towed at 0.05 m/s
(``run_wheel(..., omega=0, forward_speed=...)``), slides on its interface when the body-grain friction
is below the grains' own (mu_s = 0.707): the horizontal force is the friction plus the small
resistance of the tips. Measured (docs/mpm.md "The contact's friction is Coulomb's"): the ratio
|F_x| / F_z less the frictionless one is 0.199 / 0.410 at 8 mm cells and 0.199 / 0.404 at 5.6 mm for
mu = 0.2 / 0.4.
"""

from __future__ import annotations

import numpy as np
import pytest

from terradyn import materials
from terradyn.geometry import Polygon
from terradyn.mpm import Drive, Resolution, run_wheel

L, TIP, TOP = 0.06, 0.02, 0.03
SLED = Polygon([(-L - TIP, TIP), (-L, 0.0), (L, 0.0), (L + TIP, TIP), (L + TIP, TOP), (-L - TIP, TOP)], 0.05)
POPPY = materials.get("poppy-cp")


def _sled(mu, speed, h=0.01, duration=0.3, contact="two-field"):
    return run_wheel(SLED, POPPY, load=10.0, omega=0.0, forward_speed=speed, surface_friction=mu,
                     resolution=Resolution(cell_size=h, flip=0.99, contact=contact),
                     drive=Drive(duration=duration))  # fmt: skip


def test_a_towed_sled_resists_with_coulombs_friction():
    """Friction 0 and 0.4: the difference of the force ratios is the friction coefficient."""
    ratio = {}
    for mu in (0.0, 0.4):
        s = _sled(mu, 0.05).summary
        assert abs(s["force_z_N"] - 10.0) < 0.2, s  # the load is carried
        ratio[mu] = -s["drawbar_pull_N"] / s["force_z_N"]
    assert 0.0 < ratio[0.0] < 0.04, ratio  # the tips' resistance, small
    assert abs(ratio[0.4] - ratio[0.0] - 0.4) < 0.025, ratio


def _top_density(res, h):
    """Mean density [kg/m^3] of the grains within one cell under the sled's flat base."""
    f, s = res.final_particles, res.series
    x, z = f["x"] - s["x_m"][-1], f["z"] - s["z_m"][-1]
    under = (np.abs(x) < L - h) & (z > -h) & (z <= 0.0)
    assert under.sum() >= 10
    return float(f["density"][under].mean())


@pytest.mark.parametrize(
    ("contact", "low", "high"), [("two-field", 0.80, 0.92), ("two-field-gap", 0.96, 1.01)]
)
def test_a_resting_sled_leaves_the_grains_under_it_dense_only_with_the_gap_test(contact, low, high):
    """The sled dropped from half a cell above the bed and left to rest. Under the node test the
    sled's inner nodes hold the top grains while they are still most of a cell away: the first row is
    pulled up and compressed, and torn off the second, which loosens below the critical density and
    carries nothing (docs/mpm.md "Contact at a distance"; at 10 mm cells the cell under the base ends
    at 0.857 of the bed's density). Under the gap check both rows carry the load (0.999)."""
    h = 0.01
    res = _sled(0.0, 0.0, h=h, duration=0.1, contact=contact)
    bed = float(np.median(res.final_particles["density"]))
    assert low < _top_density(res, h) / bed < high, (_top_density(res, h), bed)
