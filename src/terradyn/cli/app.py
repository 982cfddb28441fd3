"""Entry point of the ``terradyn`` console script.

Start-up is kept light: this module imports only the standard library at import time; the command
modules (and NumPy, numba, typer behind them) load when a command runs, so ``terradyn --version`` and
``terradyn --help`` answer at once. Every way a run can end maps to one exit code
(:class:`terradyn.errors.ExitCode`, documented in the README), with one line on standard error.
"""

from __future__ import annotations

import os
import signal
import sys
from typing import Any

from .._interrupts import interrupt_seen, note_interrupt, reset_interrupts

__all__ = ["COMMANDS", "main"]

#: name -> (module under terradyn.cli, attribute, one-line help for ``terradyn --help``)
COMMANDS: dict[str, tuple[str, str, str]] = {
    "materials": ("materials_cmd", "app", "Shipped granular media and every parameter with its source."),
    "rft": ("rft_cmd", "app", "The RFT stress law itself (alpha_x, alpha_z), one point or the map."),
    "intrude": ("intrude_cmd", "intrude", "RFT force and torque on a body moving through the medium."),
    "wheel": ("wheel_cmd", "app", "Wheel locomotion: steady solves, sweeps, free rolling (RFT, DRFT, ...)."),
    "mpm": ("mpm_cmd", "app", "Plane-strain MPM continuum runs: intrusion and wheels."),
    "dem": ("dem_cmd", "app", "Discrete-element (LAMMPS) reference runs: intrusion and wheels (dem extra)."),
    "calibrate": ("calibrate_cmd", "app", "Fit RFT, Bekker or MPM parameters to measurements."),
    "replay": ("replay_cmd", "replay", "Predict a table of single-wheel runs with a terrain model; compare."),
    "study": ("study_cmd", "app", "Reproducible studies (thesis experiments)."),
    "optimize": ("optimize_cmd", "app", "Design optimisation (flapped wheels)."),
    "validate": ("validate_cmd", "validate", "Check the models against invariants and reference values."),
    "demo": ("demo_cmd", "demo", "Run the headline study into a folder."),
    "reproduce": ("reproduce_cmd", "reproduce", "Thesis chapters 3-9 as one HTML/Markdown report."),
    "warmup": ("warmup_cmd", "warmup", "Compile and cache every numerical kernel (run once after install)."),
}

_HELP = """Locomotion and intrusion in dry granular media: RFT, terramechanics, MPM.

SI units everywhere (angles in degrees on the command line). Exit codes: 0 success, 1 bad input,
2 usage, 3 solver failure, 4 failed checks, 70 a bug in terradyn, 130 interrupted (Ctrl-C), 143 terminated.
Run 'terradyn COMMAND --help' for a command's options."""


class _Terminated(KeyboardInterrupt):
    """SIGTERM, delivered as an interrupt so that the same clean-up runs."""


_terminated = False


def _on_sigterm(signum: int, frame: Any) -> None:
    global _terminated
    _terminated = True
    note_interrupt()
    raise _Terminated()


def _on_sigint(signum: int, frame: Any) -> None:
    note_interrupt()  # remembered even if the exception is swallowed (terradyn._interrupts)
    raise KeyboardInterrupt


