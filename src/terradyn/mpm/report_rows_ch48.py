"""MPM rows of chapters 4 and 8 of the reproduction report (``terradyn reproduce``).

``fig-4-1``: a plate's stress per depth over its angle and direction of motion, MPM beside the Li et
al. (2013) law of the same medium. ``ch4-plate-depth``: the force on a horizontal plate pushed down
versus depth, MPM beside RFT, in the media that have a continuum table. ``ch8-high-speed``: the
self-propelled grousered wheel of Agarwal et al. (2021) in MPM over spin rates, beside the RFT and
DRFT sweep of the same wheel. Each row is ``name(quick) -> ItemOutput``; every number in a finding
comes from the run. ``quick`` is a smoke form (coarse cells, short strokes) for the default suite.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..report.registry import Finding, ItemOutput, register_row
from .report_rows import _Setting, bed_outgrown_findings

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
    scale, shape = _map_scale_and_shape(rows)
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
    out.findings.extend(_edgewise_findings(rows, scale))
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


def _map_scale_and_shape(rows: list[dict]) -> tuple[float, float]:
    """:func:`terradyn.studies.mpm_compare.alpha_scale_and_shape` of the MPM map rows against the law."""
    from ..studies.mpm_compare import alpha_scale_and_shape

    return alpha_scale_and_shape({k: np.array([r[k] for r in rows]) for k in rows[0]}, "mpm", "rft")


def _edgewise_findings(rows: list[dict], scale: float) -> list[Finding]:
    """The cases where the plate moves along its own plane, and the shape residual without them.

    The plate is rotated by the angle about +y (its +x end tilts down) and moves the direction below
    +x, so angle = direction is edgewise motion (at 90 deg a vertical plate moving down). The one-cell
    plate of the MPM then meets the grains with its edge and two sliding faces; the Li et al. (2013)
    law, a fit to experiments, need not vanish there.
    """
    edge = [r for r in rows if r["angle_deg"] == r["direction_deg"]]
    rest = [r for r in rows if r not in edge]
    if not edge or len(rest) < 2:
        return []
    cases = "; ".join(
        f"{r['angle_deg']:g} deg: alpha_z MPM {r['alpha_z_mpm_N_per_m3'] / 1e6:.3f}, RFT x {scale:.2f} "
        f"{scale * r['alpha_z_rft_N_per_m3'] / 1e6:.3f} N/cm^3"
        for r in edge
    )
    s_rest, shape_rest = _map_scale_and_shape(rest)
    return [
        Finding(
            f"edgewise cases (the plate moving along its own plane, direction = plate angle): {cases}; "
            f"without them ({len(rest)} cases) the scale is {s_rest:.3f} and the rms shape difference "
            f"{shape_rest:.1%}",
            "info",
        )
    ]


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
    """Spin rates omega sqrt(l/g), cell size [m], drive [s], FLIP fraction and spin-up [s] of the
    MPM high-speed row; at ``history`` (a spin rate of ``omegas``) the start is also varied."""

    omegas: tuple[float, ...]
    cell_size: float
    duration: float
    flip: float
    spin_up: float
    history: float


#: quick: one spin rate, 26.5 mm cells (8 across the wheel, lugs unresolved), 0.6 s; full: 9 mm cells
#: with the FLIP 0.99 blend and a 1 s spin-up, 4 s at full spin. Why FLIP: with APIC this wheel digs
#: in at mass ratio 6 (slip 0.61 and still sinking 12 mm/s after 4 s at 0.5), with FLIP 0.99 it
#: settles (docs/mpm.md, "The transfer is a second lever"); why the spin-up: an impulsive start at
#: omega sqrt(l/g) = 1.0 digs the wheel in before it climbs out over the next 3 s ("The start").
_SPIN_QUICK = _Spin((0.5,), 0.0265, 0.6, 0.99, 0.15, 0.5)
_SPIN_FULL = _Spin((0.3, 0.5, 1.0, 1.5), 0.009, 5.0, 0.99, 1.0, 1.0)
#: a run counts as steady when its sinkage changes by less than 2 % of l per second over the last half
_STEADY_RATE = 0.02
#: starts that agree: last-quarter slips within 0.05, sinkages within 10 %
_START_SLIP, _START_SINK = 0.05, 0.10


def _spin_run(wheel: Any, mat: Any, load: float, om: float, sp: _Spin, spin_up: float, duration: float,
              initial_speed: float = 0.0) -> dict[str, Any]:  # fmt: skip
    """One self-propelled MPM run; the drive's series from the moment full spin is reached, and the
    last-quarter slip and sinkage and the sink rate over the last half."""
    from .specs import Drive, Outputs, Resolution
    from .wheel_runs import run_wheel

    res = run_wheel(wheel.body(), mat, load=load, omega=float(om),
                    resolution=Resolution(cell_size=sp.cell_size, flip=sp.flip),
                    drive=Drive(duration=duration, spin_up=spin_up, initial_speed=initial_speed),
                    outputs=Outputs(record_interval=duration / 80))  # fmt: skip
    ser = res.series
    d = ser["phase"] == "drive"
    t = ser["time_s"][d] - ser["time_s"][d][0] - spin_up
    sink, vx, w = ser["sinkage_m"][d], ser["vx_m_s"][d], ser["omega_rad_s"][d]
    radius = 0.5 * wheel.outer_diameter
    slip_t = np.where(w > 0.2 * om, 1.0 - vx / np.maximum(w, 1e-12) / radius, np.nan)
    late = t >= 0.5 * t[-1]
    last = t >= 0.75 * t[-1]
    return {
        "t": t,
        "sinkage": sink,
        "slip_t": slip_t,
        "slip": float(1.0 - float(vx[last].mean()) / (om * radius)),
        "sinkage_m": float(sink[last].mean()),
        "rate": float(np.polyfit(t[late], sink[late], 1)[0]),
        "speed": float(vx[last].mean()),
        "metadata": res.metadata,
    }


def high_speed(quick: bool) -> ItemOutput:
    """The self-propelled grousered wheel (l = 0.212 m, mass ratio 6, poppy-cp): MPM beside DRFT, and
    the MPM wheel's steady state against the way it is started."""
    import matplotlib.pyplot as plt

    from .. import materials
    from ..studies.high_speed import HighSpeedWheel, high_speed_sweep

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
    fig_start, axes_start = plt.subplots(1, 2, figsize=(12, 4.2), layout="constrained")
    out = ItemOutput(
        figures={"high_speed_mpm": fig, "high_speed_mpm_start": fig_start},
        settings={
            "material": mat.name,
            "outer_diameter_m": ell,
            "mass_ratio": wheel.mass_ratio,
            "load_N": load,
            "grousers_m": [wheel.grouser_count, wheel.grouser_height, wheel.grouser_thickness],
            "cell_size_m": sp.cell_size,
            "drive_s": sp.duration,
            "spin_up_s": sp.spin_up,
            "flip": sp.flip,
        },
    )
    rows, runs = [], {}
    for k, (w_hat, om) in enumerate(zip(sp.omegas, omegas, strict=True)):
        r = runs[w_hat] = _spin_run(wheel, mat, load, om, sp, sp.spin_up, sp.duration)
        slip, sinkage, rate = r["slip"], r["sinkage_m"], r["rate"]
        sel = (drft["model"] == "drft") & np.isclose(drft["omega_rad_s"], om)
        d_slip, d_sink = float(drft["slip"][sel][0]), float(drft["sinkage_m"][sel][0])
        rows.append({"omega_normalised": w_hat, "slip_mpm": slip, "sinkage_mpm_m": sinkage,
                     "sink_rate_mpm_m_s": rate, "slip_drft": d_slip, "sinkage_drft_m": d_sink})  # fmt: skip
        axes[0].plot(r["t"], r["sinkage"] * 1e3, color=f"C{k}", label=f"MPM omega sqrt(l/g) = {w_hat:g}")
        axes[0].axhline(d_sink * 1e3, color=f"C{k}", ls="--", lw=0.8, label=f"DRFT steady, {w_hat:g}")
        axes[1].plot(r["t"], r["slip_t"], color=f"C{k}", label=f"MPM {w_hat:g}")
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
    out.findings.extend(
        bed_outgrown_findings({f"omega sqrt(l/g) = {w:g}": r["metadata"] for w, r in runs.items()})
    )
    if len(rows) >= 2:
        slips = [row["slip_mpm"] for row in rows]
        rising = all(b >= a for a, b in itertools.pairwise(slips))
        out.findings.append(
            Finding(
                "MPM slip against spin rate: "
                + ", ".join(f"{row['omega_normalised']:g}: {row['slip_mpm']:.2f}" for row in rows)
                + (" (rising with spin" if rising else " (not rising with spin")
                + ", where the experiments' slip rises past an onset near omega sqrt(l/g) = 0.46)",
                "agrees" if rising else "disagrees",
            )
        )
    _start_history(out, axes_start, wheel, mat, load, sp, runs[sp.history], ell)
    axes[0].set_ylabel("sinkage [mm]")
    axes[1].set_ylabel("slip [-]")
    for ax in (*axes, *axes_start):
        ax.set_xlabel("time since full spin was reached [s] (the spin-up is at t < 0)")
        ax.grid(True, alpha=0.35)
        ax.legend(fontsize=7)
    for ax in (axes[1], axes_start[1]):
        ax.set_ylim(-0.2, 1.05)
    title = (f"Grousered wheel, l = {ell * 1e3:g} mm, mass ratio {wheel.mass_ratio:g}, {mat.name}: "
             f"MPM at {sp.cell_size * 1e3:g} mm cells, FLIP {sp.flip:g} (self-propelled)")  # fmt: skip
    fig.suptitle(title, fontsize=10)
    fig_start.suptitle(f"{title}: three starts at omega sqrt(l/g) = {sp.history:g}", fontsize=10)
    out.findings.append(
        Finding(
            "the MPM wheel carries the physical 18 mm lugs, the RFT and DRFT wheel lugs at a third of "
            "that height (terradyn.studies.high_speed); the MPM medium is about twice as strong as its "
            "RFT medium on a plate (docs/mpm.md, 'Against RFT'); the MPM wheel is not "
            "resolution-converged: at 0.5 it sinks 57 / 73 / 94 mm and slips 0.47 / 0.63 / 0.79 at "
            "9 / 6.5 / 4.5 mm cells (docs/mpm.md, 'The start'); at a fixed slip of 0.5 its sinkage "
            "(57.9 / 59.5 / 59.7 mm) and torque converge but its pull (+2.7 / -3.0 / -9.4 N) falls by 7 % "
            "of the load per refinement, and the self-propelled slip is the zero of that flat pull curve "
            "(docs/mpm.md, 'Why the slip does not converge')"
            + (
                "; quick form: 26.5 mm cells (lugs unresolved), 0.6 s of drive; not converged"
                if quick
                else ""
            ),
            "info",
        )
    )
    return out


