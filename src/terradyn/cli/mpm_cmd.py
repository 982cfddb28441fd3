"""``terradyn mpm``: plane-strain MPM runs (intrusion and wheels)."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np
import typer

from .. import materials
from ..errors import InputError, check_finite
from ._bodies import BodyKind, BodyOptions, build_body
from ._common import OutputFormat, atomic_write_text, emit, save_figure

app = typer.Typer(
    help="Plane-strain MPM continuum solver (Dunatunga-Kamrin granular model).", no_args_is_help=True
)


def register(root: typer.Typer) -> None:
    root.add_typer(app, name="mpm")


class MPMOptions:
    cell_size = typer.Option(None, "--cell-size", help="Grid cell size [m] (default from the body size).")
    ppc = typer.Option(2, "--particles-per-cell", help="Particles per cell along each axis.")
    packing = typer.Option("consolidated", "--packing", help="consolidated or unconsolidated bed.")
    walls = typer.Option(None, "--walls", help="Wall condition: free-slip, no-slip or frictional.")
    checkpoint = typer.Option(None, "--checkpoint", help="Checkpoint file (written atomically).")
    checkpoint_interval = typer.Option(600.0, "--checkpoint-interval", help="Wall-clock seconds.")
    resume = typer.Option(False, "--resume", help="Continue a killed run from --checkpoint.")
    snapshots = typer.Option(None, "--snapshots", help="Folder for particle snapshots (NetCDF).")
    series = typer.Option(None, "--series", help="Time series CSV.")
    fields = typer.Option(
        None, "--fields", help="Plot of particle speed and pressure at the end of the run (PNG/PDF)."
    )
    animate = typer.Option(None, "--animate", help="Animation of particle speed (GIF or MP4).")
    frames = typer.Option(40, "--frames", help="Frames in the --animate animation.")


@contextmanager
def _progress_bar(label: str) -> Iterator[Callable[[float, float], None]]:
    import os
    import sys

    if not sys.stderr.isatty() or os.environ.get("CI"):
        yield lambda t, f: None
        return
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn, TimeRemainingColumn

    with Progress(
        TextColumn(label),
        BarColumn(),
        TextColumn("t = {task.fields[t]:.4f} s"),
        TimeElapsedColumn(),
        TimeRemainingColumn(),
        transient=True,
    ) as bar:
        task = bar.add_task(label, total=1.0, t=0.0)

        def update(t: float, fraction: float) -> None:
            bar.update(task, completed=fraction, t=t)

        yield update


def _write_series(result: Any, path: Path | None) -> None:
    if path is not None:
        atomic_write_text(path, result.to_dataframe().to_csv(index=False))


def _check_field_outputs(plot: Path | None, fields: Path | None, animate: Path | None, frames: int) -> int:
    """Validate the plot options before the run; returns the frame count to keep."""
    from ..plotting.animation import check_animation_path
    from ._common import check_figure_path

    if plot is not None:
        check_figure_path(plot, "--plot")
    if fields is not None:
        check_figure_path(fields, "--fields")
    if animate is None:
        return 0
    check_animation_path(animate, "--animate")
    if not 2 <= frames <= 500:
        raise InputError("--frames", frames, "an integer in [2, 500]")
    return frames


def _field_outputs(result: Any, fields: Path | None, animate: Path | None) -> None:
    from ..plotting.mpm import animate_frames, plot_fields

    final = result.final_frame
    seg = np.asarray(final["segments"])
    pts = seg.reshape(-1, 2)
    reach = 0.5 * float(np.ptp(pts, axis=0).max())
    cx, cz = pts.mean(axis=0)
    window = (cx - 5 * reach, cx + 5 * reach, cz - 4 * reach, cz + 2 * reach)
    if fields is not None:
        fig = plot_fields(
            result.final_particles,
            segments=seg,
            window=window,
            title=f"MPM, t = {float(final['time_s']):.3f} s",
        )
        save_figure(fig, fields, "--fields")
    if animate is not None:
        lo = min(float(np.asarray(f["segments"]).reshape(-1, 2)[:, 0].min()) for f in result.frames)
        hi = max(float(np.asarray(f["segments"]).reshape(-1, 2)[:, 0].max()) for f in result.frames)
        win = (lo - 3 * reach, hi + 3 * reach, window[2], window[3])
        animate_frames(result.frames, animate, window=win)


def _plot_series(result: Any, path: Path, keys: tuple[str, ...]) -> None:
    import matplotlib.pyplot as plt

    df = result.to_dataframe()
    xkey = "depth_m" if "depth_m" in df.columns else "t_s" if "t_s" in df.columns else df.columns[0]
    fig, ax = plt.subplots(figsize=(7, 4))
    for key in keys:
        if key in df.columns:
            ax.plot(df[xkey], df[key], label=key)
    ax.set_xlabel(xkey)
    ax.legend()
    ax.set_title("MPM")
    save_figure(fig, path)


@app.command("intrude")
def intrude(
    body: BodyKind = typer.Argument(..., help="Body shape."),
    depth: float = typer.Option(..., "--depth", help="Depth [m] of the reference point for the report."),
    angle: float = typer.Option(0.0, "--angle", help="Body rotation about +y [deg], clockwise."),
    direction: float = typer.Option(90.0, "--direction", help="Motion direction below +x [deg]."),
    speed: float = typer.Option(0.05, "--speed", help="Intrusion speed [m/s]."),
    material: str = typer.Option("MS", "--material", help="Medium name or TOML file."),
    length: float | None = BodyOptions.length,
    width: float = BodyOptions.width,
    thickness: float | None = BodyOptions.thickness,
    radius: float | None = BodyOptions.radius,
    side: float | None = BodyOptions.side,
    base: float | None = BodyOptions.base,
    height: float | None = BodyOptions.height,
    tip_offset: float | None = BodyOptions.tip_offset,
    grouser_count: int | None = BodyOptions.grouser_count,
    grouser_height: float | None = BodyOptions.grouser_height,
    grouser_thickness: float | None = BodyOptions.grouser_thickness,
    hub_radius: float | None = BodyOptions.hub_radius,
    flap_count: int | None = BodyOptions.flap_count,
    flap_length: float | None = BodyOptions.flap_length,
    flap_angle: float | None = BodyOptions.flap_angle,
    points_file: Path | None = BodyOptions.points_file,
    cell_size: float | None = MPMOptions.cell_size,
    particles_per_cell: int = MPMOptions.ppc,
    packing: str = MPMOptions.packing,
    walls: str | None = MPMOptions.walls,
    checkpoint: Path | None = MPMOptions.checkpoint,
    checkpoint_interval: float = MPMOptions.checkpoint_interval,
    resume: bool = MPMOptions.resume,
    record_spacing: float | None = typer.Option(
        None, "--record-spacing", help="Travel [m] per time-series row (default cell/4)."
    ),
    snapshot_spacing: float | None = typer.Option(
        None, "--snapshot-spacing", help="Travel [m] between --snapshots files (default 4 cells)."
    ),
    snapshots: Path | None = MPMOptions.snapshots,
    series: Path | None = MPMOptions.series,
    fields: Path | None = MPMOptions.fields,
    animate: Path | None = MPMOptions.animate,
    frames: int = MPMOptions.frames,
    fmt: OutputFormat = typer.Option(OutputFormat.table, "--format", help="Output format."),
    out: Path | None = typer.Option(None, "--out", help="Also write the summary to this file."),
    plot: Path | None = typer.Option(None, "--plot", help="Force history plot (PNG/PDF)."),
) -> None:
    """Push BODY into a settled bed with MPM; force and torque as its reference point passes --depth."""
    from ..mpm import run_intrusion

    shape = build_body(
        body,
        width,
        length=length,
        thickness=thickness,
        radius=radius,
        side=side,
        base=base,
        height=height,
        tip_offset=tip_offset,
        grouser_count=grouser_count,
        grouser_height=grouser_height,
        grouser_thickness=grouser_thickness,
        hub_radius=hub_radius,
        flap_count=flap_count,
        flap_length=flap_length,
        flap_angle=flap_angle,
        points_file=points_file,
    )
    if resume and checkpoint is None:
        raise InputError("--resume", True, "together with --checkpoint FILE")
    frame_count = _check_field_outputs(plot, fields, animate, frames)
    with _progress_bar("MPM intrusion") as bar:
        res = run_intrusion(
            shape,
            materials.get(material),
            depth=depth,
            direction=math.radians(check_finite("--direction", direction)),
            angle=math.radians(check_finite("--angle", angle)),
            speed=speed,
            cell_size=cell_size,
            particles_per_cell=particles_per_cell,
            packing=packing,
            walls=walls,
            checkpoint_path=checkpoint,
            checkpoint_interval=checkpoint_interval,
            resume=resume,
            record_spacing=record_spacing,
            snapshot_spacing=snapshot_spacing,
            snapshot_dir=snapshots,
            progress=bar,
            frame_count=frame_count,
        )
    _write_series(res, series)
    _field_outputs(res, fields, animate)
    if plot is not None:
        _plot_series(res, plot, ("force_x_N", "force_z_N"))
    emit({k: res.summary[k] for k in ("force_x_N", "force_z_N", "torque_y_Nm")}, fmt, out)


@app.command("wheel")
def wheel(
    material: str = typer.Option("MS", "--material", help="Medium name or TOML file."),
    load: float = typer.Option(..., "--load", help="Vertical load [N]."),
    omega: float | None = typer.Option(None, "--omega", help="Spin rate [rad/s] (or --drive-torque)."),
    slip: float | None = typer.Option(None, "--slip", help="Imposed slip; omit for self-propelled."),
    drive_torque: float | None = typer.Option(
        None, "--drive-torque", help="Drive torque [N m] instead of --omega: the spin is free."
    ),
    max_omega: float = typer.Option(5.0, "--max-omega", help="Largest spin [rad/s] with --drive-torque."),
    drawbar_load: float = typer.Option(
        0.0, "--drawbar-load", help="Horizontal load on the axle [N] (+ backwards) when x is free."
    ),
    duration: float | None = typer.Option(None, "--duration", help="Driving time [s]."),
    radius: float | None = typer.Option(0.13, "--radius", help="Radius [m] (rim for grousered)."),
    width: float = typer.Option(0.16, "--width", help="Wheel width [m]."),
    shape: str = typer.Option("circular", "--shape", help="circular, grousered or flapped."),
    grouser_count: int | None = BodyOptions.grouser_count,
    grouser_height: float | None = BodyOptions.grouser_height,
    grouser_thickness: float | None = BodyOptions.grouser_thickness,
    hub_radius: float | None = BodyOptions.hub_radius,
    flap_count: int | None = BodyOptions.flap_count,
    flap_length: float | None = BodyOptions.flap_length,
    flap_angle: float | None = BodyOptions.flap_angle,
    thickness: float | None = BodyOptions.thickness,
    cell_size: float | None = MPMOptions.cell_size,
    particles_per_cell: int = MPMOptions.ppc,
    packing: str = MPMOptions.packing,
    walls: str | None = MPMOptions.walls,
    checkpoint: Path | None = MPMOptions.checkpoint,
    checkpoint_interval: float = MPMOptions.checkpoint_interval,
    resume: bool = MPMOptions.resume,
    record_interval: float | None = typer.Option(
        None, "--record-interval", help="Simulated seconds per time-series row (default duration/200)."
    ),
    snapshot_interval: float | None = typer.Option(
        None, "--snapshot-interval", help="Simulated seconds between --snapshots files (default duration/20)."
    ),
    snapshots: Path | None = MPMOptions.snapshots,
    series: Path | None = MPMOptions.series,
    fields: Path | None = MPMOptions.fields,
    animate: Path | None = MPMOptions.animate,
    frames: int = MPMOptions.frames,
    fmt: OutputFormat = typer.Option(OutputFormat.table, "--format", help="Output format."),
    out: Path | None = typer.Option(None, "--out", help="Also write the summary to this file."),
    plot: Path | None = typer.Option(None, "--plot", help="Force history plot (PNG/PDF)."),
) -> None:
    """Wheel on a settled MPM bed: forced slip (--slip), self-propelled at --omega (optionally towing
    --drawbar-load), or torque-driven (--drive-torque); sinkage, pull, torque and slip."""
    from ..mpm import run_wheel
    from .wheel_cmd import WheelShape, _shape_flags, wheel_body

    try:
        kind = WheelShape(shape)
    except ValueError:
        raise InputError("--shape", shape, "circular, grousered or flapped") from None
    body = wheel_body(
        kind,
        width,
        _shape_flags(
            kind,
            {
                "radius": radius,
                "thickness": thickness,
                "grouser_count": grouser_count,
                "grouser_height": grouser_height,
                "grouser_thickness": grouser_thickness,
                "hub_radius": hub_radius,
                "flap_count": flap_count,
                "flap_length": flap_length,
                "flap_angle": flap_angle,
                "points_file": None,
            },
        ),
    )
    if resume and checkpoint is None:
        raise InputError("--resume", True, "together with --checkpoint FILE")
    frame_count = _check_field_outputs(plot, fields, animate, frames)
    with _progress_bar("MPM wheel") as bar:
        res = run_wheel(
            body,
            materials.get(material),
            load=load,
            omega=omega,
            slip=slip,
            drive_torque=drive_torque,
            max_omega=max_omega,
            drawbar_load=drawbar_load,
            duration=duration,
            cell_size=cell_size,
            particles_per_cell=particles_per_cell,
            packing=packing,
            walls=walls,
            checkpoint_path=checkpoint,
            checkpoint_interval=checkpoint_interval,
            resume=resume,
            record_interval=record_interval,
            snapshot_interval=snapshot_interval,
            snapshot_dir=snapshots,
            progress=bar,
            frame_count=frame_count,
        )
    _write_series(res, series)
    _field_outputs(res, fields, animate)
    if plot is not None:
        _plot_series(res, plot, ("drawbar_pull_N", "force_z_N", "sinkage_m"))
    keys = (
        "sinkage_m",
        "drawbar_pull_N",
        "drive_torque_Nm",
        "force_x_N",
        "force_z_N",
        "torque_y_Nm",
        "slip",
        "omega_rad_s",
        "forward_speed_m_s",
    )
    emit({k: res.summary[k] for k in keys if k in res.summary}, fmt, out)