def _root() -> Any:
    """The root command: a group whose subcommands are imported on first use."""
    os.environ.setdefault("TYPER_USE_RICH", "0")
    import typer
    import typer.main
    from typer.core import TyperGroup

    from .._version import __version__

    class LazyGroup(TyperGroup):
        def list_commands(self, ctx: Any) -> list[str]:
            return list(COMMANDS)

        def get_command(self, ctx: Any, cmd_name: str) -> Any:
            return load_command(cmd_name) if cmd_name in COMMANDS else None

        def format_commands(self, ctx: Any, formatter: Any) -> None:
            with formatter.section("Commands"):
                formatter.write_dl([(name, about) for name, (_, _, about) in COMMANDS.items()])

    root = typer.Typer(
        cls=LazyGroup,
        name="terradyn",
        help=_HELP,
        no_args_is_help=True,
        add_completion=False,
        rich_markup_mode=None,
        context_settings={"help_option_names": ["--help", "-h"], "max_content_width": 100},
    )

    def _version(value: bool) -> None:
        if value:
            sys.stdout.write(f"terradyn {__version__}\n")
            raise typer.Exit(0)

    @root.callback()
    def _options(
        version: bool = typer.Option(
            False, "--version", is_eager=True, callback=_version, help="Print the version and exit."
        ),
        threads: int | None = typer.Option(
            None,
            "--threads",
            help="Worker threads for compiled kernels (default: TERRADYN_THREADS, else all cores).",
        ),
    ) -> None:
        if threads is not None:
            from .. import set_threads
            from ..errors import InputError

            cores = os.cpu_count() or 1
            if not 1 <= threads <= cores:
                raise InputError(
                    "--threads", threads, f"a whole number of threads in [1, {cores}] (the cores here)"
                )
            try:
                set_threads(threads)
            except InputError as exc:
                raise InputError("--threads", threads, exc.allowed, exc.hint) from None

    return typer.main.get_command(root)


def load_command(name: str) -> Any:
    """The click command of the top-level command ``name`` (imports its module)."""
    import importlib

    os.environ.setdefault("TYPER_USE_RICH", "0")
    import typer
    import typer.main

    module_name, attr, about = COMMANDS[name]
    module = importlib.import_module(f"terradyn.cli.{module_name}")
    obj = getattr(module, attr)
    if isinstance(obj, typer.Typer):
        obj._add_completion = False
        if obj.registered_callback is None:
            obj.callback()(_group_callback)  # a group even when it has one subcommand
    if not isinstance(obj, typer.Typer):
        single = typer.Typer(add_completion=False, rich_markup_mode=None)
        single.command(name, help=obj.__doc__)(obj)
        obj = single
    command = typer.main.get_command(obj)
    _record_flags(command)
    command.name = name
    if not command.help:
        command.help = about
    return command


def _group_callback() -> None:
    """A command group."""


def _record_flags(command: Any) -> None:
    """Make every leaf command record its flags when it runs (for messages that name them)."""
    import functools

    from .options import set_active_flags

    subcommands = getattr(command, "commands", None)
    if subcommands:
        for sub in subcommands.values():
            _record_flags(sub)
        return
    callback = command.callback
    if callback is None:
        return

    @functools.wraps(callback)
    def recorded(*args: Any, **kwargs: Any) -> Any:
        set_active_flags(command.params)
        return callback(*args, **kwargs)

    command.callback = recorded


def _usage_message(exc: Any) -> str:
    """One line for a click usage error, naming the command it belongs to."""
    message = " ".join(str(exc.format_message()).split())
    ctx = getattr(exc, "ctx", None)
    where = f" (see '{ctx.command_path} --help')" if ctx is not None else ""
    return f"{message}{where}"


def _import_framework() -> None:
    """Import the command-line framework with SIGINT and SIGTERM held, then deliver them.

    Measured: a Ctrl-C that landed inside typer's import (about 0.4 s after start on a busy machine)
    was either lost (the run went on) or left the interpreter to end itself by SIGINT; held, it is
    raised here, just after the import, and handled like any other interrupt.
    """
    held = {signal.SIGINT, signal.SIGTERM}
    try:
        previous = signal.pthread_sigmask(signal.SIG_BLOCK, held)
    except (AttributeError, ValueError, OSError):  # no POSIX signal masks: import as it is
        previous = None
    try:
        os.environ.setdefault("TYPER_USE_RICH", "0")
        import typer
        import typer.main  # noqa: F401
    finally:
        if previous is not None:
            signal.pthread_sigmask(signal.SIG_SETMASK, previous)


