"""``terradyn study``: list and run named studies or study TOML files."""

from __future__ import annotations

import typer

from ..errors import InputError
from ..models import model_names
from ._common import OutputFormat, atomic_write_text, emit, fraction_progress, save_figure
from .options import FORMAT, OUT, OUT_FOLDER_HELP, QUICK, input_file, out_file, out_folder

app = typer.Typer(
    help="Reproducible studies (thesis experiments).", no_args_is_help=True, rich_markup_mode=None
)


@app.command("list")
def list_(
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
) -> None:
    """List the built-in studies."""
    from ..studies.registry import STUDIES, load_studies

    out_path = out_file("--out", out)
    load_studies()
    emit([{"study": k, "about": v[2]} for k, v in sorted(STUDIES.items())], fmt, out_path)


@app.command("run")
def run(
    study: str = typer.Argument(..., help="Study name (see `study list`) or a study TOML file."),
    out: str = typer.Option("terradyn-study", "--out", help=OUT_FOLDER_HELP),
    material: str | None = typer.Option(None, "--material", help="Override the study's medium."),
    quick: bool = QUICK,
    fmt: OutputFormat = FORMAT,
) -> None:
    """Run a study; write its tables (CSV) and plots (PNG) to a folder and print a summary."""
    from ..io import current_output_set
    from ..studies.registry import STUDIES, load_studies, run_study

    folder = out_folder("--out", out)
    assert folder is not None
    load_studies()
    if study.endswith(".toml"):
        input_file("STUDY", study)
    elif study not in STUDIES:
        raise InputError("STUDY", study, f"a study name ({', '.join(sorted(STUDIES))}) or a .toml file")
    overrides = {"material": material} if material else {}
    from ..parallel import reporting

    with fraction_progress(f"study {study}", "points") as update:
        with reporting(lambda done, total: update(done, done / max(1, total))):
            kind, result = run_study(study, quick=quick, overrides=overrides)
    outs = current_output_set()
    if outs is not None:
        outs.folder(folder)
    else:
        folder.mkdir(parents=True, exist_ok=True)
    for name, table in result.tables.items():
        atomic_write_text(folder / f"{name}.csv", table.to_dataframe().to_csv(index=False))
    for name, fig in result.figures.items():
        save_figure(fig, folder / f"{name}.png")
    emit(result.summary, fmt, None, title=f"study {kind}")


@app.command("high-speed")
def high_speed(
    material: str = typer.Option(
        "poppy-cp",
        "--material",
        help="Medium with a critical density (default: the poppy seeds of the thesis high-speed study).",
    ),
    model: str = typer.Option(
        "rft,drft",
        "--model",
        help="Terrain models, comma separated: " + ", ".join(model_names(use="dynamics")) + ".",
    ),
    omega: str | None = typer.Option(None, "--omega", help="Spin rates [rad/s]: list or start:stop:count."),
    gravity: float = typer.Option(9.81, "--gravity", help="Gravity [m/s^2]."),
    initial_velocity: float = typer.Option(0.0, "--initial-velocity", help="Initial speed [m/s]."),
    ramp: float | None = typer.Option(None, "--ramp", help="Spin ramp rate [rad/s^2]."),
    slip_margin: float = typer.Option(0.05, "--slip-margin", help="Slip rise that defines the onset."),
    quick: bool = QUICK,
    out: str | None = typer.Option(None, "--out", help=OUT_FOLDER_HELP),
    fmt: OutputFormat = FORMAT,
) -> None:
    """Grousered wheel on poppy seeds over spin rates: the onset of the sharp rise in slip (ch. 8)."""
    from ..io import current_output_set
    from ..studies.high_speed import high_speed_sweep
    from ._common import parse_float_list

    folder = out_folder("--out", out)
    names = [m.strip() for m in model.split(",") if m.strip()]
    omegas = parse_float_list("--omega", omega) if omega else None
    with fraction_progress("high-speed sweep", "points") as update:
        res = high_speed_sweep(
            material=material,
            models=names,
            omegas=omegas,
            gravity=gravity,
            initial_velocity=initial_velocity,
            ramp=ramp,
            slip_margin=slip_margin,
            reduced=quick,
            progress=lambda done, total: update(done, done / total),
        )
    if folder is not None:
        outs = current_output_set()
        if outs is not None:
            outs.folder(folder)
        else:
            folder.mkdir(parents=True, exist_ok=True)
        atomic_write_text(folder / "high_speed.csv", res.table.to_dataframe().to_csv(index=False))
        from ..plotting.studies import plot_high_speed

        save_figure(plot_high_speed(res), folder / "high_speed.png")
    onset = res.onset
    rec = {
        "omega_onset_rad_s": onset.get("omega_onset_rad_s"),
        "omega_onset_normalised": onset.get("omega_onset_normalised"),
    }
    rec.update({k: v for k, v in onset.items() if k not in rec})
    emit(rec, fmt, None, title="slip onset")
