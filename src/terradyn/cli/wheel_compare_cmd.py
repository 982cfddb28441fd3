"""``terradyn wheel compare``: one wheel case through several models and engines, one table.

A thin layer over :func:`terradyn.locomotion.compare_models`: it builds the
:class:`~terradyn.locomotion.WheelCase` and each engine's settings from the flags, and prints one row
per model with the same columns (:data:`terradyn.locomotion.wheel_run.SUMMARY_KEYS`).
"""

from __future__ import annotations

from typing import Any

import typer

from .. import materials
from ..errors import InputError
from ..models import model_entry, model_names
from ._common import OutputFormat, emit, fraction_progress
from .options import FORMAT, MATERIAL, OMEGA, OUT, WHEEL_WIDTH, out_file
from .wheel_options import WheelShape, shape_flags, wheel_body


def compare(
    model: str = typer.Option(
        "rft,drft,wong-reece",
        "--model",
        help="Models, comma separated: " + ", ".join(model_names(use="run-wheel")) + ".",
    ),
    material: str = MATERIAL,
    load: float = typer.Option(..., "--load", help="Vertical load W [N]."),
    slip: float | None = typer.Option(None, "--slip", help="Slip [-] (classic); omit for free rolling."),
    omega: float = OMEGA,
    shape: WheelShape = typer.Option(WheelShape.circular, "--shape", help="Wheel shape."),
    width: float = WHEEL_WIDTH,
    sizes: dict[str, Any] = {},  # the wheel size flags (WHEEL_SIZE_FLAGS)  # noqa: B006
    duration: float | None = typer.Option(
        None, "--duration", help="Simulated drive [s] of the time-stepped engines (default: each engine's)."
    ),
    dynamics: bool = typer.Option(
        False, "--dynamics", help="Integrate the force laws in time too (a row per law and engine)."
    ),
    cell_size: float | None = typer.Option(
        None, "--cell-size", help="MPM cell size [m] (default: the MPM's rule, 32 cells across the wheel)."
    ),
    grain_diameter: float | None = typer.Option(
        None, "--grain-diameter", help="DEM grain diameter [m] (default: the medium's)."
    ),
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
) -> None:
    """One wheel case through several models (RFT family, Wong-Reece, MPM, DEM): the same columns each."""
    from ..locomotion import DEMSettings, Dynamics, MPMSettings, WheelCase, run_wheel
    from ..mpm import Resolution

    out_path = out_file("--out", out)
    names = [m.strip() for m in model.split(",") if m.strip()]
    if not names:
        raise InputError("--model", model, "one or more of " + ", ".join(model_names(use="run-wheel")))
    entries = [model_entry(n, use="run-wheel", field="--model") for n in names]
    body = wheel_body(shape, width, shape_flags(shape, sizes))
    case = WheelCase(body, materials.get(material), load=load, slip=slip, omega=omega, duration=duration)
    settings: dict[str, Any] = {
        "mpm": MPMSettings(resolution=Resolution(cell_size=cell_size)),
        "dem": DEMSettings(grain_diameter=grain_diameter),
    }
    jobs = [(e.name, settings.get(e.name)) for e in entries]
    if dynamics:
        jobs += [(e.name, Dynamics()) for e in entries if e.kind.value == "force-law" and e.dimension == 2]
    rows = []
    with fraction_progress("wheel compare", "models") as update:
        for k, (name, spec) in enumerate(jobs):

            def report(_t: float, fraction: float, k: int = k) -> None:
                update(k + fraction, (k + fraction) / len(jobs))

            run = run_wheel(case, name, settings=spec, progress=report)
            rows.append(run.to_dict())
            update(k + 1, (k + 1) / len(jobs))
    emit(rows, fmt, out_path, title=f"wheel compare: {material}, W = {load:g} N")