def _run(args: list[str]) -> int:
    _import_framework()
    from typer import _click as click
    from typer.exceptions import Abort, Exit

    from ..errors import ExitCode
    from ..io import output_set

    root = _root()
    try:
        with root.make_context("terradyn", list(args)) as ctx:
            with output_set():
                root.invoke(ctx)
    except click.exceptions.NoArgsIsHelpError as exc:
        sys.stderr.write(exc.ctx.get_help() + "\n")
        return ExitCode.USAGE
    except Exit as exc:
        return int(getattr(exc, "exit_code", 0) or 0)
    except Abort:
        raise KeyboardInterrupt from None
    except click.exceptions.ClickException as exc:
        sys.stderr.write(f"terradyn: error: {_usage_message(exc)}\n")
        return ExitCode.USAGE if isinstance(exc, click.exceptions.UsageError) else ExitCode.INPUT
    return ExitCode.OK


def _interrupted(exc: KeyboardInterrupt) -> int:
    terminated = _terminated or isinstance(exc, _Terminated)
    what = "terminated" if terminated else "interrupted"
    detail = getattr(exc, "message", "") or ""
    sys.stderr.write(f"terradyn: {what}{'; ' + detail if detail else ''}\n")
    return 143 if terminated else 130


def _forget_unhandled_interrupt() -> None:
    """Clear CPython's record of a KeyboardInterrupt that escaped a nested ``PyRun_*`` call.

    An interrupt that lands while an import runs code through ``PyRun_*`` (measured: during the
    command-line framework's import, about 0.4 s after start) sets the interpreter's "unhandled
    KeyboardInterrupt" flag even though this module handles the exception; at exit the interpreter
    then kills itself with SIGINT (exit status -2 instead of the 130 printed). Each ``PyRun_*`` call
    clears the flag first, so an empty one clears it.
    """
    try:
        import ctypes

        ctypes.pythonapi.PyRun_SimpleString(b"")
    except (ImportError, AttributeError, OSError):  # not CPython: no such flag
        pass


def _quiet_interrupt_hook(previous: Any) -> Any:
    """An unraisable-exception hook that is silent once the run has been interrupted.

    Measured (CI, SIGINT 0.4 s after start): the handler's ``KeyboardInterrupt`` landed in llvmlite's
    ``ObjectRef.__del__``; the interpreter cannot raise out of a destructor, so it printed "Exception
    ignored in ... Traceback" before the one-line message. Measured too (SIGINT 1 s after start on a
    fresh kernel cache): an interrupt that lands inside llvmlite's ``detach`` leaves the object half
    closed, and its finaliser then fails later with ``AttributeError``. The interrupt is recorded
    (:func:`terradyn._interrupts.note_interrupt`) and ends the run, so once it has been delivered the
    printouts of failing finalisers are dropped; before that, every unraisable exception goes to the
    previous hook unchanged.
    """

    def hook(unraisable: Any) -> None:
        if interrupt_seen() or isinstance(unraisable.exc_value, KeyboardInterrupt):
            return
        previous(unraisable)

    return hook


def main(argv: list[str] | None = None) -> None:
    """Run the CLI: every ending is one line on stderr (none on success) and an exit code."""
    previous = previous_int = None
    reset_interrupts()
    previous_hook = sys.unraisablehook
    sys.unraisablehook = _quiet_interrupt_hook(previous_hook)
    try:
        previous = signal.signal(signal.SIGTERM, _on_sigterm)
        previous_int = signal.signal(signal.SIGINT, _on_sigint)
    except ValueError:  # not the main thread (embedded use): leave signals alone
        pass
    # fully vectorise every copy of a kernel this process compiles itself (terradyn.warmup explains why
    # in-process compiles are otherwise slower than cached code); the CLI runs no user numba code
    os.environ.setdefault("NUMBA_OPT", "max")
    code = 70
    try:
        code = _guarded(sys.argv[1:] if argv is None else list(argv))
    except KeyboardInterrupt as exc:
        code = _interrupted(exc)
        _forget_unhandled_interrupt()
    else:
        if interrupt_seen():  # delivered but swallowed on the way (terradyn._interrupts)
            code = _interrupted(KeyboardInterrupt())
    finally:
        for sig, handler in ((signal.SIGTERM, previous), (signal.SIGINT, previous_int)):
            if handler is not None:
                try:
                    signal.signal(sig, handler)
                except (ValueError, TypeError):
                    pass
        sys.unraisablehook = previous_hook
    try:
        sys.stdout.flush()
    except BrokenPipeError:
        _silence_stdout()
    sys.exit(code)


