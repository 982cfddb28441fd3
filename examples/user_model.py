"""Bring your own terrain model: a force law written here, run by terradyn's wheel solve and replay.

Any object with a ``name`` and ``wrench(body, pose, twist, *, about=None) -> Wrench2D`` is a terrain
model (:class:`terradyn.terrain.TerrainModel`); a plain function ``wrench(body, pose, twist)`` works
too (:func:`terradyn.models.as_terrain_model`). This one is a frictional pressure law: every leading
element below the free surface (outward normal facing its motion) carries a normal pressure
``k * depth`` and a tangential stress opposing its sliding, ``mu`` times the pressure once the sliding
speed is well above ``mobilising_speed`` (``tanh`` of their ratio: friction mobilised by slip).

The script runs it through :func:`terradyn.locomotion.wheel_steady` beside terradyn's RFT on the same
wheel, then replays the synthetic runs table that ships with terradyn with it (the same call as
``ReplayModel("rft")``, with ``terrain=`` the user's model).

Run: python examples/user_model.py
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

import numpy as np

from terradyn import materials
from terradyn.geometry import WheelCircular
from terradyn.kinematics import Pose2D, Twist2D, Wrench2D, point_velocities, rotation_matrix, torque_about
from terradyn.locomotion import wheel_steady
from terradyn.models import build_model
from terradyn.replay import ReplayModel, read_runs, replay


class FrictionalPressure:
    """Normal pressure ``k`` [N/m^3] x depth on leading elements, and a tangential stress of up to
    ``mu`` [-] times it, mobilised by the sliding speed (``mobilising_speed`` [m/s])."""

    name = "frictional-pressure"

    def __init__(self, k: float, mu: float, mobilising_speed: float = 0.02) -> None:
        self.k, self.mu, self.mobilising_speed = k, mu, mobilising_speed

    def wrench(
        self, body: object, pose: Pose2D, twist: Twist2D, *, about: tuple[float, float] | None = None
    ) -> Wrench2D:
        el = body.discretize()  # type: ignore[attr-defined]
        rot = rotation_matrix(pose.theta)
        offsets = el.midpoints @ rot.T
        points = offsets + np.array([pose.x, pose.z])
        normals = el.normals @ rot.T
        velocity = point_velocities(offsets, twist)
        depth = np.maximum(-points[:, 1], 0.0)
        leading = np.einsum("ij,ij->i", normals, velocity) > 0.0
        pressure = np.where(leading, self.k * depth, 0.0)
        tangent = np.column_stack((-normals[:, 1], normals[:, 0]))
        sliding = np.tanh(np.einsum("ij,ij->i", tangent, velocity) / self.mobilising_speed)
        stress = -pressure[:, None] * normals - (self.mu * pressure * sliding)[:, None] * tangent
        forces = stress * (el.lengths * el.width)[:, None]
        centre = (pose.x, pose.z) if about is None else about
        return Wrench2D(
            float(forces[:, 0].sum()), float(forces[:, 1].sum()), torque_about(points, forces, centre)
        )


def main() -> dict[str, float]:
    ms = materials.get("MS")
    wheel = WheelCircular(radius=0.125, width=0.06)
    mine = FrictionalPressure(k=ms.zeta, mu=0.5)
    rft = build_model("rft", ms)  # terradyn's own model from the model table
    out: dict[str, float] = {}
    print("slip   pull [N] (mine / RFT)   sinkage [mm] (mine / RFT)")
    for slip in (0.1, 0.3, 0.5):
        a = wheel_steady(wheel, mine, load=20.0, slip=slip)
        b = wheel_steady(wheel, rft, load=20.0, slip=slip)
        # the solve balances the load with the user's force law: evaluate it at the solved state
        twist = Twist2D(a.forward_velocity_m_s, 0.0, a.omega_rad_s)
        carried = mine.wrench(wheel, Pose2D(0.0, a.axle_height_m, 0.0), twist).fz
        assert abs(carried - 20.0) < 1e-3 * 20.0, carried
        print(f"{slip:4.1f}   {a.drawbar_pull_N:7.2f} / {b.drawbar_pull_N:6.2f}"
              f"        {a.sinkage_m * 1e3:6.2f} / {b.sinkage_m * 1e3:6.2f}")  # fmt: skip
        out[f"pull_{slip:g}"] = a.drawbar_pull_N
    # more slip, more pull, as for any frictional law
    assert out["pull_0.1"] < out["pull_0.3"] < out["pull_0.5"]

    table = read_runs(Path(str(resources.files("terradyn.replay").joinpath("data/example_runs.csv"))))
    res = replay(table, ReplayModel("frictional-pressure", terrain=lambda m: FrictionalPressure(m.zeta, 0.5)))
    pulls = {r["quantity"]: r for r in res.metrics if r["set"] == "all"}
    print(f"replayed {len(table)} runs: pull RMSE {pulls['drawbar_pull_N']['rmse']:.3g} N, "
          f"r = {pulls['drawbar_pull_N']['pearson_r']:.3f}")  # fmt: skip
    assert not res.failures
    out["replay_pull_rmse"] = pulls["drawbar_pull_N"]["rmse"]
    return out


if __name__ == "__main__":
    main()
