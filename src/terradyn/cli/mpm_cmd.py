"""``terradyn mpm``: plane-strain MPM runs (intrusion, drag and wheels)."""

from __future__ import annotations

import math
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np
import typer

from .. import materials
from ..errors import InputError, check_finite
from ..mpm.specs import Bed, Drive, Outputs, Resolution
from ._bodies import BODY_SIZE_FLAGS, BodyKind, BodyOptions, build_body
from ._common import OutputFormat, atomic_write_text, emit, fraction_progress, save_figure
from .mpm_options import MPMOptions
from .mpm_verify_cmd import verify_app
from .options import (
    ANGLE,
    ANIMATE,
    DIRECTION,
    FORMAT,
    MATERIAL,
    OUT,
    WHEEL_WIDTH,
    animation_file,
    out_file,
    out_folder,
    plot_file,
    with_flags,
)

app = typer.Typer(
    help="Plane-strain MPM continuum solver (Dunatunga-Kamrin granular model).",
    no_args_is_help=True,
    rich_markup_mode=None,
)
app.add_typer(verify_app, name="verify")


def _dilatancy(value: float) -> float | None:
    """The model override of --dilatancy: K in [0, MAX_DILATANCY], None when off."""
    from ..mpm.model import MAX_DILATANCY

    value = check_finite("--dilatancy", value)
    if not 0.0 <= value <= MAX_DILATANCY:
        raise InputError("--dilatancy", value, f"a number in [0, {MAX_DILATANCY:g}] [-] (0 = off)")
    return value or None


def _resolution(
    cell_size: float | None, particles_per_cell: int, contact: str, volumetric: str, flip: float
) -> Resolution:
    """The resolution spec of --cell-size, --particles-per-cell, --contact, --volumetric and --flip."""
    return Resolution(
        cell_size=cell_size,
        particles_per_cell=particles_per_cell,
        contact=contact,
        volumetric=volumetric,
        flip=flip,
    )


def _surface_friction(value: float | None) -> float | None:
    """The model override of --surface-friction (None: the medium's)."""
    return None if value is None else check_finite("--surface-friction", value)


def _write_series(result: Any, path: Path | None) -> None:
    if path is not None:
        atomic_write_text(path, result.to_dataframe().to_csv(index=False), field_name="--series")


class _Outputs:
    """Every MPM output path, checked before the run."""

    def __init__(self, *, out: str | None, plot: str | None, series: str | None, fields: str | None,
                 animate: str | None, frames: int, snapshots: str | None, checkpoint: str | None,
                 resume: bool) -> None:  # fmt: skip
        self.out = out_file("--out", out)
        self.plot = plot_file("--plot", plot)
        self.series = out_file("--series", series, (".csv",))
        self.fields = plot_file("--fields", fields)
        self.animate = animation_file("--animate", animate)
        self.snapshots = out_folder("--snapshots", snapshots)
        if self.snapshots is not None:
            import importlib.util

            if importlib.util.find_spec("xarray") is None:
                raise InputError(
                    "--snapshots", snapshots, "the fields extra (pip install 'terradyn[fields]')"
                )
        self.checkpoint = out_file("--checkpoint", checkpoint, (".npz",), "checkpoint file")
        if resume and self.checkpoint is None:
            raise InputError("--resume", True, "together with --checkpoint FILE")
        if resume and self.checkpoint is not None and not self.checkpoint.is_file():
            raise InputError("--checkpoint", checkpoint, "an existing checkpoint file with --resume",
                             "no such file: run without --resume to start")  # fmt: skip
        if not resume and self.checkpoint is not None and self.checkpoint.exists():
            raise InputError("--checkpoint", checkpoint, "a new file, or --resume to continue the run in it",
                             "remove the file to start afresh")  # fmt: skip
        self.frames = 0
        if self.animate is not None:
            if not 2 <= frames <= 500:
                raise InputError("--frames", frames, "an integer in [2, 500]")
            self.frames = frames

    def spec(self, checkpoint_interval: float, resume: bool, progress: Any, **intervals: Any) -> Outputs:
        """The library's :class:`~terradyn.mpm.Outputs` for these paths."""
        return Outputs(
            snapshot_dir=self.snapshots,
            checkpoint_path=self.checkpoint,
            checkpoint_interval=checkpoint_interval,
            resume=resume,
            progress=progress,
            frame_count=self.frames,
            **intervals,
        )


