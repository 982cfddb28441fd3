"""Chapter 6 of the thesis reproduction report: wheels.

``tab-6-1``: the medium parameters (Bekker / Wong-Reece set and RFT constant) checked unit by unit.
``tab-6-2``: wheels A, B and C of :mod:`terradyn.studies.thesis_wheels`. ``fig-6-8``: wheel A in forced
slip on the four media, RFT beside Wong-Reece (one sweep), and MPM against the RFT steady solve.
``ch6-wheels-bc``: wheels B (the 212 mm grousered wheel of Agarwal et al. 2021, 15 lugs) and C
(terradyn's stand-in, the same rim without lugs) in forced slip: RFT and Wong-Reece, and MPM beside the
RFT steady solve of the same wheel; MPM resolves B's physical lugs (18 mm x 4 mm, terradyn's
assumption), RFT uses the effective lugs of :mod:`terradyn.studies.high_speed` (a third of their
height: the soil shadowed between lugs). ``ch6-flapped``: flapped wheels of the ``flapped-wheels``
study (hub radius 50 mm, 50 mm wide, radial zero-thickness flaps): the RFT sweep, and MPM
self-propelled under 10 N on CPS beside the quasi-static RFT performance of
:func:`terradyn.optimize.flapped_wheel_performance` (the normalised speed V / (omega R_out) over the
last half of the drive, and whether the two models rank the designs alike).

Each row is ``name(quick) -> ItemOutput``; every number in a finding comes from the run.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from ... import materials
from ..outputs import Finding, ItemOutput
from .common import MEDIA, MPM_MATERIAL, bed_outgrown_findings, force_slip_axes, study, verdict

__all__ = [
    "flapped_mpm",
    "flapped_rft",
    "material_audit_bekker",
    "wheel_a_force_slip_mpm",
    "wheel_a_force_slip_rft",
    "wheels_bc_force_slip_mpm",
    "wheels_bc_force_slip_rft",
    "wheels_table_theory",
]


# ---------------------------------------------------------------------------------- Tables 6.1, 6.2
def material_audit_bekker(quick: bool) -> ItemOutput:
    """Table 6.1: the printed Bekker columns, both unit readings, the settled one, the shipped values."""
    from ..bekker_audit import WHEEL_WIDTH, audit

    rows = audit()
    out = ItemOutput(settings={"wheel_width_m": WHEEL_WIDTH}, tables={"bekker_audit": rows})
    for r in rows:
        mat = materials.get(r["medium"]).require_bekker()
        shipped = math.isclose(mat.k_c, r["k_c_N_per_m_n1"], rel_tol=1e-9) and math.isclose(
            mat.k_phi, r["k_phi_N_per_m_n2"], rel_tol=1e-9
        )
        out.metrics[f"{r['medium']}_shipped_matches_reading"] = shipped
        text = (
            f"{r['medium']}: read in {r['reading']} (pressure ratio to RFT {r['ratio_if_N']:.3g} if N, "
            f"{r['ratio_if_kN']:.3g} if kN, at b = {WHEEL_WIDTH} m); shipped values "
            f"{'match' if shipped else 'DO NOT match'} that reading"
        )
        if not r["consistent"]:
            text += (
                f"; no reading is consistent: the nearer one is still {r['ratio_if_N']:.3g} x RFT, "
                f"and equals RFT only for a plate {r['width_matching_rft_m'] * 100:.2g} cm wide"
            )
        out.findings.append(Finding(text, verdict(shipped and r["consistent"])))
    return out


def wheels_table_theory(quick: bool) -> ItemOutput:
    from ...studies.thesis_wheels import WHEELS

    rows = [
        {
            "wheel": w.name,
            "kind": w.kind,
            "outer_diameter_m": w.outer_diameter_m,
            "width_m": w.width_m,
            "grousers": w.grousers,
            "loads_N": ", ".join(f"{v:g}" for v in w.loads_N),
            "source": w.source,
        }
        for w in WHEELS
    ]
    return ItemOutput(
        tables={"wheels": rows},
        findings=[
            Finding(
                "Table 6.2 and the paper's wheel table are not public: A and B are the closest documented "
                "wheels (sources per row); C is a stand-in, B's rim without lugs; "
                f"{len(rows)} rows",
                "info",
            )
        ],
    )


# ------------------------------------------------------------------- force-slip, RFT and Wong-Reece
def _point_near_slip(
    t: Any, material: str, model: str, slip: float = 0.3
) -> tuple[float, float, float] | None:
    """(slip, sinkage [m], drawbar pull [N]) of the solved point of ``model`` on ``material`` at the
    sweep's lightest load whose slip is nearest ``slip``; None when there is none."""
    c = t.columns
    m = (c["material"] == material) & (c["model"] == model) & c["solved"].astype(bool)
    m &= c["load_N"] == np.min(c["load_N"])
    if not np.any(m):
        return None
    k = np.nonzero(m)[0][int(np.argmin(np.abs(c["slip"][m] - slip)))]
    return float(c["slip"][k]), float(c["sinkage_m"][k]), float(c["drawbar_pull_N"][k])


