"""terradyn.replay: reading and checking runs tables, replay, metrics, calibration."""

from __future__ import annotations

import math

import numpy as np
import pytest

from terradyn.errors import InputError
from terradyn.replay import ReplayModel, metrics, read_runs, replay, runs_from_records, split_runs
from terradyn.replay.synthetic import design_runs, records_to_csv, synthetic_records

QUANTITIES_2D = ("drawbar_pull_N", "drive_torque_Nm", "sinkage_m")


def _write(tmp_path, records, name="runs.csv"):
    path = tmp_path / name
    path.write_text(records_to_csv(records))
    return path


@pytest.mark.parametrize("name", ["rft", "wong-reece"])
def test_replay_reproduces_a_table_made_by_the_model_itself(tmp_path, name):
    # Wong-Reece takes s = 1 - V/(omega r) >= -1 only: rig slip >= -0.5
    slips = (-0.7, -0.3, 0.0, 0.3, 0.7) if name == "rft" else (-0.3, 0.0, 0.3, 0.7)
    runs = design_runs(slips=slips, grousered=name == "rft")
    runs.append({**runs[0], "run_id": "sinkage-control", "load_N": None, "prescribed_sinkage_m": 0.01})
    model = ReplayModel(name, phase_count=4)
    records = synthetic_records(model, runs)
    assert len(records) == len(runs)
    res = replay(read_runs(_write(tmp_path, records)), model)
    assert all(r["solved"] for r in res.runs)
    for q in QUANTITIES_2D:
        resid = np.array([r[f"residual_{q}"] for r in res.runs])
        assert np.max(np.abs(resid)) == 0.0, q
    rec = {m["quantity"]: m for m in res.metrics}
    assert rec["drawbar_pull_N"]["rmse"] == 0.0 and rec["drawbar_pull_N"]["pearson_r"] == pytest.approx(1.0)


def test_replay_3d_reproduces_its_own_table_including_locked_wheel_and_90_deg(tmp_path):
    runs = design_runs(
        slips=(-1.0, -0.4, 0.0, 0.5), loads=(20.0,), grousered=False, slip_angles_deg=(0.0, 45.0, 90.0)
    )
    model = ReplayModel("rft3d")
    records = synthetic_records(model, runs)
    assert len(records) == len(runs)  # -1 (locked) and 90 deg are replayed too
    res = replay(read_runs(_write(tmp_path, records)), model)
    for q in (*QUANTITIES_2D, "side_force_N"):
        assert max(abs(r[f"residual_{q}"]) for r in res.runs) == 0.0
    side = {r["slip_angle_deg"]: r["predicted_side_force_N"] for r in res.runs if r["slip"] == 0.0}
    assert side[0.0] == pytest.approx(0.0, abs=1e-9) and side[45.0] < 0 and side[90.0] < side[45.0] < 0


def test_locked_wheel_given_by_speeds_matches_slip_minus_one():
    base = {"medium": "MS", "radius_m": 0.0625, "width_m": 0.06, "load_N": 20.0, "drawbar_pull_N": 0.0}
    t = runs_from_records(
        [
            {**base, "run_id": "a", "slip": -1.0},
            {**base, "run_id": "b", "rim_speed_m_s": 0.0, "carriage_speed_m_s": 0.01},
        ]
    )
    res = replay(t, ReplayModel("rft"))
    a, b = res.runs
    assert b["slip"] == -1.0
    assert a["predicted_drawbar_pull_N"] == pytest.approx(b["predicted_drawbar_pull_N"], rel=1e-9)
    assert a["predicted_sinkage_m"] == pytest.approx(b["predicted_sinkage_m"], rel=1e-9)


