"""``terradyn mpm verify``: the MPM against plasticity theory (strip footing) and the FE reference."""

from __future__ import annotations

import math
from typing import Any

import typer

from ..errors import InputError, check_finite
from ..mpm.specs import Resolution
from ._common import OutputFormat, emit, format_output, fraction_progress, parse_float_list, save_figure
from .mpm_options import MPMOptions
from .options import FORMAT, MATERIAL, OUT, out_file, plot_file

verify_app = typer.Typer(
    help="MPM against plasticity theory (no RFT): bearing capacity of a rigid strip footing.",
    no_args_is_help=True,
    rich_markup_mode=None,
)


@verify_app.command("strip-footing")
def verify_strip_footing(
    phi: float = typer.Option(..., "--phi", help="Friction angle phi [deg] (continuum mu_s = sin phi)."),
    base: str = typer.Option("rough", "--base", help="Footing base: rough (no slip) or smooth."),
    width: float = typer.Option(0.04, "--footing-width", help="Footing width B [m]."),
    material: str = MATERIAL,
    cell_size: float | None = typer.Option(None, "--cell-size", help="Grid cell size [m] (default B/20)."),
    settlement_ratio: float = typer.Option(
        0.1, "--settlement-ratio", help="Settlement s/B [-] about which the collapse pressure is read."
    ),
    particles_per_cell: int = MPMOptions.ppc,
    volumetric: str = MPMOptions.volumetric,
    flip: float = MPMOptions.flip,
    contact: str = MPMOptions.contact,
    grid_phases: int = typer.Option(
        1,
        "--grid-phases",
        help="Repeat the run with the grid moved by k/N of a cell against the surface (N divides "
        "--particles-per-cell) and report the mean with each phase's value and the spread.",
    ),
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    plot: str | None = typer.Option(
        None, "--plot", help="Bearing pressure against settlement (.png/.pdf/.svg/.jpg)."
    ),
    fields: str | None = typer.Option(
        None, "--fields", help="Plastic shear-rate field at the end of the run (.png/.pdf/.svg/.jpg)."
    ),
    slip_lines: bool = typer.Option(
        False, "--slip-lines", help="Overlay the Prandtl slip-line field of the same footing on --fields."
    ),
) -> None:
    """N_gamma of a rigid strip footing from MPM beside the plasticity-theory value for isochoric flow."""
    from ..studies.mpm_verification import strip_footing

    out_path, plot_path = out_file("--out", out), plot_file("--plot", plot)
    fields_path = plot_file("--fields", fields)
    if slip_lines and fields_path is None:
        raise InputError("--slip-lines", True, "together with --fields FILE")
    if base not in ("rough", "smooth"):
        raise InputError("--base", base, "rough or smooth")
    with fraction_progress("MPM strip footing", "s") as bar:
        res = strip_footing(
            phi, base, material=material, width=width, cell_size=cell_size,
            settlement_ratio=settlement_ratio, progress=bar, grid_phases=grid_phases,
            resolution=Resolution(
                particles_per_cell=particles_per_cell, volumetric=volumetric, contact=contact, flip=flip
            ),
        )  # fmt: skip
    if plot_path is not None:
        from ..plotting.studies import plot_footing

        save_figure(plot_footing(res), plot_path)
    if fields_path is not None:
        save_figure(_footing_fields(res, slip_lines), fields_path, "--fields")
    emit(res.record(), fmt, out_path, title=f"strip footing, phi = {phi:g} deg, {base} base")


@verify_app.command("fe-footing")
def verify_fe_footing(
    phi: float = typer.Option(
        ..., "--phi", help="Friction angle phi [deg]: the cone sqrt(J2) = sin(phi) p, as in the MPM."
    ),
    base: str = typer.Option("smooth", "--base", help="Footing base: rough (no slip) or smooth."),
    flow: str = typer.Option(
        "isochoric", "--flow", help="Plastic flow: isochoric (psi = 0, the MPM's) or associated."
    ),
    elements: str = typer.Option(
        "10,20,40", "--elements", help="Three or more meshes, elements per footing half-width (comma list)."
    ),
    damping: float = typer.Option(
        0.8, "--damping", help="Local damping of the explicit relaxation, in [0, 1)."
    ),
    crossings: float = typer.Option(
        200.0, "--crossings", help="Push length in wave crossings of the mesh (more = slower loading)."
    ),
    hold_crossings: float = typer.Option(
        0.0, "--hold-crossings", help="Then hold the footing still this many crossings (N_gamma_held)."
    ),
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    plot: str | None = typer.Option(
        None, "--plot", help="Bearing factor against settlement for every mesh (.png/.pdf/.svg/.jpg)."
    ),
) -> None:
    """Reference N_gamma of a strip footing on the MPM's cone from small-strain finite elements (no MPM).

    Runs each mesh and reports N_gamma with the Richardson estimate; the associated flow rule checks
    the solver against the method of characteristics (docs/plasticity.md)."""
    from ..plasticity.fe_footing import fe_n_gamma_convergence

    out_path, plot_path = out_file("--out", out), plot_file("--plot", plot)
    phi_deg = check_finite("--phi", phi)
    if not 10.0 <= phi_deg <= 45.0:
        raise InputError("--phi", phi, "an angle in [10, 45] deg")
    meshes = _int_list("--elements", elements, "a comma list of integers, e.g. 10,20,40")
    # base, flow, damping, crossings and the meshes are checked by the library, named by their flags
    with fraction_progress("FE strip footing", "of the work") as bar:
        res = fe_n_gamma_convergence(
            math.sin(math.radians(phi_deg)), flow=flow, base=base, elements=meshes,
            progress=lambda done, total: bar(done / total, done / total), damping=damping,
            crossings=crossings, hold_crossings=hold_crossings,
        )  # fmt: skip
    if plot_path is not None:
        from ..plasticity.references import strip_footing_reference
        from ..plotting.studies import plot_fe_footing

        save_figure(plot_fe_footing(res, phi_deg, strip_footing_reference(phi_deg, base)), plot_path)
    record = {"phi_deg": phi_deg, **res.record()}
    title = f"FE strip footing, phi = {phi_deg:g} deg, {base} base, {flow} flow"
    emit(record, fmt, out_path, title=title, table=_convergence_table(record, title, _FE_COLUMNS))


