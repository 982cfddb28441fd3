"""One wheel, four engines: quasi-static RFT, dynamic RFT, the MPM continuum and the DEM, one call each.

:func:`terradyn.locomotion.run_wheel` takes the same :class:`~terradyn.locomotion.WheelCase` whatever
the model; the engines' own settings (cell size, grain size) are specs of their own, and every result
has the same summary keys. The heavy engines run here at a tiny size so that the script finishes in
about a minute: 1 cm MPM cells (10 across the wheel) and 8 mm DEM grains on a 0.1 m wheel, one second of
rolling. Their numbers are a smoke test, not converged answers (with grains a sixth of the wheel's
radius the DEM wheel rides on the grain tips: its sinkage below the bed's nominal surface comes out
negative). For answers refine the MPM (``Resolution(cell_size=0.004)``, docs/mpm.md) and use the
medium's own grains in the DEM (``DEMSettings()``), at hours of CPU time.

Run: python examples/engine_comparison.py
"""

from __future__ import annotations

import math

from terradyn.geometry import WheelCircular
from terradyn.locomotion import DEMSettings, Dynamics, MPMSettings, WheelCase, compare_models, run_wheel
from terradyn.models import model_title
from terradyn.mpm import Resolution


def main() -> dict[str, float]:
    wheel = WheelCircular(radius=0.05, width=0.03)
    case = WheelCase(wheel, "MS", load=5.0, slip=0.3, omega=1.0, duration=1.0)
    settings = {
        "mpm": MPMSettings(resolution=Resolution(cell_size=0.01)),
        "dem": DEMSettings(grain_diameter=0.008),
    }
    runs = compare_models(case, ["rft", "drft", "mpm", "dem"], settings=settings)
    runs.append(run_wheel(case, "rft", settings=Dynamics()))  # the same law integrated in time
    print("model        engine        sinkage [mm]  pull [N]  torque [N m]  vertical [N]")
    for r in runs:
        s = r.summary
        sinkage, pull, torque = s["sinkage_m"] * 1e3, s["drawbar_pull_N"], s["drive_torque_Nm"]
        print(f"{model_title(r.model):12s} {r.engine.value:12s}  {sinkage:10.2f}  {pull:8.3f}  "
              f"{torque:12.4f}  {s['vertical_force_N']:11.3f}")  # fmt: skip
    out = {}
    for r in runs:
        s = r.summary
        assert all(v is None or math.isfinite(v) for v in s.values())
        # every engine carries the wheel's load and needs a driving torque at slip 0.3
        assert abs(s["vertical_force_N"] - 5.0) < 0.1 * 5.0, (r.model, s["vertical_force_N"])
        assert s["drive_torque_Nm"] > 0.0, r.model
        out[f"{r.model}_{r.engine.value}_pull"] = s["drawbar_pull_N"]
    # the quasi-static solve and the time integration of one law agree (its quasi-static limit)
    steady, dynamic = runs[0].summary, runs[-1].summary
    assert abs(steady["sinkage_m"] - dynamic["sinkage_m"]) < 0.05 * steady["sinkage_m"]
    return out


if __name__ == "__main__":
    main()