def _force_slip_findings(t: Any, out: ItemOutput, wheel: str) -> None:
    load = float(np.min(t.columns["load_N"]))
    for name in MEDIA:
        vals = {}
        for model in ("rft", "wong-reece"):
            point = _point_near_slip(t, name, model)
            if point is not None:
                vals[model] = point
        if len(vals) < 2:
            out.findings.append(
                Finding(
                    f"wheel {wheel}, {name}, W = {load:g} N: solved only by {list(vals) or 'no model'}",
                    "disagrees",
                )
            )
            continue
        (s, z_r, dp_r), (_, z_w, dp_w) = vals["rft"], vals["wong-reece"]
        ratio = z_r / z_w if z_w > 0 else math.inf
        out.metrics[f"{wheel}_{name}_sinkage_rft_over_wr"] = ratio
        out.findings.append(
            Finding(
                f"wheel {wheel}, {name}, W = {load:g} N, s = {s:.2f}: sinkage RFT {z_r * 1e3:.1f} mm vs "
                f"Wong-Reece "
                f"{z_w * 1e3:.1f} mm (ratio {ratio:.2f}); drawbar pull RFT {dp_r:.1f} N vs Wong-Reece "
                f"{dp_w:.1f} N",
                verdict(0.5 <= ratio <= 2.0),
            )
        )


def wheel_a_force_slip_rft(quick: bool) -> ItemOutput:
    res = study("wheel-force-slip", quick)
    t = res.tables["wheel_force_slip"]
    out = ItemOutput(
        figures=res.figures,
        settings={
            "wheel": "A (0.26 m x 0.16 m)",
            "loads_N": [80, 130, 150, 190],
            "slips": sorted(set(t.columns["slip"].tolist())),
        },
    )
    _force_slip_findings(t, out, "A")
    out.findings.append(
        Finding(
            "The experiments of Agarwal et al. 2019 are not shipped: the models are "
            "compared with each other, not with measurements",
            "info",
        )
    )
    return out


def wheels_bc_force_slip_rft(quick: bool) -> ItemOutput:
    """Wheels B (15 effective lugs) and C (B's rim without lugs) in forced slip on the four media: RFT
    for both, Wong-Reece for the smooth cylinder (wheel C; it has no lug model, so it stands for B too)."""
    from ...locomotion import force_slip_sweep
    from ...locomotion.models import ModelSpec
    from ...plotting import new_force_slip_figure, plot_force_slip
    from ...results import TableResult
    from ...studies.thesis_wheels import WHEELS, wheel_body

    spec_b, spec_c = WHEELS[1], WHEELS[2]
    slips = np.round(np.linspace(-0.5, 0.7, 4 if quick else 13), 10)
    mats = [materials.get(m) for m in MEDIA]
    rft = {"rft": ModelSpec("rft")}
    rft_b = force_slip_sweep(
        wheel_body("B"), mats, rft, spec_b.loads_N, slips, phase_count=6 if quick else 16
    )
    rft_c = force_slip_sweep(wheel_body("C"), mats, rft, spec_c.loads_N, slips)
    wr = force_slip_sweep(
        wheel_body("C"), mats, {"wong-reece": ModelSpec("wong-reece")}, spec_c.loads_N, slips
    )
    tables = {}
    for name, part in (("B", rft_b), ("C", rft_c)):
        cols = {
            k: np.concatenate([np.asarray(part.columns[k]), np.asarray(wr.columns[k])]) for k in part.columns
        }
        tables[name] = TableResult(cols, {"wheel": name})
    figures = {}
    titles = {
        "B": "Wheel B (212 mm, 15 effective lugs): RFT (solid); Wong-Reece on B's smooth 212 mm cylinder "
        "(dashed)",
        "C": "Wheel C (stand-in: B's 212 mm rim without lugs): RFT (solid) and Wong-Reece (dashed)",
    }
    for name, t in tables.items():
        fig, axes = new_force_slip_figure(len(MEDIA))
        for row, medium in zip(axes, MEDIA, strict=True):
            plot_force_slip(t.columns, material=medium, axes=row)
        fig.suptitle(titles[name])
        figures[f"wheel_{name.lower()}_force_slip"] = fig
    out = ItemOutput(
        figures=figures,
        settings={
            "wheels": ["B", "C (stand-in)"],
            "loads_N": list(spec_b.loads_N),
            "slips": slips.tolist(),
            "wong_reece_body": "smooth cylinder of B's outer diameter and width (= wheel C)",
        },
    )
    for name, t in tables.items():
        _force_slip_findings(t, out, name)
    _lug_findings_rft(tables["B"], tables["C"], out)
    return out


