"""A vertical plate dragged through MPM grains: earth-pressure theory and convergence (slow).

The plate (40 mm, 30 mm of it below the surface, MS, 5 mm cells, 0.05 m/s) pushes a passive wedge
ahead of it. Plane-strain plasticity brackets the horizontal force per width, 0.5 gamma H^2 K:
Rankine's smooth wall, K_p = (1 + sin phi) / (1 - sin phi), is the least a rough wall can carry;
Coulomb's planar wedge for wall friction delta (here atan 0.4, the body-grain friction) is an upper
estimate (a curved surface carries less). Measured (travel 3-10 mm, after the wedge is mobilised and
before the heap ahead of the plate grows) 0.628 N, 1.13 times Coulomb; over the last 15 mm the heap (a
surcharge the level-surface theories leave out) has raised it to 0.81 N, against Rankine 0.25 N and
Coulomb 0.56 N. The test accepts the Rankine value up to 1.5 times the Coulomb one, and an upward
friction force of at most tan(delta) times the drag.
"""

from __future__ import annotations

import math

import pytest

from terradyn import materials
from terradyn.geometry import Plate
from terradyn.mpm import Resolution
from terradyn.mpm.drag import run_drag
from terradyn.mpm.model import resolve_model


def coulomb_passive(phi: float, delta: float) -> float:
    """Coulomb's passive coefficient of a vertical wall with friction ``delta`` under a level surface."""
    root = math.sqrt(math.sin(phi + delta) * math.sin(phi) / math.cos(delta))
    return math.cos(phi) ** 2 / (math.cos(delta) * (1.0 - root) ** 2)


@pytest.mark.slow
def test_vertical_plate_drag_between_rankine_and_coulomb():
    ms = materials.get("MS")
    model = resolve_model(ms)
    res = run_drag(
        Plate(0.04, 0.01),
        ms,
        depth=0.01,  # the centre: the plate spans 10 mm above to 30 mm below the surface
        distance=0.03,
        speed=0.05,
        angle=0.5 * math.pi,
        resolution=Resolution(cell_size=0.005),
    )
    phi = math.asin(model.friction_coefficient)  # the plane-strain angle of the cone (mu = sin phi)
    delta = math.atan(model.surface_friction)
    gamma = max(model.bulk_density, 1.02 * model.critical_density) * 9.81  # the consolidated bed
    scale = 0.5 * gamma * 0.03**2 * 0.01
    rankine = scale * (1 + math.sin(phi)) / (1 - math.sin(phi))
    coulomb = scale * coulomb_passive(phi, delta) * math.cos(delta)
    # once the wedge is mobilised and before the heap ahead of the plate (a surcharge the level-surface
    # theories leave out) has grown: travel 3-10 mm
    d = res.series["distance_m"]
    early = (d >= 0.003) & (d <= 0.010)
    drag, lift = res.series["drag_N"][early].mean(), res.series["lift_N"][early].mean()
    print(f"early drag {drag:.3f} N, lift {lift:.3f} N; last 15 mm {res.summary['drag_N']:.3f} N")
    assert rankine < drag < 1.5 * coulomb, (rankine, drag, coulomb)
    assert 0.0 < lift <= math.tan(delta) * drag * 1.05
    assert res.summary["drag_N"] > drag  # the heap raises the drag over the last 15 mm


@pytest.mark.slow
def test_smooth_blade_drag_converges_with_the_cell_size():
    """A smooth vertical blade ploughing a heap ahead of it: its drag settles with refinement.

    The same plate with no body-grain friction, dragged 40 mm at 0.05 m/s, at 3.5 and 2.5 mm cells
    (8.6 and 12 cells over the 30 mm in the bed). Measured (docs/mpm.md, "A blade ploughing a heap
    converges"): over the last 20 mm 0.553 / 0.491 / 0.484 N at 5 / 3.5 / 2.5 mm, steps of -11 % and
    -1.4 %. So at a given speed the front resistance of a body pushing a heap is resolved at these
    cells, unlike a bearing problem's collapse load at the same cells across. (At a quarter of the
    speed the two cell sizes read 4 % apart, and 6-12 % lower: the loading rate, documented there.)
    """
    model = resolve_model(materials.get("MS"), surface_friction=0.0)
    drags = []
    for h in (0.0035, 0.0025):
        res = run_drag(
            Plate(0.04, 0.01),
            model,
            depth=0.01,
            distance=0.04,
            speed=0.05,
            angle=0.5 * math.pi,
            resolution=Resolution(cell_size=h),
        )
        drags.append(res.summary["drag_N"])
    print("drag at 3.5 / 2.5 mm:", drags)
    assert abs(drags[1] - drags[0]) < 0.03 * drags[1], drags
