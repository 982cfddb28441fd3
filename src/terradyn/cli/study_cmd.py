"""``terradyn study``: list and run named studies or study TOML files."""

from __future__ import annotations

from pathlib import Path

import typer

from ..errors import InputError
from ._common import OutputFormat, atomic_write_text, emit, save_figure

app = typer.Typer(help="Reproducible studies (thesis experiments).", no_args_is_help=True)


def register(root: typer.Typer) -> None:
    root.add_typer(app, name="study")


@app.command("list")
def list_(
    fmt: OutputFormat = typer.Option(OutputFormat.table, "--format", help="Output format."),
    out: Path | None = typer.Option(None, "--out", help="Also write the output to this file."),
) -> None:
    """List the built-in studies."""
    from ..studies.registry import STUDIES, _load_plugins

    _load_plugins()
    emit([{"study": k, "about": v[2]} for k, v in sorted(STUDIES.items())], fmt, out)


@app.command("run")
def run(
    study: str = typer.Argument(..., help="Study name (see `study list`) or a study TOML file."),
    out: Path = typer.Option(Path("terradyn-study"), "--out", help="Folder for tables and plots."),
    material: str | None = typer.Option(None, "--material", help="Override the study's medium."),
    quick: bool = typer.Option(False, "--quick", help="Reduced resolution."),
    fmt: OutputFormat = typer.Option(OutputFormat.table, "--format", help="Summary format."),
) -> None:
    """Run a study; write its tables (CSV) and plots (PNG) to a folder and print a summary."""
    from ..studies.registry import run_study

    if out.exists() and not out.is_dir():
        raise InputError("--out", str(out), "a folder path")
    overrides = {"material": material} if material else {}
    kind, result = run_study(study, quick=quick, overrides=overrides)
    out.mkdir(parents=True, exist_ok=True)
    for name, table in result.tables.items():
        atomic_write_text(out / f"{name}.csv", table.to_dataframe().to_csv(index=False))
    for name, fig in result.figures.items():
        save_figure(fig, out / f"{name}.png")
    emit(result.summary, fmt, None, title=f"study {kind}")