@verify_app.command("node-footing")
def verify_node_footing(
    phi: float = typer.Option(..., "--phi", help="Friction angle phi [deg] (continuum mu_s = sin phi)."),
    base: str = typer.Option("smooth", "--base", help="Footing base: rough (no slip) or smooth."),
    cells_per_width: str = typer.Option(
        "10,20,40",
        "--cells",
        help="Three or more resolutions, cells across the footing width (even, comma list).",
    ),
    width: float = typer.Option(0.04, "--footing-width", help="Footing width B [m]."),
    material: str = MATERIAL,
    speed: float = typer.Option(0.01, "--speed", help="Footing speed after the start-up ramp [m/s]."),
    settlement_ratio: float = typer.Option(
        0.02, "--settlement-ratio", help="Settlement s/B [-] of the push; the reading is its last quarter."
    ),
    hold_time: float = typer.Option(
        0.0, "--hold-time", help="Then hold the footing still for this long [s] (N_gamma_held)."
    ),
    flip: float = typer.Option(
        0.0,
        "--flip",
        help="Particle velocity update: 0 the solver's APIC, 1 pure FLIP, between a blend; a diagnostic of "
        "the transfer's numerical dissipation (docs/mpm.md, 'What the rate error is').",
    ),
    domain_widths: str = typer.Option(
        "6,3", "--domain", help="Half-width and depth of the bed, in footing widths (comma pair)."
    ),
    full_domain: bool = typer.Option(
        False, "--full-domain", help="Grid both halves instead of a symmetry plane at the centre line."
    ),
    particles_per_cell: int = MPMOptions.ppc,
    volumetric: str = typer.Option(
        "patch", "--volumetric", help="Velocity divergence of the volume and stress update: patch or point."
    ),
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    plot: str | None = typer.Option(
        None, "--plot", help="Bearing factor against settlement at every resolution (.png/.pdf/.svg/.jpg)."
    ),
) -> None:
    """N_gamma of the MPM continuum under a footing whose base is a grid condition (no contact body),
    at three or more resolutions, with the Richardson estimate and the isochoric reference.

    The continuum's own check against plasticity theory: the contact's errors are left out
    (docs/mpm.md, "Footing as a grid boundary condition")."""
    from ..studies.mpm_footing_nodes import node_footing_convergence

    out_path, plot_path = out_file("--out", out), plot_file("--plot", plot)
    phi_deg = check_finite("--phi", phi)
    resolutions = _int_list("--cells", cells_per_width, "a comma list of even integers, e.g. 10,20,40")
    domain = parse_float_list("--domain", domain_widths)
    if len(domain) != 2:
        raise InputError("--domain", domain_widths, "a comma pair: half-width, depth (footing widths)")
    # the rest is checked by the library, its errors named by these flags
    with fraction_progress("MPM node footing", "of the work") as bar:
        res = node_footing_convergence(
            phi_deg, base, cells_per_width=resolutions, width=width, material=material, speed=speed,
            settlement_ratio=settlement_ratio, domain_widths=(domain[0], domain[1]),
            symmetric=not full_domain, volumetric=volumetric, particles_per_cell=particles_per_cell,
            hold_time=hold_time, flip=flip, progress=lambda done, total: bar(done / total, done / total),
        )  # fmt: skip
    if plot_path is not None:
        from ..plotting.studies import plot_node_footing

        save_figure(plot_node_footing(res), plot_path)
    record = {"phi_deg": phi_deg, "base": base, **res.record()}
    title = f"MPM node footing, phi = {phi_deg:g} deg, {base} base"
    emit(record, fmt, out_path, title=title, table=_convergence_table(record, title, _NODE_COLUMNS))


