"""Sinkage of steady wheel solves is never negative, for every wheel shape (DESIGN.md section 4)."""

import math

import numpy as np
import pytest

from terradyn import materials
from terradyn.geometry import CLeg, Polygon, WheelCircular, WheelFlapped, WheelGrousered
from terradyn.kinematics import Pose2D
from terradyn.locomotion import wheel_steady

MS = materials.get("MS")

_HEX = [(0.08 * math.cos(a), 0.08 * math.sin(a)) for a in np.arange(6) * math.pi / 3]

SHAPES = {
    "circular": WheelCircular(0.08, 0.1),
    "grousered": WheelGrousered(0.07, 0.1, 8, 0.01, 0.004),
    "flapped": WheelFlapped(0.03, 0.1, 4, 0.05),
    "c-leg": CLeg(0.05, 0.1, thickness=0.01),
    "c-leg-thin": CLeg(0.05, 0.1),
    "polygon": Polygon(_HEX, 0.1),
}


def _lowest_depth(body, axle_height, theta):
    """Depth [m] of the lowest outline point below z = 0 at one phase (negative: above)."""
    pts = np.concatenate(body.outline())
    pose = Pose2D(0.0, axle_height, theta)
    c, s = math.cos(pose.theta), math.sin(pose.theta)
    z = pose.z - s * pts[:, 0] + c * pts[:, 1]
    return -float(z.min())


@pytest.mark.parametrize("name", sorted(SHAPES))
@pytest.mark.parametrize("load", [5.0, 20.0, 60.0])
@pytest.mark.parametrize("slip", [-0.3, 0.0, 0.4])
def test_sinkage_is_never_negative(name, load, slip):
    body = SHAPES[name]
    r = wheel_steady(body, MS, load, slip, phase_count=8)
    assert r.sinkage_min_m >= 0.0
    assert r.sinkage_min_m <= r.sinkage_m <= r.sinkage_max_m
    # Phase by phase: the depth of the lowest point, or 0 where the body is clear of the surface.
    period = 2 * math.pi / {"grousered": 8, "flapped": 4}.get(name, 1)
    thetas = np.arange(r.phase_count) * period / r.phase_count if r.phase_count > 1 else np.zeros(1)
    per_phase = [max(0.0, _lowest_depth(body, r.axle_height_m, t)) for t in thetas]
    assert r.sinkage_m == pytest.approx(float(np.mean(per_phase)), rel=1e-12, abs=1e-15)
    assert r.sinkage_max_m == pytest.approx(max(per_phase), rel=1e-12, abs=1e-15)


def test_c_leg_out_of_the_ground_for_part_of_its_turn():
    """The case of the issue: the C-leg swings over its hip, clear of the medium, for part of a turn;
    those phases count 0 and the others their real depth (before: a negative mean)."""
    r = wheel_steady(SHAPES["c-leg"], MS, 20.0, 0.0, phase_count=16)
    assert r.sinkage_min_m == 0.0
    assert r.sinkage_max_m > 0.0
    assert 0.0 < r.sinkage_m < r.sinkage_max_m
