"""MPM rows of chapters 4 and 8 of the reproduction report (``terradyn reproduce``).

``fig-4-1``: a plate's stress per depth over its angle and direction of motion, MPM beside the Li et
al. (2013) law of the same medium. ``ch4-plate-depth``: the force on a horizontal plate pushed down
versus depth, MPM beside RFT, in the media that have a continuum table. ``ch8-high-speed``: the
self-propelled grousered wheel of Agarwal et al. (2021) in MPM over spin rates, beside the RFT and
DRFT sweep of the same wheel. Each row is ``name(quick) -> ItemOutput``; every number in a finding
comes from the run. ``quick`` is a smoke form (coarse cells, short strokes) for the default suite.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..report.registry import Finding, ItemOutput, register_row
from .report_rows import _Setting

__all__ = ["alpha_map", "high_speed", "plate_depth"]

_QUICK_NOTE = "quick form: coarse cells, doubled speed, short stroke, small bed; not converged"


def _intrude(body: Any, material: str, depth: float, s: _Setting, angle_deg: float = 0.0,
             direction_deg: float = 90.0) -> tuple[dict[str, np.ndarray], dict[str, float]]:  # fmt: skip
    """One MPM intrusion along a direction [deg below +x] at a plate angle [deg]."""
    from .. import materials
    from .runs import run_intrusion
    from .specs import Bed, Resolution, Stroke

    res = run_intrusion(
        body,
        materials.get(material),
        depth=depth,
        angle=math.radians(angle_deg),
        direction=math.radians(direction_deg),
        speed=s.speed,
        bed=Bed(width=s.bed_width, depth=s.bed_depth),
        resolution=Resolution(cell_size=s.cell_size, min_cells_across=s.min_cells),
        stroke=Stroke(averaging_window=s.window),
    )
    series = {k: np.asarray(res.series[k]) for k in ("depth_m", "force_x_N", "force_z_N")}
    return series, dict(res.summary)


# ------------------------------------------------------------------------------ Fig. 4-1: alpha map
_ALPHA_MATERIAL = "MS"
_ALPHA_PLATE = (0.04, 0.02)  # length, width [m]: the mpm-alpha study's plate
#: quick: 12.5 mm cells (3.2 across), 0.1 m/s, a small bed, to 20 mm; full: 5 mm cells (8 across),
#: 0.05 m/s, the default bed and window, to 40 mm (the mpm-alpha study's settings)
_ALPHA_QUICK = _Setting(0.0125, 0.1, 3, window=0.01, bed_width=0.3, bed_depth=0.125)
_ALPHA_FULL = _Setting(0.005, 0.05, 6)
_ALPHA_GRID_QUICK = ((0.0, 60.0), (0.0, 120.0))
_ALPHA_GRID_FULL = tuple((a, g) for a in (0.0, 30.0, 60.0, 90.0) for g in (30.0, 60.0, 90.0, 120.0, 150.0))


def alpha_map(quick: bool) -> ItemOutput:
    """alpha_x, alpha_z of a 40 mm plate over angle and direction: MPM against the Li et al. law."""
    import matplotlib.pyplot as plt

    from .. import materials
    from ..geometry import Plate
    from ..rft.li2013 import li2013_alpha_material
    from ..studies.mpm_compare import scale_and_shape

    s = _ALPHA_QUICK if quick else _ALPHA_FULL
    grid = _ALPHA_GRID_QUICK if quick else _ALPHA_GRID_FULL
    depth = 0.02 if quick else 0.04
    length, width = _ALPHA_PLATE
    mat = materials.get(_ALPHA_MATERIAL)
    norm = length * width * depth
    rows = []
    for a, g in grid:
        _, summ = _intrude(Plate(length, width), _ALPHA_MATERIAL, depth, s, a, g)
        law = li2013_alpha_material(-math.radians(a), math.radians(g), mat)
        rows.append(
            {
                "angle_deg": a,
                "direction_deg": g,
                # alpha_x with the law's sign: positive resists motion along +x
                "alpha_x_mpm_N_per_m3": -summ["force_x_N"] / norm,
                "alpha_z_mpm_N_per_m3": summ["force_z_N"] / norm,
                "alpha_x_rft_N_per_m3": float(law[0]),
                "alpha_z_rft_N_per_m3": float(law[1]),
            }
        )
    m = np.array([[r["alpha_x_mpm_N_per_m3"], r["alpha_z_mpm_N_per_m3"]] for r in rows]).ravel()
    f = np.array([[r["alpha_x_rft_N_per_m3"], r["alpha_z_rft_N_per_m3"]] for r in rows]).ravel()
    scale, shape = scale_and_shape(m, f)
    ratios = [r["alpha_z_mpm_N_per_m3"] / r["alpha_z_rft_N_per_m3"] for r in rows]

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.4), layout="constrained")
    gam = np.linspace(1.0, 179.0, 90)
    for k, a in enumerate(sorted({r["angle_deg"] for r in rows})):
        curve = np.array([li2013_alpha_material(-math.radians(a), math.radians(x), mat) for x in gam])
        sel = [r for r in rows if r["angle_deg"] == a]
        for ax, comp, j in ((axes[0], "z", 1), (axes[1], "x", 0)):
            ax.plot(gam, scale * curve[:, j] / 1e6, "-", color=f"C{k}", label=f"RFT x {scale:.2f}, {a:g} deg")
            ax.plot([r["direction_deg"] for r in sel], [r[f"alpha_{comp}_mpm_N_per_m3"] / 1e6 for r in sel],
                    "o", color=f"C{k}", mec="k", label=f"MPM, {a:g} deg")  # fmt: skip
    for ax, comp in zip(axes, ("z", "x"), strict=True):
        ax.set_xlabel("direction of motion [deg below +x]")
        ax.set_ylabel(rf"$\alpha_{comp}$ [N/cm$^3$]")
        ax.axhline(0.0, color="k", lw=0.5)
        ax.set_xlim(0.0, 180.0)
        ax.grid(True, alpha=0.35)
        ax.legend(fontsize=7, ncols=2)
    fig.suptitle(
        f"Plate {length * 1e3:g} mm at {depth * 1e3:g} mm, {mat.name}: MPM ({s.cell_size * 1e3:g} mm cells, "
        f"{s.speed:g} m/s) against the Li et al. law scaled by the best-fit factor"
    )
    out = ItemOutput(
        figures={"alpha_map_mpm": fig},
        settings={"material": mat.name, "plate_m": list(_ALPHA_PLATE), "depth_m": depth, **s.as_dict()},
        tables={"alpha_map": rows},
        metrics={"best_fit_scale_mpm_over_rft": scale, "shape_rms_difference_after_scale": shape},
    )
    out.findings.append(
        Finding(
            f"{len(rows)} cases: MPM / RFT alpha_z {min(ratios):.3f} to {max(ratios):.3f}; one scale factor "
            f"for both components {scale:.3f}, rms shape difference after it {shape:.1%} (the shape "
            "agrees below 20 %; the scale is the two media's strength ratio, docs/mpm.md)",
            "agrees" if shape <= 0.2 else "disagrees",
        )
    )
    pairs = [(r, q) for r in rows for q in rows
             if r["angle_deg"] == q["angle_deg"] == 0.0 and r["direction_deg"] < 90.0
             and q["direction_deg"] == 180.0 - r["direction_deg"]]  # fmt: skip
    for r, q in pairs:
        dz = abs(r["alpha_z_mpm_N_per_m3"] - q["alpha_z_mpm_N_per_m3"]) / abs(r["alpha_z_mpm_N_per_m3"])
        sx = r["alpha_x_mpm_N_per_m3"] * q["alpha_x_mpm_N_per_m3"]
        out.findings.append(
            Finding(
                f"mirror pair, horizontal plate, directions {r['direction_deg']:g} / {q['direction_deg']:g} "
                f"deg: alpha_z differ by {dz:.2%}, alpha_x {r['alpha_x_mpm_N_per_m3'] / 1e6:+.3f} / "
                f"{q['alpha_x_mpm_N_per_m3'] / 1e6:+.3f} N/cm^3 (mirror symmetry: equal and opposite)",
                "agrees" if dz < 0.02 and sx < 0 else "disagrees",
            )
        )
    if quick:
        out.findings.append(Finding(_QUICK_NOTE + "; full form: 20 cases at 5 mm cells", "info"))
    return out


# --------------------------------------------------------------------- chapter 4: plate versus depth
_DEPTH_PLATE = (0.05, 0.02)  # the RFT row's plate
_DEPTH_MEDIA_QUICK = ("MS",)
_DEPTH_MEDIA_FULL = ("generic", "MS", "MMS", "LPS", "CPS")
_DEPTH_QUICK = _Setting(0.0125, 0.1, 3, window=0.01, bed_width=0.3, bed_depth=0.15)
_DEPTH_FULL = _Setting(0.005, 0.05, 6)


def plate_depth(quick: bool) -> ItemOutput:
    """Force on a 50 mm horizontal plate pushed down versus depth: MPM beside RFT in each medium."""
    import matplotlib.pyplot as plt

    from .. import materials
    from ..geometry import Plate
    from ..studies.intrusion import intrusion_forces

    s = _DEPTH_QUICK if quick else _DEPTH_FULL
    depth = 0.03 if quick else 0.08
    plate = Plate(*_DEPTH_PLATE)
    fig, ax = plt.subplots(figsize=(7, 4.6), layout="constrained")
    settings = {"plate_m": list(_DEPTH_PLATE), "max_depth_m": depth, **s.as_dict()}
    out = ItemOutput(figures={"plate_depth_mpm": fig}, settings=settings)
    rows = []
    for k, name in enumerate(_DEPTH_MEDIA_QUICK if quick else _DEPTH_MEDIA_FULL):
        series, _ = _intrude(plate, name, depth, s)
        keep = (series["depth_m"] >= 0.0) & (series["depth_m"] <= depth)  # the stroke below the surface
        d, fz = series["depth_m"][keep], series["force_z_N"][keep]
        rft = np.asarray(intrusion_forces(plate, materials.get(name), d).columns["force_z_N"])
        lower = (d >= 0.5 * depth) & (d <= 0.75 * depth)
        upper = d > 0.75 * depth
        slope = float(np.polyfit(d[d >= 0.5 * depth], fz[d >= 0.5 * depth], 1)[0])
        rft_slope = float(np.polyfit(d[d >= 0.5 * depth], rft[d >= 0.5 * depth], 1)[0])
        f_end, f_before = float(fz[upper].mean()), float(fz[lower].mean())
        grows = f_end > f_before
        rows.append({"material": name, "slope_mpm_N_per_m": slope, "slope_rft_N_per_m": rft_slope,
                     "force_end_mpm_N": f_end, "force_end_rft_N": float(rft[upper].mean())})  # fmt: skip
        ax.plot(d * 1e3, fz, "-", color=f"C{k}", lw=1.0, label=f"{name} MPM")
        ax.plot(d * 1e3, rft, "--", color=f"C{k}", lw=1.2, label=f"{name} RFT")
        out.findings.append(
            Finding(
                f"{name}: MPM dF_z/d(depth) over the second half {slope:.1f} N/m against RFT "
                f"{rft_slope:.1f} N/m (ratio {slope / rft_slope:.2f}); the mean force over the last quarter "
                f"of the stroke {'exceeds' if grows else 'does NOT exceed'} the one before it (deep-footing "
                "theory and RFT: the force keeps growing with depth)",
                "agrees" if grows and slope > 0 else "disagrees",
            )
        )
        out.metrics[f"{name}_slope_ratio_mpm_over_rft"] = slope / rft_slope
    out.tables["plate_depth"] = rows
    ax.set_xlabel("depth of the plate [mm]")
    ax.set_ylabel("vertical force F_z [N]")
    ax.set_title(f"Plate {_DEPTH_PLATE[0] * 1e3:g} x {_DEPTH_PLATE[1] * 1e3:g} mm pushed down: "
                 f"MPM ({s.cell_size * 1e3:g} mm cells) and RFT")  # fmt: skip
    ax.grid(True, alpha=0.35)
    ax.legend(fontsize=8, ncols=2)
    if quick:
        out.findings.append(Finding(_QUICK_NOTE, "info"))
    return out


# ----------------------------------------------------------------- chapter 8: the high-speed wheel
@dataclass(frozen=True)
class _Spin:
    """Spin rates omega sqrt(l/g), cell size [m] and drive [s] of the MPM high-speed row."""

    omegas: tuple[float, ...]
    cell_size: float
    duration: float


#: quick: one spin rate, 26.5 mm cells (8 across the wheel, lugs unresolved), 0.6 s; full: the
#: docs/mpm.md resolution study's finest affordable cells (6.5 mm) and 3 s of drive
_SPIN_QUICK = _Spin((0.5,), 0.0265, 0.6)
_SPIN_FULL = _Spin((0.3, 0.5, 1.0), 0.0065, 3.0)
#: a run counts as steady when its sinkage changes by less than 2 % of l per second over the last half
_STEADY_RATE = 0.02


def high_speed(quick: bool) -> ItemOutput:
    """The self-propelled grousered wheel (l = 0.212 m, mass ratio 6, poppy-cp): MPM beside DRFT."""
    import matplotlib.pyplot as plt

    from .. import materials
    from ..studies.high_speed import HighSpeedWheel, high_speed_sweep
    from .specs import Drive, Outputs, Resolution
    from .wheel_runs import run_wheel

    sp = _SPIN_QUICK if quick else _SPIN_FULL
    wheel = HighSpeedWheel(effective_grousers=False)  # MPM resolves the physical lugs
    mat = materials.get("poppy-cp")
    rho_c = mat.critical_density
    assert rho_c is not None
    ell, g = wheel.outer_diameter, 9.81
    load = wheel.mass(rho_c) * g
    omegas = np.array(sp.omegas) * math.sqrt(g / ell)
    # the sweep needs two or more rates: a slow one (0.1) is added below the row's
    sweep = np.unique(np.concatenate([[0.1 * math.sqrt(g / ell)], omegas]))
    drft = high_speed_sweep(models=("rft", "drft"), omegas=sweep, reduced=True).table.columns
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.2), layout="constrained")
    out = ItemOutput(
        figures={"high_speed_mpm": fig},
        settings={
            "material": mat.name,
            "outer_diameter_m": ell,
            "mass_ratio": wheel.mass_ratio,
            "load_N": load,
            "grousers_m": [wheel.grouser_count, wheel.grouser_height, wheel.grouser_thickness],
            "cell_size_m": sp.cell_size,
            "drive_s": sp.duration,
        },
    )
    rows = []
    for k, (w_hat, om) in enumerate(zip(sp.omegas, omegas, strict=True)):
        res = run_wheel(wheel.body(), mat, load=load, omega=float(om),
                        resolution=Resolution(cell_size=sp.cell_size), drive=Drive(duration=sp.duration),
                        outputs=Outputs(record_interval=sp.duration / 60))  # fmt: skip
        ser = res.series
        d = ser["phase"] == "drive"
        t, sink, vx = ser["time_s"][d], ser["sinkage_m"][d], ser["vx_m_s"][d]
        t = t - t[0]
        late = t >= 0.5 * t[-1]
        rate = float(np.polyfit(t[late], sink[late], 1)[0])
        slip = 1.0 - float(vx[t >= 0.75 * t[-1]].mean()) / (om * 0.5 * ell)
        sinkage = float(sink[t >= 0.75 * t[-1]].mean())
        sel = (drft["model"] == "drft") & np.isclose(drft["omega_rad_s"], om)
        d_slip, d_sink = float(drft["slip"][sel][0]), float(drft["sinkage_m"][sel][0])
        rows.append({"omega_normalised": w_hat, "slip_mpm": slip, "sinkage_mpm_m": sinkage,
                     "sink_rate_mpm_m_s": rate, "slip_drft": d_slip, "sinkage_drft_m": d_sink})  # fmt: skip
        axes[0].plot(t, sink * 1e3, color=f"C{k}", label=f"MPM omega sqrt(l/g) = {w_hat:g}")
        axes[0].axhline(d_sink * 1e3, color=f"C{k}", ls="--", lw=0.8, label=f"DRFT steady, {w_hat:g}")
        axes[1].plot(t, 1.0 - vx / (om * 0.5 * ell), color=f"C{k}", label=f"MPM {w_hat:g}")
        axes[1].axhline(d_slip, color=f"C{k}", ls="--", lw=0.8, label=f"DRFT steady, {w_hat:g}")
        steady = abs(rate) < _STEADY_RATE * ell
        out.metrics[f"slip_mpm_at_{w_hat:g}"] = slip
        out.metrics[f"sink_rate_mpm_at_{w_hat:g}_m_s"] = rate
        out.findings.append(
            Finding(
                f"omega sqrt(l/g) = {w_hat:g}: MPM slip {slip:.2f} and sinkage {sinkage * 1e3:.0f} mm "
                f"over the last quarter, sinking at {rate * 1e3:.1f} mm/s over the last half "
                f"({'steady' if steady else 'NOT steady'}: the bound is "
                f"{_STEADY_RATE * ell * 1e3:.1f} mm/s); DRFT slip {d_slip:.2f}, "
                f"sinkage {d_sink * 1e3:.0f} mm",
                "agrees" if steady and abs(slip - d_slip) <= 0.1 else "disagrees",
            )
        )
    out.tables["high_speed"] = rows
    axes[0].set_ylabel("sinkage [mm]")
    axes[1].set_ylabel("slip [-]")
    for ax in axes:
        ax.set_xlabel("time since the spin started [s]")
        ax.grid(True, alpha=0.35)
        ax.legend(fontsize=7)
    fig.suptitle(f"Grousered wheel, l = {ell * 1e3:g} mm, mass ratio {wheel.mass_ratio:g}, {mat.name}: "
                 f"MPM at {sp.cell_size * 1e3:g} mm cells (self-propelled)")  # fmt: skip
    out.findings.append(
        Finding(
            "the MPM wheel carries the physical 18 mm lugs, the RFT and DRFT wheel lugs at a third of "
            "that height (terradyn.studies.high_speed); the MPM medium is about twice as strong as its "
            "RFT medium on a plate (docs/mpm.md, 'Against RFT')"
            + (
                "; quick form: 26.5 mm cells (lugs unresolved), 0.6 s of drive; not converged"
                if quick
                else ""
            ),
            "info",
        )
    )
    return out


register_row("fig-4-1", "mpm", "terradyn.mpm.report_rows_ch48:alpha_map")
register_row("ch4-plate-depth", "mpm", "terradyn.mpm.report_rows_ch48:plate_depth")
register_row("ch8-high-speed", "mpm", "terradyn.mpm.report_rows_ch48:high_speed")