def _silence_stdout() -> None:
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):
        pass


def _root_help() -> str:
    width = max(len(n) for n in COMMANDS) + 2
    lines = ["Usage: terradyn [OPTIONS] COMMAND [ARGS]...", "", *("  " + ln for ln in _HELP.splitlines()), ""]
    lines += ["Options:", "  --version      Print the version and exit.",
              "  --threads N    Worker threads for compiled kernels (default: the TERRADYN_THREADS",
              "                 variable, else the number of cores).",
              "  -h, --help     Show this message and exit.", "", "Commands:"]  # fmt: skip
    lines += [f"  {name.ljust(width)}{about}" for name, (_, _, about) in COMMANDS.items()]
    return "\n".join(lines) + "\n"


def _open_figures() -> set[int]:
    pyplot = sys.modules.get("matplotlib.pyplot")
    return set() if pyplot is None else set(pyplot.get_fignums())


def _close_figures(before: set[int]) -> None:
    """A command's figures are written by then: close the ones it opened, so that commands run one
    after another in one process (tests, notebooks calling main) do not pile figures up."""
    pyplot = sys.modules.get("matplotlib.pyplot")
    if pyplot is not None:
        for number in set(pyplot.get_fignums()) - before:
            pyplot.close(number)


def _guarded(args: list[str]) -> int:
    """Run and turn every exception except interrupts into (one line, exit code)."""
    if args == ["--version"]:  # answered without importing the command line framework
        from .._version import __version__

        sys.stdout.write(f"terradyn {__version__}\n")
        return 0
    if args in ([], ["--help"], ["-h"]):
        (sys.stdout if args else sys.stderr).write(_root_help())
        return 0 if args else 2
    try:
        from ..errors import ExitCode, InputError, TerradynError
    except KeyboardInterrupt:
        raise
    figures = _open_figures()
    try:
        try:
            return _run(args)
        except Exception:
            # measured (CI, stop 34): a budget's SIGINT swallowed inside matplotlib left a figure half
            # laid out, and saving it then failed with "ValueError: Invalid bounding box". After an
            # interrupt, a failure is its consequence, not a bug to report: the run was interrupted.
            if interrupt_seen():
                raise KeyboardInterrupt from None
            raise
        finally:
            _close_figures(figures)
    except KeyboardInterrupt:
        raise
    except InputError as exc:
        from .options import flag_for

        sys.stderr.write(f"terradyn: error: {exc.render(flag_for(exc.field))}\n")
        return exc.exit_code
    except TerradynError as exc:
        sys.stderr.write(f"terradyn: error: {' '.join(str(exc).split())}\n")
        return int(exc.exit_code)
    except BrokenPipeError:
        _silence_stdout()
        return 141
    except OSError as exc:  # the file system refused: a bad path, a full disk, no permission
        where = f": {exc.filename}" if exc.filename else ""
        sys.stderr.write(f"terradyn: error: {exc.strerror or type(exc).__name__}{where}\n")
        return ExitCode.INPUT
    except MemoryError:
        sys.stderr.write("terradyn: error: not enough memory for this run (reduce its size)\n")
        return ExitCode.INPUT
    except Exception as exc:
        if os.environ.get("TERRADYN_DEBUG"):
            raise
        text = " ".join(str(exc).split())[:300]
        sys.stderr.write(
            f"terradyn: internal error: {type(exc).__name__}: {text} "
            "(set TERRADYN_DEBUG=1 for a traceback and please report it)\n"
        )
        return ExitCode.INTERNAL