@contextmanager
def _interruptible(outputs: _Outputs) -> Iterator[None]:
    """Turn an interrupt into one line saying where the run stopped and how to continue it.

    Snapshots are written as the run goes. With --checkpoint they belong to a resumable run and stay
    when it stops; without one, a run that fails or is interrupted removes the snapshots it wrote (and
    the folder if it made it): no partial output."""
    folder = outputs.snapshots
    existed = folder is not None and folder.exists()
    before = set(folder.iterdir()) if folder is not None and existed else set()
    try:
        yield
    except BaseException as exc:
        if folder is not None and outputs.checkpoint is None:
            _remove_new_snapshots(folder, before, existed)
        if not isinstance(exc, KeyboardInterrupt):
            raise
        _explain_interrupt(exc, outputs)
        raise


def _remove_new_snapshots(folder: Path, before: set[Path], existed: bool) -> None:
    if not folder.exists():
        return
    for p in set(folder.iterdir()) - before:
        if p.is_file():
            p.unlink(missing_ok=True)
    if not existed and not any(folder.iterdir()):
        folder.rmdir()


def _explain_interrupt(exc: KeyboardInterrupt, outputs: _Outputs) -> None:
    """Attach the one-line explanation the CLI prints for an interrupted run."""
    t = getattr(exc, "time_s", None)
    at = f" at t = {t:.4g} s" if isinstance(t, float) else ""
    saved = getattr(exc, "checkpoint_path", None)
    if saved is None and outputs.checkpoint is not None and outputs.checkpoint.exists():
        saved = outputs.checkpoint
    failure = " ".join(str(getattr(exc, "failure", "") or "").split())
    if saved is not None and not failure:
        message = f"run stopped{at}; checkpoint written to {saved}: rerun the same command with --resume"
    elif saved is not None:
        message = f"run stopped{at}; the checkpoint could not be written ({failure})"
    else:
        message = f"run stopped{at}; nothing saved (give --checkpoint FILE to keep the work of a run)"
    exc.message = message  # type: ignore[attr-defined]


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
        with fraction_progress("rendering the animation", "frames") as update:
            animate_frames(
                result.frames, animate, window=win, progress=lambda i, n: update(i + 1, (i + 1) / n)
            )


def _plot_series(result: Any, path: Path, kind: str) -> None:
    from ..plotting.mpm import plot_mpm_history

    save_figure(plot_mpm_history(result, kind=kind), path)


