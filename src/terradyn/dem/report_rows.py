"""DEM rows of the reproduction report (``terradyn reproduce``), listed when the ``dem`` extra imports.

``fig-4-1``: the plate alpha map of the ``dem-alpha`` study (DEM beside the Li et al. law of the
same medium). ``ch4-plate-depth``: the force on a horizontal plate pushed down versus depth in DEM,
beside RFT. ``ch9-plate-packing``: a horizontal plate pushed down in dense and loose beds of the same
grains (several bed seeds each): the dense / loose force ratio beside the packing fractions.
``ch9-plowing``: a vertical plate dragged through dense and loose beds (:func:`terradyn.dem.drag.run_drag`):
mean drag and the character of its fluctuations beside Gravish et al. (2010). Each row
is ``name(quick) -> ItemOutput``; every number in a finding comes from the run.
``quick`` is a smoke form (a plate of a few coarse grains, a few hundred grains in the bed) for the
default suite.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from ..report.registry import Finding, ItemOutput, register_row

__all__ = ["alpha_map", "plate_depth", "plate_packing", "plowing"]

_QUICK_NOTE = "quick form: a plate a few grains long, a few hundred grains; not converged"


def alpha_map(quick: bool) -> ItemOutput:
    """alpha_x, alpha_z of a plate over angle and direction in DEM (study ``dem-alpha``) against RFT."""
    from ..studies.dem_compare import DEMAlphaParams, _run_alpha

    p = DEMAlphaParams.model_validate({"quick": quick})
    res = _run_alpha(p)
    (summary,) = res.summary
    table = res.tables["dem_alpha"]
    out = ItemOutput(
        figures={"alpha_map_dem": res.figures["dem_alpha"]},
        settings={k: v for k, v in p.model_dump().items() if k != "mpm_csv"},
        tables={"alpha_map_dem": table.records()},
        metrics={k: summary[k] for k in ("best_fit_scale_dem_over_rft", "shape_rms_difference_after_scale",
                                          "alpha_z_ratio_mean", "grain_count", "dem_wall_time_s")},
    )  # fmt: skip
    n = int(summary["points"])
    shape = float(summary["shape_rms_difference_after_scale"])
    out.findings.append(
        Finding(
            f"{n} case{'s' if n > 1 else ''}, {summary['grain_count']} grains: DEM / RFT alpha_z "
            f"{summary['alpha_z_ratio_min']:.3f} to {summary['alpha_z_ratio_max']:.3f}; one scale factor for "
            f"both components {summary['best_fit_scale_dem_over_rft']:.3f}, rms shape difference after it "
            f"{shape:.1%} (the scale is the strength ratio of the medium's [dem] and [rft] tables, not "
            "calibrated to each other: calibrate rft --from-dem)",
            "info" if n < 3 else ("agrees" if shape <= 0.3 else "disagrees"),
        )
    )
    if quick:
        out.findings.append(Finding(_QUICK_NOTE, "info"))
    return out


@dataclass(frozen=True)
class _Depth:
    """Media, plate (length, width) [m], final depth [m], grain diameter [m] and speed [m/s]."""

    media: tuple[str, ...]
    plate: tuple[float, float]
    depth: float
    grain_diameter: float
    speed: float


#: quick: a 24 mm plate of six 4 mm grains to 16 mm; full: a 50 mm x 20 mm plate (as the RFT and MPM
#: rows) of 3 mm grains (the dem-alpha study's coarse-graining) to 60 mm, in the media whose [dem]
#: tables differ once the grain size is set: MS (generic's table is MS's but for the grain size:
#: measured, the same forces to the last digit), MMS (more friction and rolling resistance) and LPS
#: (light seeds; CPS has LPS's table, the two differ in packing only)
_DEPTH_QUICK = _Depth(("MS",), (0.024, 0.02), 0.016, 0.004, 0.05)
_DEPTH_FULL = _Depth(("MS", "MMS", "LPS"), (0.05, 0.02), 0.06, 0.003, 0.04)


def plate_depth(quick: bool) -> ItemOutput:
    """Force on a horizontal plate pushed down versus depth: DEM beside RFT in each medium."""
    import matplotlib.pyplot as plt

    from .. import materials
    from ..geometry import Plate
    from ..studies.dem_compare import dem_plate_body
    from ..studies.intrusion import intrusion_forces
    from .runs import run_intrusion

    s = _DEPTH_QUICK if quick else _DEPTH_FULL
    length, width = s.plate
    fig, ax = plt.subplots(figsize=(7, 4.6), layout="constrained")
    out = ItemOutput(figures={"plate_depth_dem": fig}, settings={**asdict(s), "packing": "loose"})
    rows = []
    for k, name in enumerate(s.media):
        mat = materials.get(name)
        res = run_intrusion(Plate(length, width), mat, depth=s.depth, direction=math.pi / 2, speed=s.speed,
                            packing="loose", grain_diameter=s.grain_diameter)  # fmt: skip
        h = res.history
        keep = (h["depth_m"] >= 0.0) & (h["depth_m"] <= s.depth)
        d, fz = np.asarray(h["depth_m"])[keep], np.asarray(h["force_z_N"])[keep]
        # RFT on the plate as the DEM resolves it (a quarter grain thicker on each side)
        rft_body = dem_plate_body(length, width, s.grain_diameter)
        rft = np.asarray(intrusion_forces(rft_body, mat, d).columns["force_z_N"])
        half = d >= 0.5 * s.depth
        slope = float(np.polyfit(d[half], fz[half], 1)[0])
        rft_slope = float(np.polyfit(d[half], rft[half], 1)[0])
        lower = half & (d <= 0.75 * s.depth)
        upper = d > 0.75 * s.depth
        grows = float(fz[upper].mean()) > float(fz[lower].mean())
        rows.append({"material": name, "grain_count": int(res.summary["grain_count"]),
                     "slope_dem_N_per_m": slope, "slope_rft_N_per_m": rft_slope,
                     "force_end_dem_N": float(fz[upper].mean()),
                     "force_end_rft_N": float(rft[upper].mean())})  # fmt: skip
        ax.plot(d * 1e3, fz, "-", color=f"C{k}", lw=1.0, label=f"{name} DEM")
        ax.plot(d * 1e3, rft, "--", color=f"C{k}", lw=1.2, label=f"{name} RFT")
        out.findings.append(
            Finding(
                f"{name} ({rows[-1]['grain_count']} grains of {s.grain_diameter * 1e3:g} mm): DEM "
                f"dF_z/d(depth) over the second half {slope:.1f} N/m against RFT {rft_slope:.1f} N/m (ratio "
                f"{slope / rft_slope:.2f}: the [dem] table is not calibrated to zeta); the mean force over "
                f"the last quarter of the stroke {'exceeds' if grows else 'does NOT exceed'} the one before "
                "it (RFT and deep-footing theory: the force keeps growing with depth)",
                # the quick plate spans a few grains: its force swings with each grain layer passed
                "info" if quick else ("agrees" if grows and slope > 0 else "disagrees"),
            )
        )
        out.metrics[f"{name}_slope_ratio_dem_over_rft"] = slope / rft_slope
    out.tables["plate_depth"] = rows
    ax.set_xlabel("depth of the plate centre [mm]")
    ax.set_ylabel("vertical force F_z [N]")
    ax.set_title(f"Plate {length * 1e3:g} x {width * 1e3:g} mm pushed down: DEM (loose, "
                 f"{s.grain_diameter * 1e3:g} mm grains, {s.speed:g} m/s) and RFT", fontsize=10)  # fmt: skip
    ax.grid(True, alpha=0.35)
    ax.legend(fontsize=8, ncols=2)
    if quick:
        out.findings.append(Finding(_QUICK_NOTE, "info"))
    return out


@dataclass(frozen=True)
class _Packing:
    """Medium, plate length [m], final depth [m], grain diameter [m], speed [m/s] and bed seeds."""

    medium: str
    length: float
    depth: float
    grain_diameter: float
    speed: float
    seeds: tuple[int, ...]


#: quick: a 24 mm plate of six 4 mm grains to 12 mm, one bed of each packing; full: the MPM row's
#: 40 mm plate to 20 mm in MS grains coarse-grained to 2 mm (20 along the plate), three beds each
_PACKING_QUICK = _Packing("MS", 0.024, 0.012, 0.004, 0.05, (1,))
_PACKING_FULL = _Packing("MS", 0.04, 0.02, 0.002, 0.04, (1, 2, 3))


def plate_packing(quick: bool) -> ItemOutput:
    """A plate pushed down in dense and in loose DEM beds (thesis ch. 9, consolidated / unconsolidated)."""
    import matplotlib.pyplot as plt

    from .. import materials
    from ..geometry import Plate
    from .runs import default_bed_spec, run_intrusion

    s = _PACKING_QUICK if quick else _PACKING_FULL
    mat = materials.get(s.medium)
    plate = Plate(s.length, 0.02)
    fig, ax = plt.subplots(figsize=(7, 4.6), layout="constrained")
    out = ItemOutput(figures={"plate_packing_dem": fig}, settings=asdict(s))
    rows: list[dict[str, float | int | str]] = []
    forces: dict[str, list[float]] = {"dense": [], "loose": []}
    fractions: dict[str, list[float]] = {"dense": [], "loose": []}
    for k, packing in enumerate(forces):
        for seed in s.seeds:
            spec = default_bed_spec(
                plate,
                depth=s.depth,
                direction=math.pi / 2,
                angle=0.0,
                grain_diameter=s.grain_diameter,
                packing=packing,
                seed=seed,
            )
            res = run_intrusion(
                plate, mat, depth=s.depth, direction=math.pi / 2, speed=s.speed, bed_spec=spec
            )
            h = res.history
            keep = (h["depth_m"] >= 0.0) & (h["depth_m"] <= s.depth)
            d, fz = np.asarray(h["depth_m"])[keep], np.asarray(h["force_z_N"])[keep]
            forces[packing].append(float(fz[d > 0.75 * s.depth].mean()))
            fractions[packing].append(float(res.bed["packing_fraction"]))
            rows.append(
                {
                    "packing": packing,
                    "seed": seed,
                    "grain_count": int(res.summary["grain_count"]),
                    "packing_fraction": fractions[packing][-1],
                    "force_last_quarter_N": forces[packing][-1],
                }
            )
            label = f"{packing}, bed seed {seed} (packing fraction {fractions[packing][-1]:.3f})"
            ax.plot(d * 1e3, fz, "-", color=f"C{k}", lw=1.0, alpha=0.9, label=label)
    out.tables["plate_packing"] = rows
    dense, loose = forces["dense"], forces["loose"]
    ratio = float(np.mean(dense)) / float(np.mean(loose))
    phi_d, phi_l = float(np.mean(fractions["dense"])), float(np.mean(fractions["loose"]))
    out.metrics.update(
        {"dense_over_loose": ratio, "packing_fraction_dense": phi_d, "packing_fraction_loose": phi_l}
    )
    separated = min(dense) > max(loose)
    out.findings.append(
        Finding(
            f"mean F_z over the last quarter of the stroke: dense {np.mean(dense):.3f} N (beds "
            f"{min(dense):.3f}-{max(dense):.3f}), loose {np.mean(loose):.3f} N ({min(loose):.3f}-"
            f"{max(loose):.3f}); dense / loose {ratio:.2f} at packing fractions {phi_d:.3f} / {phi_l:.3f}; "
            + ("every dense bed carries more than every loose one" if separated else
               "the dense and loose beds overlap"),
            "info" if quick else ("agrees" if separated else "disagrees"),
        )
    )  # fmt: skip
    out.findings.append(
        Finding(
            "the DEM beds differ in preparation only (dense: settled with a tenth of the grain friction; "
            "loose: with the full friction), the same grains and contact law; the MPM row's contrast comes "
            "from the bed density and the dilatancy law instead (docs/mpm.md)",
            "info",
        )
    )
    ax.set_xlabel("depth of the plate [mm]")
    ax.set_ylabel("vertical force F_z [N]")
    ax.set_title(f"Plate {s.length * 1e3:g} mm pushed down at {s.speed:g} m/s, {mat.name} grains of "
                 f"{s.grain_diameter * 1e3:g} mm: dense and loose DEM beds", fontsize=10)  # fmt: skip
    ax.grid(True, alpha=0.35)
    ax.legend(fontsize=7)
    if quick:
        out.findings.append(Finding(_QUICK_NOTE, "info"))
    return out


@dataclass(frozen=True)
class _Plow:
    """Grain diameter [m], speed [m/s], travel [m] and bed seeds of the plowing row."""

    grain_diameter: float
    speed: float
    distance: float
    seeds: tuple[int, ...]


#: quick: 5 mm grains (the plate seven grains long), 15 mm at 0.1 m/s, one bed each; full: 2 mm grains
#: (15 grains immersed), 60 mm at 0.05 m/s (the MPM row's travel and speed), two beds each
_PLOW_QUICK = _Plow(0.005, 0.1, 0.015, (1,))
_PLOW_FULL = _Plow(0.002, 0.05, 0.06, (1, 2))


def plowing(quick: bool) -> ItemOutput:
    """A vertical plate dragged through dense and loose DEM beds: drag and its fluctuations (ch. 9)."""
    import matplotlib.pyplot as plt

    from .. import materials
    from ..geometry import Plate
    from ..mpm.report_rows_ch9 import (
        _GRAVISH_TRANSITION,
        _MATERIAL,
        _PLOW_IMMERSED,
        _PLOW_LENGTH,
        fluctuations,
    )
    from .drag import run_drag

    s = _PLOW_QUICK if quick else _PLOW_FULL
    mat = materials.get(_MATERIAL)
    plate = Plate(_PLOW_LENGTH, 0.02)
    centre = _PLOW_IMMERSED - 0.5 * _PLOW_LENGTH  # the MPM row's plate: 30 mm of 35 mm in the bed
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.2), layout="constrained")
    rows: list[dict[str, Any]] = []
    for k, packing in enumerate(("dense", "loose")):
        for seed in s.seeds:
            res = run_drag(plate, mat, depth=centre, distance=s.distance, speed=s.speed, angle=0.5 * math.pi,
                           packing=packing, grain_diameter=s.grain_diameter, seed=seed)  # fmt: skip
            h = res.history
            late = h["travel_m"] >= s.distance - res.summary["averaging_window_m"] - 1e-12
            fl = fluctuations(h["travel_m"][late], h["drag_N"][late])
            rows.append({
                "packing": packing, "seed": seed, "packing_fraction": float(res.bed["packing_fraction"]),
                "grain_count": int(res.summary["grain_count"]), "drag_mean_N": res.summary["drag_N"],
                "lift_mean_N": res.summary["lift_N"], "drag_relative_std": fl["relative_std"],
                "autocorrelation_peak_lag_m": fl["peak_lag_m"],
                "autocorrelation_peak_height": fl["peak_height"],
            })  # fmt: skip
            label = f"{packing}, seed {seed} (packing fraction {rows[-1]['packing_fraction']:.3f})"
            axes[0].plot(h["travel_m"] * 1e3, h["drag_N"], "-", color=f"C{k}", lw=0.9, label=label)
    by = {p: [r for r in rows if r["packing"] == p] for p in ("dense", "loose")}
    for k, (p, sel) in enumerate(by.items()):
        phis = [r["packing_fraction"] for r in sel]
        axes[1].plot(phis, [r["drag_relative_std"] for r in sel], "o", color=f"C{k}",
                     label=f"{p}: std / mean of the detrended drag")  # fmt: skip
        axes[1].plot(phis, [r["autocorrelation_peak_height"] for r in sel], "s", mfc="none", color=f"C{k}",
                     label=f"{p}: autocorrelation peak")  # fmt: skip
    axes[1].axvline(_GRAVISH_TRANSITION, color="0.5", ls=":", label="Gravish et al. 2010 transition")
    axes[0].set_xlabel("travel [mm]")
    axes[0].set_ylabel("drag on the plate [N]")
    axes[1].set_xlabel("packing fraction of the bed [-]")
    axes[1].set_ylabel("fluctuation measure over the last half [-]")
    for ax in axes:
        ax.grid(True, alpha=0.35)
        ax.legend(fontsize=7)
    fig.suptitle(f"DEM plowing, {mat.name} grains of {s.grain_diameter * 1e3:g} mm: vertical plate "
                 f"{_PLOW_IMMERSED * 1e3:g} mm deep at {s.speed:g} m/s, dense and loose beds")  # fmt: skip
    out = ItemOutput(figures={"plowing_dem": fig},
                     settings={**asdict(s), "material": mat.name, "plate_m": _PLOW_LENGTH,
                               "immersed_m": _PLOW_IMMERSED}, tables={"plowing": rows})  # fmt: skip
    mean = {p: float(np.mean([r["drag_mean_N"] for r in sel])) for p, sel in by.items()}
    rel = {p: float(np.mean([r["drag_relative_std"] for r in sel])) for p, sel in by.items()}
    peak = {p: float(np.mean([r["autocorrelation_peak_height"] for r in sel])) for p, sel in by.items()}
    phi = {p: float(np.mean([r["packing_fraction"] for r in sel])) for p, sel in by.items()}
    gain = mean["dense"] / mean["loose"]
    out.metrics.update(
        dense_over_loose_drag=gain, relative_std_dense=rel["dense"], relative_std_loose=rel["loose"]
    )
    separated = min(r["drag_mean_N"] for r in by["dense"]) > max(r["drag_mean_N"] for r in by["loose"])
    out.findings.append(
        Finding(
            f"mean drag over the last half: dense {mean['dense']:.3f} N at packing fraction "
            f"{phi['dense']:.3f}, loose {mean['loose']:.3f} N at {phi['loose']:.3f} ({gain:.2f}x); "
            + ("every dense bed resists more than every loose one" if separated else
               "the dense and loose beds overlap"),
            "info" if quick else ("agrees" if separated else "disagrees"),
        )
    )  # fmt: skip
    # across beds, not on means: every dense bed must fluctuate more, and more periodically, than
    # every loose one
    larger = min(r["drag_relative_std"] for r in by["dense"]) > max(
        r["drag_relative_std"] for r in by["loose"]
    )
    periodic = min(r["autocorrelation_peak_height"] for r in by["dense"]) > max(
        r["autocorrelation_peak_height"] for r in by["loose"]
    )
    out.findings.append(
        Finding(
            f"fluctuations: std / mean of the detrended drag {rel['loose']:.3f} (loose) and "
            f"{rel['dense']:.3f} (dense); autocorrelation peak {peak['loose']:.2f} / {peak['dense']:.2f} "
            "(means over the beds). Gravish et al. 2010 see smooth drag below a packing fraction of about "
            "0.605 and periodic fluctuations above it; every dense bed "
            + ("fluctuates more" if larger else "does NOT fluctuate more")
            + " and "
            + ("more periodically" if periodic else "NOT more periodically")
            + " than every loose one",
            "info" if quick else ("agrees" if larger and periodic else "disagrees"),
        )
    )
    if quick:
        out.findings.append(Finding(_QUICK_NOTE, "info"))
    return out


register_row("fig-4-1", "dem", "terradyn.dem.report_rows:alpha_map")
register_row("ch9-plowing", "dem", "terradyn.dem.report_rows:plowing")
register_row("ch9-plate-packing", "dem", "terradyn.dem.report_rows:plate_packing")
register_row("ch4-plate-depth", "dem", "terradyn.dem.report_rows:plate_depth")
