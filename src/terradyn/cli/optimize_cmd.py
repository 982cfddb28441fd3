"""``terradyn optimize``: design optimisation."""

from __future__ import annotations

import math

import typer

from .. import materials
from ._common import OutputFormat, atomic_write_text, emit, fraction_progress, save_figure
from .options import FORMAT, MATERIAL, OUT, PLOT, out_file, plot_file

app = typer.Typer(help="Design optimisation.", no_args_is_help=True, rich_markup_mode=None)


@app.command("flapped-wheel")
def flapped_wheel(
    material: str = MATERIAL,
    hub_radius: float = typer.Option(0.05, "--hub-radius", help="Hub radius [m]."),
    width: float = typer.Option(0.05, "--width", help="Wheel width [m]."),
    load: float = typer.Option(10.0, "--load", help="Vertical load [N]."),
    metric: str = typer.Option("velocity", "--metric", help="velocity or cost-of-transport."),
    method: str = typer.Option("steady", "--method", help="steady (quasi-static) or dynamic (free body)."),
    flap_count_max: int = typer.Option(12, "--flap-count-max", help="Largest flap count."),
    length_ratio_max: float = typer.Option(
        1.5, "--length-ratio-max", help="Largest flap length / hub radius."
    ),
    angle_max: float = typer.Option(60.0, "--angle-max", help="Largest |flap angle| [deg]."),
    iterations: int = typer.Option(15, "--iterations", help="Differential-evolution generations."),
    population: int = typer.Option(8, "--population", help="Population size multiplier."),
    seed: int = typer.Option(0, "--seed", help="Random seed."),
    plot_params: str = typer.Option(
        "flap_count,flap_length_ratio", "--plot-params", help="Two parameters for the objective map."
    ),
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    trace: str | None = typer.Option(None, "--trace", help="Write every evaluation here (.csv)."),
    plot: str | None = PLOT,
) -> None:
    """Best flap count, length and angle of a flapped wheel (quasi-static RFT, global search)."""
    from ..errors import InputError
    from ..optimize import optimize_flapped_wheel

    out_path, plot_path = out_file("--out", out), plot_file("--plot", plot)
    trace_path = out_file("--trace", trace, (".csv",))
    mat = materials.get(material)
    if not 1 <= iterations <= 10000:
        raise InputError("--iterations", iterations, "an integer in [1, 10000]")
    if not 1 <= population <= 1000:
        raise InputError("--population", population, "an integer in [1, 1000]")
    if flap_count_max < 3:
        raise InputError("--flap-count-max", flap_count_max, "an integer >= 3")
    names = [n.strip() for n in plot_params.split(",")]
    allowed = ("flap_count", "flap_length_ratio", "flap_angle")
    if len(names) != 2 or any(n not in allowed for n in names) or names[0] == names[1]:
        raise InputError("--plot-params", plot_params, f"two different names from {list(allowed)}")
    with fraction_progress("optimising", "generations") as update:
        res = optimize_flapped_wheel(
            mat,
            hub_radius=hub_radius,
            width=width,
            load=load,
            metric=metric,
            flap_count=(2, flap_count_max),
            flap_length_ratio=(0.1, length_ratio_max),
            flap_angle=(-math.radians(angle_max), math.radians(angle_max)),
            seed=seed,
            max_iterations=iterations,
            population=population,
            method=method,
            progress=lambda done, total: update(done, done / total),
        )
    if trace_path is not None:
        atomic_write_text(trace_path, res.evaluations.to_dataframe().to_csv(index=False))
    if plot_path is not None:
        from ..plotting.studies import plot_optimization

        save_figure(plot_optimization(res, names, metric), plot_path)
    best: dict[str, object] = {
        "flap_count": int(res.best["flap_count"]),
        "flap_length_ratio": res.best["flap_length_ratio"],
        "flap_angle_deg": math.degrees(res.best["flap_angle"]),
    }
    best["objective"] = res.best_value
    best["metric"] = metric
    best["evaluations"] = len(res.evaluations)
    best["generations"] = len(res.trace)
    emit(best, fmt, out_path, title="best flapped wheel")