@app.command("intrude")
@with_flags("sizes", BODY_SIZE_FLAGS)
def intrude(
    body: BodyKind = typer.Argument(..., help="Body shape."),
    depth: float = typer.Option(..., "--depth", help="Depth [m] of the reference point for the report."),
    angle: float = ANGLE,
    direction: float = DIRECTION,
    speed: float = typer.Option(0.05, "--speed", help="Intrusion speed [m/s]."),
    material: str = MATERIAL,
    width: float = BodyOptions.width,
    sizes: dict[str, Any] = {},  # the body size flags (BODY_SIZE_FLAGS)  # noqa: B006
    cell_size: float | None = MPMOptions.cell_size,
    particles_per_cell: int = MPMOptions.ppc,
    volumetric: str = MPMOptions.volumetric,
    flip: float = MPMOptions.flip,
    packing: str = MPMOptions.packing,
    walls: str | None = MPMOptions.walls,
    contact: str = MPMOptions.contact,
    dilatancy: float = MPMOptions.dilatancy,
    surface_friction: float | None = MPMOptions.surface_friction,
    checkpoint: str | None = MPMOptions.checkpoint,
    checkpoint_interval: float = MPMOptions.checkpoint_interval,
    resume: bool = MPMOptions.resume,
    record_interval: float | None = MPMOptions.record_interval,
    snapshot_interval: float | None = MPMOptions.snapshot_interval,
    snapshots: str | None = MPMOptions.snapshots,
    series: str | None = MPMOptions.series,
    fields: str | None = MPMOptions.fields,
    animate: str | None = ANIMATE,
    frames: int = MPMOptions.frames,
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    plot: str | None = MPMOptions.plot,
) -> None:
    """Push BODY into a settled bed with MPM; force and torque as its reference point passes --depth."""
    from ..mpm import run_intrusion

    shape = build_body(body, width, **sizes)
    outs = _Outputs(out=out, plot=plot, series=series, fields=fields, animate=animate, frames=frames,
                    snapshots=snapshots, checkpoint=checkpoint, resume=resume)  # fmt: skip
    speed = check_finite("--speed", speed)
    if not speed > 0:
        raise InputError("--speed", speed, "a speed > 0 [m/s]")
    bed = Bed(packing=packing, walls=walls)
    resolution = _resolution(cell_size, particles_per_cell, contact, volumetric, flip)
    intervals = _intervals(record_interval, snapshot_interval)
    with _interruptible(outs), fraction_progress("MPM intrusion", "s") as bar:
        res = run_intrusion(
            shape,
            materials.get(material),
            depth=depth,
            direction=math.radians(check_finite("--direction", direction)),
            angle=math.radians(check_finite("--angle", angle)),
            speed=speed,
            bed=bed,
            resolution=resolution,
            outputs=outs.spec(checkpoint_interval, resume, bar, **intervals),
            dilatancy=_dilatancy(dilatancy),
            surface_friction=_surface_friction(surface_friction),
        )
    _write_series(res, outs.series)
    _field_outputs(res, outs.fields, outs.animate)
    if outs.plot is not None:
        _plot_series(res, outs.plot, "intrusion")
    emit({k: res.summary[k] for k in ("force_x_N", "force_z_N", "torque_y_Nm")}, fmt, outs.out)


#: the longest output interval accepted [s] of simulated time (MPM runs are seconds long)
MAX_INTERVAL_S = 1000.0


def _interval(flag: str, interval: float | None, duration: float | None = None) -> float | None:
    """A simulated-time interval [s] in (0, duration] (or (0, 1000 s] without a duration)."""
    if interval is None:
        return None
    interval = check_finite(flag, interval)
    top = MAX_INTERVAL_S if duration is None or not duration > 0 else duration
    if not 0 < interval <= top:
        raise InputError(flag, interval, f"a time in (0, {top:g}] [s]")
    return interval


def _intervals(
    record_interval: float | None, snapshot_interval: float | None, duration: float | None = None
) -> dict[str, float | None]:
    """--record-interval and --snapshot-interval checked (:func:`_interval`), as Outputs keywords."""
    return {
        "record_interval": _interval("--record-interval", record_interval, duration),
        "snapshot_interval": _interval("--snapshot-interval", snapshot_interval, duration),
    }


