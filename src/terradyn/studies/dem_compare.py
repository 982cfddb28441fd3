"""DEM against RFT (thesis Fig. 4-1 with the discrete model): plate alpha maps from LAMMPS intrusions.

The DEM cases are plate intrusions at several (angle, direction) pairs from one poured bed
(:func:`terradyn.dem.sweeps.intrusion_sweep`); each gives alpha = F / (plate area x depth) beside
RFT's alpha for the same plate, evaluated as :func:`terradyn.studies.mpm_compare.mpm_alpha_map` does
(the thin-plate law and RFT summed over the faces of the body the model resolves).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, Literal

import numpy as np
from pydantic import Field

from .. import materials
from ..errors import InputError
from ..geometry import Plate
from ..materials import Material
from ..results import TableResult
from ..rft import li2013_alpha_material
from ._base import StudyEntry, StudyOutput, _Params
from .mpm_compare import _rft_on_body, alpha_scale_and_shape, style_alpha_axes

__all__ = ["dem_alpha_map", "dem_plate_body", "run_dem_alpha", "window_alpha"]


def dem_plate_body(length: float, width: float, grain_diameter: float) -> Plate:
    """The plate as the DEM resolves it: the outline thickened by a quarter grain on each side
    (body spheres of half a grain's diameter on the outline), so ``length + d/2`` by ``d/2`` thick."""
    half = 0.5 * grain_diameter
    return Plate(length + half, width, thickness=half)


def window_alpha(history: dict[str, np.ndarray], *, depth: float, window: float, area: float
                 ) -> tuple[float, float, float, float, int]:  # fmt: skip
    """alpha_x, alpha_z [N/m^3] of one DEM history: the mean over the rows whose reference depth lies
    within ``window / 2`` of ``depth`` of each row's F / (area x its own depth) (alpha_x with the law's
    sign: positive resists motion along +x), and the standard deviations of those per-row values
    (the force's scatter over the window) and the number of rows."""
    z = np.asarray(history["depth_m"], dtype=float)
    sel = (np.abs(z - depth) <= 0.5 * window + 1e-12) & (z > 0.0)
    if not sel.any():
        raise InputError("window", window, "a depth window that holds at least one history row")
    ax = -np.asarray(history["force_x_N"])[sel] / (area * z[sel])
    az = np.asarray(history["force_z_N"])[sel] / (area * z[sel])
    return float(ax.mean()), float(az.mean()), float(ax.std()), float(az.std()), int(sel.sum())


def dem_alpha_map(
    material: str | Material = "MS",
    *,
    angles_deg: Sequence[float] = (0.0, 30.0, 60.0),
    directions_deg: Sequence[float] = (45.0, 90.0, 135.0),
    length: float = 0.03,
    width: float = 0.02,
    depth: float = 0.024,
    grain_diameter: float | None = 0.003,
    packing: str = "loose",
    speed: float = 0.04,
    window: float | None = None,
    seed: int = 12345,
    scheduler: str = "serial",
    workers: int | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> TableResult:
    """Stress per depth of a plate from DEM (LAMMPS) and from RFT over plate angles and motion directions.

    DEM: one bed of ``material``'s ``[dem]`` grains (``grain_diameter`` [m] coarse-grains them; None
    keeps the table's size) is poured for the widest path of all cases and each (angle, direction)
    case [deg] pushes the plate (``length`` x ``width`` [m]; a slab bed, so the force is per unit width
    times ``width`` as the plane models report it) from a copy of it at ``speed`` [m/s] until its
    centre is ``depth + window / 2`` deep. Depth averaging: a window around the target depth, not the
    intrusion summary's last grain of travel: alpha = F / (length x width x z) of every history row
    (a tenth of a grain of travel each) whose centre depth z lies within ``window / 2`` of ``depth``,
    averaged (``window`` [m], default two grain diameters). alpha_x has the law's sign (positive
    resists motion along +x). ``alpha_*_dem_std`` is the standard deviation of the per-row values in
    the window (the force's scatter; rows are correlated over about a grain, so it is not an error
    of the mean). RFT: the Li et al. (2013) law of the same medium at beta = -angle, gamma = direction
    (thin plate) and RFT summed over the faces of the plate as the DEM resolves it
    (:func:`dem_plate_body`). Cases run on ``scheduler`` / ``workers``
    (:func:`terradyn.parallel.map_items`); ``progress(done, total)`` after the bed and each case.
    Raises :class:`terradyn.dem.DEMUnavailable` (one line) without the ``dem`` extra.
    """
    from ..dem import load_lammps
    from ..dem.sweeps import IntrusionCase, intrusion_sweep

    mat = materials.get(material) if isinstance(material, str) else material
    dem = mat.require_dem()
    d = dem.grain_diameter if grain_diameter is None else float(grain_diameter)
    if not (math.isfinite(d) and d > 0):
        raise InputError("grain_diameter", grain_diameter, "a grain diameter > 0 [m]")
    w = 2.0 * d if window is None else float(window)
    if not (math.isfinite(w) and 0 < w < 2 * depth):
        raise InputError("window", window, f"a depth window > 0 and below {2 * depth:g} m (twice the depth)")
    if not angles_deg or not directions_deg:
        raise InputError("angles_deg", list(angles_deg), "at least one angle and one direction")
    load_lammps()
    start = time.perf_counter()
    grid = [(float(a), float(g)) for a in angles_deg for g in directions_deg]
    cases = [IntrusionCase(depth + 0.5 * w, math.radians(g), math.radians(a)) for a, g in grid]
    plate = Plate(length, width)
    sweep = intrusion_sweep(plate, mat, cases, speed=speed, grain_diameter=d, packing=packing, seed=seed,
                            scheduler=scheduler, workers=workers, progress=progress)  # fmt: skip
    wall = time.perf_counter() - start
    area = length * width
    dem_rows = [window_alpha(r.history, depth=depth, window=w, area=area) for r in sweep.results]
    norm = area * depth
    rft = [li2013_alpha_material(-math.radians(a), math.radians(g), mat) for a, g in grid]
    body = dem_plate_body(length, width, d)
    rft_body = [_rft_on_body(body, mat, a, g, depth) for a, g in grid]
    cols = {
        "angle_deg": np.array([a for a, _ in grid], dtype=float),
        "direction_deg": np.array([g for _, g in grid], dtype=float),
        "alpha_x_dem_N_per_m3": np.array([r[0] for r in dem_rows]),
        "alpha_z_dem_N_per_m3": np.array([r[1] for r in dem_rows]),
        "alpha_x_dem_std_N_per_m3": np.array([r[2] for r in dem_rows]),
        "alpha_z_dem_std_N_per_m3": np.array([r[3] for r in dem_rows]),
        "window_rows": np.array([r[4] for r in dem_rows], dtype=float),
        "alpha_x_rft_N_per_m3": np.array([float(r[0]) for r in rft]),
        "alpha_z_rft_N_per_m3": np.array([float(r[1]) for r in rft]),
        "alpha_x_rft_body_N_per_m3": np.array([-r[0] / norm for r in rft_body]),
        "alpha_z_rft_body_N_per_m3": np.array([r[1] / norm for r in rft_body]),
    }
    meta = {
        "material": mat.name,
        "grain_diameter_m": d,
        "packing": packing,
        "depth_m": depth,
        "window_m": w,
        "speed_m_s": speed,
        "froude_number": speed / math.sqrt(9.81 * d),
        "plate_length_m": length,
        "plate_width_m": width,
        "dem_plate_length_m": body.length,
        "dem_plate_thickness_m": body.thickness,
        "grain_count": sweep.bed["grain_count"],
        "packing_fraction": sweep.bed["packing_fraction"],
        "bed_length_m": sweep.bed["bed_length_m"],
        "rft_body": "RFT summed over the faces of the plate as the DEM resolves it (size above)",
        "wall_time_s": wall,
    }
    return TableResult(cols, meta)


class DEMAlphaParams(_Params):
    angles_deg: list[float] = Field(default_factory=lambda: [0.0, 30.0, 60.0])
    directions_deg: list[float] = Field(default_factory=lambda: [45.0, 90.0, 135.0])
    length_m: float = Field(0.03, gt=0)
    width_m: float = Field(0.02, gt=0)
    depth_m: float = Field(0.024, gt=0)
    grain_diameter_m: float | None = Field(
        0.003, gt=0, description="Coarse-grained DEM grain size [m] (None: the [dem] table's)."
    )
    packing: Literal["loose", "dense"] = "loose"
    speed_m_s: float = Field(0.04, gt=0, le=1.0)
    window_m: float | None = Field(None, gt=0, description="Depth window [m] (default 2 grains).")
    workers: int = Field(1, ge=1, le=256, description="Worker processes (1: run in this process).")
    mpm_csv: str | None = Field(None, description="An mpm_alpha.csv (study mpm-alpha) to draw beside.")


def _read_mpm(path: str | None) -> Any:
    if path is None:
        return None
    import pandas as pd

    p = Path(path)
    if not p.is_file():
        raise InputError("mpm_csv", path, "an existing mpm_alpha.csv written by study mpm-alpha")
    df = pd.read_csv(p)
    need = {"angle_deg", "direction_deg", "alpha_x_mpm_N_per_m3", "alpha_z_mpm_N_per_m3"}
    if not need <= set(df.columns):
        raise InputError("mpm_csv", path, f"a CSV with columns {sorted(need)}")
    return df


def _figure(t: TableResult, p: DEMAlphaParams, angles: Sequence[float], mpm: Any) -> Any:
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    c, md = t.columns, t.metadata
    mat = materials.get(p.material)
    body = dem_plate_body(md["plate_length_m"], md["plate_width_m"], md["grain_diameter_m"])
    norm = md["plate_length_m"] * md["plate_width_m"] * md["depth_m"]
    gam = np.linspace(1.0, 179.0, 90)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6), sharex=True, layout="constrained")
    for k, a in enumerate(angles):
        colour = f"C{k}"
        law = np.array([li2013_alpha_material(-math.radians(a), math.radians(g), mat) for g in gam])
        on_body = np.array([_rft_on_body(body, mat, a, g, md["depth_m"]) for g in gam]) / norm
        on_body[:, 0] *= -1.0
        sel = c["angle_deg"] == a
        for ax, comp, j in ((axes[0], "z", 1), (axes[1], "x", 0)):
            ax.plot(gam, law[:, j] / 1e6, "-", color=colour, lw=0.8, alpha=0.6)
            ax.plot(gam, on_body[:, j] / 1e6, "--", color=colour, lw=1.2)
            ax.errorbar(c["direction_deg"][sel], c[f"alpha_{comp}_dem_N_per_m3"][sel] / 1e6,
                        yerr=c[f"alpha_{comp}_dem_std_N_per_m3"][sel] / 1e6, fmt="o", color=colour,
                        mec="k", capsize=3)  # fmt: skip
            if mpm is not None:
                m = mpm[np.isclose(mpm["angle_deg"], a)]
                ax.plot(m["direction_deg"], m[f"alpha_{comp}_mpm_N_per_m3"] / 1e6, "s", color=colour,
                        mfc="none", ms=8)  # fmt: skip
    handles = style_alpha_axes(axes, angles, "DEM", "DEM (bar: scatter in window)")
    if mpm is not None:
        mpm_handle = Line2D([], [], color="0.3", marker="s", mfc="none", ls="none", label="MPM (mpm-alpha)")
        handles.append(mpm_handle)
    fig.legend(handles=handles, loc="outside lower center", ncols=min(len(handles), 4), fontsize=8)
    fig.suptitle(
        f"Plate stress per depth, DEM ({md['grain_count']} grains of {md['grain_diameter_m'] * 1e3:.3g} mm, "
        f"{md['speed_m_s']:g} m/s, depth {md['depth_m'] * 1e3:g} mm) vs RFT, {mat.name}"
    )
    return fig