@verify_app.command("loading-rate")
def verify_loading_rate(
    phi: float = typer.Option(..., "--phi", help="Friction angle phi [deg] (continuum mu_s = sin phi)."),
    base: str = typer.Option("smooth", "--base", help="Footing base: rough (no slip) or smooth."),
    cells_per_width: int = typer.Option(10, "--cells", help="Cells (and elements) across the footing width."),
    width: float = typer.Option(0.04, "--footing-width", help="Footing width B [m]."),
    speeds: str = typer.Option(
        "0.01,0.0025,0.000625,0.00015625", "--speeds", help="MPM footing speeds [m/s] (comma list)."
    ),
    crossings: str = typer.Option(
        "100,200,800,1600", "--crossings", help="FE push lengths in wave crossings of the mesh (comma list)."
    ),
    dampings: str = typer.Option("0.8,0.5", "--dampings", help="FE local dampings in [0, 1) (comma list)."),
    hold_time: float = typer.Option(0.05, "--hold-time", help="MPM: hold the footing still this long [s]."),
    hold_crossings: float = typer.Option(
        50.0, "--hold-crossings", help="FE: hold the footing still this many crossings."
    ),
    flips: str = typer.Option(
        "0",
        "--flips",
        help="MPM: FLIP fractions of the velocity update, each run at every speed (comma list; 0 = APIC).",
    ),
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    plot: str | None = typer.Option(
        None, "--plot", help="Bearing factor against push duration, pushing and held (.png/.pdf/.svg/.jpg)."
    ),
) -> None:
    """The MPM node footing and the FE footing (medium MS) at one cell size, each pushed at several
    rates and then held: both materials are rate independent, so the rate-independent reading is
    where the pushing and held loads meet (docs/mpm.md, "Loading rate")."""
    from ..studies.mpm_footing_nodes import footing_loading_rate

    out_path, plot_path = out_file("--out", out), plot_file("--plot", plot)
    phi_deg = check_finite("--phi", phi)
    lists = {flag: parse_float_list(flag, text) for flag, text in
             (("--speeds", speeds), ("--crossings", crossings), ("--dampings", dampings),
              ("--flips", flips))}  # fmt: skip
    with fraction_progress("footing loading rate", "of the runs") as bar:
        res = footing_loading_rate(
            phi_deg, base, cells_per_width=cells_per_width, width=width, speeds=lists["--speeds"],
            crossings=lists["--crossings"], dampings=lists["--dampings"], hold_time=hold_time,
            hold_crossings=hold_crossings, flips=lists["--flips"],
            progress=lambda done, total: bar(done / total, done / total),
        )  # fmt: skip
    if plot_path is not None:
        from ..plotting.studies import plot_loading_rate

        save_figure(plot_loading_rate(res), plot_path)
    record = res.record()
    title = f"footing loading rate, phi = {phi_deg:g} deg, {base} base, B/{cells_per_width}"
    emit(record, fmt, out_path, title=title, table=_convergence_table(record, title, _RATE_COLUMNS))


_RATE_COLUMNS = ("model", "speed_m_s", "flip", "damping", "push_time_s", "N_gamma", "N_gamma_held")


_FE_COLUMNS = (
    "elements_per_half_width",
    "element_size_m",
    "N_gamma",
    "N_gamma_peak",
    "N_gamma_spread",
    "N_gamma_held",
    "wall_s",
)
_NODE_COLUMNS = (
    "cells_per_width",
    "cell_size_m",
    "N_gamma",
    "N_gamma_spread",
    "N_gamma_peak_ratio",
    "plateau",
    "N_gamma_held",
    "particles",
    "steps",
    "wall_s",
)


def _convergence_table(record: dict[str, Any], title: str, columns: tuple[str, ...]) -> str:
    """A convergence record as two tables: one row per resolution, then the estimate."""
    rows = [{k: run[k] for k in columns if k in run} for run in record["runs"]]
    summary = {k: v for k, v in record.items() if k != "runs"}
    table = OutputFormat.table
    return (
        format_output(rows, table, title=f"{title}: runs") + "\n" + format_output(summary, table, title=title)
    )


def _int_list(flag: str, text: str, allowed: str) -> tuple[int, ...]:
    try:
        return tuple(int(v) for v in text.split(","))
    except ValueError:
        raise InputError(flag, text, allowed) from None


def _footing_fields(res: Any, slip_lines: bool) -> Any:
    from ..plotting.mpm import plot_fields

    b = res.width_m
    window = (-3.0 * b, 3.0 * b, -1.5 * b, 0.5 * b)
    fig = plot_fields(
        res.final_particles,
        segments=res.final_segments,
        quantities=("plastic_shear_rate",),
        window=window,
        title=f"MPM strip footing, phi = {res.friction_angle_deg:g} deg, {res.base.value} base, "
        f"s/B = {res.settlement_m / b:.2g}",
    )
    if slip_lines:
        from ..plasticity.slipline import prandtl_field
        from ..plotting.slipline import plot_slip_lines

        field = prandtl_field(b, math.radians(res.friction_angle_deg), base=res.base.value)
        ax = fig.axes[0]
        plot_slip_lines(field, ax=ax)
        ax.set_xlim(window[0], window[1])
        ax.set_ylim(window[2], window[3])
    return fig