@app.command("drag")
@with_flags("sizes", BODY_SIZE_FLAGS)
def drag(
    body: BodyKind = typer.Argument(..., help="Body shape."),
    depth: float = typer.Option(..., "--depth", help="Depth [m] of the body's reference point."),
    distance: float = typer.Option(..., "--distance", help="Horizontal travel [m]."),
    speed: float = typer.Option(
        0.05, "--speed", help="Horizontal velocity [m/s]: + drags along +x, - along -x."
    ),
    angle: float = ANGLE,
    averaging_window: float | None = typer.Option(
        None, "--averaging-window", help="Travel [m] at the end averaged in the summary (default: half)."
    ),
    window: float | None = typer.Option(
        None,
        "--window",
        help="Length [m] of the moving window of grains stepped around the body; 0 = the whole bed "
        "(default: the body and its clearance ahead on either side).",
    ),
    material: str = MATERIAL,
    width: float = BodyOptions.width,
    sizes: dict[str, Any] = {},  # the body size flags (BODY_SIZE_FLAGS)  # noqa: B006
    cell_size: float | None = MPMOptions.cell_size,
    particles_per_cell: int = MPMOptions.ppc,
    volumetric: str = MPMOptions.volumetric,
    flip: float = MPMOptions.flip,
    packing: str = MPMOptions.packing,
    walls: str | None = MPMOptions.walls,
    contact: str = MPMOptions.contact,
    dilatancy: float = MPMOptions.dilatancy,
    surface_friction: float | None = MPMOptions.surface_friction,
    checkpoint: str | None = MPMOptions.checkpoint,
    checkpoint_interval: float = MPMOptions.checkpoint_interval,
    resume: bool = MPMOptions.resume,
    record_interval: float | None = MPMOptions.record_interval,
    snapshot_interval: float | None = MPMOptions.snapshot_interval,
    snapshots: str | None = MPMOptions.snapshots,
    series: str | None = MPMOptions.series,
    fields: str | None = MPMOptions.fields,
    animate: str | None = ANIMATE,
    frames: int = MPMOptions.frames,
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
) -> None:
    """Drag BODY, buried at --depth, horizontally through a settled bed with MPM; drag and lift.

    Grains inside the body are removed before the bed settles around it (terradyn.mpm.run_drag)."""
    from ..mpm.drag import run_drag
    from ..mpm.specs import Stroke

    shape = build_body(body, width, **sizes)
    outs = _Outputs(out=out, plot=None, series=series, fields=fields, animate=animate, frames=frames,
                    snapshots=snapshots, checkpoint=checkpoint, resume=resume)  # fmt: skip
    intervals = _intervals(record_interval, snapshot_interval)
    with _interruptible(outs), fraction_progress("MPM drag", "s") as bar:
        res = run_drag(
            shape,
            materials.get(material),
            depth=depth,
            distance=distance,
            speed=check_finite("--speed", speed),
            angle=math.radians(check_finite("--angle", angle)),
            bed=Bed(packing=packing, walls=walls, window=window),
            resolution=_resolution(cell_size, particles_per_cell, contact, volumetric, flip),
            outputs=outs.spec(checkpoint_interval, resume, bar, **intervals),
            stroke=Stroke(averaging_window=averaging_window),
            dilatancy=_dilatancy(dilatancy),
            surface_friction=_surface_friction(surface_friction),
        )
    _write_series(res, outs.series)
    _field_outputs(res, outs.fields, outs.animate)
    keys = ("drag_N", "lift_N", "drag_std_N", "force_x_N", "force_z_N", "torque_y_Nm")
    emit({k: res.summary[k] for k in keys}, fmt, outs.out)


def _mpm_wheel(shape: str, width: float, sizes: dict[str, Any]) -> Any:
    """The wheel of an MPM command from --shape (circular, grousered or flapped) and its size flags."""
    from .wheel_options import WheelShape, shape_flags, wheel_body

    allowed = (WheelShape.circular, WheelShape.grousered, WheelShape.flapped)
    kind = next((k for k in allowed if k.value == shape), None)
    if kind is None:
        raise InputError("--shape", shape, "circular, grousered or flapped")
    return wheel_body(kind, width, shape_flags(kind, {**sizes, "points_file": None}))


def _mpm_wheel_flags() -> Any:
    from .wheel_options import WHEEL_SIZE_FLAGS

    return with_flags("sizes", {k: v for k, v in WHEEL_SIZE_FLAGS.items() if k != "points_file"})


