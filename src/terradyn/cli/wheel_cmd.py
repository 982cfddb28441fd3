"""``terradyn wheel``: steady wheel solves, sweeps and free rolling with RFT or Wong-Reece."""

from __future__ import annotations

import math
from enum import Enum
from pathlib import Path
from typing import Any

import typer

from .. import materials
from ..errors import InputError, check_finite
from ..geometry import Body
from ..locomotion.models import MODEL_NAMES
from ..materials import Material
from ._bodies import BodyKind, _declared, build_body
from ._common import (
    OutputFormat,
    atomic_write,
    emit,
    fraction_progress,
    parse_float_list,
    progress,
    save_figure,
    spinner,
)
from .options import (
    ANIMATE,
    DRAWBAR_LOAD,
    ELEMENT_SIZE,
    FORMAT,
    GRAVITY,
    LOAD,
    MATERIAL,
    OMEGA,
    OUT,
    PHASES,
    PLOT,
    WHEEL_RADIUS,
    WHEEL_WIDTH,
    animation_file,
    input_file,
    out_file,
    plot_file,
    with_flags,
)

app = typer.Typer(
    help="Wheel locomotion: steady solves, sweeps, free rolling.", no_args_is_help=True, rich_markup_mode=None
)


class WheelShape(str, Enum):
    circular = "circular"
    grousered = "grousered"
    flapped = "flapped"
    c_leg = "c-leg"
    polygon = "polygon"


_SHAPE_TO_BODY = {
    WheelShape.circular: BodyKind.wheel,
    WheelShape.grousered: BodyKind.grousered,
    WheelShape.flapped: BodyKind.flapped,
    WheelShape.c_leg: BodyKind.c_leg,
    WheelShape.polygon: BodyKind.polygon,
}


class WongReeceOptions:
    c1 = typer.Option(0.43, "--c1", help="Wong-Reece theta_m coefficient c1 [-].")
    c2 = typer.Option(0.32, "--c2", help="Wong-Reece theta_m coefficient c2 [-].")
    exit_angle = typer.Option(0.0, "--exit-angle", help="Wong-Reece exit angle [deg].")


def model_factory(
    name: str, *, c1: float, c2: float, exit_angle_deg: float, element_size: float | None
) -> Any:
    """A picklable ``material -> terrain model`` factory for a model name."""
    from ..locomotion.models import ModelSpec

    exit_angle = math.radians(check_finite("--exit-angle", exit_angle_deg))
    if name.strip().lower() not in (*MODEL_NAMES, "wongreece", "wr"):
        raise InputError("--model", name, f"one of {list(MODEL_NAMES)}")
    return ModelSpec(name, element_size=element_size, c1=c1, c2=c2, exit_angle=exit_angle)


#: the size flags of every wheel shape, declared once for all wheel commands
WHEEL_SIZE_FLAGS = _declared(
    ("radius", "thickness", "grouser_count", "grouser_height", "grouser_thickness", "hub_radius",
     "flap_count", "flap_length", "flap_angle", "points_file"),
    radius=WHEEL_RADIUS,
)  # fmt: skip
wheel_flags = with_flags("sizes", WHEEL_SIZE_FLAGS)


def wheel_body(shape: WheelShape, width: float, flags: dict[str, Any]) -> Body:
    return build_body(_SHAPE_TO_BODY[shape], width, **flags)


def _steady_record(res: Any) -> dict[str, Any]:
    rec = res.summary()
    rec.update(
        {
            "slip": res.slip,
            "load_N": res.load_N,
            "omega_rad_s": res.omega_rad_s,
            "forward_velocity_m_s": res.forward_velocity_m_s,
            "tractive_efficiency": res.tractive_efficiency,
            "entry_angle_deg": math.degrees(res.entry_angle_rad),
            "model": res.model,
        }
    )
    if res.phase_count > 1:
        rec.update(
            {
                "drawbar_pull_min_N": res.drawbar_pull_min_N,
                "drawbar_pull_max_N": res.drawbar_pull_max_N,
                "drive_torque_min_Nm": res.drive_torque_min_Nm,
                "drive_torque_max_Nm": res.drive_torque_max_Nm,
                "sinkage_min_m": res.sinkage_min_m,
                "sinkage_max_m": res.sinkage_max_m,
            }
        )
    if "drawbar_load_N" in res.extra:
        rec["drawbar_load_N"] = res.extra["drawbar_load_N"]
    return rec