def run_dem_alpha(p: DEMAlphaParams) -> StudyOutput:
    """The ``dem-alpha`` study: the plate's alpha map in DEM beside RFT (and an MPM table if given)."""
    mpm = _read_mpm(p.mpm_csv)
    angles = p.angles_deg[:1] if p.quick else p.angles_deg
    dirs = [90.0] if p.quick else p.directions_deg
    # quick: a plate five grains long at half its length deep (a few hundred grains)
    d = p.length_m / 5.0 if p.quick else p.grain_diameter_m
    depth = 0.5 * p.length_m if p.quick else p.depth_m
    t = dem_alpha_map(
        p.material,
        angles_deg=angles,
        directions_deg=dirs,
        length=p.length_m,
        width=p.width_m,
        depth=depth,
        grain_diameter=d,
        packing=p.packing,
        speed=p.speed_m_s,
        window=p.window_m,
        scheduler="serial" if p.workers == 1 or len(angles) * len(dirs) == 1 else "processes",
        workers=p.workers,
    )
    c = t.columns
    fig = _figure(t, p, angles, mpm)
    scale_thin, shape_thin = alpha_scale_and_shape(c, "dem", "rft")
    scale_body, shape_body = alpha_scale_and_shape(c, "dem", "rft_body")
    rz = c["alpha_z_rft_N_per_m3"]
    ratio = c["alpha_z_dem_N_per_m3"] / np.where(rz != 0, rz, np.nan)
    summary = [
        {
            "points": len(t),
            "grain_count": t.metadata["grain_count"],
            "alpha_z_ratio_mean": float(np.nanmean(ratio)),
            "alpha_z_ratio_min": float(np.nanmin(ratio)),
            "alpha_z_ratio_max": float(np.nanmax(ratio)),
            "best_fit_scale_dem_over_rft": scale_thin,
            "shape_rms_difference_after_scale": shape_thin,
            "best_fit_scale_dem_over_rft_body": scale_body,
            "shape_rms_difference_after_scale_body": shape_body,
            "dem_wall_time_s": t.metadata["wall_time_s"],
        }
    ]
    return StudyOutput({"dem_alpha": t}, {"dem_alpha": fig}, summary)


def study_entries() -> tuple[StudyEntry, ...]:
    """The studies this module provides (:mod:`terradyn.studies.registry` lists them)."""
    return (("dem-alpha", DEMAlphaParams, run_dem_alpha, "plate alpha over angle and direction: DEM vs RFT"),)
