"""``terradyn validate``: run the built-in model checks; non-zero exit if any fails."""

from __future__ import annotations

from pathlib import Path

import typer

from ._common import OutputFormat, emit


def register(root: typer.Typer) -> None:
    root.command("validate")(validate)


def validate(
    fmt: OutputFormat = typer.Option(OutputFormat.table, "--format", help="Output format."),
    out: Path | None = typer.Option(None, "--out", help="Also write the output to this file."),
) -> None:
    """Check the models against their invariants and reference values."""
    from ..studies.validation import run_checks

    checks = run_checks()
    rows = [c.record() for c in checks]
    if fmt is OutputFormat.table:
        rows = [{k: v for k, v in r.items() if k != "about"} for r in rows]
    emit(rows, fmt, out, title="terradyn validate")
    failed = [c.name for c in checks if not c.passed]
    if failed:
        typer.echo(f"terradyn: {len(failed)} check(s) failed: {', '.join(failed)}", err=True)
        raise typer.Exit(1)