def _plot_steady(body: Body, mat: Material, res: Any, path: Path, element_size: float | None) -> None:
    import numpy as np

    from ..kinematics import Pose2D, Twist2D, to_world
    from ..plotting import plot_body_tractions
    from ..rft import rft_element_forces

    pose = Pose2D(0.0, res.axle_height_m, 0.0)
    el = rft_element_forces(
        body, mat, pose, Twist2D(res.forward_velocity_m_s, 0.0, res.omega_rad_s), element_size=element_size
    )
    outline = [to_world(np.asarray(p), pose) for p in body.outline()]
    ax = plot_body_tractions(
        outline, el.positions, el.forces, title=f"{mat.name}, W = {res.load_N:g} N, s = {res.slip:.3g} (RFT)"
    )
    save_figure(ax.figure, path)


@app.command("steady")
@wheel_flags
def steady(
    material: str = MATERIAL,
    load: float = LOAD,
    slip: float = typer.Option(..., "--slip", help="Slip s = 1 - V/(omega r), in [-1, 1]."),
    omega: float = OMEGA,
    model: str = typer.Option("rft", "--model", help="Terrain model: rft, drft, wong-reece or rft3d."),
    shape: WheelShape = typer.Option(WheelShape.circular, "--shape", help="Wheel shape."),
    width: float = WHEEL_WIDTH,
    sizes: dict[str, Any] = {},  # the wheel size flags (WHEEL_SIZE_FLAGS)  # noqa: B006
    phases: int = PHASES,
    element_size: float | None = ELEMENT_SIZE,
    c1: float = WongReeceOptions.c1,
    c2: float = WongReeceOptions.c2,
    exit_angle: float = WongReeceOptions.exit_angle,
    mesh: str | None = typer.Option(None, "--mesh", help="Wheel mesh (STL/OBJ/PLY) for --model rft3d."),
    slip_angle: float = typer.Option(0.0, "--slip-angle", help="Slip angle [deg] for --model rft3d."),
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    plot: str | None = typer.Option(
        None, "--plot", help="Wheel with RFT traction arrows (.png/.pdf/.svg/.jpg)."
    ),
) -> None:
    """Sinkage, drawbar pull, drive torque and power of a wheel at a load and slip."""
    from ..locomotion import wheel_steady

    out_path, plot_path = out_file("--out", out), plot_file("--plot", plot)
    flags = _shape_flags(shape, sizes)
    if model.strip().lower() == "rft3d":
        if plot_path is not None:
            raise InputError("--plot", plot, "a plane model (--model rft)")
        mesh_path = input_file("--mesh", mesh)
        angle = check_finite("--slip-angle", slip_angle)
        if not abs(angle) < 90.0:
            raise InputError("--slip-angle", slip_angle, "an angle in (-90, 90) [deg]")
        with spinner("3D steady solve"):
            rec = _steady_3d(shape, flags, width, mesh_path, material, load, slip, angle, omega, phases)
        emit(rec, fmt, out_path)
        return
    if mesh is not None or slip_angle != 0.0:
        raise InputError(
            "--mesh" if mesh is not None else "--slip-angle", mesh or slip_angle, "only with --model rft3d"
        )
    body = wheel_body(shape, width, flags)
    mat = materials.get(material)
    factory = model_factory(model, c1=c1, c2=c2, exit_angle_deg=exit_angle, element_size=element_size)
    if plot_path is not None and factory.name != "rft":
        raise InputError("--plot", plot, "only with --model rft (traction arrows of RFT elements)")
    res = wheel_steady(body, factory(mat), load, slip, omega=omega, phase_count=phases)
    if plot_path is not None:
        _plot_steady(body, mat, res, plot_path, element_size)
    emit(_steady_record(res), fmt, out_path)


@app.command("self-propelled")
@wheel_flags
def self_propelled(
    material: str = MATERIAL,
    load: float = LOAD,
    drawbar_load: float = DRAWBAR_LOAD,
    omega: float = OMEGA,
    model: str = typer.Option("rft", "--model", help="Terrain model: rft, drft, wong-reece or rft3d."),
    shape: WheelShape = typer.Option(WheelShape.circular, "--shape", help="Wheel shape."),
    width: float = WHEEL_WIDTH,
    sizes: dict[str, Any] = {},  # the wheel size flags (WHEEL_SIZE_FLAGS)  # noqa: B006
    phases: int = PHASES,
    element_size: float | None = ELEMENT_SIZE,
    c1: float = WongReeceOptions.c1,
    c2: float = WongReeceOptions.c2,
    exit_angle: float = WongReeceOptions.exit_angle,
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
) -> None:
    """Slip and sinkage at which the wheel's pull balances a drawbar load (0: free rolling)."""
    from ..locomotion import wheel_self_propelled

    out_path = out_file("--out", out)
    body = wheel_body(shape, width, _shape_flags(shape, sizes))
    factory = model_factory(model, c1=c1, c2=c2, exit_angle_deg=exit_angle, element_size=element_size)
    res = wheel_self_propelled(
        body,
        factory(materials.get(material)),
        load,
        drawbar_load=drawbar_load,
        omega=omega,
        phase_count=phases,
    )
    emit(_steady_record(res), fmt, out_path)