#: the wheel bed's size flags of `mpm wheel` and `mpm converge wheel`
BED_LENGTH = typer.Option(
    None,
    "--bed-length",
    help="Length [m] of the bed along the drive (default: the wheel's travel, its margins and room "
    "ahead for the heap it pushes).",
)
BED_DEPTH = typer.Option(
    None,
    "--bed-depth",
    help="Depth [m] of the bed's grains (default: two wheel reaches and the bed margin).",
)


@app.command("wheel")
@_mpm_wheel_flags()
def wheel(
    material: str = MATERIAL,
    load: float = typer.Option(..., "--load", help="Vertical load W [N]."),
    omega: float | None = typer.Option(None, "--omega", help="Spin rate [rad/s] (or --drive-torque)."),
    slip: float | None = typer.Option(None, "--slip", help="Imposed slip; omit for self-propelled."),
    forward_speed: float | None = typer.Option(
        None,
        "--forward-speed",
        help="Imposed forward speed [m/s] instead of --slip (towed); with --omega 0 a locked wheel dragged.",
    ),
    drive_torque: float | None = typer.Option(
        None, "--drive-torque", help="Drive torque [N m] instead of --omega: the spin is free."
    ),
    max_omega: float = typer.Option(5.0, "--max-omega", help="Largest spin [rad/s] with --drive-torque."),
    drawbar_load: float = typer.Option(
        0.0, "--drawbar-load", help="Horizontal load on the axle [N] (+ backwards) when x is free."
    ),
    duration: float | None = typer.Option(None, "--duration", help="Driving time [s]."),
    spin_up: float = typer.Option(
        0.0,
        "--spin-up",
        help="Time [s] over which --omega (and a forced-slip forward speed) ramps up linearly from "
        "rest at the start of the drive; 0 = impulsive start.",
    ),
    initial_speed: float = typer.Option(
        0.0,
        "--initial-speed",
        help="Forward velocity [m/s] of a self-propelled wheel when the drive starts (default from rest).",
    ),
    window: float | None = typer.Option(
        None,
        "--window",
        help="Length [m] of the moving window of grains stepped around the wheel; 0 = the whole bed "
        "(default: the wheel and its bed margin on either side; it grows ahead of the heap the wheel "
        "pushes).",
    ),
    bed_length: float | None = BED_LENGTH,
    bed_depth: float | None = BED_DEPTH,
    width: float = WHEEL_WIDTH,
    shape: str = typer.Option("circular", "--shape", help="Wheel shape: circular, grousered or flapped."),
    sizes: dict[str, Any] = {},  # the wheel size flags (MPM_WHEEL_SIZE_FLAGS)  # noqa: B006
    cell_size: float | None = MPMOptions.cell_size,
    particles_per_cell: int = MPMOptions.ppc,
    volumetric: str = MPMOptions.volumetric,
    flip: float = MPMOptions.flip,
    packing: str = MPMOptions.packing,
    walls: str | None = MPMOptions.walls,
    contact: str = MPMOptions.contact,
    dilatancy: float = MPMOptions.dilatancy,
    surface_friction: float | None = MPMOptions.surface_friction,
    checkpoint: str | None = MPMOptions.checkpoint,
    checkpoint_interval: float = MPMOptions.checkpoint_interval,
    resume: bool = MPMOptions.resume,
    record_interval: float | None = typer.Option(
        None, "--record-interval", help="Simulated time [s] per time-series row (default duration/200)."
    ),
    snapshot_interval: float | None = typer.Option(
        None,
        "--snapshot-interval",
        help="Simulated time [s] between --snapshots files (default duration/20).",
    ),
    snapshots: str | None = MPMOptions.snapshots,
    series: str | None = MPMOptions.series,
    fields: str | None = MPMOptions.fields,
    animate: str | None = ANIMATE,
    frames: int = MPMOptions.frames,
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    plot: str | None = MPMOptions.plot,
) -> None:
    """Wheel on a settled MPM bed: forced slip (--slip), towed at --forward-speed, self-propelled at
    --omega (optionally towing --drawbar-load), or torque-driven (--drive-torque); sinkage, pull,
    torque and slip."""
    from ..mpm import run_wheel

    body = _mpm_wheel(shape, width, sizes)
    outs = _Outputs(out=out, plot=plot, series=series, fields=fields, animate=animate, frames=frames,
                    snapshots=snapshots, checkpoint=checkpoint, resume=resume)  # fmt: skip
    intervals = _intervals(record_interval, snapshot_interval, duration)
    with _interruptible(outs), fraction_progress("MPM wheel", "s") as bar:
        res = run_wheel(
            body, materials.get(material), load=load, omega=omega, slip=slip, forward_speed=forward_speed,
            drive_torque=drive_torque, max_omega=max_omega, drawbar_load=drawbar_load,
            bed=Bed(packing=packing, walls=walls, window=window, width=bed_length, depth=bed_depth),
            resolution=_resolution(cell_size, particles_per_cell, contact, volumetric, flip),
            outputs=outs.spec(checkpoint_interval, resume, bar, **intervals),
            drive=Drive(duration=duration, spin_up=spin_up, initial_speed=initial_speed),
            dilatancy=_dilatancy(dilatancy), surface_friction=_surface_friction(surface_friction),
        )  # fmt: skip
    _report_wheel(res, outs, fmt)


