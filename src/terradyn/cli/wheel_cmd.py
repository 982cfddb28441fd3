"""``terradyn wheel``: steady wheel solves, sweeps and free rolling with RFT or Wong-Reece."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import typer

from .. import materials
from ..errors import InputError, check_finite
from ..geometry import Body
from ..materials import Material
from ..models import model_entry, model_names
from . import wheel_compare_cmd as _wheel_compare
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
    WHEEL_WIDTH,
    animation_file,
    input_file,
    out_file,
    plot_file,
)
from .wheel_options import WheelShape, shape_flags, wheel_body, wheel_flags

app = typer.Typer(
    help="Wheel locomotion: steady solves, sweeps, free rolling.", no_args_is_help=True, rich_markup_mode=None
)


def _model_help(use: str) -> str:
    """``--model`` help from the model table (:mod:`terradyn.models`)."""
    return "Terrain model: " + ", ".join(model_names(use=use)) + "."


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
    model_entry(name, allowed=model_names(use="self-propelled"), field="--model")
    return ModelSpec(name, element_size=element_size, c1=c1, c2=c2, exit_angle=exit_angle)


class Wheel3DOptions:
    """Flags of the 3D wheel path (--model rft3d)."""

    mesh = typer.Option(None, "--mesh", help="Wheel mesh (STL/OBJ/PLY) for --model rft3d.")
    mesh_units = typer.Option("m", "--mesh-units", help="Length unit of the mesh file: m, cm or mm.")
    axle = typer.Option("y", "--axle", help="Mesh axis the wheel turns about: x, y or z.")
    center = typer.Option(
        None, "--center", help="Axle centre X,Y,Z [mesh units] (default: fitted to the mesh)."
    )
    xi = typer.Option(None, "--xi", help="3D-RFT media scale xi [N/m^3] (default: from --material).")
    slip_angle = typer.Option(0.0, "--slip-angle", help="Slip angle [deg], -90 to 90, for --model rft3d.")
    cull = typer.Option(
        None, "--cull/--no-cull",
        help="Drop facets the soil cannot reach (hub, inner rim), by visibility; default on with --mesh.",
    )  # fmt: skip


class KinematicsOptions:
    """How the wheel moves: a slip under a named definition, or the rim and carriage speeds."""

    slip_definition = typer.Option(
        "classic", "--slip-definition",
        help="classic: s = 1 - V/(omega r); bounded: s = (omega r - V)/max(omega r, V), -1 = locked.",
    )  # fmt: skip
    rim_speed = typer.Option(None, "--rim-speed", help="Rim speed omega r [m/s] (with --carriage-speed).")
    carriage_speed = typer.Option(
        None, "--carriage-speed", help="Axle speed over the ground [m/s] (with --rim-speed)."
    )


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
    load: float | None = typer.Option(None, "--load", help="Vertical load W [N] (or --sinkage)."),
    sinkage: float | None = typer.Option(
        None, "--sinkage", help="Prescribed sinkage [m] instead of --load: the forces at that depth."
    ),
    slip: float | None = typer.Option(
        None, "--slip", help="Slip [-] in [-1, 1] (see --slip-definition), or give the speeds."
    ),
    slip_definition: str = KinematicsOptions.slip_definition,
    rim_speed: float | None = KinematicsOptions.rim_speed,
    carriage_speed: float | None = KinematicsOptions.carriage_speed,
    omega: float = OMEGA,
    model: str = typer.Option("rft", "--model", help=_model_help("steady")),
    shape: WheelShape = typer.Option(WheelShape.circular, "--shape", help="Wheel shape."),
    width: float = WHEEL_WIDTH,
    sizes: dict[str, Any] = {},  # the wheel size flags (WHEEL_SIZE_FLAGS)  # noqa: B006
    phases: int = PHASES,
    element_size: float | None = ELEMENT_SIZE,
    c1: float = WongReeceOptions.c1,
    c2: float = WongReeceOptions.c2,
    exit_angle: float = WongReeceOptions.exit_angle,
    mesh: str | None = Wheel3DOptions.mesh,
    mesh_units: str = Wheel3DOptions.mesh_units,
    axle: str = Wheel3DOptions.axle,
    center: str | None = Wheel3DOptions.center,
    xi: float | None = Wheel3DOptions.xi,
    slip_angle: float = Wheel3DOptions.slip_angle,
    cull: bool | None = Wheel3DOptions.cull,
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    plot: str | None = typer.Option(
        None, "--plot", help="Wheel with RFT traction arrows (.png/.pdf/.svg/.jpg)."
    ),
) -> None:
    """Sinkage, drawbar pull, drive torque and power of a wheel at a load (or sinkage) and slip."""
    out_path, plot_path = out_file("--out", out), plot_file("--plot", plot)
    flags = shape_flags(shape, sizes)
    _load_or_sinkage(load, sinkage)
    kin = _kinematics(slip, slip_definition, rim_speed, carriage_speed)
    if model_entry(model, use="steady", field="--model").dimension == 3:
        if plot_path is not None:
            raise InputError("--plot", plot, "a plane model (--model rft)")
        angle = _slip_angle_deg(slip_angle, kin)
        culling = mesh is not None if cull is None else cull
        spec = _Wheel3DSpec(mesh, mesh_units, axle, center, culling)
        wheel, phase_count = _wheel_3d(shape, flags, width, spec, phases)
        medium = _medium_3d(material, xi)
        with spinner("3D steady solve"):
            rec = _steady_3d(wheel, medium, load, sinkage, kin, angle, omega, phase_count, culling)
        emit(rec, fmt, out_path)
        return
    for flag, value, default in (
        ("--mesh", mesh, None), ("--slip-angle", slip_angle, 0.0), ("--xi", xi, None),
        ("--center", center, None), ("--mesh-units", mesh_units, "m"), ("--axle", axle, "y"),
        ("--cull", cull, None),
    ):  # fmt: skip
        if value != default:
            raise InputError(flag, value, "only with --model rft3d")
    from ..locomotion import wheel_steady
    from ..locomotion.prescribed import wheel_at_sinkage

    body = wheel_body(shape, width, flags)
    mat = materials.get(material)
    factory = model_factory(model, c1=c1, c2=c2, exit_angle_deg=exit_angle, element_size=element_size)
    if plot_path is not None and factory.name != "rft":
        raise InputError("--plot", plot, "only with --model rft (traction arrows of RFT elements)")
    s, spin = _plane_slip(kin, omega, body)
    if sinkage is not None:
        res = wheel_at_sinkage(body, factory(mat), sinkage, s, omega=spin, phase_count=phases,
                               slip_definition=kin.definition)  # fmt: skip
    else:
        assert load is not None
        res = wheel_steady(body, factory(mat), load, s, omega=spin, phase_count=phases,
                           slip_definition=kin.definition)  # fmt: skip
    if plot_path is not None:
        _plot_steady(body, mat, res, plot_path, element_size)
    rec = _steady_record(res)
    rec["slip_definition"] = kin.definition
    emit(rec, fmt, out_path)


class _Kinematics:
    """The wheel's motion as the user gave it (slip, or rim and carriage speeds)."""

    def __init__(
        self, slip: float | None, definition: str, rim: float | None, carriage: float | None
    ) -> None:
        self.slip, self.definition, self.rim, self.carriage = slip, definition, rim, carriage


