"""MPM row of chapter 6 of the reproduction report (``terradyn reproduce``): wheel B in forced slip.

``ch6-wheels-bc``: wheel B of :mod:`terradyn.report.wheels_abc` (the 212 mm grousered wheel of
Agarwal et al. 2021, 15 lugs) under forced slip, MPM beside the RFT steady solve of the same wheel.
MPM resolves the physical lugs (18 mm x 4 mm, terradyn's assumption); RFT uses the effective lugs of
:mod:`terradyn.studies.high_speed` (a third of their height: the soil shadowed between lugs), as the
RFT and Wong-Reece row of the item does. Wheel C has no public specification and is not run. The row
is ``wheel_b_force_slip(quick) -> ItemOutput``; every number in a finding comes from the run.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any

from ..report.registry import Finding, ItemOutput, register_row

__all__ = ["wheel_b_force_slip"]


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


def wheel_b_force_slip(quick: bool) -> ItemOutput:
    """Wheel B (212 mm, 15 lugs) at its lighter load under forced slip: MPM against RFT."""
    import matplotlib.pyplot as plt

    from .. import materials
    from ..locomotion.steady import wheel_steady
    from ..report.wheels_abc import WHEELS, wheel_body
    from ..studies.high_speed import HighSpeedWheel
    from .specs import Drive, Resolution
    from .wheel_runs import run_wheel

    s = _QUICK if quick else _FULL
    spec = WHEELS[1]
    load = float(spec.loads_N[0])
    physical = HighSpeedWheel(effective_grousers=False).body()
    effective = wheel_body("B")
    radius = 0.5 * float(spec.outer_diameter_m)  # type: ignore[arg-type]
    rows: list[dict[str, Any]] = []
    for name in s.media:
        mat = materials.get(name)
        for slip in s.slips:
            res = run_wheel(physical, mat, load=load, omega=s.omega, slip=slip,
                            resolution=Resolution(cell_size=s.cell_size),
                            drive=Drive(duration=s.duration))  # fmt: skip
            m = res.summary
            st = wheel_steady(effective, mat, load, slip, omega=s.omega, phase_count=6 if quick else 16)
            rows.append({"material": name, "slip": slip, "sinkage_mpm_m": m["sinkage_m"],
                         "sinkage_rft_m": st.sinkage_m, "drawbar_pull_mpm_N": m["drawbar_pull_N"],
                         "drawbar_pull_rft_N": st.drawbar_pull_N, "drive_torque_mpm_Nm": m["drive_torque_Nm"],
                         "drive_torque_rft_Nm": st.drive_torque_Nm})  # fmt: skip
    fig, axes = plt.subplots(1, 3, figsize=(14, 3.8), layout="constrained")
    for k, name in enumerate(s.media):
        sel = [r for r in rows if r["material"] == name]
        x = [r["slip"] for r in sel]
        for ax, key, scale in ((axes[0], "drawbar_pull", 1.0), (axes[1], "drive_torque", 1.0),
                               (axes[2], "sinkage", 1e3)):  # fmt: skip
            unit = {"drawbar_pull": "N", "drive_torque": "Nm", "sinkage": "m"}[key]
            ax.plot(
                x, [r[f"{key}_mpm_{unit}"] * scale for r in sel], "o-", color=f"C{k}", label=f"{name} MPM"
            )
            ax.plot(
                x, [r[f"{key}_rft_{unit}"] * scale for r in sel], "s--", color=f"C{k}", label=f"{name} RFT"
            )
    for ax, label in zip(axes, ("drawbar pull [N]", "drive torque [N m]", "sinkage [mm]"), strict=True):
        ax.set_xlabel("slip [-]")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.35)
        ax.legend(fontsize=8)
    fig.suptitle(
        f"Wheel B (212 mm, 15 lugs), {load:g} N, forced slip: MPM (physical lugs, {s.cell_size * 1e3:g} mm "
        f"cells, {s.duration:g} s at {s.omega:g} rad/s) and the RFT steady solve (effective lugs)"
    )
    out = ItemOutput(
        figures={"wheel_b_mpm": fig},
        settings={"wheel": "B", "load_N": load, "mpm_lugs": "physical", "rft_lugs": "effective", **asdict(s)},
        tables={"force_slip": rows},
    )
    for r in rows:
        tq = r["drive_torque_mpm_Nm"] / r["drive_torque_rft_Nm"]
        dp = r["drawbar_pull_mpm_N"] - r["drawbar_pull_rft_N"]
        out.metrics[f"{r['material']}_torque_ratio_slip{r['slip']:g}"] = tq
        out.findings.append(
            Finding(
                f"{r['material']}, slip {r['slip']:g}: torque MPM {r['drive_torque_mpm_Nm']:.2f} N m, RFT "
                f"{r['drive_torque_rft_Nm']:.2f} N m (ratio {tq:.2f}); drawbar pull MPM "
                f"{r['drawbar_pull_mpm_N']:+.1f} N, RFT {r['drawbar_pull_rft_N']:+.1f} N "
                f"({dp / load:+.0%} of the load); sinkage MPM {r['sinkage_mpm_m'] * 1e3:.1f} mm, RFT "
                f"{r['sinkage_rft_m'] * 1e3:.1f} mm (radius {radius * 1e3:g} mm)",
                "info"
                if quick
                else ("agrees" if abs(tq - 1.0) <= 0.15 and abs(dp) <= 0.05 * load else "disagrees"),
            )
        )
    if quick:
        out.findings.append(
            Finding(
                "quick form: 26.5 mm cells leave the 18 mm lugs unresolved; a smoke run, not converged",
                "info",
            )
        )
    out.findings.append(Finding("Wheel C: no public specification, not run (0 runs)", "info"))
    return out


register_row("ch6-wheels-bc", "mpm", "terradyn.mpm.report_rows_ch6:wheel_b_force_slip")
