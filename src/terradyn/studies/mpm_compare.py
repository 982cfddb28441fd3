"""MPM against RFT (thesis Fig. 4-1 and section 6.1.2): plate alpha maps and a forced-slip wheel."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from pydantic import Field

from .. import materials
from ..geometry import Body, Plate, WheelCircular
from ..locomotion import wheel_steady
from ..mpm.bodies import effective_body
from ..mpm.wheel_runs import WHEEL_CELLS_ACROSS
from ..results import TableResult
from ..rft import li2013_alpha_material
from ._base import StudyEntry, StudyOutput, _Params

__all__ = ["mpm_alpha_map", "mpm_wheel_versus_rft"]


def _alpha_point(args: tuple) -> tuple[float, float, float, float]:
    """One MPM plate intrusion (module level so worker processes can run it)."""
    from ..mpm import Resolution, run_intrusion

    material, length, width, thickness, depth, cell_size, speed, angle_deg, direction_deg = args
    plate = Plate(length, width, thickness=thickness)
    res = run_intrusion(
        plate,
        materials.get(material),
        depth=depth,
        angle=math.radians(angle_deg),
        direction=math.radians(direction_deg),
        speed=speed,
        resolution=Resolution(cell_size=cell_size),
    )
    s = res.summary
    return s["force_x_N"], s["force_z_N"], s["torque_y_Nm"], res.metadata["wall_time_s"]


def mpm_alpha_map(
    material: str = "MS",
    *,
    angles_deg: Sequence[float] = (0.0, 30.0, 60.0, 90.0),
    directions_deg: Sequence[float] = (30.0, 90.0, 150.0),
    length: float = 0.04,
    width: float = 0.02,
    depth: float = 0.04,
    cell_size: float = 0.005,
    speed: float = 0.05,
    thickness: float | None = None,
    scheduler: str = "serial",
    workers: int | None = None,
) -> TableResult:
    """Stress per depth of a plate from MPM and from RFT over plate angles and motion directions.

    MPM: the plate (``length`` x ``width``, ``thickness`` thick, default one cell; the two-field grid
    contact needs no thickening) enters the settled
    bed at ``speed`` [m/s] along the direction and its force is averaged as its centre passes ``depth``;
    alpha = F / (length width depth) [N/m^3], alpha_x with the law's sign (positive resists motion
    along +x). RFT: the Li et al. (2013) law of the same medium at beta = -angle, gamma = direction.
    Points run on ``scheduler`` (see :func:`terradyn.parallel.map_items`; ``"processes"`` uses both
    cores of a small machine).
    """
    from ..parallel import map_items

    mat = materials.get(material)
    thick = cell_size if thickness is None else thickness
    grid = [(a, g) for a in angles_deg for g in directions_deg]
    jobs = [(material, length, width, thick, depth, cell_size, speed, a, g) for a, g in grid]
    out = map_items(_alpha_point, jobs, scheduler=scheduler, workers=workers)
    norm = length * width * depth
    rft = [li2013_alpha_material(-math.radians(a), math.radians(g), mat) for a, g in grid]
    body = effective_body(Plate(length, width, thickness=thick), cell_size)
    assert isinstance(body, Plate)
    rft_body = [_rft_on_body(body, mat, a, g, depth) for a, g in grid]
    cols = {
        "angle_deg": np.array([a for a, _ in grid], dtype=float),
        "direction_deg": np.array([g for _, g in grid], dtype=float),
        "alpha_x_mpm_N_per_m3": np.array([-o[0] / norm for o in out]),
        "alpha_z_mpm_N_per_m3": np.array([o[1] / norm for o in out]),
        "alpha_x_rft_N_per_m3": np.array([float(r[0]) for r in rft]),
        "alpha_z_rft_N_per_m3": np.array([float(r[1]) for r in rft]),
        "alpha_x_rft_body_N_per_m3": np.array([-r[0] / norm for r in rft_body]),
        "alpha_z_rft_body_N_per_m3": np.array([r[1] / norm for r in rft_body]),
        "torque_y_mpm_Nm": np.array([o[2] for o in out]),
        "wall_time_s": np.array([o[3] for o in out]),
    }
    meta = {
        "material": mat.name,
        "cell_size_m": cell_size,
        "depth_m": depth,
        "speed_m_s": speed,
        "plate_length_m": length,
        "plate_width_m": width,
        "mpm_plate_thickness_m": body.thickness,
        "rft_body": "RFT summed over the faces of the plate as MPM resolves it (thickness above)",
    }
    return TableResult(cols, meta)


def style_alpha_axes(axes: Any, angles: Sequence[float], model: str, marker_label: str) -> list[Any]:
    """Axes of an alpha map (alpha_z, alpha_x against direction) and the legend handles shared by the
    MPM and DEM maps: one colour per plate angle, the model's markers, RFT dashed (on the plate as
    ``model`` resolves it) and thin (the thin-plate law)."""
    from matplotlib.lines import Line2D

    for ax, comp in zip(axes, ("z", "x"), strict=True):
        ax.set_xlabel(r"direction of motion $\gamma$ [deg below +x]")
        ax.set_ylabel(rf"$\alpha_{comp}$ [N/cm$^3$] (= N/m$^3$ $\times$ 10$^{{-6}}$)")
        ax.axhline(0.0, color="k", lw=0.5)
        ax.set_xlim(0.0, 180.0)
        ax.set_xticks(np.arange(0.0, 181.0, 30.0))
        ax.grid(True, alpha=0.35)
    return [
        *(Line2D([], [], color=f"C{k}", lw=2, label=f"plate angle {a:g} deg") for k, a in enumerate(angles)),
        Line2D([], [], color="0.3", marker="o", mec="k", ls="none", label=marker_label),
        Line2D([], [], color="0.3", ls="--", label=f"RFT on the {model} plate (with thickness)"),
        Line2D([], [], color="0.3", lw=0.8, label="RFT, thin plate"),
    ]


def scale_and_shape(model: np.ndarray, rft: np.ndarray) -> tuple[float, float]:
    """One scale factor (RFT's material constant zeta) fitted by least squares to ``model`` against
    ``rft`` (alpha_x and alpha_z together), and the rms difference left after it relative to the
    scaled RFT values: the shape of the map."""
    scale = float(np.dot(model, rft) / np.dot(rft, rft))
    resid = np.sqrt(np.mean((model - scale * rft) ** 2)) / np.sqrt(np.mean((scale * rft) ** 2))
    return scale, float(resid)


def alpha_scale_and_shape(c: dict[str, np.ndarray], model: str, kind: str) -> tuple[float, float]:
    """:func:`scale_and_shape` of an alpha-map table: columns ``alpha_{x,z}_{model}_N_per_m3``
    against ``alpha_{x,z}_{kind}_N_per_m3``."""
    both = [np.concatenate([c[f"alpha_x_{k}_N_per_m3"], c[f"alpha_z_{k}_N_per_m3"]]) for k in (model, kind)]
    return scale_and_shape(both[0], both[1])


def _rft_on_body(body: Body, mat, angle_deg: float, direction_deg: float, depth: float):
    """RFT force (fx, fz) [N] on ``body`` with its centre at ``depth`` moving along the direction."""
    from ..kinematics import Pose2D, Twist2D
    from ..rft import rft_wrench

    d = math.radians(direction_deg)
    w = rft_wrench(
        body, mat, Pose2D(0.0, -depth, math.radians(angle_deg)), Twist2D(math.cos(d), -math.sin(d), 0.0)
    )
    return w.fx, w.fz


def _wheel_point(args: tuple) -> tuple[float, float, float, float, float]:
    """One forced-slip MPM wheel run (module level so worker processes can run it)."""
    from ..mpm import Drive, Resolution, run_wheel

    material, radius, width, load, slip, omega, cell_size, duration = args
    m = run_wheel(
        WheelCircular(radius, width),
        materials.get(material),
        load=load,
        omega=omega,
        slip=slip,
        resolution=Resolution(cell_size=cell_size),
        drive=Drive(duration=duration),
    )
    s = m.summary
    return (
        s["sinkage_m"],
        s["drawbar_pull_N"],
        s["drive_torque_Nm"],
        s["force_z_N"],
        m.metadata["wall_time_s"],
    )


def mpm_wheel_versus_rft(
    material: str = "MS",
    *,
    radius: float = 0.13,
    width: float = 0.16,
    load: float = 130.0,
    slips: Sequence[float] = (0.1, 0.3),
    omega: float = 1.0,
    cell_size: float | None = None,
    duration: float | None = None,
    scheduler: str = "serial",
    workers: int | None = None,
) -> TableResult:
    """Forced-slip wheel: MPM sinkage, drawbar pull and torque against the RFT steady solve.

    MPM (:func:`terradyn.mpm.run_wheel`): the wheel sinks under ``load``, then spins at ``omega`` with
    the forward speed ``(1 - s) omega radius`` prescribed and the vertical motion free for ``duration``
    (default 3 / omega: the pull settles after about two radians of rotation); values are averaged
    over the second half of the drive. RFT: the implicit
    steady solve of the same wheel, load and slip. The 2D MPM force per width is scaled by ``width``.
    """
    from ..parallel import map_items

    mat = materials.get(material)
    wheel = WheelCircular(radius, width)
    jobs = [(material, radius, width, load, float(s), omega, cell_size, duration) for s in slips]
    out = map_items(_wheel_point, jobs, scheduler=scheduler, workers=workers)
    keys = (
        "slip",
        "sinkage_mpm_m",
        "sinkage_rft_m",
        "drawbar_pull_mpm_N",
        "drawbar_pull_rft_N",
        "drive_torque_mpm_Nm",
        "drive_torque_rft_Nm",
        "force_z_mpm_N",
        "wall_time_s",
    )
    rows: dict[str, list[float]] = {k: [] for k in keys}
    for s, (sink, dp, torque, fz, wall) in zip(slips, out, strict=True):
        r = wheel_steady(wheel, mat, load, s, omega=omega)
        vals = (s, sink, r.sinkage_m, dp, r.drawbar_pull_N, torque, r.drive_torque_Nm, fz, wall)
        for k, v in zip(keys, vals, strict=True):
            rows[k].append(float(v))
    return TableResult(
        {k: np.asarray(v) for k, v in rows.items()},
        {
            "material": mat.name,
            "load_N": load,
            "radius_m": radius,
            "width_m": width,
            "omega_rad_s": omega,
            "cell_size_m": cell_size if cell_size is not None else 2 * radius / WHEEL_CELLS_ACROSS,
        },
    )


class MPMAlphaParams(_Params):
    angles_deg: list[float] = Field(default_factory=lambda: [0.0, 30.0, 60.0, 90.0])
    directions_deg: list[float] = Field(default_factory=lambda: [30.0, 60.0, 90.0, 120.0, 150.0])
    length_m: float = Field(0.04, gt=0)
    cell_size_m: float = Field(0.005, gt=0)
    depth_m: float = Field(0.04, gt=0)
    speed_m_s: float = Field(0.05, gt=0, le=1.0)
    workers: int = Field(2, ge=1, le=256, description="Worker processes (1: run in this process).")


class MPMWheelParams(_Params):
    load_N: float = Field(130.0, gt=0)
    slips: list[float] = Field(default_factory=lambda: [0.1, 0.3, 0.5])
    cell_size_m: float | None = Field(None, gt=0)
    duration_s: float | None = Field(None, gt=0)
    workers: int = Field(2, ge=1, le=256, description="Worker processes (1: run in this process).")


def _run_alpha(p: MPMAlphaParams) -> StudyOutput:
    import matplotlib.pyplot as plt

    angles = p.angles_deg[:1] if p.quick else p.angles_deg
    dirs = [90.0] if p.quick else p.directions_deg
    cell = p.length_m / 6.0 if p.quick else p.cell_size_m
    t = mpm_alpha_map(
        p.material,
        angles_deg=angles,
        directions_deg=dirs,
        length=p.length_m,
        cell_size=cell,
        depth=p.depth_m,
        speed=p.speed_m_s,
        scheduler="serial" if p.workers == 1 or len(angles) * len(dirs) == 1 else "processes",
        workers=p.workers,
    )
    c = t.columns
    mat = materials.get(p.material)
    md = t.metadata
    body = Plate(md["plate_length_m"], md["plate_width_m"], thickness=md["mpm_plate_thickness_m"])
    norm = md["plate_length_m"] * md["plate_width_m"] * md["depth_m"]
    gam = np.linspace(1.0, 179.0, 90)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6), sharex=True, layout="constrained")
    for k, a in enumerate(angles):
        colour = f"C{k}"
        law = np.array([li2013_alpha_material(-math.radians(a), math.radians(g), mat) for g in gam])
        on_body = np.array([_rft_on_body(body, mat, a, g, p.depth_m) for g in gam]) / norm
        on_body[:, 0] *= -1.0
        sel = c["angle_deg"] == a
        for ax, comp, j in ((axes[0], "z", 1), (axes[1], "x", 0)):
            ax.plot(gam, law[:, j] / 1e6, "-", color=colour, lw=0.8, alpha=0.6)
            ax.plot(gam, on_body[:, j] / 1e6, "--", color=colour, lw=1.2)
            ax.plot(
                c["direction_deg"][sel],
                c[f"alpha_{comp}_mpm_N_per_m3"][sel] / 1e6,
                "o",
                color=colour,
                mec="k",
            )
    handles = style_alpha_axes(axes, angles, "MPM", "MPM")
    fig.legend(handles=handles, loc="outside lower center", ncols=min(len(handles), 4), fontsize=8)
    fig.suptitle(
        f"Plate stress per depth, MPM (cell {cell * 1e3:.3g} mm, {p.speed_m_s:g} m/s) vs RFT, {mat.name}"
    )
    scale_thin, shape_thin = alpha_scale_and_shape(c, "mpm", "rft")
    scale_body, shape_body = alpha_scale_and_shape(c, "mpm", "rft_body")
    rz, rr = c["alpha_z_rft_N_per_m3"], c["alpha_z_mpm_N_per_m3"]
    ratio = rr / np.where(rz != 0, rz, np.nan)
    summary = [
        {
            "points": len(t),
            "alpha_z_ratio_mean": float(np.nanmean(ratio)),
            "alpha_z_ratio_min": float(np.nanmin(ratio)),
            "alpha_z_ratio_max": float(np.nanmax(ratio)),
            "best_fit_scale_mpm_over_rft": scale_thin,
            "shape_rms_difference_after_scale": shape_thin,
            "best_fit_scale_mpm_over_rft_body": scale_body,
            "shape_rms_difference_after_scale_body": shape_body,
            "mpm_wall_time_s": float(c["wall_time_s"].sum()),
        }
    ]
    return StudyOutput({"mpm_alpha": t}, {"mpm_alpha": fig}, summary)


def _run_wheel(p: MPMWheelParams) -> StudyOutput:
    import matplotlib.pyplot as plt

    slips = p.slips[:1] if p.quick else p.slips
    cell = 0.26 / 8.0 if p.quick else p.cell_size_m  # quick: 8 cells across the default wheel
    t = mpm_wheel_versus_rft(
        p.material,
        load=p.load_N,
        slips=slips,
        cell_size=cell,
        duration=0.5 if p.quick else p.duration_s,
        scheduler="serial" if p.workers == 1 or len(slips) == 1 else "processes",
        workers=p.workers,
    )
    c = t.columns
    fig, axes = plt.subplots(1, 3, figsize=(13, 3.8), layout="constrained")
    for ax, key, label, scale in (
        (axes[0], "sinkage", "sinkage [mm]", 1e3),
        (axes[1], "drawbar_pull", "drawbar pull [N]", 1.0),
        (axes[2], "drive_torque", "drive torque [N m]", 1.0),
    ):
        unit = "m" if key == "sinkage" else ("N" if key == "drawbar_pull" else "Nm")
        ax.plot(c["slip"], c[f"{key}_rft_{unit}"] * scale, "s-", label="RFT (steady)")
        ax.plot(c["slip"], c[f"{key}_mpm_{unit}"] * scale, "o--", label="MPM (plane strain)")
        ax.set_xlabel("slip [-]")
        ax.set_ylabel(label)
        ax.axhline(0.0, color="0.7", lw=0.8)
        ax.grid(True, alpha=0.35)
        if len(slips) == 1:
            ax.set_xlim(slips[0] - 0.1, slips[0] + 0.1)
    axes[0].legend()
    fig.suptitle(f"Forced-slip wheel, {t.metadata['material']}, load {p.load_N:g} N")
    return StudyOutput({"mpm_wheel": t}, {"mpm_wheel": fig}, t.records())


def study_entries() -> tuple[StudyEntry, ...]:
    """The studies this module provides (:mod:`terradyn.studies.registry` lists them)."""
    return (
        ("mpm-alpha", MPMAlphaParams, _run_alpha, "plate alpha over angle and direction: MPM vs RFT"),
        ("mpm-wheel", MPMWheelParams, _run_wheel, "forced-slip wheel: MPM vs the RFT steady solve"),
    )
