"""``terradyn demo``: the built-in default study."""

from __future__ import annotations

from pathlib import Path

import typer


def register(app: typer.Typer) -> None:
    app.command("demo")(demo)


def demo(
    out: Path = typer.Option(Path("terradyn-demo"), "--out", help="Folder for tables and plots."),
) -> None:
    """Run the headline study and write its tables and plots to a folder."""
    from ..studies.demo import run_demo

    run_demo(out)