def _start_history(out: ItemOutput, axes: Any, wheel: Any, mat: Any, load: float, sp: _Spin,
                   ramped: dict[str, Any], ell: float) -> None:  # fmt: skip
    """The wheel at ``sp.history`` started three ways: the row's spin-up, an impulsive spin-up from
    rest, and an impulsive one moving at the spin-up run's steady forward speed."""
    om = sp.history * math.sqrt(9.81 / ell)
    full = sp.duration - sp.spin_up
    starts = {
        f"spin-up {sp.spin_up:g} s from rest": ramped,
        "impulsive, from rest": _spin_run(wheel, mat, load, om, sp, 0.0, full),
        f"impulsive, moving at {ramped['speed']:.3g} m/s": _spin_run(
            wheel, mat, load, om, sp, 0.0, full, initial_speed=ramped["speed"]
        ),
    }
    out.findings.extend(
        bed_outgrown_findings(
            {f"start {label}": r["metadata"] for label, r in starts.items() if r is not ramped}
        )
    )
    rows = []
    for k, (label, r) in enumerate(starts.items()):
        axes[0].plot(r["t"], r["sinkage"] * 1e3, color=f"C{k}", label=label)
        axes[1].plot(r["t"], r["slip_t"], color=f"C{k}", label=label)
        rows.append({"start": label, "slip_mpm": r["slip"], "sinkage_mpm_m": r["sinkage_m"],
                     "sink_rate_mpm_m_s": r["rate"]})  # fmt: skip
    axes[0].set_ylabel("sinkage [mm]")
    axes[1].set_ylabel("slip [-]")
    out.tables["high_speed_start"] = rows
    slips = [row["slip_mpm"] for row in rows]
    sinks = [row["sinkage_mpm_m"] for row in rows]
    same = max(slips) - min(slips) <= _START_SLIP and max(sinks) - min(sinks) <= _START_SINK * min(sinks)
    out.findings.append(
        Finding(
            f"start history at omega sqrt(l/g) = {sp.history:g} (last quarter of {full:g} s at full spin): "
            + "; ".join(
                f"{row['start']}: slip {row['slip_mpm']:.2f}, sinkage {row['sinkage_mpm_m'] * 1e3:.0f} mm"
                for row in rows
            )
            + f". The experiments' steady state does not depend on the start (thesis, cited by Agarwal et "
            f"al. 2021); here the slips span {max(slips) - min(slips):.2f} and the sinkages "
            f"{(max(sinks) - min(sinks)) * 1e3:.0f} mm (bounds {_START_SLIP:g} and "
            f"{_START_SINK:.0%} of the smallest)",
            "agrees" if same else "disagrees",
        )
    )


register_row("fig-4-1", "mpm", "terradyn.mpm.report_rows_ch48:alpha_map")
register_row("ch4-plate-depth", "mpm", "terradyn.mpm.report_rows_ch48:plate_depth")
register_row("ch8-high-speed", "mpm", "terradyn.mpm.report_rows_ch48:high_speed")
