"""Figures of the optimisation and the high-speed study (each returns a matplotlib Figure)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..errors import InputError
from .core import new_figure

__all__ = ["plot_convergence", "plot_footing", "plot_high_speed", "plot_optimization"]

# Display name, scale from the stored SI value, unit, of the parameters the optimiser varies.
_PARAMETERS: dict[str, tuple[str, float, str]] = {
    "flap_count": ("flap count", 1.0, "-"),
    "flap_length_ratio": ("flap length / hub radius", 1.0, "-"),
    "flap_angle": ("flap angle", 180.0 / math.pi, "deg"),
}
_METRICS: dict[str, str] = {
    "velocity": r"normalised speed $V / (\omega R_{out})$ [-]",
    "cost-of-transport": r"cost of transport $P / (W V)$ [-]",
}


def _parameter(name: str) -> tuple[str, float]:
    label, scale, unit = _PARAMETERS.get(name, (name.replace("_", " "), 1.0, "-"))
    return f"{label} [{unit}]", scale


def plot_optimization(result: Any, names: Sequence[str], metric: str) -> Any:
    """Convergence of a design optimisation and its objective over two of the parameters.

    ``result`` is an :class:`~terradyn.optimize.OptimizationResult` (e.g. of
    :func:`~terradyn.optimize.optimize_flapped_wheel`), ``names`` the two parameters of the map
    (angles are shown in degrees), ``metric`` the objective's name ("velocity", "cost-of-transport" or
    any label). Left: the best objective per generation; right: every feasible evaluation coloured by
    its objective, infeasible ones as grey crosses, the best design as a star. Returns the Figure.
    """
    names = list(names)
    cols = result.evaluations.columns
    if len(names) != 2 or names[0] == names[1] or any(n not in cols for n in names):
        raise InputError(
            "names", names, f"two different parameters from {[k for k in cols if k in _PARAMETERS]}"
        )
    ylabel = _METRICS.get(metric, f"{metric} [-]")
    fig, axes = new_figure(1, 2, figsize=(11.0, 4.4))
    a0, a1 = axes[0]
    gen = np.arange(1, len(result.trace) + 1)
    a0.plot(gen, result.trace, marker="o", label="best of generation")
    a0.axhline(result.best_value, color="0.5", ls="--", lw=0.9, label=f"final best = {result.best_value:.4g}")
    a0.set_xlabel("generation [-]")
    a0.set_ylabel(ylabel)
    a0.set_title("convergence (" + ("maximised" if result.maximize else "minimised") + ")")
    if len(gen):
        a0.set_xticks(gen if len(gen) <= 15 else gen[:: math.ceil(len(gen) / 15)])
    a0.grid(True, alpha=0.35)
    a0.legend(fontsize=8)
    (xl, xs), (yl, ys) = _parameter(names[0]), _parameter(names[1])
    ok = np.asarray(cols["feasible"]).astype(bool)
    x, y = np.asarray(cols[names[0]], dtype=float) * xs, np.asarray(cols[names[1]], dtype=float) * ys
    if np.any(~ok):
        a1.plot(x[~ok], y[~ok], "x", color="0.6", ms=4, label="infeasible")
    sc = a1.scatter(
        x[ok], y[ok], c=np.asarray(cols["objective"])[ok], cmap="viridis", s=16, label="evaluated"
    )
    a1.plot(
        [result.best[names[0]] * xs],
        [result.best[names[1]] * ys],
        "*",
        color="tab:red",
        mec="k",
        ms=15,
        label="best",
    )
    fig.colorbar(sc, ax=a1, label=ylabel)
    a1.set_xlabel(xl)
    a1.set_ylabel(yl)
    a1.set_title("objective over the evaluated designs")
    a1.grid(True, alpha=0.35)
    a1.legend(fontsize=8)
    return fig


_HIGH_SPEED = (
    ("velocity_normalised", r"speed $V / \sqrt{g \ell}$ [-]"),
    ("slip", "slip [-]"),
    ("sinkage_normalised", r"sinkage / $\ell$ [-]"),
)


def plot_high_speed(result: Any) -> Any:
    """Steady speed, slip and sinkage versus normalised spin of a high-speed sweep, one line per model.

    ``result`` is a :class:`~terradyn.studies.high_speed.HighSpeedResult`; ell is the wheel's outer
    diameter. A dashed vertical line in the model's colour marks its slip onset where one was found.
    Returns the Figure.
    """
    c = result.table.columns
    normalised = "omega_normalised" in c
    keys = [(k, lab) for k, lab in _HIGH_SPEED if k in c]
    fig, axes = new_figure(1, len(keys), figsize=(4.6 * len(keys), 4.0), sharex=True)
    onsets = getattr(result, "onsets", {}) or {}
    for k, model in enumerate(dict.fromkeys(np.asarray(c["model"]).tolist())):
        m = np.asarray(c["model"]) == model
        x = np.asarray(c["omega_normalised" if normalised else "omega_rad_s"], dtype=float)[m]
        order = np.argsort(x)
        onset = onsets.get(model, {}).get("omega_onset_normalised" if normalised else "omega_onset_rad_s")
        for ax, (key, _) in zip(axes[0], keys, strict=True):
            ax.plot(
                x[order],
                np.asarray(c[key], dtype=float)[m][order],
                marker="o",
                ms=4,
                color=f"C{k}",
                label=model.upper(),
            )
            if onset is not None and np.isfinite(onset):
                ax.axvline(onset, color=f"C{k}", ls="--", lw=0.9, label=f"{model.upper()} slip onset")
    material = result.table.metadata.get("material", "")
    for ax, (_, label) in zip(axes[0], keys, strict=True):
        ax.set_xlabel(r"spin $\omega \sqrt{\ell / g}$ [-]" if normalised else r"spin $\omega$ [rad/s]")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.35)
    axes[0, 0].legend(fontsize=8)
    wheel = result.table.metadata.get("wheel", {})
    ell = wheel.get("outer_diameter") if isinstance(wheel, dict) else None
    size = rf", $\ell$ = {ell * 1e3:g} mm" if ell else ""
    fig.suptitle(f"Grousered wheel at high spin, {material}{size}".replace(", ,", ","))
    return fig


_UNITS = {"_N": "N", "_Nm": "N m", "_m": "m", "_m_s": "m/s", "_rad_s": "rad/s"}


def _quantity_label(name: str) -> str:
    for suffix, unit in sorted(_UNITS.items(), key=lambda kv: -len(kv[0])):
        if name.endswith(suffix):
            return f"{name[: -len(suffix)].replace('_', ' ')} [{unit}]"
    return f"{name.replace('_', ' ')} [-]"


def plot_convergence(result: Any) -> Any:
    """Each quantity of a :class:`~terradyn.studies.convergence.ConvergenceResult` against cell size
    [mm], with the Richardson extrapolation at zero cell size and the error band of the finest result.
    Returns the Figure."""
    names = list(result.values)
    fig, axes = new_figure(1, len(names), figsize=(4.6 * len(names), 3.8))
    h_mm = np.asarray(result.cell_sizes) * 1e3
    for ax, name in zip(axes[0], names, strict=True):
        est = result.estimates[name]
        phases = getattr(result, "phase_values", {}).get(name)
        ax.plot(
            h_mm,
            result.values[name],
            "o-",
            color="C0",
            label="MPM" if not phases else "MPM, mean of the grid phases",
        )
        if phases:
            for k in range(len(phases[0])):
                ax.plot(h_mm, [p[k] for p in phases], "x", color="0.45", ms=5,
                        label="each grid phase" if k == 0 else None)  # fmt: skip
        finest = h_mm.min()
        band = (
            "error band of the finest (GCI)" if est.extrapolated is not None else "spread of the three finest"
        )
        ax.errorbar([finest], [est.finest], yerr=[est.error_band], color="C3", capsize=4, label=band)
        if est.extrapolated is not None:
            order = "" if est.order is None else f", order {est.order:.2g}"
            ax.plot([0.0], [est.extrapolated], "*", ms=12, color="C2", label=f"Richardson{order}")
            ax.plot([0.0, finest], [est.extrapolated, est.finest], ":", color="C2")
        fit = getattr(result, "fits", {}).get(name)
        if fit is not None:
            hh = np.linspace(0.0, float(h_mm.max()), 60)
            ax.plot(
                hh, fit.extrapolated + fit.coefficient * (1e-3 * hh) ** fit.order, "--", color="C1", lw=1.0
            )
            ax.errorbar([0.0], [fit.extrapolated], yerr=[fit.standard_error], fmt="s", color="C1", capsize=4,
                        label=f"least squares, order {fit.order:g} (+- 1 s.e.)")  # fmt: skip
        ax.set_xlim(left=-0.04 * float(h_mm.max()))
        ax.set_xlabel("cell size [mm]")
        ax.set_ylabel(_quantity_label(name))
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    return fig


def plot_footing(result: Any) -> Any:
    """Bearing pressure [kPa] against settlement / width of an MPM strip footing
    (:class:`~terradyn.studies.mpm_verification.StripFootingResult`), with the fitted embedment line,
    its intercept (the collapse pressure of the MPM) and the theory value 0.5 gamma B N_gamma."""
    fig, axes = new_figure(1, 1, figsize=(6.4, 4.2))
    ax = axes[0, 0]
    b, gamma = result.width_m, result.unit_weight_N_m3
    cell = f"cell {result.cell_size_m * 1e3:.3g} mm"
    phases = getattr(result, "phases", ())
    if len(phases) > 1:  # every grid phase's curve, each with its own intercept
        for k, (offset, n_gamma, (s, q)) in enumerate(phases):
            label = rf"MPM, {cell}, grid offset {offset:g} cell: $N_\gamma$ = {n_gamma:.3g}"
            ax.plot(s / b, q / 1e3, color=f"C{(0, 4, 5, 6)[k % 4]}", lw=1.1, label=label)
        fit_label = rf"mean fit of the {len(phases)} phases, intercept: $N_\gamma$ = {result.N_gamma_mpm:.3g}"
    else:
        s, q = result.curve
        ax.plot(s / b, q / 1e3, color="C0", lw=1.2, label=f"MPM, {cell}")
        fit_label = rf"fit, intercept: $N_\gamma$ = {result.N_gamma_mpm:.3g}"
    q_u = 0.5 * gamma * b * result.N_gamma_mpm
    x = np.array([0.0, 1.5 * result.settlement_m / b])
    ax.plot(x, (q_u + gamma * result.embedment_slope * x * b) / 1e3, "--", color="C1", label=fit_label)
    ref = result.reference.get("N_gamma_reference")
    kind = str(result.reference.get("reference_kind", ""))
    if ref:
        what = "theory (isochoric)"
        band = result.reference.get("N_gamma_fe_band")
        if kind.startswith("computed, finite elements"):
            what = "finite elements (isochoric)"
            lo, hi = (0.5 * gamma * b * (float(ref) + d * float(band or 0.0)) / 1e3 for d in (-1.0, 1.0))
            ax.axhspan(lo, hi, color="C2", alpha=0.12, lw=0)
        text = rf"{what}: $N_\gamma$ = {float(ref):.3g}" + (rf" $\pm$ {float(band):.2g}" if band else "")
        ax.axhline(0.5 * gamma * b * float(ref) / 1e3, color="C2", ls=":", label=text)
        davis = result.reference.get("N_gamma_davis_estimate")
        if davis and kind.startswith("computed, finite elements"):
            ax.axhline(0.5 * gamma * b * float(davis) / 1e3, color="C7", ls=":",
                       label=rf"Davis estimate (isochoric): $N_\gamma$ = {float(davis):.3g}")  # fmt: skip
    for key, style, what in (
        ("N_gamma_upper_bound", "-.", "associated Mohr-Coulomb"),
        ("N_gamma_upper_bound_cone", (0, (5, 2, 1, 2, 1, 2)), "associated MPM cone (bound of the MPM)"),
    ):
        value = result.reference.get(key)
        if value:
            ax.axhline(0.5 * gamma * b * float(value) / 1e3, color="C3", ls=style, lw=1.0,
                       label=rf"{what}: $N_\gamma$ = {float(value):.3g}")  # fmt: skip
    ax.set_xlabel("settlement / footing width [-]")
    ax.set_ylabel("bearing pressure [kPa]")
    ax.set_xlim(left=0.0)
    ax.set_ylim(bottom=0.0)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(
        rf"rigid strip footing, $\phi$ = {result.friction_angle_deg:g} deg, {result.base.value} base"
    )
    return fig


def plot_fe_footing(result: Any, phi_deg: float, reference: dict[str, Any] | None = None) -> Any:
    """Bearing factor 2 q / (gamma B) against settlement / width of the FE strip footing at every mesh
    (:class:`~terradyn.plasticity.fe_footing.FEConvergence`), with each mesh's reading (the mean of
    the last quarter), the Richardson estimate and, from ``reference``
    (:func:`~terradyn.plasticity.references.strip_footing_reference`), the Davis estimate and the
    associated values."""
    fig, axes = new_figure(1, 1, figsize=(6.4, 4.2))
    ax = axes[0, 0]
    for k, (n, run) in enumerate(zip(result.elements_per_half_width, result.runs, strict=True)):
        s, q = run.curve[:, 0], run.curve[:, 1]
        scale = 2.0 / (run.unit_weight_N_m3 * run.width_m)
        ax.plot(s / run.width_m, q * scale, color=f"C{k}", lw=1.0,
                label=rf"{n} elements per half-width: $N_\gamma$ = {run.N_gamma:.3g}")  # fmt: skip
    _richardson_line(ax, result.estimate)
    _reference_lines(
        ax, reference, ("N_gamma_davis_estimate", "N_gamma_associated", "N_gamma_upper_bound_cone")
    )
    first = result.runs[0]
    _bearing_axes(ax)
    ax.set_title(rf"FE strip footing, cone of $\phi$ = {phi_deg:g} deg, {first.base} base, {first.flow} flow")
    return fig


def _richardson_line(ax: Any, est: Any) -> None:
    if est.extrapolated is not None:
        label = rf"Richardson (order {est.order:.2g}): $N_\gamma$ = {est.extrapolated:.3g}"
        ax.axhline(est.extrapolated, color="k", ls="--", lw=1.0, label=label)


_REFERENCE_LINES = {
    "N_gamma_davis_estimate": (":", "Davis estimate (isochoric)"),
    "N_gamma_associated": ("-.", "associated Mohr-Coulomb"),
    "N_gamma_upper_bound_cone": ((0, (5, 2, 1, 2, 1, 2)), "associated cone"),
}


def _reference_lines(ax: Any, reference: dict[str, Any] | None, keys: tuple[str, ...]) -> None:
    for key in keys:
        value = (reference or {}).get(key)
        if value:
            style, what = _REFERENCE_LINES[key]
            ax.axhline(
                float(value), color="C3", ls=style, lw=1.0, label=rf"{what}: $N_\gamma$ = {float(value):.3g}"
            )


def _bearing_axes(ax: Any) -> None:
    ax.set_xlabel("settlement / footing width [-]")
    ax.set_ylabel(r"bearing factor $2q / (\gamma B)$ [-]")
    ax.set_xlim(left=0.0)
    ax.set_ylim(bottom=0.0)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)


def plot_node_footing(result: Any) -> Any:
    """Bearing factor 2 q / (gamma B) against settlement / width of the MPM footing whose base is a
    grid condition (:class:`~terradyn.studies.mpm_footing_nodes.NodeFootingConvergence`) at every cell
    size, with each reading (the mean of the last quarter), the Richardson estimate, the isochoric
    reference with its band and the Davis and associated values."""
    fig, axes = new_figure(1, 1, figsize=(6.4, 4.2))
    ax = axes[0, 0]
    for k, run in enumerate(result.runs):
        s, q = run.curve
        scale = 2.0 / (run.unit_weight_N_m3 * run.width_m)
        label = rf"B/{run.width_m / run.cell_size_m:.0f}: $N_\gamma$ = {run.N_gamma:.3g}"
        ax.plot(s / run.width_m, q * scale, color=f"C{k}", lw=1.0, label=label)
    _richardson_line(ax, result.estimate)
    ref = result.reference.get("N_gamma_reference")
    if ref:
        band = result.reference.get("N_gamma_fe_band") or 0.0
        kind = result.reference.get("reference_kind") or "reference"
        label = rf"isochoric reference ({kind}): $N_\gamma$ = {float(ref):.3g}"
        if band:
            label += rf" $\pm$ {band:.2g}"
        ax.axhline(float(ref), color="C7", lw=1.5, label=label)
        if band:
            ax.axhspan(float(ref) - band, float(ref) + band, color="C7", alpha=0.2, lw=0)
    _reference_lines(ax, result.reference, ("N_gamma_davis_estimate", "N_gamma_associated"))
    _bearing_axes(ax)
    first = result.runs[0]
    ax.set_title(
        rf"MPM footing as a grid condition, $\phi$ = {first.friction_angle_deg:g} deg, {first.base} base, "
        f"{first.speed_m_s:g} m/s",
        fontsize=9,
    )
    return fig


def plot_loading_rate(study: Any) -> Any:
    """Bearing factor against push duration (log scale) for the MPM node footing and the FE footing
    of :func:`~terradyn.studies.mpm_footing_nodes.footing_loading_rate`: the pushing reading (filled
    markers, solid lines) and the load after the footing is held still (open markers, dashed)."""
    fig, axes = new_figure(1, 1, figsize=(6.4, 4.2))
    ax = axes[0, 0]
    flips = list(dict.fromkeys(r.flip for r in study.mpm))
    series = [
        (
            f"MPM node footing, {'APIC' if f == 0 else f'FLIP {f:g}'}",
            f"C{k}",
            "o",
            [r for r in study.mpm if r.flip == f],
        )
        for k, f in enumerate(flips)
    ]
    series += [
        (f"FE, damping {d:g}", f"C{k + len(flips)}", "s", runs) for k, (d, runs) in enumerate(study.fe)
    ]
    for label, color, marker, runs in series:
        runs = sorted(runs, key=lambda r: r.push_time_s)
        t = [r.push_time_s for r in runs]
        ax.plot(t, [r.N_gamma for r in runs], color=color, marker=marker, lw=1.2, label=f"{label}, pushing")
        ax.plot(t, [r.N_gamma_held for r in runs], color=color, marker=marker, mfc="none", lw=1.0, ls="--",
                label=f"{label}, held")  # fmt: skip
    ax.set_xscale("log")
    ax.set_xlabel("push duration to s = 0.02 B [s]")
    ax.set_ylabel(r"$N_\gamma$ = 2 q / ($\gamma$ B) [-]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    ax.set_title(
        rf"Loading rate, $\phi$ = {study.friction_angle_deg:g} deg, {study.base} base, "
        f"cells B/{study.width_m / study.cell_size_m:.0f}",
        fontsize=9,
    )
    return fig
