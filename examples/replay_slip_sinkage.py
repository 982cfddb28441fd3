"""Slip-sinkage RFT against plane RFT on runs that slip-sink: calibrate both, compare on held-out runs.

A synthetic campaign made by the slip-sinkage model itself (``rft-ss`` with excavation 0.8, seeded
noise) stands in for a rig whose wheels dig in as they slip. Plane RFT, even with its scale fitted,
cannot follow the sinkage rise and the levelling pull; slip-sinkage RFT, fitted on the same half of the
runs, recovers its coefficients and predicts the other half to the noise level.

Run: python examples/replay_slip_sinkage.py
"""

from __future__ import annotations

from terradyn.replay import ReplayModel, replay, runs_from_records
from terradyn.replay.synthetic import design_runs, synthetic_records

NOISE = {"drawbar_pull_N": 0.1, "drive_torque_Nm": 5e-3, "sinkage_m": 3e-4}


def main() -> dict[str, float]:
    runs = design_runs(loads=(20.0,), slips=(-0.6, -0.3, 0.0, 0.2, 0.4, 0.6, 0.8), grousered=False)
    truth = ReplayModel("rft-ss", excavation=0.8, bulldozing=1.0)
    table = runs_from_records(synthetic_records(truth, runs, noise=NOISE, seed=11))
    held_rmse = {}
    for name in ("rft", "rft-ss"):
        res = replay(table, ReplayModel(name), calibrate_on=0.6, seed=4)
        assert res.calibration is not None
        held = {m["quantity"]: m for m in res.metrics if m["set"] == "held-out"}
        held_rmse[name] = held["sinkage_m"]["rmse"]
        fitted = ", ".join(f"{k} {v:.3f}" for k, v in res.calibration.parameters.items())
        print(
            f"{name:7s} fitted {fitted}; held-out RMSE: sinkage {held['sinkage_m']['rmse'] * 1e3:.2f} mm, "
            f"drawbar pull {held['drawbar_pull_N']['rmse']:.2f} N"
        )
    assert held_rmse["rft-ss"] < 0.5 * held_rmse["rft"]
    return held_rmse


if __name__ == "__main__":
    main()