def _lug_findings_rft(t_b: Any, t_c: Any, out: ItemOutput) -> None:
    """What B's lugs add to C's drawbar pull in RFT, at the lighter load and slip 0.3."""
    load = float(np.min(t_b.columns["load_N"]))
    for name in MEDIA:
        b, c = _point_near_slip(t_b, name, "rft"), _point_near_slip(t_c, name, "rft")
        if b is None or c is None:
            out.findings.append(Finding(f"lugs, {name}: B or C not solved by RFT", "disagrees"))
            continue
        (s, _, dp_b), (_, _, dp_c) = b, c
        out.metrics[f"lug_pull_gain_{name}_N"] = dp_b - dp_c
        out.findings.append(
            Finding(
                f"lugs, {name}, W = {load:g} N, s = {s:.2f}: RFT drawbar pull B {dp_b:+.1f} N, "
                f"C {dp_c:+.1f} N (lugs add {dp_b - dp_c:+.1f} N, {(dp_b - dp_c) / load:+.0%} of the load)",
                "info",
            )
        )


# --------------------------------------------------------------------------------- force-slip, MPM
def wheel_a_force_slip_mpm(quick: bool) -> ItemOutput:
    """Wheel A (0.13 m x 0.16 m, 130 N) under forced slip, MPM against the RFT steady solve: on MS in
    the quick form, on the four media of Fig. 6-8 in the full form."""
    import matplotlib.pyplot as plt

    from ...studies.mpm_compare import mpm_wheel_versus_rft

    # quick: MS, one slip, 25 mm cells (10 across the wheel), 1 s drive at 2 rad/s (a smoke run);
    # full: the resolution study of docs/mpm.md (11 mm cells, 4 s drive at 1 rad/s, slips 0.1-0.5) on
    # each medium of Fig. 6-8
    if quick:
        media: tuple[str, ...] = (MPM_MATERIAL,)
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
_FORCE_SLIP_QUICK = _ForceSlip(("MS",), (0.3,), 0.0265, 0.6, 2.0)
_FORCE_SLIP_FULL = _ForceSlip(("MS", "CPS"), (0.1, 0.3, 0.5), 0.0065, 4.5, 1.0)


def wheels_bc_force_slip_mpm(quick: bool) -> ItemOutput:
    """Wheels B (212 mm, 15 lugs) and C (B's rim without lugs) at their lighter load under forced slip:
    MPM against RFT, and what the lugs add in each."""
    from ... import materials
    from ...locomotion.steady import wheel_steady
    from ...mpm.specs import Drive, Resolution
    from ...mpm.wheel_runs import run_wheel
    from ...studies.high_speed import HighSpeedWheel
    from ...studies.thesis_wheels import WHEELS, wheel_body

    s = _FORCE_SLIP_QUICK if quick else _FORCE_SLIP_FULL
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
    out.findings.extend(_lug_findings_mpm(rows, load))
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


def _lug_findings_mpm(rows: list[dict[str, Any]], load: float) -> list[Finding]:
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


# ---------------------------------------------------------------------------------- flapped wheels
def flapped_rft(quick: bool) -> ItemOutput:
    res = study("flapped-wheels", quick)
    out = ItemOutput(figures=res.figures, settings={"quick": quick})
    for row in res.summary:
        out.findings.append(
            Finding(
                f"{row['material']}: best of the sweep {row['best_flap_count']} flaps, L / r = "
                f"{row['best_flap_length_ratio']:g}, V / (omega R) = {row['velocity_normalised']:.3f} at "
                f"{row['load_N']:g} N",
                "info",
            )
        )
    return out


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


def flapped_mpm(quick: bool) -> ItemOutput:
    """Self-propelled flapped wheels in MPM beside the quasi-static RFT performance (ch. 6.2)."""
    import matplotlib.pyplot as plt

    from ... import materials
    from ...errors import SolverError
    from ...geometry import WheelFlapped
    from ...mpm.specs import Drive, Outputs, Resolution
    from ...mpm.wheel_runs import run_wheel
    from ...optimize import flapped_wheel_performance

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
    _flapped_findings(out, rows, quick)
    if quick:
        out.findings.append(Finding(_FLAP_QUICK_NOTE, "info"))
    return out


def _flapped_findings(out: ItemOutput, rows: list[dict[str, Any]], quick: bool) -> None:
    """Each design's MPM and RFT speed and sinkage (metrics and findings), and whether the two models
    find the same fastest design."""
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