def _report_wheel(res: Any, outs: _Outputs, fmt: OutputFormat) -> None:
    """The outputs of a wheel run: series, fields, plot, the summary record and the bed warnings."""
    _write_series(res, outs.series)
    _field_outputs(res, outs.fields, outs.animate)
    if outs.plot is not None:
        _plot_series(res, outs.plot, "wheel")
    emit(wheel_record(res.summary), fmt, outs.out)
    _warn_bed_outgrown(res.metadata)


def _warn_bed_outgrown(metadata: dict[str, Any]) -> None:
    """One line on stderr for each way the wheel outgrew its bed (:func:`~terradyn.mpm.wheel_runs.bed_limits`:
    a heap held by the bed's end, which moved a wheel's pull by 11 % of its load, or a wheel that sank
    closer to the floor than the depth rule was checked for), naming the flag to enlarge. The result
    is still written."""
    from ..mpm.wheel_runs import bed_limits

    for text, size, present in bed_limits(metadata):
        sys.stderr.write(f"terradyn: warning: {text}; rerun with a --bed-{size} above {present:.3g} m\n")


#: the wheel quantities every wheel command reports, under the same keys (SI, unit-suffixed)
WHEEL_KEYS = (
    "sinkage_m",
    "drawbar_pull_N",
    "drive_torque_Nm",
    "vertical_force_N",
    "slip",
    "load_N",
    "omega_rad_s",
    "forward_velocity_m_s",
    "drawbar_load_N",
    "applied_torque_Nm",
)


def wheel_record(summary: dict[str, Any]) -> dict[str, Any]:
    """An MPM wheel summary under the wheel keys shared by every wheel command."""
    rec = dict(summary)
    if "force_z_N" in rec:
        rec["vertical_force_N"] = rec.pop("force_z_N")
    return {k: rec[k] for k in WHEEL_KEYS if k in rec}


converge_app = typer.Typer(
    help="One MPM case at three or more cell sizes: observed order, Richardson estimate, error band.",
    no_args_is_help=True,
    rich_markup_mode=None,
)
app.add_typer(converge_app, name="converge")

CELL_SIZES = typer.Option(
    ..., "--cell-sizes", help="Three or more cell sizes [m]: a comma list or start:stop:count."
)
GRID_PHASES = typer.Option(
    1,
    "--grid-phases",
    help="Run each cell size N times with the grid moved by k/N of a cell against the surface (N "
    "divides --particles-per-cell) and use the mean; each phase's spread is reported.",
)