def test_calibration_recovers_the_scale_from_noisy_data():
    """Data made with zeta x 1.3, Gaussian noise (0.1 N on pull, 0.3 mm on sinkage, 0.005 N m on torque:
    2-5 % of the values); fitted on half, held out on the rest. Sinkage ~ zeta^(-2/3) and ~12 noisy
    sinkages of ~10 mm pin the scale to about 1 %: the band is 4 %."""
    runs = design_runs(slips=(-0.6, -0.3, 0.0, 0.2, 0.4, 0.6), loads=(15.0, 25.0), grousered=False)
    truth = ReplayModel("rft", scale=1.3)
    noise = {"drawbar_pull_N": 0.1, "sinkage_m": 3e-4, "drive_torque_Nm": 5e-3}
    records = synthetic_records(truth, runs, noise=noise, seed=7)
    table = runs_from_records(records)
    res = replay(table, ReplayModel("rft"), calibrate_on=0.5, seed=3)
    assert res.calibration is not None
    assert res.model.scale == pytest.approx(1.3, rel=0.04)
    held = {m["quantity"]: m for m in res.metrics if m["set"] == "held-out"}
    assert held["sinkage_m"]["rmse"] < 3 * noise["sinkage_m"]
    assert held["drawbar_pull_N"]["rmse"] < 3 * noise["drawbar_pull_N"]
    # an uncalibrated model is clearly worse on the same held-out runs
    plain = replay(table, ReplayModel("rft"))
    held_ids = set(res.calibration.held_out_runs)
    plain_sink = [r["residual_sinkage_m"] for r in plain.runs if r["run_id"] in held_ids]
    assert math.sqrt(np.mean(np.square(plain_sink))) > 3 * held["sinkage_m"]["rmse"]


def test_split_is_seeded_and_column_split_uses_booleans():
    recs = synthetic_records(ReplayModel("rft"), design_runs(grousered=False, loads=(20.0,)))
    for i, r in enumerate(recs):
        r["fit"] = "yes" if i % 3 == 0 else "no"
    t = runs_from_records(recs)
    assert split_runs(t, 0.4, seed=1) == split_runs(t, 0.4, seed=1)
    assert split_runs(t, 0.4, seed=1) != split_runs(t, 0.4, seed=2)
    cal, held = split_runs(t, "fit")
    assert cal == [r.index for r in t.rows if r.extra["fit"] == "yes"] and len(cal) + len(held) == len(t)
    recs[1]["fit"] = "maybe"
    with pytest.raises(InputError, match=r"row 2 column fit = 'maybe'"):
        split_runs(runs_from_records(recs), "fit")


def test_metrics_by_hand_and_per_group():
    runs = [
        {
            "set": "all",
            "g": "a",
            "measured_sinkage_m": 1.0,
            "predicted_sinkage_m": 2.0,
            "residual_sinkage_m": 1.0,
        },
        {
            "set": "all",
            "g": "a",
            "measured_sinkage_m": 3.0,
            "predicted_sinkage_m": 3.0,
            "residual_sinkage_m": 0.0,
        },
        {
            "set": "all",
            "g": "b",
            "measured_sinkage_m": 5.0,
            "predicted_sinkage_m": 3.0,
            "residual_sinkage_m": -2.0,
        },
    ]
    for r in runs:
        for q in ("drawbar_pull_N", "drive_torque_Nm", "side_force_N"):
            r.update({f"measured_{q}": None, f"predicted_{q}": None, f"residual_{q}": None})
    out = metrics(runs, group_by="g")
    whole = next(m for m in out if m["g"] == "all")
    assert whole["n"] == 3 and whole["mae"] == pytest.approx(1.0) and whole["bias"] == pytest.approx(-1 / 3)
    assert whole["rmse"] == pytest.approx(math.sqrt(5 / 3)) and whole["nrmse"] == pytest.approx(
        math.sqrt(5 / 3) / 4
    )
    assert whole["pearson_r"] == pytest.approx(np.corrcoef([1, 3, 5], [2, 3, 3])[0, 1])
    b = next(m for m in out if m["g"] == "b")
    assert b["n"] == 1 and b["pearson_r"] is None and b["nrmse"] is None


BASE = "run_id,medium,radius_m,width_m,load_N,slip,drawbar_pull_N\n"


@pytest.mark.parametrize(
    ("body", "message"),
    [
        (
            "a,MS,0.06,0.06,20,0.1,1\nb,MS,0.06,0.06,heavy,0.1,1\n",
            "runs.csv row 2 column load_N = 'heavy' is not allowed; expected a number > 0 [N]",
        ),
        (
            "a,MS,0.06,0.06,20,1.5,1\n",
            "runs.csv row 1 column slip = '1.5' is not allowed; expected a number in [-1, 1]",
        ),
        (
            "a,MS,-1,0.06,20,0.1,1\n",
            "runs.csv row 1 column radius_m = '-1' is not allowed; expected a number > 0 [m]",
        ),
        ("a,MS,0.06,0.06,20,0.1,nan\n", "runs.csv row 1 column drawbar_pull_N = 'nan'"),
        ("a,MS,0.06,,20,0.1,1\n", "runs.csv row 1 column width_m"),
        ("a,MS,0.06,0.06,20,0.1\n", "runs.csv row 1 = '6 cells' is not allowed; expected 7 cells"),
        (
            "a,MS,0.06,0.06,20,0.1,1\na,MS,0.06,0.06,20,0.2,1\n",
            "column run_id = 'a' is not allowed; expected a distinct",
        ),
    ],
)
def test_bad_cells_give_one_line_naming_row_column_and_value(tmp_path, body, message):
    path = tmp_path / "runs.csv"
    path.write_text(BASE + body)
    with pytest.raises(InputError) as exc:
        read_runs(path)
    text = str(exc.value)
    assert message in text and "\n" not in text


