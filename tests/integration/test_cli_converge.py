"""terradyn mpm converge: the command's plumbing (fast, with a stand-in solver) and a real tiny case."""

from __future__ import annotations

import json
from types import SimpleNamespace

import pytest


def test_converge_intrude_reports_runs_and_estimates(run_cli, tmp_path, monkeypatch):
    import terradyn.mpm as mpm

    calls = []

    def fake_run(body, material, *, resolution, bed, **kw):
        assert bed == mpm.Bed() and resolution.particles_per_cell == 2
        cell_size = resolution.cell_size
        calls.append(cell_size)
        return SimpleNamespace(summary={"force_z_N": 20.0 + 500.0 * cell_size, "force_x_N": 0.0,
                                        "torque_y_Nm": 0.0})  # fmt: skip

    monkeypatch.setattr(mpm, "run_intrusion", fake_run)
    out, plot = tmp_path / "c.json", tmp_path / "c.png"
    code, stdout, err = run_cli(
        "mpm", "converge", "intrude", "plate", "--length", "0.06", "--depth", "0.02",
        "--cell-sizes", "0.005,0.01,0.0075", "--format", "json", "--out", str(out), "--plot", str(plot),
    )  # fmt: skip
    assert code == 0, err
    assert calls == [0.01, 0.0075, 0.005]
    rec = json.loads(stdout)
    fz = next(e for e in rec["estimates"] if e["quantity"] == "force_z_N")
    assert fz["observed_order"] == pytest.approx(1.0) and fz["extrapolated"] == pytest.approx(20.0)
    assert [r["cell_size_m"] for r in rec["runs"]] == [0.01, 0.0075, 0.005]
    assert json.loads(out.read_text()) == rec and plot.stat().st_size > 10_000


def test_converge_drag_passes_the_case_and_reports_drag_and_lift(run_cli, monkeypatch):
    import terradyn.mpm as mpm

    calls = []

    def fake_run(body, material, *, resolution, bed, depth, distance, speed, angle, surface_friction):
        assert (depth, distance, speed, angle, surface_friction) == (0.05, 0.04, -0.1, 0.0, 0.0)
        assert bed == mpm.Bed() and body.radius == pytest.approx(0.0127)
        calls.append(resolution.cell_size)
        h = resolution.cell_size
        return SimpleNamespace(summary={"drag_N": 3.0 + 100.0 * h**2, "lift_N": 0.6 - 20.0 * h})

    monkeypatch.setattr(mpm, "run_drag", fake_run)
    code, stdout, err = run_cli(
        "mpm", "converge", "drag", "cylinder", "--radius", "0.0127", "--depth", "0.05", "--distance",
        "0.04", "--speed", "-0.1", "--surface-friction", "0", "--cell-sizes", "0.004,0.002,0.001",
        "--format", "json",
    )  # fmt: skip
    assert code == 0, err
    assert calls == [0.004, 0.002, 0.001]
    est = {e["quantity"]: e for e in json.loads(stdout)["estimates"]}
    assert est["drag_N"]["observed_order"] == pytest.approx(2.0)
    assert est["drag_N"]["extrapolated"] == pytest.approx(3.0)
    assert est["lift_N"]["observed_order"] == pytest.approx(1.0)
    assert est["lift_N"]["extrapolated"] == pytest.approx(0.6)


@pytest.mark.parametrize("sizes", ["0.01,0.005", "0.01,0.01,0.005", "0.01,-0.005,0.002", "x"])
def test_converge_needs_three_distinct_sizes(run_cli, sizes):
    code, _, err = run_cli("mpm", "converge", "intrude", "plate", "--length", "0.06", "--depth", "0.02",
                           "--cell-sizes", sizes)  # fmt: skip
    assert code == 1 and err.startswith("terradyn: error: --cell-sizes = ")


@pytest.mark.slow
def test_converge_real_tiny_case(run_cli):
    code, stdout, err = run_cli(
        "mpm", "converge", "intrude", "plate", "--length", "0.06", "--width", "0.02", "--depth", "0.02",
        "--cell-sizes", "0.01,0.008,0.0065", "--format", "json",
    )  # fmt: skip
    assert code == 0, err
    rec = json.loads(stdout)
    forces = [r["force_z_N"] for r in rec["runs"]]
    assert all(f > 0 for f in forces)
    fz = next(e for e in rec["estimates"] if e["quantity"] == "force_z_N")
    assert fz["error_band"] > 0