def _cell_sizes(text: str) -> list[float]:
    from ._common import parse_float_list

    sizes = parse_float_list("--cell-sizes", text)
    if len(set(sizes)) < 3 or min(sizes) <= 0:
        raise InputError("--cell-sizes", text, "three or more distinct cell sizes > 0 [m]")
    return sizes


def _emit_convergence(res: Any, fmt: OutputFormat, out: Path | None, plot: Path | None, title: str) -> None:
    if plot is not None:
        from ..plotting.studies import plot_convergence

        save_figure(plot_convergence(res), plot)
    if fmt is OutputFormat.json:
        emit({"runs": res.runs(), "estimates": res.summary()}, fmt, out)
        return
    emit(res.runs(), fmt, None, title=f"{title}: runs")
    emit(res.summary(), fmt, out, title=f"{title}: Richardson estimates")


@converge_app.command("intrude")
@with_flags("sizes", BODY_SIZE_FLAGS)
def converge_intrude(
    body: BodyKind = typer.Argument(..., help="Body shape."),
    depth: float = typer.Option(..., "--depth", help="Depth [m] of the reference point for the report."),
    cell_sizes: str = CELL_SIZES,
    angle: float = ANGLE,
    direction: float = DIRECTION,
    speed: float = typer.Option(0.05, "--speed", help="Intrusion speed [m/s]."),
    material: str = MATERIAL,
    width: float = BodyOptions.width,
    sizes: dict[str, Any] = {},  # the body size flags (BODY_SIZE_FLAGS)  # noqa: B006
    particles_per_cell: int = MPMOptions.ppc,
    volumetric: str = MPMOptions.volumetric,
    flip: float = MPMOptions.flip,
    packing: str = MPMOptions.packing,
    walls: str | None = MPMOptions.walls,
    grid_phases: int = GRID_PHASES,
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    plot: str | None = typer.Option(None, "--plot", help="Force against cell size (.png/.pdf/.svg/.jpg)."),
) -> None:
    """Force and torque of an MPM intrusion at several cell sizes, with their converged estimates."""
    from ..studies.convergence import converge_intrusion

    out_path, plot_path = out_file("--out", out), plot_file("--plot", plot)
    cells = _cell_sizes(cell_sizes)
    shape = build_body(body, width, **sizes)
    mat = materials.get(material)
    with fraction_progress("MPM convergence", "runs") as bar:
        res = converge_intrusion(
            shape,
            mat,
            cell_sizes=cells,
            quantities=("force_z_N", "force_x_N", "torque_y_Nm"),
            progress=lambda done, total: bar(done, done / total),
            depth=depth,
            direction=math.radians(check_finite("--direction", direction)),
            angle=math.radians(check_finite("--angle", angle)),
            speed=speed,
            bed=Bed(packing=packing, walls=walls),
            resolution=Resolution(particles_per_cell=particles_per_cell, volumetric=volumetric, flip=flip),
            grid_phases=grid_phases,
        )
    _emit_convergence(res, fmt, out_path, plot_path, f"MPM {body.value} intrusion")


