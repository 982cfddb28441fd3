"""MPM rows of the thesis reproduction report (``terradyn reproduce``).

Each row is ``name(quick) -> ItemOutput`` and is registered with the report on import. Every number in
a finding comes from the run, except the resolution studies quoted from docs/mpm.md, which the text
labels "measured separately" with their cell sizes. ``quick`` selects coarse cells and a faster,
shorter stroke (a smoke form for the default test suite; its numbers are not converged); the full
form uses the resolutions of docs/mpm.md.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..report.registry import Finding, ItemOutput, register_row

__all__ = ["footing", "plate_packing", "wedges", "wheel_force_slip"]

_MATERIAL = "MS"
#: dilatancy constant of the packing row; not calibrated to any medium (see docs/mpm.md "Dilatancy")
_K = 4.0


def bed_outgrown_findings(runs: dict[str, dict[str, Any]]) -> list[Finding]:
    """One finding naming the wheel runs (label -> run metadata) that outgrew their bed
    (:func:`~terradyn.mpm.wheel_runs.bed_limits`), or none when none did."""
    from .wheel_runs import bed_limits

    parts = [f"{label}: {text}" for label, meta in runs.items() for text, _, _ in bed_limits(meta)]
    if not parts:
        return []
    return [
        Finding(
            "bed outgrown, so these readings depend on the bed's size (docs/mpm.md, sections on the floor "
            "under a wheel that sinks and on the bow wave): " + "; ".join(parts),
            "info",
        )
    ]


@dataclass(frozen=True)
class _Setting:
    """Resolution, stroke and bed of an intrusion row: cell size [m], speed [m/s], minimum cells across,
    averaging window [m] (None: the run's default), bed width and depth [m] (None: the sizing rule)."""

    cell_size: float
    speed: float
    min_cells: int
    window: float | None = None
    bed_width: float | None = None
    bed_depth: float | None = None

    def as_dict(self) -> dict[str, Any]:
        return {
            "cell_size_m": self.cell_size,
            "speed_m_s": self.speed,
            "min_cells_across": self.min_cells,
            "averaging_window_m": self.window or "default",
            "bed_m": "sized by the intrusion rule"
            if self.bed_width is None
            else f"{self.bed_width:g} x {self.bed_depth:g} (smaller than the sizing rule)",
        }


#: quick: 12.5 mm cells (3.2 across the 40 mm plate), 0.1 m/s, a 10 mm averaging window and a small
#: bed (a smoke form); full: 5 mm cells, 0.05 m/s and the default bed and window (docs/mpm.md tables)
_QUICK = _Setting(0.0125, 0.1, 3, window=0.01, bed_width=0.3, bed_depth=0.125)
_FULL = _Setting(0.005, 0.05, 6)


def _setting(quick: bool) -> _Setting:
    return _QUICK if quick else _FULL


@functools.lru_cache(maxsize=32)
def _intrude(
    body: Any, depth: float, setting: _Setting, packing: str, dilatancy: float
) -> tuple[dict[str, np.ndarray], dict[str, float]]:
    """One MPM intrusion in MS (cached in-process: rows run serially share the plate run)."""
    from .. import materials
    from .runs import run_intrusion
    from .specs import Bed, Resolution, Stroke

    res = run_intrusion(
        body,
        materials.get(_MATERIAL),
        depth=depth,
        speed=setting.speed,
        bed=Bed(packing=packing, width=setting.bed_width, depth=setting.bed_depth),
        resolution=Resolution(cell_size=setting.cell_size, min_cells_across=setting.min_cells),
        stroke=Stroke(averaging_window=setting.window),
        dilatancy=dilatancy,
    )
    series = {k: np.asarray(res.series[k]) for k in ("depth_m", "force_x_N", "force_z_N")}
    return series, dict(res.summary)


# ------------------------------------------------------------------------- chapter 9: packing
def plate_packing(quick: bool) -> ItemOutput:
    """40 mm plate pushed to 20 mm in consolidated and unconsolidated MS, with and without dilatancy."""
    import matplotlib.pyplot as plt

    from ..geometry import Plate

    s = _setting(quick)
    depth = 0.02
    plate = Plate(0.04, 0.01)
    force: dict[tuple[str, float], float] = {}
    fig, ax = plt.subplots(figsize=(6.5, 4.2), layout="constrained")
    for packing, color in (("consolidated", "C0"), ("unconsolidated", "C3")):
        for k, style in ((_K, "-"), (0.0, "--")):
            series, summary = _intrude(plate, depth, s, packing, k)
            force[(packing, k)] = summary["force_z_N"]
            # rows once the stroke has stopped repeat the last depth: keep the advancing ones
            shown = (series["depth_m"] >= 0.0) & np.append(np.diff(series["depth_m"]) > 0.0, False)
            label = f"{packing}, " + (f"dilatancy K = {k:g}" if k else "no dilatancy")
            ax.plot(
                series["depth_m"][shown] * 1e3, series["force_z_N"][shown], style, color=color, label=label
            )
    ax.axvline(depth * 1e3, color="0.6", lw=0.8, ls=":", label="reading depth (window average)")
    ax.set_xlabel("plate depth [mm]")
    ax.set_ylabel("vertical force on the plate [N]")
    ax.set_title(f"MPM, {_MATERIAL}: 40 mm plate, {s.cell_size * 1e3:g} mm cells, {s.speed:g} m/s")
    ax.grid(True, alpha=0.35)
    ax.legend(fontsize=8)
    with_k = force[("consolidated", _K)] / force[("unconsolidated", _K)]
    without = force[("consolidated", 0.0)] / force[("unconsolidated", 0.0)]
    out = ItemOutput(
        figures={"plate_packing": fig},
        settings={
            "material": _MATERIAL,
            "plate_m": 0.04,
            "depth_m": depth,
            "dilatancy_K": _K,
            "packing": "consolidated 1.02 rho_c, unconsolidated 0.98 rho_c (Bed defaults)",
            **s.as_dict(),
        },
        metrics={
            **{f"force_{p}_K{k:g}_N": v for (p, k), v in force.items()},
            "dense_over_loose_dilatant": with_k,
            "dense_over_loose_no_dilatancy": without,
        },
        tables={
            "forces at 20 mm": [
                {"packing": p, "dilatancy_K": k, "force_z_N": round(v, 3)} for (p, k), v in force.items()
            ]
        },
    )
    out.findings.append(
        Finding(
            f"force at {depth * 1e3:g} mm, dense / loose: {with_k:.2f} with dilatancy K = {_K:g} "
            f"({force[('consolidated', _K)]:.2f} / {force[('unconsolidated', _K)]:.2f} N), {without:.2f} "
            f"without ({force[('consolidated', 0.0)]:.2f} / {force[('unconsolidated', 0.0)]:.2f} N), "
            f"{s.cell_size * 1e3:g} mm cells: the consolidated bed is the stronger, and dilatancy "
            "widens the gap",
            "agrees" if with_k > without > 1.0 else "disagrees",
        )
    )
    out.findings.append(
        Finding(
            f"K = {_K:g} is not calibrated to any medium (no shipped medium carries a dilatancy "
            "constant), so the size of the gain is not a prediction",
            "info",
        )
    )
    out.findings.append(
        Finding(
            "the dense / loose gain shrinks with refinement (a local dilatant law: the shear band is a "
            "cell wide), measured separately at 6.6 / 5 / 3.3 mm cells, 40 mm plate at 20 mm, 0.05 m/s: "
            "1.72 / 1.61 / 1.49 with K = 4, 1.19 / 1.15 / 1.13 without (docs/mpm.md); no value here is "
            "converged"
            + (
                " and the quick form's coarse cells and doubled speed are for smoke testing only"
                if quick
                else ""
            ),
            "disagrees",
        )
    )
    return out


# ------------------------------------------------------------------------- chapter 9: wedges
#: (height [m], tip offset [m]) of the wedges; base 40 mm as the RFT row (study wedges)
_WEDGES_QUICK = ((0.0125, 0.0), (0.0125, 0.01))
_WEDGES_FULL = ((0.01, 0.0), (0.02, 0.0), (0.04, 0.0), (0.02, 0.01), (0.02, 0.02))


def wedges(quick: bool) -> ItemOutput:
    """Wedges against a plate with the wedge's base at the plate's depth (equal projected depth)."""
    import matplotlib.pyplot as plt

    from .. import materials
    from ..geometry import Plate, Wedge
    from ..studies.intrusion import intrusion_forces

    s = _setting(quick)
    base, width = 0.04, 0.01
    depth = 0.02 if quick else 0.05  # the RFT row's base depth is 50 mm; the quick stroke stops at 20 mm
    cases = _WEDGES_QUICK if quick else _WEDGES_FULL
    _, plate_summary = _intrude(Plate(base, width), depth, s, "consolidated", 0.0)
    plate_fz = plate_summary["force_z_N"]
    mat = materials.get(_MATERIAL)
    rft_plate = float(intrusion_forces(Plate(base, width), mat, [depth]).columns["force_z_N"][0])
    rows: list[dict[str, Any]] = []
    for height, offset in cases:
        wedge = Wedge(base=base, height=height, tip_offset=offset, width=width)
        # the wedge's origin is its tip: the tip at depth + height puts the base at ``depth``
        _, summary = _intrude(wedge, depth + height, s, "consolidated", 0.0)
        rft = intrusion_forces(wedge, mat, [depth + height]).columns
        rows.append(
            {
                "height_m": height,
                "tip_offset_m": offset,
                "tip_half_angle_deg": math.degrees(math.atan(0.5 * base / height)),
                "mpm_ratio": summary["force_z_N"] / plate_fz,
                "mpm_lateral_ratio": summary["force_x_N"] / plate_fz,
                "rft_ratio": float(rft["force_z_N"][0]) / rft_plate,
                "rft_lateral_ratio": float(rft["force_x_N"][0]) / rft_plate,
                "mpm_force_z_N": summary["force_z_N"],
                "mpm_force_x_N": summary["force_x_N"],
            }
        )
    fig, axes = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
    for ax, key, ylabel in (
        (axes[0], "ratio", "wedge / plate vertical force [-]"),
        (axes[1], "lateral_ratio", "wedge lateral / plate vertical force [-]"),
    ):
        for i, offset in enumerate(sorted({r["tip_offset_m"] for r in rows})):
            sel = [r for r in rows if r["tip_offset_m"] == offset]
            x = [r["tip_half_angle_deg"] for r in sel]
            ax.plot(
                x,
                [r[f"mpm_{key}"] for r in sel],
                "o-",
                color=f"C{i}",
                label=f"MPM, offset {offset * 1e3:g} mm",
            )
            ax.plot(
                x,
                [r[f"rft_{key}"] for r in sel],
                "s:",
                color=f"C{i}",
                label=f"RFT, offset {offset * 1e3:g} mm",
            )
        ax.set_xlabel("tip half-angle of the symmetric wedge of that height [deg]")
        ax.set_ylabel(ylabel)
        ax.grid(True, alpha=0.35)
        ax.legend(fontsize=8)
    axes[0].axhline(1.0, color="0.6", lw=0.8, ls=":")
    axes[1].axhline(0.0, color="0.6", lw=0.8, ls=":")
    fig.suptitle(
        f"MPM and RFT, {_MATERIAL}: wedge base and 40 mm plate at {depth * 1e3:g} mm, "
        f"{s.cell_size * 1e3:g} mm cells, {s.speed:g} m/s"
    )
    out = ItemOutput(
        figures={"wedges_mpm": fig},
        settings={
            "material": _MATERIAL,
            "base_m": base,
            "base_depth_m": depth,
            "comparison": "equal base depth",
            **s.as_dict(),
        },
        metrics={"plate_force_z_N": plate_fz},
        tables={"wedges": rows},
    )
    sym = [r for r in rows if r["tip_offset_m"] == 0.0 and r["height_m"] <= base]
    if sym:
        lo, hi = min(r["mpm_ratio"] for r in sym), max(r["mpm_ratio"] for r in sym)
        rlo, rhi = min(r["rft_ratio"] for r in sym), max(r["rft_ratio"] for r in sym)
        out.metrics.update(symmetric_ratio_min=lo, symmetric_ratio_max=hi)
        out.findings.append(
            Finding(
                f"symmetric wedges no taller than their base at equal base depth: MPM wedge / plate "
                f"vertical force {lo:.3f}-{hi:.3f}, RFT {rlo:.3f}-{rhi:.3f} ({s.cell_size * 1e3:g} mm "
                "cells); the projected area setting the force would put it within 0.85-1.15",
                "agrees" if 0.85 <= lo and hi <= 1.15 else "disagrees",
            )
        )
    asym = [r for r in rows if r["tip_offset_m"] != 0.0]
    for r in asym:
        same = math.copysign(1.0, r["mpm_lateral_ratio"]) == math.copysign(1.0, r["rft_lateral_ratio"])
        out.findings.append(
            Finding(
                f"asymmetric wedge (height {r['height_m'] * 1e3:g} mm, tip offset "
                f"{r['tip_offset_m'] * 1e3:g} mm): lateral / plate vertical force MPM "
                f"{r['mpm_lateral_ratio']:+.3f}, RFT "
                f"{r['rft_lateral_ratio']:+.3f} ({'same' if same else 'opposite'} sign); vertical ratio "
                f"MPM {r['mpm_ratio']:.3f}, RFT {r['rft_ratio']:.3f}",
                "agrees" if same else "disagrees",
            )
        )
    out.findings.append(
        Finding(
            f"the MPM plate carries {plate_fz:.2f} N against RFT's {rft_plate:.2f} N: MS as shipped is "
            "weaker in MPM than its RFT medium (docs/mpm.md), so only ratios are compared"
            + ("; quick form: coarse cells, doubled speed, not converged" if quick else ""),
            "info",
        )
    )
    return out


# ------------------------------------------------------------------- chapter 9: strip footing
#: (friction angle [deg], base) of the footing cases; the quick form runs the first only
_FOOTINGS = ((34.0, "smooth"), (30.0, "rough"))


@functools.lru_cache(maxsize=8)
def _footing_run(phi: float, base: str, quick: bool) -> Any:
    """One strip-footing run (cached in-process like :func:`_intrude`)."""
    from ..studies.mpm_verification import strip_footing
    from .specs import Bed

    return strip_footing(phi, base, **_footing_kwargs(quick, Bed))


def _footing_kwargs(quick: bool, bed_spec: Any) -> dict[str, Any]:
    # quick: B = 40 mm at B/6.7 cells, read at s/B = 0.3, 0.1 m/s (a smoke run, far from converged);
    # full: the study's defaults (B = 40 mm, B/20 cells, s/B = 0.1, 0.02 m/s) at two grid phases (the
    # reading depends on where the node lines lie: docs/mpm.md, "Why the rough footing reads high")
    if not quick:
        return {"grid_phases": 2}
    return dict(
        width=0.04, cell_size=0.006, settlement_ratio=0.3, speed=0.1, bed=bed_spec(width=0.3, depth=0.125)
    )


def footing(quick: bool) -> ItemOutput:
    """MPM bearing factor N_gamma of a strip footing against Radenkovic's bracket."""
    import matplotlib.pyplot as plt

    from .specs import Bed

    kwargs = _footing_kwargs(quick, Bed)
    cases = _FOOTINGS[:1] if quick else _FOOTINGS
    records = []
    fig, axes = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
    for i, (phi, base) in enumerate(cases):
        res = _footing_run(phi, base, quick)
        rec = res.record()
        records.append(rec)
        s, q = res.curve
        gamma = res.unit_weight_N_m3
        axes[0].plot(
            s / res.width_m, 2 * q / (gamma * res.width_m), color=f"C{i}", label=f"phi = {phi:g} deg, {base}"
        )
        lo, hi = rec["N_gamma_lower_bound"], rec["N_gamma_upper_bound"]
        if lo is not None and hi is not None:
            axes[1].vlines(
                i, lo, hi, color="0.4", lw=6, alpha=0.4, label="Radenkovic bracket" if i == 0 else None
            )
        elif hi is not None:
            axes[1].plot(i, hi, "v", color="0.4", ms=9, label="upper bound" if i == 0 else None)
        axes[1].plot(i, rec["N_gamma_mpm"], "o", color=f"C{i}", ms=8, label=f"MPM, phi = {phi:g} deg, {base}")
    axes[0].set_xlabel("settlement s / B [-]")
    axes[0].set_ylabel("2 q / (gamma B) [-]")
    axes[0].set_title("MPM pressure-settlement")
    axes[1].set_xticks(range(len(cases)), [f"{p:g} deg {b}" for p, b in cases])
    axes[1].set_xlim(-0.6, len(cases) - 0.4)
    axes[1].set_xlabel("case (friction angle, base) [-]")
    axes[1].set_ylabel("N_gamma [-]")
    axes[1].set_title("intercept N_gamma against the bracket")
    for ax in axes:
        ax.grid(True, alpha=0.35)
        ax.legend(fontsize=8)
    h_over_b = records[0]["width_m"] / records[0]["cell_size_m"]
    fig.suptitle(
        f"MPM strip footing, {_MATERIAL} grains, B = {records[0]['width_m'] * 1e3:g} mm, "
        f"B/{h_over_b:.3g} cells"
    )
    out = ItemOutput(
        figures={"footing_n_gamma": fig},
        settings={
            "material": _MATERIAL,
            **{k: v for k, v in kwargs.items()},
            "cases": [list(c) for c in cases],
        },
        tables={
            "N_gamma": [
                {
                    k: rec[k]
                    for k in (
                        "friction_angle_deg",
                        "base",
                        "cell_size_m",
                        "N_gamma_mpm",
                        "N_gamma_lower_bound",
                        "N_gamma_upper_bound",
                        "within_bounds",
                    )
                }
                for rec in records
            ]
        },
    )
    for rec in records:
        tag = f"phi{rec['friction_angle_deg']:g}_{rec['base']}"
        out.metrics[f"N_gamma_{tag}"] = rec["N_gamma_mpm"]
        lo, hi, inside = rec["N_gamma_lower_bound"], rec["N_gamma_upper_bound"], rec["within_bounds"]
        bracket = f"[{'-' if lo is None else f'{lo:.2f}'}, {'-' if hi is None else f'{hi:.2f}'}]"
        where = "unknown" if inside is None else ("inside" if inside else "outside")
        out.findings.append(
            Finding(
                f"phi = {rec['friction_angle_deg']:g} deg, {rec['base']} base, B/"
                f"{rec['width_m'] / rec['cell_size_m']:.3g} cells, read at s/B = "
                f"{rec['settlement_m'] / rec['width_m']:.2g}: MPM N_gamma = {rec['N_gamma_mpm']:.2f}, "
                f"Radenkovic bracket {bracket}: {where}"
                + (
                    f" (mean of {rec['grid_phases']} grid phases, "
                    + " / ".join(f"{v:.2f}" for v in rec["N_gamma_phase_values"])
                    + f": spread {rec['N_gamma_phase_spread']:.2f})"
                    if "grid_phases" in rec
                    else ""
                ),
                "info" if inside is None else ("agrees" if inside else "disagrees"),
            )
        )
    out.findings.append(
        Finding(
            "measured separately at full resolution (B = 40 mm, two grid phases): phi = 34 deg smooth "
            "14.1 / 15.2 at B/10 / B/14 cells (point update), 15.4 / 14.7 at B/14 / B/20 (patch), 18-29 % "
            "above the computed isochoric value 11.9 +- 0.9 (small-strain finite elements of the same "
            "cone, docs/plasticity.md), so not within 10 %; the finite elements at the same element size "
            "read the same (14.5 / 13.0 at B/20, 16.0 / 14.6 at B/14): both converge slowly with the mesh",
            "disagrees",
        )
    )
    out.findings.append(
        Finding(
            "measured separately: phi = 30 deg rough with the patch update 22.8 / 17.3 / 18.7 at B/10 / "
            "B/14 / B/20 cells (grid on the surface) and 18.9 / 15.2 / 16.4 with the grid half a cell "
            "down (intercept standard error 2.3-5.5), above the associated upper bound 14.8 and the "
            "computed isochoric value 12.4 +- 0.5 (finite elements, 14.5 at B/20 themselves). The cause "
            "is the contact: the pressure steps up each time the base crosses a node line; before the "
            "first crossing it holds 7.0-11.5 at B/20, inside the bracket (docs/mpm.md, 'Why the rough "
            "footing reads high')",
            "disagrees",
        )
    )
    if quick:
        out.findings.append(
            Finding(
                "quick form: B/6.7 cells, s/B = 0.3, 0.1 m/s and a 0.3 m x 0.125 m bed, a smoke run of "
                "the pipeline whose N_gamma is not a measurement (compare the full-resolution values "
                "measured separately)",
                "info",
            )
        )
    return out


# ------------------------------------------------------------------- chapter 6: wheel force-slip
def force_slip_axes(
    axes: Any,
    rows: list[dict[str, Any]],
    media: Sequence[str],
    *,
    rft_label: str = "RFT",
    title: str = "",
    legend: bool = True,
) -> None:
    """Drawbar pull, drive torque and sinkage against slip on three ``axes``: MPM solid, RFT dashed,
    one colour per medium of ``media``; ``rows`` hold ``material``, ``slip`` and the ``*_mpm_*`` /
    ``*_rft_*`` values of the wheel rows. ``legend``: one legend for the figure, below the axes (the
    figure needs constrained layout), so it never covers a curve."""
    quantities = (("drawbar_pull", "N", 1.0), ("drive_torque", "Nm", 1.0), ("sinkage", "m", 1e3))
    for k, name in enumerate(media):
        sel = [r for r in rows if r["material"] == name]
        slips = [r["slip"] for r in sel]
        for ax, (key, unit, scale) in zip(axes, quantities, strict=True):
            for model, style, label in (("mpm", "o-", "MPM"), ("rft", "s--", rft_label)):
                values = [r[f"{key}_{model}_{unit}"] * scale for r in sel]
                ax.plot(slips, values, style, color=f"C{k}", label=f"{name} {label}")
    for ax, ylabel in zip(axes, ("drawbar pull [N]", "drive torque [N m]", "sinkage [mm]"), strict=True):
        if title:
            ax.set_title(f"{title}: {ylabel.split(' [')[0]}")
        ax.set_xlabel("slip [-]")
        ax.set_ylabel(ylabel)
        ax.grid(True, alpha=0.35)
    if legend:
        handles, labels = axes[0].get_legend_handles_labels()
        ncols = min(len(labels), 8)
        axes[0].figure.legend(handles, labels, loc="outside lower center", ncols=ncols, fontsize=8)


def wheel_force_slip(quick: bool) -> ItemOutput:
    """Wheel A (0.13 m x 0.16 m, 130 N) under forced slip, MPM against the RFT steady solve: on MS in
    the quick form, on the four media of Fig. 6-8 in the full form."""
    import matplotlib.pyplot as plt

    from ..studies.mpm_compare import mpm_wheel_versus_rft

    # quick: MS, one slip, 25 mm cells (10 across the wheel), 1 s drive at 2 rad/s (a smoke run);
    # full: the resolution study of docs/mpm.md (11 mm cells, 4 s drive at 1 rad/s, slips 0.1-0.5) on
    # each medium of Fig. 6-8
    if quick:
        media: tuple[str, ...] = (_MATERIAL,)
        setting: dict[str, Any] = dict(slips=(0.3,), omega=2.0, cell_size=0.025, duration=1.0)
    else:
        media = ("MS", "MMS", "LPS", "CPS")
        setting = dict(slips=(0.1, 0.3, 0.5), omega=1.0, cell_size=0.011, duration=4.0)
    rows: list[dict[str, Any]] = []
    for name in media:
        t = mpm_wheel_versus_rft(name, radius=0.13, width=0.16, load=130.0, **setting)
        rows += [{"material": name, **r} for r in t.records()]
    fig, axes = plt.subplots(1, 3, figsize=(14, 3.8), layout="constrained")
    force_slip_axes(axes, rows, media, rft_label="RFT steady solve")
    fig.suptitle(
        f"Wheel A (r = 0.13 m, b = 0.16 m), {', '.join(media)}, 130 N: MPM at "
        f"{setting['cell_size'] * 1e3:g} mm cells, {setting['duration']:g} s drive at "
        f"{setting['omega']:g} rad/s"
    )
    out = ItemOutput(
        figures={"wheel_mpm": fig},
        settings={"media": list(media), "radius_m": 0.13, "width_m": 0.16, "load_N": 130.0, **setting},
        tables={"force_slip": rows},
    )
    for r in rows:
        tq = r["drive_torque_mpm_Nm"] / r["drive_torque_rft_Nm"]
        dp = r["drawbar_pull_mpm_N"] - r["drawbar_pull_rft_N"]
        out.metrics[f"{r['material']}_torque_ratio_slip{r['slip']:g}"] = tq
        out.metrics[f"{r['material']}_pull_difference_slip{r['slip']:g}_N"] = dp
        out.findings.append(
            Finding(
                f"{r['material']}, slip {r['slip']:g}: torque MPM {r['drive_torque_mpm_Nm']:.2f} N m, RFT "
                f"{r['drive_torque_rft_Nm']:.2f} N m (ratio {tq:.2f}); sinkage MPM "
                f"{r['sinkage_mpm_m'] * 1e3:.1f} mm, RFT {r['sinkage_rft_m'] * 1e3:.1f} mm",
                "agrees" if abs(tq - 1.0) <= 0.15 else "disagrees",
            )
        )
        out.findings.append(
            Finding(
                f"{r['material']}, slip {r['slip']:g}: drawbar pull MPM {r['drawbar_pull_mpm_N']:+.1f} N, "
                f"RFT {r['drawbar_pull_rft_N']:+.1f} N ({dp:+.1f} N, {dp / 130.0:+.0%} of the load)",
                "agrees" if abs(dp) <= 0.05 * 130.0 else "disagrees",
            )
        )
    out.findings.append(
        Finding(
            "the load is 130 N, the MPM case of docs/mpm.md (the RFT row of this item runs 80 N); the "
            "pull depends on calibration: MS as shipped is weaker in MPM than its RFT medium and the "
            "wheel-grain friction is 0.4 (docs/mpm.md, 'Why the pull is about zero at slip 0.3')"
            + ("; quick form: 25 mm cells, 1 s drive, not converged" if quick else ""),
            "info",
        )
    )
    return out


register_row("ch9-plate-packing", "mpm", "terradyn.mpm.report_rows:plate_packing")
register_row("ch9-wedges", "mpm", "terradyn.mpm.report_rows:wedges")
register_row("fig-9-1", "mpm", "terradyn.mpm.report_rows:footing")
register_row("fig-6-8", "mpm", "terradyn.mpm.report_rows:wheel_force_slip")

# the chapter 9 rows of the drag runs and of superposition live in their own module; importing it
# registers them
from . import report_rows_ch6 as _report_rows_ch6  # noqa: E402, F401
from . import report_rows_ch9 as _report_rows_ch9  # noqa: E402, F401
from . import report_rows_ch48 as _report_rows_ch48  # noqa: E402, F401
