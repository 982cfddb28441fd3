"""The MPM rows of the report: registered for their items, and a quick row builds with computed numbers."""

import math

import numpy as np
import pytest

from terradyn.report import reproduce
from terradyn.report.registry import item, rows_of

MPM_ROWS = {
    "ch9-plate-packing": "terradyn.report.rows.ch9_intrusion:plate_packing_mpm",
    "ch9-wedges": "terradyn.report.rows.ch9_intrusion:wedges_mpm",
    "fig-9-1": "terradyn.report.rows.ch9_footing:footing_mpm",
    "fig-6-8": "terradyn.report.rows.ch6:wheel_a_force_slip_mpm",
    "fig-4-1": "terradyn.report.rows.ch4:alpha_map_mpm",
    "ch4-plate-depth": "terradyn.report.rows.ch4:plate_depth_mpm",
    "ch8-high-speed": "terradyn.report.rows.ch7_8:high_speed_mpm",
    "ch6-wheels-bc": "terradyn.report.rows.ch6:wheels_bc_force_slip_mpm",
    "ch6-flapped": "terradyn.report.rows.ch6:flapped_mpm",
}


def test_mpm_rows_are_registered_not_pending():
    for key, spec in MPM_ROWS.items():
        assert dict(rows_of(item(key)))["mpm"] == spec


def test_flapped_speed_is_averaged_over_whole_flap_periods():
    from terradyn.report.rows.ch6 import _flap_window

    period = 2 * math.pi / 4  # 4 flaps at 1 rad/s
    assert _flap_window(4.5, 4) == pytest.approx(period)  # 2.25 s of last half hold one period
    assert _flap_window(10.0, 4) == pytest.approx(3 * period)
    assert _flap_window(1.6, 4) == pytest.approx(period)  # only one period in the drive
    assert _flap_window(1.0, 4) == pytest.approx(0.5)  # not even one: the last half


def test_the_alpha_map_names_its_edgewise_cases_and_the_shape_without_them():
    from terradyn.geometry import Plate
    from terradyn.mpm.bodies import body_segments, body_segments_world
    from terradyn.report.rows.ch4 import _edgewise_findings

    # angle = direction is motion along the plate: the MPM plate's long axis lies along (cos g, -sin g)
    g = math.radians(30.0)
    plate = body_segments(Plate(0.04, 0.02, thickness=0.005), 0.005)
    pts = body_segments_world(plate, np.array([0.0, 0.0, g]))[:, 0, :]
    w, v = np.linalg.eigh(np.cov((pts - pts.mean(axis=0)).T))
    assert abs(v[:, -1] @ np.array([math.sin(g), math.cos(g)])) < 1e-9  # no component across the motion
    assert w[-1] > 10 * w[0]

    def row(a, g, mx, mz, fx, fz):
        return {"angle_deg": a, "direction_deg": g, "alpha_x_mpm_N_per_m3": mx, "alpha_z_mpm_N_per_m3": mz,
                "alpha_x_rft_N_per_m3": fx, "alpha_z_rft_N_per_m3": fz}  # fmt: skip

    rows = [row(0, 90, 0.0, 5e5, 0.0, 1e6), row(30, 90, -1e5, 3e5, -2e5, 6e5)]
    rows.append(row(30, 30, 0.0, 1e4, 1e5, 8e5))
    (f,) = _edgewise_findings(rows, 0.5)
    assert f.verdict == "info"
    assert "30 deg: alpha_z MPM 0.010, RFT x 0.50 0.400 N/cm^3" in f.text
    # the two other cases are exactly half the law: scale 0.5, no shape difference left
    assert "without them (2 cases) the scale is 0.500 and the rms shape difference 0.0%" in f.text
    assert _edgewise_findings(rows[:2], 0.5) == []  # no edgewise case, no finding
    assert _edgewise_findings([row(90, 90, 0.0, 1.0, 0.0, 1.0), *rows[:2]], 0.5)  # vertical plate moving down


@pytest.fixture(scope="module")
def wedge_report(tmp_path_factory):
    folder = tmp_path_factory.mktemp("mpm_report")
    return folder, reproduce(folder, quick=True, only=["ch9-wedges"])


def test_quick_wedge_row_builds_beside_rft(wedge_report):
    folder, run = wedge_report
    assert run.failures == []
    r = run.results[("ch9-wedges", "mpm")]
    assert r["status"] == "ran" and r["figures"]
    html = (folder / "report.html").read_text(encoding="utf-8")
    assert "<b>MPM</b> (" in html and "<b>RFT</b> (" in html
    rows = r["tables"]["wedges"]
    sym = next(x for x in rows if x["tip_offset_m"] == 0.0)
    asym = next(x for x in rows if x["tip_offset_m"] > 0.0)
    # a symmetric wedge centred on the path feels (almost) no lateral force; an offset tip does
    assert abs(sym["mpm_lateral_ratio"]) < 0.5 * abs(asym["mpm_lateral_ratio"])
    assert all(math.isfinite(v) and v > 0 for v in (sym["mpm_ratio"], asym["mpm_ratio"]))
    # the numbers in the text are the run's
    texts = " ".join(f["text"] for f in r["findings"])
    assert f"{asym['mpm_lateral_ratio']:+.3f}" in texts
    assert f"{r['metrics']['plate_force_z_N']:.2f} N" in texts


def test_a_wheel_row_names_the_runs_that_outgrew_their_bed():
    """The wheel rows turn each run's bed flags (heap at the bed's end, wheel close to the floor) into
    one finding naming the run, the way `terradyn mpm wheel` warns; runs that fit add nothing."""
    from terradyn.mpm.wheel_runs import FLOOR_CLEARANCE_REACHES, floor_metadata
    from terradyn.report.rows.common import bed_outgrown_findings

    reach, depth = 0.1, 0.4
    fits = {"bed_depth_m": depth, **floor_metadata(np.array([0.0, 0.05, 0.09]), depth, reach)}
    deep = {"bed_depth_m": depth, **floor_metadata(np.array([0.0, 0.05, 0.11]), depth, reach)}
    held = {"heap_reached_bed_end": True, "heap_ahead_m": 0.5, "bed_width_m": 2.0, **fits}
    assert FLOOR_CLEARANCE_REACHES == 3.0  # 0.09 m deep leaves 3.1 reaches, 0.11 m leaves 2.9
    assert not fits["floor_near"] and deep["floor_near"]
    assert bed_outgrown_findings({"a": fits}) == []
    [finding] = bed_outgrown_findings({"a": fits, "b": deep, "c": held})
    assert finding.verdict == "info"
    assert "b: the wheel sank 0.11 m, leaving 0.29 m" in finding.text
    assert "c: the grains heaped 0.5 m ahead" in finding.text and "a:" not in finding.text