@app.command("sweep")
@wheel_flags
def sweep(
    material: str = typer.Option("MS", "--material", help="Media (names or TOML files), comma separated."),
    load: str = typer.Option("80,130,150,190", "--load", help="Loads [N]: a comma list or start:stop:count."),
    slip: str = typer.Option("-0.7:0.7:15", "--slip", help="Slips [-]: a comma list or start:stop:count."),
    model: str = typer.Option("rft,wong-reece", "--model", help="Models, comma separated."),
    omega: float = OMEGA,
    shape: WheelShape = typer.Option(WheelShape.circular, "--shape", help="Wheel shape."),
    width: float = WHEEL_WIDTH,
    sizes: dict[str, Any] = {},  # the wheel size flags (WHEEL_SIZE_FLAGS)  # noqa: B006
    phases: int = PHASES,
    element_size: float | None = ELEMENT_SIZE,
    c1: float = WongReeceOptions.c1,
    c2: float = WongReeceOptions.c2,
    exit_angle: float = WongReeceOptions.exit_angle,
    scheduler: str = typer.Option(
        "serial", "--scheduler", help="serial, local (Dask processes) or a Dask scheduler address."
    ),
    workers: int | None = typer.Option(None, "--workers", help="Local Dask worker processes."),
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    plot: str | None = PLOT,
) -> None:
    """Force-slip and sinkage-slip curves over media x models x loads x slips."""
    from ..locomotion import force_slip_sweep

    out_path, plot_path = out_file("--out", out), plot_file("--plot", plot)
    if workers is not None and not 1 <= workers <= 256:
        raise InputError("--workers", workers, "an integer in [1, 256]")
    body = wheel_body(shape, width, _shape_flags(shape, sizes))
    media = [materials.get(m) for m in material.split(",") if m.strip()]
    if not media:
        raise InputError("--material", material, "one or more media, comma separated")
    names = [m.strip() for m in model.split(",") if m.strip()]
    factories = {
        n: model_factory(n, c1=c1, c2=c2, exit_angle_deg=exit_angle, element_size=element_size) for n in names
    }
    if not factories:
        raise InputError("--model", model, f"one or more of {list(MODEL_NAMES)}")
    loads = parse_float_list("--load", load)
    slips = parse_float_list("--slip", slip)
    total = len(media) * len(factories) * len(loads) * len(slips)
    with progress(total, "wheel sweep") as advance:
        table = force_slip_sweep(
            body,
            media,
            factories,
            loads,
            slips,
            omega=omega,
            phase_count=phases,
            on_point=advance,
            scheduler=scheduler,
            workers=workers,
        )
    if plot_path is not None:
        plot_sweep(table.columns, [m.name for m in media], plot_path)
    failures = table.metadata["failures"]
    if failures:
        first = " ".join(str(failures[0]).split())
        typer.echo(f"terradyn: {len(failures)} point(s) not solved, e.g. {first}", err=True)
    emit(table.records(), fmt, out_path, title="wheel sweep")


def plot_sweep(columns: dict[str, Any], media: list[str], path: Path) -> None:
    from ..plotting import new_force_slip_figure, plot_force_slip

    fig, axes = new_force_slip_figure(len(media))
    for row, name in zip(axes, media, strict=True):
        plot_force_slip(columns, material=name, axes=row)
    save_figure(fig, path)


def _shape_flags(shape: WheelShape, values: dict[str, Any]) -> dict[str, Any]:
    keys = (
        "radius",
        "thickness",
        "grouser_count",
        "grouser_height",
        "grouser_thickness",
        "hub_radius",
        "flap_count",
        "flap_length",
        "flap_angle",
        "points_file",
    )
    flags = {k: values[k] for k in keys}
    if shape in (WheelShape.flapped, WheelShape.polygon):
        flags["radius"] = None  # the default --radius belongs to circular and grousered wheels
    return flags