@pytest.mark.parametrize(
    ("header", "message"),
    [
        ("run_id,medium,radius_m,width_m,laod_N,slip,drawbar_pull_N", "header column laod_N = 'laod_N'"),
        (
            "run_id,medium,radius_m,width_m,slip,drawbar_pull_N",
            "a 'load_N' or a 'prescribed_sinkage_m' column",
        ),
        ("run_id,medium,radius_m,width_m,load_N,drawbar_pull_N", "a 'slip' column or both"),
        ("run_id,medium,radius_m,width_m,load_N,slip", "at least one measured column"),
    ],
)
def test_bad_headers_give_one_line(tmp_path, header, message):
    path = tmp_path / "runs.csv"
    path.write_text(header + "\n" + ",".join(["1"] * len(header.split(","))) + "\n")
    with pytest.raises(InputError, match=message.replace("(", r"\(").replace(")", r"\)")):
        read_runs(path)


def test_both_load_and_sinkage_or_slip_and_speeds_refused():
    base = {"run_id": "a", "medium": "MS", "radius_m": 0.06, "width_m": 0.06, "drawbar_pull_N": 1.0}
    with pytest.raises(InputError, match="exactly one of load_N and prescribed_sinkage_m"):
        runs_from_records([{**base, "load_N": 20, "prescribed_sinkage_m": 0.01, "slip": 0.1}])
    with pytest.raises(
        InputError, match=r"column rim_speed_m_s = '0\.1' is not allowed; expected empty when slip"
    ):
        runs_from_records(
            [{**base, "load_N": 20, "slip": 0.1, "rim_speed_m_s": 0.1, "carriage_speed_m_s": 0.1}]
        )


def test_plane_model_reports_slip_angle_rows_as_not_replayed():
    recs = synthetic_records(
        ReplayModel("rft3d"), design_runs(grousered=False, loads=(20,), slips=(0.2,), slip_angles_deg=(0, 30))
    )
    res = replay(runs_from_records(recs), ReplayModel("rft"))
    flags = {r["slip_angle_deg"]: (r["solved"], r["reason"]) for r in res.runs}
    assert flags[0.0][0] and not flags[30.0][0] and "3D model" in flags[30.0][1]


def test_processes_scheduler_gives_the_serial_answer():
    recs = synthetic_records(ReplayModel("rft"), design_runs(grousered=False, loads=(20,), slips=(0.0, 0.5)))
    t = runs_from_records(recs)
    a = replay(t, ReplayModel("rft"))
    b = replay(t, ReplayModel("rft"), scheduler="processes", workers=2)
    assert [r["predicted_drawbar_pull_N"] for r in a.runs] == [r["predicted_drawbar_pull_N"] for r in b.runs]