def _kinematics(
    slip: float | None, definition: str, rim: float | None, carriage: float | None
) -> _Kinematics:
    from ..kinematics import SlipDefinition

    choices = [d.value for d in SlipDefinition]
    name = definition.strip().lower()
    if name not in choices:
        raise InputError("--slip-definition", definition, f"one of {choices}")
    if slip is not None and (rim is not None or carriage is not None):
        raise InputError("--slip", slip, "either --slip or --rim-speed with --carriage-speed, not both")
    if slip is None:
        if rim is None and carriage is None:
            raise InputError("--slip", None, "a slip [-] (or --rim-speed and --carriage-speed)")
        if rim is None or carriage is None:
            flag = "--rim-speed" if rim is None else "--carriage-speed"
            raise InputError(flag, None, "a speed [m/s] (--rim-speed and --carriage-speed go together)")
        if not (math.isfinite(rim) and rim >= 0.0):
            raise InputError("--rim-speed", rim, "a rim speed omega r >= 0 [m/s]")
        if not (math.isfinite(carriage) and carriage > 0.0):
            raise InputError("--carriage-speed", carriage, "a speed > 0 [m/s]")
        if name == "classic" and rim == 0.0:
            raise InputError(
                "--rim-speed", rim, "a rim speed > 0 [m/s] with --slip-definition classic",
                "a locked wheel needs --slip-definition bounded",
            )  # fmt: skip
    else:
        hint = "s = 1 - V/(omega r)" if name == "classic" else "s = (omega r - V)/max(omega r, V)"
        if not (math.isfinite(slip) and -1.0 <= slip <= 1.0):
            raise InputError("--slip", slip, "a number in [-1, 1]", hint)
    return _Kinematics(slip, name, rim, carriage)


