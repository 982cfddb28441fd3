"""Entry point of the ``terradyn`` console script."""

from __future__ import annotations

import os
import sys

import typer

from .. import __version__
from ..errors import TerradynError

app = typer.Typer(
    name="terradyn",
    help="Locomotion and intrusion in dry granular media: RFT, terramechanics, MPM.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)


def _version(value: bool) -> None:
    if value:
        typer.echo(f"terradyn {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: bool = typer.Option(
        False, "--version", callback=_version, is_eager=True, help="Print the version and exit."
    ),
) -> None:
    """terradyn command line."""


def _register() -> None:
    from . import demo_cmd, intrude_cmd, materials_cmd, rft_cmd

    app.add_typer(materials_cmd.app, name="materials")
    app.add_typer(rft_cmd.app, name="rft")
    intrude_cmd.register(app)
    demo_cmd.register(app)
    for module_name in ("wheel_cmd", "calibrate_cmd", "study_cmd", "mpm_cmd", "validate_cmd", "optimize_cmd"):
        try:
            module = __import__(f"terradyn.cli.{module_name}", fromlist=["register"])
        except ModuleNotFoundError as exc:
            if exc.name != f"terradyn.cli.{module_name}":
                raise
            continue
        module.register(app)


_register()


def main(argv: list[str] | None = None) -> None:
    """Run the CLI: errors become one line on stderr and a non-zero exit code, never a traceback."""
    args = sys.argv[1:] if argv is None else list(argv)
    if not args:
        args = ["--help"]
    try:
        app(args=args, prog_name="terradyn", standalone_mode=False)
    except TerradynError as exc:
        typer.echo(f"terradyn: error: {exc}", err=True)
        sys.exit(exc.exit_code)
    except KeyboardInterrupt:
        typer.echo("terradyn: interrupted", err=True)
        sys.exit(130)
    except Exception as exc:
        kind = type(exc).__name__
        if kind == "Exit":  # typer.Exit / click Exit
            sys.exit(getattr(exc, "exit_code", 0))
        if kind == "Abort":
            typer.echo("terradyn: aborted", err=True)
            sys.exit(130)
        if hasattr(exc, "format_message") and hasattr(exc, "exit_code"):  # usage errors
            typer.echo(f"terradyn: error: {exc.format_message()}", err=True)
            sys.exit(exc.exit_code)
        if os.environ.get("TERRADYN_DEBUG"):
            raise
        typer.echo(
            f"terradyn: internal error: {kind}: {exc} "
            "(set TERRADYN_DEBUG=1 for a traceback and please report it)",
            err=True,
        )
        sys.exit(70)
    sys.exit(0)