def test_mesh_wheel_in_mm_with_axle_z_and_offset_origin_gives_the_primitive_answer(tmp_path):
    from terradyn.geometry3d import TriangleMesh, save_mesh, wheel_cylinder

    body = wheel_cylinder(0.0625, 0.06, circumferential_resolution=360, axial_resolution=2)
    to_file = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])  # body y -> file z
    verts = (body.vertices @ to_file.T + np.array([0.2, -0.1, 0.05])) * 1e3
    save_mesh(TriangleMesh(verts, body.faces), tmp_path / "wheel_mm.stl")
    base = {"medium": "MS", "load_N": 20.0, "slip": 0.3, "slip_angle_deg": 30.0, "drawbar_pull_N": 0.0}
    recs = [
        {**base, "run_id": "primitive", "radius_m": 0.0625, "width_m": 0.06},
        {**base, "run_id": "mesh", "mesh_file": "wheel_mm.stl", "mesh_units": "mm", "mesh_axle": "z"},
    ]
    (tmp_path / "runs.csv").write_text(records_to_csv(recs))
    a, b = replay(read_runs(tmp_path / "runs.csv"), ReplayModel("rft3d")).runs
    for q in ("sinkage_m", "drawbar_pull_N", "side_force_N", "drive_torque_Nm"):
        assert b[f"predicted_{q}"] == pytest.approx(a[f"predicted_{q}"], rel=1e-4, abs=1e-6), q
    recs[1]["mesh_units"] = "m"  # a 125 m wheel: refused, naming the row and the column
    (tmp_path / "runs.csv").write_text(records_to_csv(recs))
    with pytest.raises(InputError, match=r"runs.csv row 2 column mesh_file") as exc:
        replay(read_runs(tmp_path / "runs.csv"), ReplayModel("rft3d"))
    assert "\n" not in str(exc.value)


@pytest.mark.slow
def test_dask_local_cluster_gives_the_serial_answer():
    pytest.importorskip("dask.distributed")
    recs = synthetic_records(ReplayModel("rft"), design_runs(grousered=False, loads=(20,), slips=(0.0, 0.5)))
    t = runs_from_records(recs)
    a = replay(t, ReplayModel("rft"))
    b = replay(t, ReplayModel("rft"), scheduler="local", workers=2)
    assert [r["predicted_sinkage_m"] for r in a.runs] == [r["predicted_sinkage_m"] for r in b.runs]


def test_culling_leaves_a_closed_outer_wheel_unchanged(tmp_path):
    from terradyn.geometry3d import save_mesh, wheel_grousered

    mesh = wheel_grousered(0.0625, 0.06, grouser_count=8, grouser_height=0.006, grouser_thickness=0.004,
                           circumferential_resolution=120, axial_resolution=2)  # fmt: skip
    save_mesh(mesh, tmp_path / "lugged.stl")
    base = {"medium": "MS", "mesh_file": str(tmp_path / "lugged.stl"), "load_N": 20.0, "drawbar_pull_N": 0.0}
    t = runs_from_records(
        [{**base, "run_id": "a", "slip": 0.3}, {**base, "run_id": "b", "slip": -1.0, "slip_angle_deg": -60}]
    )
    a = replay(t, ReplayModel("rft3d", phase_count=2))
    b = replay(t, ReplayModel("rft3d", phase_count=2, cull=False))
    for ra, rb in zip(a.runs, b.runs, strict=True):
        for q in ("sinkage_m", "drawbar_pull_N", "side_force_N", "drive_torque_Nm"):
            assert ra[f"predicted_{q}"] == pytest.approx(rb[f"predicted_{q}"], rel=1e-9, abs=1e-12), q


def test_culling_drops_an_enclosed_hub(tmp_path):
    from terradyn.geometry3d import TriangleMesh, save_mesh, wheel_cylinder

    tyre = wheel_cylinder(0.0625, 0.06, circumferential_resolution=120, axial_resolution=2)
    hub = wheel_cylinder(0.058, 0.05, circumferential_resolution=120, axial_resolution=1)  # inside the tyre
    both = TriangleMesh(
        np.vstack((tyre.vertices, hub.vertices)), np.vstack((tyre.faces, hub.faces + len(tyre.vertices)))
    )
    save_mesh(tyre, tmp_path / "tyre.stl")
    save_mesh(both, tmp_path / "tyre_hub.stl")
    base = {"medium": "MS", "load_N": 20.0, "slip": 0.3, "drawbar_pull_N": 0.0}
    t = runs_from_records(
        [{**base, "run_id": n, "mesh_file": str(tmp_path / f"{n}.stl")} for n in ("tyre", "tyre_hub")]
    )
    culled = replay(t, ReplayModel("rft3d")).runs
    plain = replay(t, ReplayModel("rft3d", cull=False)).runs
    assert culled[1]["predicted_sinkage_m"] == pytest.approx(culled[0]["predicted_sinkage_m"], rel=1e-9)
    assert culled[1]["predicted_drawbar_pull_N"] == pytest.approx(
        culled[0]["predicted_drawbar_pull_N"], rel=1e-9
    )
    assert plain[1]["predicted_sinkage_m"] != pytest.approx(plain[0]["predicted_sinkage_m"], rel=1e-3)
