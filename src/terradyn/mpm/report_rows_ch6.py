"""MPM rows of chapter 6 of the reproduction report (``terradyn reproduce``): wheel B in forced slip
and the self-propelled flapped wheel.

``ch6-wheels-bc``: wheels B and C of :mod:`terradyn.studies.thesis_wheels` (the 212 mm grousered wheel of
Agarwal et al. 2021, 15 lugs, and terradyn's stand-in for C, the same rim without lugs) under forced
slip, MPM beside the RFT steady solve of the same wheel. MPM resolves B's physical lugs (18 mm x 4 mm,
terradyn's assumption); RFT uses the effective lugs of :mod:`terradyn.studies.high_speed` (a third of
their height: the soil shadowed between lugs), as the RFT and Wong-Reece row of the item does. The row
is ``wheels_bc_force_slip(quick) -> ItemOutput``; every number in a finding comes from the run.

``ch6-flapped``: flapped wheels of the ``flapped-wheels`` study (hub radius 50 mm, 50 mm wide, radial
zero-thickness flaps) self-propelled under 10 N on CPS, MPM beside the quasi-static RFT performance of
:func:`terradyn.optimize.flapped_wheel_performance`: the normalised speed V / (omega R_out) over the
last half of the drive, and whether the two models rank the designs alike.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

from ..report.registry import Finding, ItemOutput, register_row
from .report_rows import bed_outgrown_findings, force_slip_axes

__all__ = ["flapped_self_propelled", "wheels_bc_force_slip"]


@dataclass(frozen=True)
class _ForceSlip:
    """Media, slips, cell size [m], drive [s] and spin [rad/s] of the MPM wheel-B row."""

    media: tuple[str, ...]
    slips: tuple[float, ...]
    cell_size: float
    duration: float
    omega: float


#: quick: one medium and slip, 26.5 mm cells (8 across the wheel, lugs unresolved), 0.6 s at 2 rad/s
#: (a smoke run); full: the weakest and the strongest of the four media at three slips, 6.5 mm cells
#: (the finest of the docs/mpm.md high-speed resolution study), 4.5 s at 1 rad/s (4.5 rad of rotation,
#: run_wheel's default drive)
_QUICK = _ForceSlip(("MS",), (0.3,), 0.0265, 0.6, 2.0)
_FULL = _ForceSlip(("MS", "CPS"), (0.1, 0.3, 0.5), 0.0065, 4.5, 1.0)


def wheels_bc_force_slip(quick: bool) -> ItemOutput:
    """Wheels B (212 mm, 15 lugs) and C (B's rim without lugs) at their lighter load under forced slip:
    MPM against RFT, and what the lugs add in each."""
    from .. import materials
    from ..locomotion.steady import wheel_steady
    from ..studies.high_speed import HighSpeedWheel
    from ..studies.thesis_wheels import WHEELS, wheel_body
    from .specs import Drive, Resolution
    from .wheel_runs import run_wheel

    s = _QUICK if quick else _FULL
    load = float(WHEELS[1].loads_N[0])
    radius = 0.5 * float(WHEELS[1].outer_diameter_m)  # type: ignore[arg-type]
    # (MPM body, RFT body): B's lugs are resolved in MPM and effective in RFT; C is one cylinder
    bodies = {
        "B": (HighSpeedWheel(effective_grousers=False).body(), wheel_body("B")),
        "C": (wheel_body("C"), wheel_body("C")),
    }
    rows: list[dict[str, Any]] = []
    beds: dict[str, dict[str, Any]] = {}
    for wheel, (physical, rft_body) in bodies.items():
        for name in s.media:
            mat = materials.get(name)
            for slip in s.slips:
                res = run_wheel(physical, mat, load=load, omega=s.omega, slip=slip,
                                resolution=Resolution(cell_size=s.cell_size),
                                drive=Drive(duration=s.duration))  # fmt: skip
                beds[f"wheel {wheel}, {name}, slip {slip:g}"] = res.metadata
                m = res.summary
                st = wheel_steady(rft_body, mat, load, slip, omega=s.omega, phase_count=6 if quick else 16)
                rows.append({"wheel": wheel, "material": name, "slip": slip, "sinkage_mpm_m": m["sinkage_m"],
                             "sinkage_rft_m": st.sinkage_m, "drawbar_pull_mpm_N": m["drawbar_pull_N"],
                             "drawbar_pull_rft_N": st.drawbar_pull_N,
                             "drive_torque_mpm_Nm": m["drive_torque_Nm"],
                             "drive_torque_rft_Nm": st.drive_torque_Nm})  # fmt: skip
    fig = _force_slip_figure(rows, bodies, s)
    fig.suptitle(
        f"Wheels B (212 mm, 15 lugs) and C (B's rim without lugs), {load:g} N, forced slip\nMPM "
        f"({s.cell_size * 1e3:g} mm cells, {s.duration:g} s at {s.omega:g} rad/s; B's lugs physical) and "
        "the RFT steady solve (B's lugs effective)"
    )
    out = ItemOutput(
        figures={"wheels_bc_mpm": fig},
        settings={
            "wheels": ["B", "C (stand-in)"],
            "load_N": load,
            "mpm_lugs": "physical",
            "rft_lugs": "effective",
            **asdict(s),
        },
        tables={"force_slip": rows},
    )
    out.findings.extend(bed_outgrown_findings(beds))
    for r in rows:
        tq = r["drive_torque_mpm_Nm"] / r["drive_torque_rft_Nm"]
        dp = r["drawbar_pull_mpm_N"] - r["drawbar_pull_rft_N"]
        out.metrics[f"{r['wheel']}_{r['material']}_torque_ratio_slip{r['slip']:g}"] = tq
        out.findings.append(
            Finding(
                f"wheel {r['wheel']}, {r['material']}, slip {r['slip']:g}: torque MPM "
                f"{r['drive_torque_mpm_Nm']:.2f} N m, RFT "
                f"{r['drive_torque_rft_Nm']:.2f} N m (ratio {tq:.2f}); drawbar pull MPM "
                f"{r['drawbar_pull_mpm_N']:+.1f} N, RFT {r['drawbar_pull_rft_N']:+.1f} N "
                f"({dp / load:+.0%} of the load); sinkage MPM {r['sinkage_mpm_m'] * 1e3:.1f} mm, RFT "
                f"{r['sinkage_rft_m'] * 1e3:.1f} mm (radius {radius * 1e3:g} mm)",
                "info"
                if quick
                else ("agrees" if abs(tq - 1.0) <= 0.15 and abs(dp) <= 0.05 * load else "disagrees"),
            )
        )
    out.findings.extend(_lug_findings(rows, load))
    if quick:
        out.findings.append(
            Finding(
                "quick form: 26.5 mm cells leave the 18 mm lugs unresolved; a smoke run, not converged",
                "info",
            )
        )
    out.findings.append(
        Finding("wheel C is terradyn's stand-in (B's rim without lugs), not the thesis's wheel C", "info")
    )
    return out


def _lug_findings(rows: list[dict[str, Any]], load: float) -> list[Finding]:
    """Drawbar pull of B less C at each medium and slip, in MPM and in RFT (the lugs' share)."""
    out = []
    by = {(r["wheel"], r["material"], r["slip"]): r for r in rows}
    for (wheel, name, slip), b in by.items():
        c = by.get(("C", name, slip))
        if wheel != "B" or c is None:
            continue
        gain = {k: b[f"drawbar_pull_{k}_N"] - c[f"drawbar_pull_{k}_N"] for k in ("mpm", "rft")}
        out.append(
            Finding(
                f"lugs, {name}, slip {slip:g}: B less C drawbar pull MPM {gain['mpm']:+.1f} N "
                f"({gain['mpm'] / load:+.0%} of the load), RFT {gain['rft']:+.1f} N "
                f"({gain['rft'] / load:+.0%})",
                "info",
            )
        )
    return out


def _force_slip_figure(rows: list[dict[str, Any]], bodies: dict[str, Any], s: _ForceSlip) -> Any:
    """One row of three axes (pull, torque, sinkage versus slip) per wheel; colour per medium."""
    import matplotlib.pyplot as plt

    fig, grid = plt.subplots(len(bodies), 3, figsize=(14, 3.6 * len(bodies) + 0.5), layout="constrained",
                             squeeze=False)  # fmt: skip
    for k, (axes, wheel) in enumerate(zip(grid, bodies, strict=True)):
        sel = [r for r in rows if r["wheel"] == wheel]
        force_slip_axes(axes, sel, s.media, title=f"wheel {wheel}", legend=k == len(bodies) - 1)
    return fig


@dataclass(frozen=True)
class _Flapped:
    """Designs (flap count, flap length / hub radius), cell size [m], drive [s] of the flapped row."""

    designs: tuple[tuple[int, float], ...]
    cell_size: float
    duration: float


#: the study's wheel (hub radius 50 mm, 50 mm wide) under its larger load on its first medium
_FLAP_HUB, _FLAP_WIDTH, _FLAP_LOAD, _FLAP_MEDIUM, _FLAP_OMEGA = 0.05, 0.05, 10.0, "CPS", 1.0
#: quick: one design at 25 mm cells (8 across the outer diameter: a smoke run), 1.6 s (one flap period
#: and a little); full: three flap counts at L / r = 1 and a shorter flap at 4 flaps, 8.33 mm cells
#: (24 across the outer diameter, 6 along a 50 mm flap), 4.5 s (4.5 rad). The speed is averaged over
#: whole flap periods (_flap_window).
_FLAP_QUICK = _Flapped(((4, 1.0),), 0.025, 1.6)
_FLAP_FULL = _Flapped(((3, 1.0), (4, 1.0), (6, 1.0), (4, 0.5)), 0.2 / 24, 4.5)
_FLAP_QUICK_NOTE = "quick form: 25 mm cells (8 across the wheel); a smoke run, not converged"
#: a design agrees when the two normalised speeds differ by at most this
_FLAP_SPEED_TOLERANCE = 0.1


def _flap_window(duration: float, count: int) -> float:
    """Averaging window [s]: the most whole flap periods (2 pi / (count omega)) that fit in the last half
    of the drive, one period when only one fits in the drive, else the last half."""
    period = 2.0 * math.pi / (count * _FLAP_OMEGA)
    whole = math.floor(0.5 * duration / period)
    if whole >= 1:
        return whole * period
    return period if duration >= period else 0.5 * duration


def flapped_self_propelled(quick: bool) -> ItemOutput:
    """Self-propelled flapped wheels in MPM beside the quasi-static RFT performance (ch. 6.2)."""
    import matplotlib.pyplot as plt
    import numpy as np

    from .. import materials
    from ..errors import SolverError
    from ..geometry import WheelFlapped
    from ..optimize import flapped_wheel_performance
    from .specs import Drive, Outputs, Resolution
    from .wheel_runs import run_wheel

    s = _FLAP_QUICK if quick else _FLAP_FULL
    mat = materials.get(_FLAP_MEDIUM)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.2), layout="constrained")
    rows: list[dict[str, Any]] = []
    beds: dict[str, dict[str, Any]] = {}
    for k, (count, ratio) in enumerate(s.designs):
        wheel = WheelFlapped(hub_radius=_FLAP_HUB, width=_FLAP_WIDTH, flap_count=count,
                             flap_length=ratio * _FLAP_HUB)  # fmt: skip
        r_out = wheel.outer_radius
        try:
            perf = flapped_wheel_performance(mat, hub_radius=_FLAP_HUB, width=_FLAP_WIDTH, flap_count=count,
                                             flap_length=ratio * _FLAP_HUB, flap_angle=0.0, load=_FLAP_LOAD,
                                             omega=_FLAP_OMEGA, phase_count=8 if quick else 24)  # fmt: skip
            v_rft, sink_rft = float(perf["velocity_normalised"]), float(perf["sinkage_m"])
        except SolverError:  # the design cannot carry the load in RFT
            v_rft, sink_rft = float("nan"), float("nan")
        res = run_wheel(wheel, mat, load=_FLAP_LOAD, omega=_FLAP_OMEGA,
                        resolution=Resolution(cell_size=s.cell_size), drive=Drive(duration=s.duration),
                        outputs=Outputs(record_interval=s.duration / 90))  # fmt: skip
        beds[f"{count} flaps, L / r = {ratio:g}"] = res.metadata
        ser = res.series
        d = ser["phase"] == "drive"
        t, vx, sink = ser["time_s"][d], ser["vx_m_s"][d], ser["sinkage_m"][d]
        t = t - t[0]
        late = t >= t[-1] - _flap_window(float(t[-1]), count)
        v_mpm = float(vx[late].mean()) / (_FLAP_OMEGA * r_out)
        rows.append({"flap_count": count, "flap_length_ratio": ratio, "outer_radius_m": r_out,
                     "velocity_normalised_mpm": v_mpm, "velocity_normalised_rft": v_rft,
                     "sinkage_mpm_m": float(sink[late].mean()), "sinkage_rft_m": sink_rft})  # fmt: skip
        label = f"{count} flaps, L / r = {ratio:g}"
        axes[0].axvspan(float(t[late][0]), float(t[-1]), color=f"C{k}", alpha=0.06)
        axes[0].plot(t, vx / (_FLAP_OMEGA * r_out), color=f"C{k}", lw=0.9, label=f"MPM, {label}")
        if np.isfinite(v_rft):
            axes[0].axhline(v_rft, color=f"C{k}", ls="--", lw=0.8, label=f"RFT, {label}")
        axes[1].plot(t, sink * 1e3, color=f"C{k}", lw=0.9, label=f"MPM, {label}")
        if np.isfinite(sink_rft):
            axes[1].axhline(sink_rft * 1e3, color=f"C{k}", ls="--", lw=0.8, label=f"RFT, {label}")
    axes[0].set_ylabel(r"normalised forward speed $V / (\omega R_{out})$ [-]")
    axes[1].set_ylabel("sinkage of the lowest point [mm]")
    for ax in axes:
        ax.set_xlabel("time since the spin started [s]")
        ax.grid(True, alpha=0.35)
        ax.legend(fontsize=7)
    fig.suptitle(f"Flapped wheels (hub radius {_FLAP_HUB * 1e3:g} mm), {_FLAP_LOAD:g} N on {mat.name}, "
                 f"self-propelled at {_FLAP_OMEGA:g} rad/s: MPM ({s.cell_size * 1e3:.3g} mm cells) and "
                 "quasi-static RFT")  # fmt: skip
    out = ItemOutput(
        figures={"flapped_mpm": fig},
        settings={
            "material": mat.name,
            "hub_radius_m": _FLAP_HUB,
            "width_m": _FLAP_WIDTH,
            "load_N": _FLAP_LOAD,
            "omega_rad_s": _FLAP_OMEGA,
            **asdict(s),
            "averaging": "MPM speed and sinkage over the most whole flap periods in the last half of "
            "the drive (shaded)",
        },
        tables={"flapped": rows},
    )
    out.findings.extend(bed_outgrown_findings(beds))
    for r in rows:
        dv = r["velocity_normalised_mpm"] - r["velocity_normalised_rft"]
        key = f"{r['flap_count']}_flaps_L{r['flap_length_ratio']:g}"
        out.metrics[f"velocity_normalised_mpm_{key}"] = r["velocity_normalised_mpm"]
        rft = (
            "RFT cannot carry the load"
            if not np.isfinite(dv)
            else f"RFT {r['velocity_normalised_rft']:.3f} (difference {dv:+.3f})"
        )
        out.findings.append(
            Finding(
                f"{r['flap_count']} flaps, L / r = {r['flap_length_ratio']:g}: V / (omega R_out) MPM "
                f"{r['velocity_normalised_mpm']:.3f}, {rft}; sinkage MPM {r['sinkage_mpm_m'] * 1e3:.1f} mm, "
                f"RFT {r['sinkage_rft_m'] * 1e3:.1f} mm",
                "info" if quick or not np.isfinite(dv) else
                ("agrees" if abs(dv) <= _FLAP_SPEED_TOLERANCE else "disagrees"),
            )
        )  # fmt: skip
    ranked = [r for r in rows if np.isfinite(r["velocity_normalised_rft"])]
    if len(ranked) >= 2:
        best_mpm = max(ranked, key=lambda r: r["velocity_normalised_mpm"])
        best_rft = max(ranked, key=lambda r: r["velocity_normalised_rft"])
        same = best_mpm is best_rft
        out.findings.append(
            Finding(
                f"fastest design: MPM {best_mpm['flap_count']} flaps at L / r = "
                f"{best_mpm['flap_length_ratio']:g}, RFT {best_rft['flap_count']} flaps at L / r = "
                f"{best_rft['flap_length_ratio']:g} ({'the same' if same else 'not the same'})",
                "agrees" if same else "disagrees",
            )
        )
    if quick:
        out.findings.append(Finding(_FLAP_QUICK_NOTE, "info"))
    return out


register_row("ch6-wheels-bc", "mpm", "terradyn.mpm.report_rows_ch6:wheels_bc_force_slip")
register_row("ch6-flapped", "mpm", "terradyn.mpm.report_rows_ch6:flapped_self_propelled")
