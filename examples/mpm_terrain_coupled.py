"""Drop a loaded footing on a sand bed: the same driver on MPM (stateful) and on RFT (stateless).

MPM is a stateful terrain model: ``init`` settles a bed around the body, ``step`` advances the grains
with the body moving rigidly and returns the wrench. ``simulate_coupled`` integrates the body's free
vertical motion under its load with any terrain model, so the comparison is one argument apart.
Coarse grid (1 cm cells) so that it runs in seconds; refine ``cell_size`` for numbers.

Run: python examples/mpm_terrain_coupled.py
"""

from __future__ import annotations

from terradyn import materials
from terradyn.geometry import Plate
from terradyn.kinematics import Pose2D
from terradyn.locomotion import simulate_coupled
from terradyn.mpm import MPMTerrain


def main() -> dict[str, float]:
    sand = materials.get("MS")
    footing = Plate(length=0.06, width=0.05, thickness=0.02)
    load = 20.0  # N
    start = Pose2D(0.0, 0.0105)  # bottom face just above the surface
    mpm = MPMTerrain(sand, bed_width=0.3, bed_depth=0.08, cell_size=0.01, max_speed=0.5)
    out = {}
    for name, terrain in (("mpm", mpm), ("rft", sand)):
        res = simulate_coupled(footing, terrain, load=load, pose=start, duration=0.25, dt=1e-3)
        s = res.summary
        out[name] = s["sinkage_m"]
        print(f"{name}: sinkage {s['sinkage_m'] * 1e3:6.2f} mm, soil force {s['force_z_N']:6.2f} N")
        assert abs(s["force_z_N"] - load) < 0.05 * load  # at rest, the soil carries the load
    print(f"MPM bed: {mpm}")
    return out


if __name__ == "__main__":
    main()
