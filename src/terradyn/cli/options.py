"""The command line's one option vocabulary: every shared flag is declared here, once.

Commands take these as parameter defaults, so a flag has the same name, unit, default and help text
in every command that has it. Output paths are taken as text and checked (with
:func:`terradyn.io.check_output_file`) before any work starts. :func:`flag_for` turns a library
field name in an error into the flag the user typed.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import typer

from ..io import FIGURE_SUFFIXES, OutputFormat, check_output_file, check_output_folder

__all__ = [
    "DEFAULT_MEDIUM",
    "DEFAULT_WHEEL_RADIUS",
    "DEFAULT_WHEEL_WIDTH",
    "flag_for",
    "out_file",
    "out_folder",
    "plot_file",
]

#: one default medium and one default wheel for every command (Agarwal et al. 2019's MS wheel)
DEFAULT_MEDIUM = "MS"
DEFAULT_WHEEL_RADIUS = 0.13
DEFAULT_WHEEL_WIDTH = 0.16
#: default out-of-plane width of intruders (plates, wedges, cylinders) [m]
DEFAULT_BODY_WIDTH = 0.01

MATERIAL = typer.Option(
    DEFAULT_MEDIUM, "--material", help="Medium name (see 'materials list') or a TOML file."
)
FORMAT = typer.Option(OutputFormat.table, "--format", help="Output format: table, json (SI keys) or csv.")
OUT = typer.Option(None, "--out", help="Also write the output to this file (.json or .csv).")
PLOT = typer.Option(None, "--plot", help="Write a plot here (.png, .pdf, .svg or .jpg).")
QUICK = typer.Option(False, "--quick", help="Reduced resolution and fewer points (a quick look).")
ELEMENT_SIZE = typer.Option(None, "--element-size", help="Surface element size [m] (default: from the body).")
PHASES = typer.Option(16, "--phases", help="Wheel angles per period averaged for non-circular wheels.")
OMEGA = typer.Option(1.0, "--omega", help="Spin rate [rad/s].")
LOAD = typer.Option(..., "--load", help="Vertical load W [N].")
WHEEL_RADIUS = typer.Option(
    DEFAULT_WHEEL_RADIUS, "--radius", help="Wheel radius [m] (rim radius for grousered wheels)."
)
WHEEL_WIDTH = typer.Option(DEFAULT_WHEEL_WIDTH, "--width", help="Wheel width [m].")
GRAVITY = typer.Option(9.81, "--gravity", help="Gravity [m/s^2].")
DRAWBAR_LOAD = typer.Option(0.0, "--drawbar-load", help="Rearward load on the axle [N].")
ANGLE = typer.Option(0.0, "--angle", help="Body rotation about +y [deg], clockwise.")
DIRECTION = typer.Option(90.0, "--direction", help="Motion direction below +x [deg] (90 = straight down).")
ANIMATE = typer.Option(None, "--animate", help="Animation file (.gif, or .mp4 with the video extra).")
OUT_FOLDER_HELP = "Folder for tables (CSV) and plots (PNG)."

#: library parameter names -> the CLI parameter that feeds them (where the names differ)
_SYNONYMS = {
    "phase_count": "phases",
    "checkpoint_path": "checkpoint",
    "snapshot_dir": "snapshots",
    "frame_count": "frames",
    "path": "points_file",
    "flap_thickness": "thickness",
    "max_iterations": "iterations",
    "omegas": "omega",
    "friction_angle_deg": "phi",
}

_ACTIVE: dict[str, str] = {}


def set_active_flags(params: Sequence[Any]) -> None:
    """Record the running command's parameters (python name -> flag) for :func:`flag_for`."""
    _ACTIVE.clear()
    for p in params:
        opts = [o for o in getattr(p, "opts", []) if o.startswith("--")]
        if opts:
            _ACTIVE[p.name] = opts[0]
        elif getattr(p, "param_type_name", "") == "argument" and p.name:
            _ACTIVE[p.name] = p.name.upper()