def _load_or_sinkage(load: float | None, sinkage: float | None) -> None:
    if (load is None) == (sinkage is None):
        flag, value = ("--sinkage", sinkage) if load is not None else ("--load", load)
        raise InputError(flag, value, "exactly one of --load [N] and --sinkage [m]")
    if load is not None and not (math.isfinite(load) and load > 0.0):
        raise InputError("--load", load, "a load > 0 [N]")
    if sinkage is not None and not (math.isfinite(sinkage) and sinkage >= 0.0):
        raise InputError("--sinkage", sinkage, "a depth >= 0 [m]")


def _plane_slip(kin: _Kinematics, omega: float, body: Body) -> tuple[float, float]:
    """(slip in the chosen definition, the omega the plane solver takes) for a plane wheel."""
    from ..kinematics import slip_from_speeds
    from ..locomotion import wheel_nominal_radius

    if kin.slip is not None:
        return kin.slip, omega
    assert kin.rim is not None and kin.carriage is not None
    radius = wheel_nominal_radius(body)
    s = slip_from_speeds(kin.rim, kin.carriage, definition=kin.definition)
    scale = kin.rim if kin.definition == "classic" else max(kin.rim, kin.carriage)
    return s, scale / radius


def _slip_angle_deg(slip_angle: float, kin: _Kinematics) -> float:
    angle = check_finite("--slip-angle", slip_angle)
    if not abs(angle) <= 90.0:
        raise InputError("--slip-angle", slip_angle, "an angle in [-90, 90] [deg]")
    if abs(angle) == 90.0 and kin.slip is not None:
        raise InputError(
            "--slip-angle", slip_angle, "an angle in (-90, 90) [deg] with --slip",
            "at 90 deg the slip does not fix the motion: give --rim-speed and --carriage-speed",
        )  # fmt: skip
    return angle


