"""run_drag: a buried body dragged horizontally. Invariants: mirror symmetry, drag rising with depth,
grains removed from inside a closed body only, and one clear error per bad input."""

import math

import numpy as np
import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.geometry import Cylinder, Plate
from terradyn.mpm.drag import drag_clearance, remove_grains_inside, run_drag
from terradyn.mpm.model import resolve_model
from terradyn.mpm.solver import BedGrid, make_bed
from terradyn.report.rows.ch9_drag import _LD_QUICK, _SIZE, _drag

CYLINDER = Cylinder(0.5 * _SIZE, _SIZE)


def test_mirror_symmetry_of_a_cylinder_dragged_both_ways():
    """Dragging along -x from the mirrored start gives the mirrored forces: F_x changes sign, F_z and
    the drag do not (the bed, the grid and the cylinder's outline are mirror-symmetric about x = 0)."""
    _, forward, _, _ = _drag(CYLINDER, _SIZE, _LD_QUICK, 1.0)
    _, backward, _, _ = _drag(CYLINDER, _SIZE, _LD_QUICK, -1.0)
    assert forward["drag_N"] > 0 and backward["drag_N"] > 0
    assert backward["force_x_N"] == pytest.approx(-forward["force_x_N"], rel=1e-3)
    assert backward["drag_N"] == pytest.approx(forward["drag_N"], rel=1e-3)
    assert backward["lift_N"] == pytest.approx(forward["lift_N"], rel=1e-3, abs=1e-3 * forward["drag_N"])
    assert backward["torque_y_Nm"] == pytest.approx(
        -forward["torque_y_Nm"], abs=1e-3 * forward["drag_N"] * _SIZE
    )


def test_drag_grows_with_depth():
    _, shallow, _, _ = _drag(CYLINDER, 0.5 * _SIZE, _LD_QUICK)
    _, deep, _, _ = _drag(CYLINDER, _SIZE, _LD_QUICK)
    assert deep["drag_N"] > 1.2 * shallow["drag_N"] > 0


def test_travel_runs_from_the_start_and_the_summary_averages_its_end():
    series, summary, _, _ = _drag(CYLINDER, _SIZE, _LD_QUICK, -1.0)
    d = series["distance_m"]
    assert d[0] < 0.1 * _LD_QUICK.distance and np.all(np.diff(d) >= 0)
    assert d[-1] == pytest.approx(_LD_QUICK.distance, rel=0.02)
    end = d >= _LD_QUICK.distance - summary["averaging_window_m"] - 1e-12
    assert 0 < end.sum() < len(d)
    assert summary["drag_N"] == pytest.approx(series["drag_N"][end].mean())


def test_grains_inside_a_closed_body_only_are_removed():
    model = resolve_model(materials.get("MS"))
    grid = BedGrid(0.1, 0.06, 0.02, 0.004, -0.05)
    bed = make_bed(model, grid)
    pose = np.array([0.0, -0.03, 0.0])
    kept = remove_grains_inside(bed, np.array(_segments(CYLINDER)), pose)
    r = np.hypot(kept.pos[:, 0], kept.pos[:, 1] + 0.03)
    assert r.min() >= 0.5 * _SIZE * (1 - 1e-3)  # none left inside
    removed = len(bed) - len(kept)
    area = math.pi * (0.5 * _SIZE) ** 2
    assert removed * bed.vol[0] == pytest.approx(area, rel=0.15)  # about the body's area
    assert len(remove_grains_inside(bed, np.array(_segments(Plate(0.03, 0.01))), pose)) == len(bed)


def _segments(body):
    from terradyn.mpm.bodies import body_segments

    return body_segments(body, 0.004)


def test_drag_clearance_grows_with_depth():
    model = resolve_model(materials.get("MS"))
    assert drag_clearance(model, 0.01, 0.08)[0] > drag_clearance(model, 0.01, 0.02)[0] > 0


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"depth": -0.01}, "depth"),
        ({"distance": 0.0}, "distance"),
        ({"speed": 0.0}, "speed"),
        ({"speed": float("nan")}, "speed"),
        ({"cell_size": 0.02}, "cell_size"),
        ({"averaging_window": 0.05}, "averaging_window"),
        ({"bed_depth": 0.02}, "bed_depth"),
        ({"bed_width": 0.03}, "bed_width"),
    ],
)
def test_bad_input_names_the_field(kwargs, field):
    args = {"depth": 0.03, "distance": 0.02, "speed": 0.1, **kwargs}
    with pytest.raises(InputError) as err:
        run_drag(CYLINDER, materials.get("MS"), **args)
    assert err.value.field == field
    assert "\n" not in str(err.value)


# --- CLI ------------------------------------------------------------------------------------------

DRAG_ARGS = ["mpm", "drag", "plate", "--length", "0.03", "--depth", "0.02", "--distance", "0.01"]


@pytest.mark.parametrize(
    ("flag", "value"), [("--speed", "0"), ("--speed", "nan"), ("--distance", "-1"), ("--window", "0.001")]
)
def test_cli_bad_input_is_one_line(run_cli, flag, value):
    args = [a for a in DRAG_ARGS if a != "--distance" and a != "0.01"] if flag == "--distance" else DRAG_ARGS
    code, _, err = run_cli(*args, flag, value)
    assert code == 1, err
    assert flag in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


@pytest.mark.slow
def test_cli_drag_runs_and_reports_drag_and_lift(run_cli, tmp_path):
    import json

    out = tmp_path / "drag.json"
    code, _, err = run_cli(
        *DRAG_ARGS, "--cell-size", "0.005", "--speed", "0.1", "--format", "json", "--out", str(out)
    )
    assert code == 0, err
    summary = json.loads(out.read_text())
    assert summary["drag_N"] > 0 and math.isfinite(summary["lift_N"])
    assert summary["force_x_N"] == pytest.approx(-summary["drag_N"])