def flag_for(field: str) -> str:
    """The flag the user typed for a library ``field`` of the running command (else ``field``)."""
    if field.startswith("-") or not _ACTIVE:
        return field
    key = _SYNONYMS.get(field, field)
    if key in _ACTIVE:
        return _ACTIVE[key]
    if field in _ACTIVE:
        return _ACTIVE[field]
    if field + "s" in _ACTIVE:  # e.g. cell_size of one run of --cell-sizes
        return _ACTIVE[field + "s"]
    return field


def out_file(
    flag: str, value: str | None, suffixes: Sequence[str] | None = (".json", ".csv"), what: str = "file"
) -> Path | None:
    """``value`` as a checked output path (None stays None)."""
    if value is None:
        return None
    return check_output_file(flag, value, suffixes=suffixes, what=what)


def plot_file(flag: str, value: str | None) -> Path | None:
    """A checked figure path (.png/.pdf/.svg/.jpg) or None."""
    return out_file(flag, value, FIGURE_SUFFIXES, "figure file")


def out_folder(flag: str, value: str | None) -> Path | None:
    """A checked output folder path or None."""
    if value is None:
        return None
    return check_output_folder(flag, value)


def input_file(flag: str, value: str | None) -> Path | None:
    """An existing, readable file or None."""
    if value is None:
        return None
    from ..errors import InputError

    if not value.strip():
        raise InputError(flag, value, "a file path", "the name is empty")
    p = Path(value)
    try:
        exists, is_file = p.exists(), p.is_file()
        readable = is_file and os.access(p, os.R_OK)
    except OSError as exc:  # e.g. a name too long for the file system
        raise InputError(flag, value, "an existing file", exc.strerror or "cannot be accessed") from None
    if not is_file:
        raise InputError(flag, value, "an existing file", "it is a folder" if exists else "no such file")
    if not readable:
        raise InputError(flag, value, "a file you can read")
    return p


def animation_file(flag: str, value: str | None) -> Path | None:
    """A checked animation path: .gif, or .mp4 when the video extra is installed (checked now, not
    after the run)."""
    if value is None:
        return None
    p = check_output_file(flag, value, suffixes=(".gif", ".mp4"), what="animation file")
    if p.suffix.lower() == ".mp4":
        import importlib.util

        from ..errors import InputError

        if importlib.util.find_spec("imageio_ffmpeg") is None:
            raise InputError(
                flag, value, "a .gif, or install the video extra for MP4 (pip install 'terradyn[video]')"
            )
    return p


def with_flags(target: str, declared: dict[str, tuple[Any, Any]]) -> Any:
    """Declare a group of flags once and give them to a command as one dict.

    ``declared`` maps a parameter name to ``(annotation, typer.Option)``. The decorated command has a
    parameter ``target`` (a dict) in place of which the group's flags appear in its signature (and so
    in its ``--help``); the wrapper collects their values into that dict."""
    import functools
    import inspect
    import typing

    def decorate(func: Any) -> Any:
        signature = inspect.signature(func)
        hints = typing.get_type_hints(func)
        params: list[inspect.Parameter] = []
        for p in signature.parameters.values():
            if p.name == target:
                params += [
                    inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=opt, annotation=ann)
                    for name, (ann, opt) in declared.items()
                ]
            else:
                params.append(p.replace(kind=inspect.Parameter.KEYWORD_ONLY, annotation=hints.get(p.name)))

        @functools.wraps(func)
        def wrapper(**kwargs: Any) -> Any:
            kwargs[target] = {name: kwargs.pop(name) for name in declared}
            return func(**kwargs)

        wrapper.__signature__ = signature.replace(parameters=params)  # type: ignore[attr-defined]
        wrapper.__annotations__ = {p.name: p.annotation for p in params}
        del wrapper.__wrapped__
        return wrapper

    return decorate
