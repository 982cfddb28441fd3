"""Gravity scaling of a wheel in DEM (Slonaker et al. 2017): one wheel test at g and at lambda_g g.

The pair is made by :func:`terradyn.scaling.scale_test` with ``ScaleFactors(gravity=lambda_g)``: the
same wheel (size and mass), the same grains, the spin times sqrt(lambda_g), so the load (its weight)
times lambda_g and the run time over the same travel times 1 / sqrt(lambda_g). Each run pours and
settles its own bed at its own gravity (same bed size, seed and packing) and rolls the wheel at the
same prescribed slip (:func:`terradyn.dem.wheel.run_wheel`, free to sink under its weight). The
scaling says sinkage / L, drawbar pull / (M g), drive torque / (M g L) and vertical force / (M g) are
the same for both (L the wheel radius, M its mass, g each run's gravity).

Prescribed slip, not a free wheel: at prescribed slip and spin the kinematics of both runs are equal
by construction and the comparison is of the soil's response only; a free wheel adds the slip as one
more output, found through the drawbar balance, whose noise (the drawbar pull is the small difference
of large forces) feeds back into the kinematics and makes the pair noisier.

What does not scale: the grains keep their Young's modulus, so the stiffness number E / (rho_s g d)
is 1 / lambda_g times larger in the weaker gravity (both far above the quasi-static limit of about
1e4 at the defaults), and the viscous rolling damping of the contact law is a fixed coefficient, not
one scaled with sqrt(g). The bed seeds' spread measures how much two realisations of the same bed
differ: the same case at the reference gravity is run with every seed in ``seeds``; the pair's
difference is reported against that spread.

References
----------
J. Slonaker et al., "General scaling relations for locomotion in granular media", Phys. Rev. E 95,
052901 (2017). doi:10.1103/PhysRevE.95.052901
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from pydantic import Field

from .. import materials
from ..errors import InputError
from ..geometry import WheelCircular
from ..materials import Material
from ..results import TableResult
from ..scaling import ScaleFactors, WheelTest, scale_test
from ._base import StudyEntry, StudyOutput, _Params

__all__ = ["DIMENSIONLESS", "GravityPairResult", "dem_gravity_pair", "pair_comparison"]

#: dimensionless summary columns (the late-half means of each run) and their labels
DIMENSIONLESS = {
    "sinkage_over_L": "sinkage / L",
    "drawbar_pull_over_Mg": "drawbar pull / (M g)",
    "drive_torque_over_MgL": "drive torque / (M g L)",
    "vertical_force_over_Mg": "vertical force / (M g)",
}
#: a ratio or a difference over spread with a zero denominator (a zero reference mean or spread)
NO_VALUE = -1.0


@dataclass(frozen=True, eq=False)
class GravityPairResult:
    """Per run (one row each): the case, the bed and the dimensionless late-half means (``runs``);
    per run its dimensionless history (``histories``, keys: ``travel_over_L``, ``time_hat`` =
    t sqrt(g / L), and the :data:`DIMENSIONLESS` keys)."""

    runs: TableResult
    histories: list[dict[str, np.ndarray]]


def _medium(material: str | Material, youngs_modulus: float | None) -> Material:
    mat = materials.get(material) if isinstance(material, str) else material
    dem = mat.require_dem()
    if youngs_modulus is None:
        return mat
    if not (math.isfinite(youngs_modulus) and youngs_modulus > 0):
        raise InputError("youngs_modulus", youngs_modulus, "a Young's modulus > 0 [Pa]")
    return mat.with_changes(
        name=f"{mat.name}-E{youngs_modulus:g}", dem=dataclasses.replace(dem, youngs_modulus=youngs_modulus)
    )


def check_case(positive: dict[str, float], slip: float, seeds: Sequence[int]) -> None:
    """One line naming the first bad input of a DEM wheel case: ``positive`` values > 0, a slip in
    (-1, 1), two or more distinct bed seeds."""
    for name, value in positive.items():
        if not (math.isfinite(value) and value > 0):
            raise InputError(name, value, "a value > 0")
    if not -1.0 < slip < 1.0:
        raise InputError("slip", slip, "a slip in (-1, 1)")
    if len(seeds) < 2 or len(set(seeds)) != len(seeds):
        raise InputError("seeds", list(seeds), "two or more distinct bed seeds (the run-to-run spread)")


def dem_gravity_pair(
    material: str | Material = "generic",
    *,
    gravity: float = 9.81,
    factors: Sequence[float] = (1.0 / 6.0,),
    seeds: Sequence[int] = (1, 2),
    radius: float = 0.016,
    width: float = 0.05,
    load: float = 1.0,
    omega: float = 6.0,
    slip: float = 0.3,
    travel: float = 0.032,
    grain_diameter: float = 0.002,
    youngs_modulus: float | None = 1.0e6,
    packing: str = "loose",
    rows: int = 40,
) -> GravityPairResult:
    """Roll one DEM wheel test at ``gravity`` [m/s^2] and its scaled copies at ``gravity * factor``.

    The test: a circular wheel of ``radius`` and ``width`` [m] under ``load`` [N] (its weight at
    ``gravity``: mass M = load / gravity, kept at every gravity) spinning at ``omega`` [rad/s] at
    ``slip`` over ``travel`` [m] of axle travel (the same at every gravity, so the run lasts
    travel / ((1 - slip) omega r), ``rows`` history rows), on a slab bed of ``material``'s ``[dem]``
    grains of ``grain_diameter`` [m] (``youngs_modulus`` [Pa] softens them; None keeps the table's),
    poured and settled at each run's gravity. Scaled copies: :func:`terradyn.scaling.scale_test` with
    ``ScaleFactors(gravity=factor)`` (spin x sqrt(factor), load x factor, same mass and size).

    Runs: the reference gravity with every seed of ``seeds`` (the run-to-run spread), each scaled
    gravity with the first seed. One LAMMPS run at a time, in this process (progress through
    :func:`terradyn.parallel.map_items`). Raises :class:`terradyn.dem.DEMUnavailable` (one line)
    without the ``dem`` extra.
    """
    from ..dem import load_lammps

    mat = _medium(material, youngs_modulus)
    positive = {"gravity": gravity, "radius": radius, "width": width, "load": load, "omega": omega,
                "travel": travel, "grain_diameter": grain_diameter}  # fmt: skip
    check_case(positive, slip, seeds)
    if not factors or any(not (math.isfinite(f) and f > 0) for f in factors):
        raise InputError("factors", list(factors), "one or more gravity ratios > 0")
    load_lammps()
    body = WheelCircular(radius, width)
    base = WheelTest(body=body, material=mat, mass=load / gravity, omega=omega, gravity=gravity)
    cases = [(1.0, int(s)) for s in seeds] + [(float(f), int(seeds[0])) for f in factors]

    from ..parallel import map_items

    def one(case: tuple[float, int]) -> tuple[dict[str, Any], dict[str, np.ndarray]]:
        return _run_case(base, case[0], case[1], slip=slip, travel=travel, grain_diameter=grain_diameter,
                         packing=packing, rows=rows)  # fmt: skip

    done = map_items(one, cases)
    cols = {k: np.array([r[k] for r, _ in done]) for k in done[0][0]}
    meta = {
        "material": mat.name,
        "youngs_modulus_Pa": mat.require_dem().youngs_modulus,
        "grain_diameter_m": grain_diameter,
        "packing": packing,
        "wheel_radius_m": radius,
        "wheel_width_m": width,
        "mass_kg": base.mass,
        "slip": slip,
        "travel_m": travel,
        "reference_gravity_m_s2": gravity,
        "scaling": "Slonaker et al. 2017 (terradyn.scaling.scale_test, same mass and size)",
        "summary_window": "mean over the second half of each run",
    }
    return GravityPairResult(TableResult(cols, meta), [h for _, h in done])


def _run_case(base: WheelTest, factor: float, seed: int, *, slip: float, travel: float, grain_diameter: float,
              packing: str, rows: int) -> tuple[dict[str, Any], dict[str, np.ndarray]]:  # fmt: skip
    from ..dem.wheel import run_wheel, wheel_radius

    test = scale_test(base, ScaleFactors(gravity=factor)) if factor != 1.0 else base
    r = wheel_radius(base.body)  # the wheel's nominal radius, as run_wheel takes it
    duration = travel / ((1.0 - slip) * test.omega * r)
    start = time.perf_counter()
    res = run_wheel(test.body, test.material, load=test.load, omega=test.omega, slip=slip, duration=duration,
                    packing=packing, grain_diameter=grain_diameter, seed=seed, gravity=test.gravity,
                    record_interval=duration / rows)  # fmt: skip
    wall = time.perf_counter() - start
    g, m, s, h = test.gravity, test.mass, res.summary, res.history
    weight = m * g
    dem = test.material.require_dem()
    row = {
        "gravity_m_s2": g,
        "gravity_factor": factor,
        "seed": seed,
        "omega_rad_s": test.omega,
        "load_N": test.load,
        "duration_s": duration,
        "omega_hat": test.omega * math.sqrt(r / g),
        "stiffness_number": dem.youngs_modulus / (dem.grain_density * g * grain_diameter),
        "grain_count": int(s["grain_count"]),
        "packing_fraction": float(res.bed["packing_fraction"]),
        "sinkage_m": s["sinkage_m"],
        "drawbar_pull_N": s["drawbar_pull_N"],
        "drive_torque_Nm": s["drive_torque_Nm"],
        "vertical_force_N": s["vertical_force_N"],
        "sinkage_over_L": s["sinkage_m"] / r,
        "drawbar_pull_over_Mg": s["drawbar_pull_N"] / weight,
        "drive_torque_over_MgL": s["drive_torque_Nm"] / (weight * r),
        "vertical_force_over_Mg": s["vertical_force_N"] / weight,
        "wall_time_s": wall,
    }
    hist = {
        "time_hat": h["time_s"] * math.sqrt(g / r),
        "travel_over_L": (h["x_m"] - h["x_m"][0]) / r,
        "sinkage_over_L": h["sinkage_m"] / r,
        "drawbar_pull_over_Mg": h["drawbar_pull_N"] / weight,
        "drive_torque_over_MgL": h["drive_torque_Nm"] / (weight * r),
        "vertical_force_over_Mg": h["vertical_force_N"] / weight,
    }
    return row, hist


def pair_comparison(runs: TableResult) -> TableResult:
    """Per scaled gravity and dimensionless quantity: the reference run of the same seed and the
    scaled one, their ratio and difference, the seed spread at the reference gravity (largest minus
    smallest over the seeds) and the difference in units of that spread."""
    c = runs.columns
    ref = c["gravity_factor"] == 1.0
    first = int(c["seed"][np.flatnonzero(~ref)[0]]) if (~ref).any() else int(c["seed"][0])
    k_ref = int(np.flatnonzero(ref & (c["seed"] == first))[0])
    out: dict[str, list[Any]] = {k: [] for k in ("gravity_factor", "quantity", "reference", "scaled",
                                                 "ratio", "difference", "seed_spread",
                                                 "difference_over_spread")}  # fmt: skip
    for k in np.flatnonzero(~ref):
        for q in DIMENSIONLESS:
            a, b = float(c[q][k_ref]), float(c[q][k])
            spread = float(np.ptp(c[q][ref]))
            out["gravity_factor"].append(float(c["gravity_factor"][k]))
            out["quantity"].append(q)
            out["reference"].append(a)
            out["scaled"].append(b)
            out["ratio"].append(b / a if a != 0 else NO_VALUE)
            out["difference"].append(b - a)
            out["seed_spread"].append(spread)
            out["difference_over_spread"].append(abs(b - a) / spread if spread > 0 else NO_VALUE)
    note = f"{NO_VALUE:g} where the reference or the spread is 0"
    return TableResult({k: np.array(v) for k, v in out.items()}, {**runs.metadata, "no_value": note})


def _label(c: dict[str, np.ndarray], k: int) -> str:
    return f"g = {c['gravity_m_s2'][k]:.3g} m/s$^2$ (x{c['gravity_factor'][k]:.3g}), seed {c['seed'][k]}"


def plot_gravity_pair(result: GravityPairResult) -> Any:
    """Four panels of the dimensionless histories against travel in wheel radii (the late-half window
    shaded, its means as dashed lines), one line per run."""
    import matplotlib.pyplot as plt

    c, md = result.runs.columns, result.runs.metadata
    fig, axes = plt.subplots(2, 2, figsize=(11, 7), sharex=True, layout="constrained")
    styles = ["-", "--", ":", "-."]
    for k, h in enumerate(result.histories):
        ref = c["gravity_factor"][k] == 1.0
        colour = "C0" if ref else f"C{1 + int(np.sum(c['gravity_factor'][:k] != 1.0))}"
        ls = styles[int(np.sum(c["gravity_factor"][:k] == 1.0)) % 4] if ref else "-"
        late = h["time_hat"] > 0.5 * h["time_hat"][-1]
        for ax, q in zip(axes.ravel(), DIMENSIONLESS, strict=True):
            ax.plot(h["travel_over_L"], h[q], ls=ls, color=colour, lw=1.2, label=_label(c, k))
            ax.hlines(c[q][k], h["travel_over_L"][late][0], h["travel_over_L"][-1], colors=colour,
                      linestyles="--", lw=2.0, alpha=0.7)  # fmt: skip
    t0 = 0.5 * result.histories[0]["travel_over_L"][-1]
    for ax, label in zip(axes.ravel(), DIMENSIONLESS.values(), strict=True):
        ax.axvspan(t0, result.histories[0]["travel_over_L"][-1], color="0.92", zorder=0)
        ax.set_ylabel(f"{label} [-]")
        ax.grid(True, alpha=0.35)
    for ax in axes[1]:
        ax.set_xlabel("axle travel / wheel radius L [-]")
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=min(len(labels), 3), fontsize=8)
    fig.suptitle(
        f"DEM wheel at {len(set(c['gravity_factor']))} gravities g', Slonaker scaling (same mass and size, "
        "spin x sqrt(g'/g)): "
        f"L = {md['wheel_radius_m'] * 1e3:g} mm, slip {md['slip']:g}, {int(c['grain_count'][0])} grains "
        f"of {md['grain_diameter_m'] * 1e3:g} mm\n(shaded: late half, its means dashed)",
        fontsize=10,
    )
    return fig


class DEMGravityParams(_Params):
    material: str = "generic"
    gravity_m_s2: float = Field(9.81, gt=0.05, le=100, description="Reference gravity [m/s^2].")
    factors: list[float] = Field(default_factory=lambda: [1.0 / 6.0, 0.5], min_length=1)
    seeds: list[int] = Field(default_factory=lambda: [1, 2, 3], min_length=2)
    radius_m: float = Field(0.016, gt=0)
    width_m: float = Field(0.05, gt=0)
    load_N: float = Field(1.0, gt=0, description="Load at the reference gravity [N] (mass = load / g).")
    omega_rad_s: float = Field(6.0, gt=0, description="Spin at the reference gravity [rad/s].")
    slip: float = Field(0.3, gt=-1, lt=1)
    travel_m: float = Field(0.032, gt=0)
    grain_diameter_m: float = Field(0.002, gt=0)
    youngs_modulus_Pa: float | None = Field(1.0e6, gt=0, description="Grain stiffness [Pa] (None: table's).")
    packing: str = Field("loose", pattern="^(loose|dense)$")


def _run_gravity(p: DEMGravityParams) -> StudyOutput:
    # quick: a wheel of three 4 mm grains radius over half a radius of travel (about 900 grains), two
    # seeds and g / 6 only
    quick = {"radius": 0.012, "travel": 0.006, "grain_diameter": 0.004, "rows": 12} if p.quick else {}
    res = dem_gravity_pair(
        p.material,
        gravity=p.gravity_m_s2,
        factors=p.factors[:1] if p.quick else p.factors,
        seeds=p.seeds[:2] if p.quick else p.seeds,
        radius=quick.get("radius", p.radius_m),
        width=p.width_m,
        load=p.load_N,
        omega=p.omega_rad_s,
        slip=p.slip,
        travel=quick.get("travel", p.travel_m),
        grain_diameter=quick.get("grain_diameter", p.grain_diameter_m),
        youngs_modulus=p.youngs_modulus_Pa,
        packing=p.packing,
        rows=int(quick.get("rows", 40)),
    )
    pairs = pair_comparison(res.runs)
    hist_rows: dict[str, list[float]] = {"run": [], **{k: [] for k in res.histories[0]}}
    for k, h in enumerate(res.histories):
        hist_rows["run"].extend([float(k)] * len(h["time_hat"]))
        for key in h:
            hist_rows[key].extend(h[key].tolist())
    histories = TableResult({k: np.asarray(v) for k, v in hist_rows.items()}, res.runs.metadata)
    summary = [
        {"gravity_factor": r["gravity_factor"], "quantity": r["quantity"], "reference": r["reference"],
         "scaled": r["scaled"], "ratio": r["ratio"], "seed_spread": r["seed_spread"],
         "difference_over_spread": r["difference_over_spread"]}
        for r in pairs.records()
    ]  # fmt: skip
    return StudyOutput(
        {"dem_gravity_runs": res.runs, "dem_gravity_pairs": pairs, "dem_gravity_histories": histories},
        {"dem_gravity": plot_gravity_pair(res)},
        summary,
    )


def study_entries() -> tuple[StudyEntry, ...]:
    """The studies this module provides (:mod:`terradyn.studies.registry` lists them)."""
    return (
        (
            "dem-gravity",
            DEMGravityParams,
            _run_gravity,
            "DEM wheel at g, g/6, g/2 (Slonaker scaling) vs bed seeds",
        ),
    )