@app.command("simulate")
@wheel_flags
def simulate(
    material: str = MATERIAL,
    mass: float = typer.Option(..., "--mass", help="Wheel (and carriage) mass [kg]."),
    omega: float | None = typer.Option(None, "--omega", help="Prescribed spin [rad/s] (target of a ramp)."),
    ramp: float | None = typer.Option(None, "--ramp", help="Spin ramp rate [rad/s^2]."),
    torque: float | None = typer.Option(None, "--torque", help="Prescribed motor torque [N m] instead."),
    initial_velocity: float = typer.Option(0.0, "--initial-velocity", help="Initial forward speed [m/s]."),
    duration: float = typer.Option(..., "--duration", help="Simulated time [s]."),
    dt: float | None = typer.Option(None, "--dt", help="Time step [s] (default: stable step)."),
    inertia: float | None = typer.Option(None, "--inertia", help="Moment of inertia [kg m^2]."),
    drawbar_load: float = DRAWBAR_LOAD,
    gravity: float = GRAVITY,
    model: str = typer.Option("rft", "--model", help="Terrain model: rft or drft."),
    shape: WheelShape = typer.Option(WheelShape.circular, "--shape", help="Wheel shape."),
    width: float = WHEEL_WIDTH,
    sizes: dict[str, Any] = {},  # the wheel size flags (WHEEL_SIZE_FLAGS)  # noqa: B006
    output_every: int = typer.Option(10, "--output-every", help="Store every N-th step."),
    fmt: OutputFormat = FORMAT,
    out: str | None = typer.Option(None, "--out", help="Time series file (.csv, .json or .nc)."),
    plot: str | None = PLOT,
    animate: str | None = ANIMATE,
) -> None:
    """Free wheel driven by a spin or torque: time series and the steady state over the last revolutions."""
    from ..locomotion.dynamics import simulate_wheel

    out_path = out_file("--out", out, (".csv", ".json", ".nc"))
    plot_path = plot_file("--plot", plot)
    animate_path = animation_file("--animate", animate)
    if model not in ("rft", "drft"):
        raise InputError("--model", model, "'rft' or 'drft'")
    if out_path is not None and out_path.suffix == ".nc":
        _require("xarray", "--out", out, "the fields extra for .nc output (pip install 'terradyn[fields]')")
    body = wheel_body(shape, width, _shape_flags(shape, sizes))
    mat = materials.get(material)
    with spinner("simulating"):
        res = simulate_wheel(
            body,
            mat,
            model=model,
            mass=mass,
            inertia=inertia,
            omega=omega,
            ramp=ramp,
            torque=torque,
            duration=duration,
            dt=dt,
            initial_velocity=initial_velocity,
            drawbar_load=drawbar_load,
            gravity=gravity,
            output_every=output_every,
        )
    summary = res.steady_summary()
    if out_path is not None:
        atomic_write(out_path, res.save, suffix=out_path.suffix, field_name="--out")
    if plot_path is not None:
        from ..plotting.animation import plot_time_series

        axes = plot_time_series(res)
        save_figure(axes.ravel()[0].figure, plot_path)
    if animate_path is not None:
        from ..plotting.animation import animate_body

        with fraction_progress("rendering the animation", "frames") as update:
            animate_body(body, mat, res, animate_path, progress=lambda i, n: update(i + 1, (i + 1) / n))
    emit(summary, fmt, None)


def _require(module: str, flag: str, value: Any, what: str) -> None:
    import importlib.util

    if importlib.util.find_spec(module) is None:
        raise InputError(flag, value, what)


def _steady_3d(
    shape: WheelShape,
    flags: dict[str, Any],
    width: float,
    mesh: Path | None,
    material: str,
    load: float,
    slip: float,
    slip_angle_deg: float,
    omega: float,
    phases: int,
) -> dict[str, Any]:
    """``wheel steady --model rft3d``: 3D RFT on a mesh or a primitive wheel, with a slip angle."""
    from ..geometry3d import load_mesh, wheel_cylinder, wheel_grousered
    from ..locomotion.steady3d import steady3d_record, wheel_steady_3d

    radius = flags.get("radius")
    phase_count = 1
    if mesh is not None:
        wheel = load_mesh(mesh)
        phase_count = phases
    elif shape is WheelShape.circular:
        if radius is None:
            raise InputError("--radius", None, "a radius [m] (or --mesh)")
        wheel = wheel_cylinder(radius, width, circumferential_resolution=360, axial_resolution=2)
    elif shape is WheelShape.grousered:
        if radius is None:
            raise InputError("--radius", None, "a radius [m] (or --mesh)")
        for flag in ("grouser_count", "grouser_height", "grouser_thickness"):
            if flags.get(flag) is None:
                raise InputError(f"--{flag.replace('_', '-')}", None, "a value (required for grousered)")
        wheel = wheel_grousered(
            radius,
            width,
            grouser_count=flags["grouser_count"],
            grouser_height=flags["grouser_height"],
            grouser_thickness=flags["grouser_thickness"],
            circumferential_resolution=360,
            axial_resolution=2,
        )
        phase_count = phases
    else:
        raise InputError("--shape", shape.value, "circular or grousered for rft3d (or --mesh FILE)")
    res = wheel_steady_3d(
        wheel,
        materials.get(material),
        load,
        slip,
        slip_angle=math.radians(slip_angle_deg),
        omega=omega,
        phase_count=phase_count,
    )
    rec: dict[str, Any] = dict(steady3d_record(res))
    rec.update(
        {
            "load_N": float(load),
            "omega_rad_s": float(omega),
            "forward_velocity_m_s": float(res.longitudinal_velocity_m_s),
            "model": "rft3d",
        }
    )
    return rec