@app.command("self-propelled")
@wheel_flags
def self_propelled(
    material: str = MATERIAL,
    load: float = LOAD,
    drawbar_load: float = DRAWBAR_LOAD,
    omega: float = OMEGA,
    model: str = typer.Option("rft", "--model", help=_model_help("self-propelled")),
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
    body = wheel_body(shape, width, shape_flags(shape, sizes))
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


def _sweep_models(
    model: str, *, c1: float, c2: float, exit_angle: float, element_size: float | None
) -> tuple[list[str], list[str], dict[str, Any]]:
    """The --model names of a sweep: the 3D ones, the plane ones and the plane ones' model factories."""
    names = [m.strip() for m in model.split(",") if m.strip()]
    dimension = {n: model_entry(n, use="sweep", field="--model").dimension for n in names}
    spatial = [n for n in names if dimension[n] == 3]
    plane = [n for n in names if dimension[n] == 2]
    factories = {
        n: model_factory(n, c1=c1, c2=c2, exit_angle_deg=exit_angle, element_size=element_size) for n in plane
    }
    if not names:
        raise InputError("--model", model, f"one or more of {', '.join(model_names(use='sweep'))}")
    return spatial, plane, factories


@app.command("sweep")
@wheel_flags
def sweep(
    material: str = typer.Option("MS", "--material", help="Media (names or TOML files), comma separated."),
    load: str = typer.Option("80,130,150,190", "--load", help="Loads [N]: a comma list or start:stop:count."),
    slip: str = typer.Option("-0.7:0.7:15", "--slip", help="Slips [-]: a comma list or start:stop:count."),
    model: str = typer.Option(
        "rft,wong-reece",
        "--model",
        help="Models, comma separated: " + ", ".join(model_names(use="sweep")) + ".",
    ),
    omega: float = OMEGA,
    shape: WheelShape = typer.Option(WheelShape.circular, "--shape", help="Wheel shape."),
    width: float = WHEEL_WIDTH,
    sizes: dict[str, Any] = {},  # the wheel size flags (WHEEL_SIZE_FLAGS)  # noqa: B006
    phases: int = PHASES,
    element_size: float | None = ELEMENT_SIZE,
    c1: float = WongReeceOptions.c1,
    c2: float = WongReeceOptions.c2,
    exit_angle: float = WongReeceOptions.exit_angle,
    slip_definition: str = KinematicsOptions.slip_definition,
    slip_angle: str = typer.Option(
        "0",
        "--slip-angle",
        help="Slip angles [deg] for rft3d, -90 to 90 exclusive: a list or start:stop:count.",
    ),
    mesh: str | None = Wheel3DOptions.mesh,
    mesh_units: str = Wheel3DOptions.mesh_units,
    axle: str = Wheel3DOptions.axle,
    center: str | None = Wheel3DOptions.center,
    xi: float | None = Wheel3DOptions.xi,
    cull: bool | None = Wheel3DOptions.cull,
    scheduler: str = typer.Option(
        "serial", "--scheduler", help="serial, local (Dask processes) or a Dask scheduler address."
    ),
    workers: int | None = typer.Option(None, "--workers", help="Local Dask worker processes."),
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    plot: str | None = PLOT,
) -> None:
    """Force-slip and sinkage-slip curves over media x models x loads x slips (x slip angles in 3D)."""
    from ._wheel_sweep import SweepRun, plane_table, spatial_table, stack, sweep_grid

    out_path, plot_path = out_file("--out", out), plot_file("--plot", plot)
    if workers is not None and not 1 <= workers <= 256:
        raise InputError("--workers", workers, "an integer in [1, 256]")
    flags = shape_flags(shape, sizes)
    spatial, plane, factories = _sweep_models(
        model, c1=c1, c2=c2, exit_angle=exit_angle, element_size=element_size
    )
    kin = _kinematics(0.0, slip_definition, None, None)
    grid = sweep_grid(load, slip, slip_angle)
    if not spatial:
        for flag, value, default in (
            ("--mesh", mesh, None), ("--xi", xi, None), ("--center", center, None),
            ("--mesh-units", mesh_units, "m"), ("--axle", axle, "y"), ("--cull", cull, None),
        ):  # fmt: skip
            if value != default:
                raise InputError(flag, value, "only with --model rft3d")
        if grid.angles != [0.0]:
            raise InputError("--slip-angle", slip_angle, "only with --model rft3d")
    material_names = [m.strip() for m in material.split(",") if m.strip()]
    if not material_names:
        raise InputError("--material", material, "one or more media, comma separated")
    media = [materials.get(m) for m in material_names] if plane or xi is None else []
    tables = []
    media_3d_count = len(material_names) if xi is None else 1
    total = len(media) * len(plane) + media_3d_count * len(spatial) * len(grid.angles)
    total *= len(grid.loads) * len(grid.slips)
    with progress(total, "wheel sweep") as advance:
        run = SweepRun(omega, kin.definition, scheduler, workers, advance)
        if plane:
            tables.append(plane_table(wheel_body(shape, width, flags), media, factories, grid, run, phases))
        if spatial:
            culling = mesh is not None if cull is None else cull
            spec = _Wheel3DSpec(mesh, mesh_units, axle, center, culling)
            wheel, phase_count = _wheel_3d(shape, flags, width, spec, phases)
            media_3d = [_medium_3d(m, None) for m in material_names] if xi is None else [_medium_3d("", xi)]
            tables.append(spatial_table(wheel, media_3d, grid, run, phase_count, culling))
    table = stack(tables)
    if plot_path is not None:
        plot_sweep(table.columns, sorted(set(table.columns["material"].tolist()), key=str), plot_path)
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
    model: str = typer.Option("rft", "--model", help=_model_help("dynamics")),
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
    model = model_entry(model, use="dynamics", field="--model").name
    if out_path is not None and out_path.suffix == ".nc":
        _require("xarray", "--out", out, "the fields extra for .nc output (pip install 'terradyn[fields]')")
    body = wheel_body(shape, width, shape_flags(shape, sizes))
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


@dataclass(frozen=True)
class _Wheel3DSpec:
    mesh: str | None
    units: str
    axle: str
    center: str | None
    cull: bool


def _wheel_3d(
    shape: WheelShape, flags: dict[str, Any], width: float, spec: _Wheel3DSpec, phases: int
) -> tuple[Any, int]:
    """The 3D wheel (body frame) of --mesh (placed by --mesh-units/--axle/--center) or a primitive."""
    from ..geometry3d import wheel_cylinder, wheel_grousered

    if spec.mesh is None:
        for flag, value, default in (
            ("--center", spec.center, None), ("--mesh-units", spec.units, "m"), ("--axle", spec.axle, "y"),
        ):  # fmt: skip
            if value != default:
                raise InputError(flag, value, "only with --mesh")
    radius = flags.get("radius")
    if spec.mesh is not None:
        from ..geometry3d.mesh import load_mesh
        from ..geometry3d.wheel import Axle, MeshUnits, wheel_from_mesh

        path = input_file("--mesh", spec.mesh)
        units = spec.units.strip().lower()
        if units not in [u.value for u in MeshUnits]:
            raise InputError("--mesh-units", spec.units, "one of m, cm, mm")
        axle = spec.axle.strip().lower()
        if axle not in [a.value for a in Axle]:
            raise InputError("--axle", spec.axle, "one of x, y, z")
        centre = None if spec.center is None else parse_float_list("--center", spec.center)
        if centre is not None and len(centre) != 3:
            raise InputError("--center", spec.center, "three numbers X,Y,Z [mesh units]")
        assert path is not None
        wheel, fit = wheel_from_mesh(load_mesh(path), units=units, axle=axle, center=centre)
        typer.echo(f"terradyn: {fit.summary(units)}", err=True)
        return wheel, phases
    if shape is WheelShape.circular:
        if radius is None:
            raise InputError("--radius", None, "a radius [m] (or --mesh)")
        return wheel_cylinder(radius, width, circumferential_resolution=360, axial_resolution=2), 1
    if shape is WheelShape.grousered:
        if radius is None:
            raise InputError("--radius", None, "a radius [m] (or --mesh)")
        for flag in ("grouser_count", "grouser_height", "grouser_thickness"):
            if flags.get(flag) is None:
                raise InputError(f"--{flag.replace('_', '-')}", None, "a value (required for grousered)")
        wheel = wheel_grousered(
            radius, width, grouser_count=flags["grouser_count"], grouser_height=flags["grouser_height"],
            grouser_thickness=flags["grouser_thickness"], circumferential_resolution=360,
            axial_resolution=2,
        )  # fmt: skip
        return wheel, phases
    raise InputError("--shape", shape.value, "circular or grousered for rft3d (or --mesh FILE)")


def _medium_3d(material: str, xi: float | None) -> Any:
    """The 3D-RFT medium: --xi, else the material (its density and friction, or its plane RFT scale)."""
    from ..locomotion.steady3d import rft3d_medium

    if xi is not None:
        if not (math.isfinite(xi) and xi > 0.0):
            raise InputError("--xi", xi, "a media scale > 0 [N/m^3]")
        return float(xi)
    mat = materials.get(material)
    medium, note = rft3d_medium(mat)
    if not note:
        raise InputError(
            "--material", material, "a medium with [density] and [friction] (the 3D-RFT scaling) or an "
            "[rft] scale (a TOML from 'terradyn calibrate rft')", "or give the scale itself with --xi",
        )  # fmt: skip
    if not isinstance(medium, Material):
        typer.echo(f"terradyn: {note}", err=True)
    return medium


def _steady_3d(
    wheel: Any,
    medium: Any,
    load: float | None,
    sinkage: float | None,
    kin: _Kinematics,
    slip_angle_deg: float,
    omega: float,
    phase_count: int,
    cull: bool,
) -> dict[str, Any]:
    """``wheel steady --model rft3d``: 3D RFT at a load or a sinkage, with a slip angle."""
    from ..locomotion.steady3d import (
        steady3d_record,
        wheel_at_sinkage_3d,
        wheel_contact_mesh,
        wheel_steady_3d,
    )

    angle = math.radians(slip_angle_deg)
    facets = wheel.facet_count
    if cull:
        wheel = wheel_contact_mesh(wheel, slip_angle=angle)
    options: dict[str, Any] = {
        "slip_angle": angle, "omega": omega, "slip_definition": kin.definition,
        "rim_speed": kin.rim, "carriage_speed": kin.carriage, "phase_count": phase_count,
    }  # fmt: skip
    if sinkage is not None:
        res = wheel_at_sinkage_3d(wheel, medium, sinkage, kin.slip, **options)
    else:
        assert load is not None
        res = wheel_steady_3d(wheel, medium, load, kin.slip, **options)
    rec: dict[str, Any] = dict(steady3d_record(res))
    rec.update(
        {
            "load_N": float(res.load_N),
            "omega_rad_s": float(res.omega_rad_s),
            "forward_velocity_m_s": float(res.longitudinal_velocity_m_s),
            "lateral_velocity_m_s": float(res.lateral_velocity_m_s),
            "slip_definition": kin.definition,
            "facet_count": res.facet_count,
            "model": "rft3d",
        }
    )
    if cull:
        rec["culled_facet_count"] = facets - res.facet_count
    return rec


# one wheel case through several models: its own module, registered here with the wheel flags
app.command("compare")(wheel_flags(_wheel_compare.compare))
