"""MPM against RFT (thesis Fig. 4-1 and section 6.1.2): plate alpha maps and a forced-slip wheel."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from pydantic import Field

from .. import materials
from ..geometry import Plate, WheelCircular
from ..locomotion import wheel_steady
from ..results import TableResult
from ..rft import li2013_alpha_material
from .registry import StudyOutput, _Params, register_study

__all__ = ["mpm_alpha_map", "mpm_wheel_versus_rft"]


def mpm_alpha_map(
    material: str = "MS",
    *,
    angles_deg: Sequence[float] = (0.0, 30.0, 60.0, 90.0),
    directions_deg: Sequence[float] = (30.0, 90.0, 150.0),
    length: float = 0.04,
    width: float = 0.02,
    depth: float = 0.04,
    cell_size: float = 0.004,
    thickness: float | None = None,
) -> TableResult:
    """Stress per depth of a plate from MPM and from RFT over plate angles and motion directions.

    MPM: the plate (``length`` x ``width``, thickness at least one cell) enters the settled bed along the
    direction and its force is averaged as its centre passes ``depth``; alpha = F / (length width
    depth) [N/m^3], alpha_x with the law's sign (positive resists motion along +x).
    RFT: the Li et al. (2013) law of the same medium at beta = -angle, gamma = direction.
    """
    from ..mpm import run_intrusion

    mat = materials.get(material)
    plate = Plate(length, width, thickness=thickness if thickness is not None else cell_size)
    rows: dict[str, list[float]] = {
        k: []
        for k in (
            "angle_deg",
            "direction_deg",
            "alpha_x_mpm_N_per_m3",
            "alpha_z_mpm_N_per_m3",
            "alpha_x_rft_N_per_m3",
            "alpha_z_rft_N_per_m3",
        )
    }
    norm = length * width * depth
    for a in angles_deg:
        for g in directions_deg:
            res = run_intrusion(
                plate, mat, depth=depth, angle=math.radians(a), direction=math.radians(g), cell_size=cell_size
            )
            ax_r, az_r = li2013_alpha_material(-math.radians(a), math.radians(g), mat)
            rows["angle_deg"].append(a)
            rows["direction_deg"].append(g)
            rows["alpha_x_mpm_N_per_m3"].append(-res.summary["force_x_N"] / norm)
            rows["alpha_z_mpm_N_per_m3"].append(res.summary["force_z_N"] / norm)
            rows["alpha_x_rft_N_per_m3"].append(float(ax_r))
            rows["alpha_z_rft_N_per_m3"].append(float(az_r))
    return TableResult(
        {k: np.asarray(v) for k, v in rows.items()},
        {"material": mat.name, "cell_size_m": cell_size, "depth_m": depth},
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
) -> TableResult:
    """Forced-slip wheel: MPM sinkage, drawbar pull and torque against the RFT steady solve."""
    from ..mpm import run_wheel

    mat = materials.get(material)
    wheel = WheelCircular(radius, width)
    keys = (
        "slip",
        "sinkage_mpm_m",
        "sinkage_rft_m",
        "drawbar_pull_mpm_N",
        "drawbar_pull_rft_N",
        "drive_torque_mpm_Nm",
        "drive_torque_rft_Nm",
    )
    rows: dict[str, list[float]] = {k: [] for k in keys}
    for s in slips:
        m = run_wheel(wheel, mat, load=load, omega=omega, slip=s, cell_size=cell_size, duration=duration)
        r = wheel_steady(wheel, mat, load, s, omega=omega)
        vals = (
            s,
            m.summary["sinkage_m"],
            r.sinkage_m,
            m.summary["drawbar_pull_N"],
            r.drawbar_pull_N,
            m.summary["drive_torque_Nm"],
            r.drive_torque_Nm,
        )
        for k, v in zip(keys, vals, strict=True):
            rows[k].append(float(v))
    return TableResult(
        {k: np.asarray(v) for k, v in rows.items()},
        {"material": mat.name, "load_N": load, "radius_m": radius, "width_m": width},
    )


class MPMAlphaParams(_Params):
    angles_deg: list[float] = Field(default_factory=lambda: [0.0, 30.0, 60.0, 90.0])
    directions_deg: list[float] = Field(default_factory=lambda: [30.0, 60.0, 90.0, 120.0, 150.0])
    cell_size_m: float = Field(0.004, gt=0)
    depth_m: float = Field(0.04, gt=0)


class MPMWheelParams(_Params):
    load_N: float = Field(130.0, gt=0)
    slips: list[float] = Field(default_factory=lambda: [0.1, 0.3, 0.5])
    cell_size_m: float | None = Field(None, gt=0)


def _run_alpha(p: MPMAlphaParams) -> StudyOutput:
    import matplotlib.pyplot as plt

    angles = p.angles_deg[:1] if p.quick else p.angles_deg
    dirs = p.directions_deg[:1] if p.quick else p.directions_deg
    t = mpm_alpha_map(
        p.material, angles_deg=angles, directions_deg=dirs, cell_size=p.cell_size_m, depth=p.depth_m
    )
    c = t.columns
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for ax, comp in zip(axes, ("z", "x"), strict=True):
        ax.plot(c[f"alpha_{comp}_rft_N_per_m3"] / 1e6, c[f"alpha_{comp}_mpm_N_per_m3"] / 1e6, "o")
        lim = np.abs(np.concatenate([c[f"alpha_{comp}_rft_N_per_m3"], c[f"alpha_{comp}_mpm_N_per_m3"]])).max()
        ax.plot([-lim / 1e6, lim / 1e6], [-lim / 1e6, lim / 1e6], "k--", lw=0.8)
        ax.set_xlabel(f"RFT alpha_{comp} [N/cm^3]")
        ax.set_ylabel(f"MPM alpha_{comp} [N/cm^3]")
    fig.suptitle(f"Plate alpha: MPM vs RFT, {t.metadata['material']}")
    ratio = c["alpha_z_mpm_N_per_m3"] / np.where(c["alpha_z_rft_N_per_m3"] != 0, c["alpha_z_rft_N_per_m3"], 1)
    summary = [
        {
            "points": len(t),
            "alpha_z_ratio_mean": float(ratio.mean()),
            "alpha_z_ratio_min": float(ratio.min()),
            "alpha_z_ratio_max": float(ratio.max()),
        }
    ]
    return StudyOutput({"mpm_alpha": t}, {"mpm_alpha": fig}, summary)


def _run_wheel(p: MPMWheelParams) -> StudyOutput:
    slips = p.slips[:1] if p.quick else p.slips
    t = mpm_wheel_versus_rft(p.material, load=p.load_N, slips=slips, cell_size=p.cell_size_m)
    return StudyOutput({"mpm_wheel": t}, {}, t.records())


register_study("mpm-alpha", MPMAlphaParams, _run_alpha, "plate alpha over angle and direction: MPM vs RFT")
register_study("mpm-wheel", MPMWheelParams, _run_wheel, "forced-slip wheel: MPM vs the RFT steady solve")