@converge_app.command("drag")
@with_flags("sizes", BODY_SIZE_FLAGS)
def converge_drag_cmd(
    body: BodyKind = typer.Argument(..., help="Body shape."),
    depth: float = typer.Option(..., "--depth", help="Depth [m] of the body's reference point."),
    distance: float = typer.Option(..., "--distance", help="Horizontal travel [m]."),
    cell_sizes: str = CELL_SIZES,
    speed: float = typer.Option(
        0.05, "--speed", help="Horizontal velocity [m/s]: + drags along +x, - along -x."
    ),
    angle: float = ANGLE,
    material: str = MATERIAL,
    width: float = BodyOptions.width,
    sizes: dict[str, Any] = {},  # the body size flags (BODY_SIZE_FLAGS)  # noqa: B006
    particles_per_cell: int = MPMOptions.ppc,
    volumetric: str = MPMOptions.volumetric,
    flip: float = MPMOptions.flip,
    packing: str = MPMOptions.packing,
    walls: str | None = MPMOptions.walls,
    surface_friction: float | None = MPMOptions.surface_friction,
    grid_phases: int = GRID_PHASES,
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    plot: str | None = typer.Option(None, "--plot", help="Results against cell size (.png/.pdf/.svg/.jpg)."),
) -> None:
    """Drag and lift of a buried body dragged through an MPM bed at several cell sizes, with their
    converged estimates."""
    from ..studies.convergence import converge_drag

    out_path, plot_path = out_file("--out", out), plot_file("--plot", plot)
    cells = _cell_sizes(cell_sizes)
    shape = build_body(body, width, **sizes)
    with fraction_progress("MPM convergence", "runs") as bar:
        res = converge_drag(
            shape,
            materials.get(material),
            cell_sizes=cells,
            progress=lambda done, total: bar(done, done / total),
            depth=depth,
            distance=distance,
            speed=check_finite("--speed", speed),
            angle=math.radians(check_finite("--angle", angle)),
            bed=Bed(packing=packing, walls=walls),
            resolution=Resolution(particles_per_cell=particles_per_cell, volumetric=volumetric, flip=flip),
            grid_phases=grid_phases,
            surface_friction=_surface_friction(surface_friction),
        )
    _emit_convergence(res, fmt, out_path, plot_path, f"MPM {body.value} drag")


@converge_app.command("wheel")
@_mpm_wheel_flags()
def converge_wheel_cmd(
    load: float = typer.Option(..., "--load", help="Vertical load W [N]."),
    cell_sizes: str = CELL_SIZES,
    omega: float | None = typer.Option(None, "--omega", help="Spin rate [rad/s]."),
    slip: float | None = typer.Option(None, "--slip", help="Imposed slip; omit for self-propelled."),
    duration: float | None = typer.Option(None, "--duration", help="Driving time [s]."),
    spin_up: float = typer.Option(
        0.0, "--spin-up", help="Time [s] over which --omega ramps up linearly from rest; 0 = impulsive."
    ),
    material: str = MATERIAL,
    width: float = WHEEL_WIDTH,
    shape: str = typer.Option("circular", "--shape", help="Wheel shape: circular, grousered or flapped."),
    sizes: dict[str, Any] = {},  # the wheel size flags (MPM_WHEEL_SIZE_FLAGS)  # noqa: B006
    particles_per_cell: int = MPMOptions.ppc,
    volumetric: str = MPMOptions.volumetric,
    flip: float = MPMOptions.flip,
    packing: str = MPMOptions.packing,
    bed_length: float | None = BED_LENGTH,
    bed_depth: float | None = BED_DEPTH,
    grid_phases: int = GRID_PHASES,
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    plot: str | None = typer.Option(None, "--plot", help="Results against cell size (.png/.pdf/.svg/.jpg)."),
) -> None:
    """Sinkage, drawbar pull and torque of an MPM wheel at several cell sizes, with converged estimates."""
    from ..studies.convergence import converge_wheel

    out_path, plot_path = out_file("--out", out), plot_file("--plot", plot)
    cells = _cell_sizes(cell_sizes)
    body = _mpm_wheel(shape, width, sizes)
    with fraction_progress("MPM convergence", "runs") as bar:
        res = converge_wheel(
            body,
            materials.get(material),
            cell_sizes=cells,
            progress=lambda done, total: bar(done, done / total),
            load=load,
            omega=omega,
            slip=slip,
            bed=Bed(packing=packing, width=bed_length, depth=bed_depth),
            resolution=Resolution(particles_per_cell=particles_per_cell, volumetric=volumetric, flip=flip),
            drive=Drive(duration=duration, spin_up=spin_up),
            grid_phases=grid_phases,
        )
    _emit_convergence(res, fmt, out_path, plot_path, "MPM wheel")
