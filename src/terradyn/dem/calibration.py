"""Virtual plate tests: DEM plate intrusions at several angles and directions, fitted by RFT.

Every case starts from one settled bed (poured once, saved with :func:`~terradyn.dem.bed.save_bed` and
loaded for each run), sized for the widest path of the cases; the cases run through
:func:`terradyn.dem.sweeps.intrusion_sweep` (serial, local processes or Dask). The rows of each
force history with the plate centre below the surface become
:class:`terradyn.rft.calibration.PlateData`, which :func:`terradyn.rft.calibration.fit_rft` fits
(zeta with the generic alpha shape, or all nine coefficients with ``full``). A user without a
bevameter calibrates RFT from the medium's grain properties this way.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import InputError
from ..geometry import Plate
from ..materials import Material
from .bed import Packing
from .sweeps import IntrusionCase, intrusion_sweep

__all__ = ["VirtualPlateTest", "virtual_plate_test"]


@dataclass(frozen=True, eq=False)
class VirtualPlateTest:
    """DEM plate force histories over several (angle, direction) cases, as plate data for a fit."""

    data: Any  # terradyn.rft.calibration.PlateData
    cases: list[dict[str, float]]
    bed: dict[str, Any]


def virtual_plate_test(
    material: Material,
    *,
    plate_length: float,
    plate_width: float,
    angles: Sequence[float] = (0.0,),
    directions: Sequence[float] = (math.pi / 2,),
    depth: float,
    grain_diameter: float | None = None,
    packing: Packing | str = Packing.DENSE,
    speed: float = 0.02,
    seed: int = 12345,
    scheduler: str = "serial",
    workers: int | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> VirtualPlateTest:
    """DEM plate intrusions of every (angle, direction) pair [rad] to ``depth`` [m].

    The cases run through :func:`terradyn.dem.sweeps.intrusion_sweep` (``scheduler`` and ``workers``
    as in :func:`terradyn.parallel.map_items`; the same rows in the same order whatever the backend).
    ``progress(done, total)`` is called after the bed and after each case."""
    from ..rft.calibration import PlateData

    if len(angles) < 1 or len(directions) < 1:
        raise InputError("angles", list(angles), "at least one angle and one direction")
    plate = Plate(plate_length, plate_width)
    d = grain_diameter if grain_diameter is not None else material.require_dem().grain_diameter
    cases = [IntrusionCase(depth, float(g), float(t)) for t in angles for g in directions]
    sweep = intrusion_sweep(plate, material, cases, speed=speed, grain_diameter=d, packing=packing, seed=seed,
                            scheduler=scheduler, workers=workers, progress=progress)  # fmt: skip
    rows: dict[str, list[float]] = {k: [] for k in ("depth_m", "force_z_N", "force_x_N", "angle", "dir")}
    out_cases = []
    for case, res in zip(sweep.cases, sweep.results, strict=True):
        theta, gamma = case.angle, case.direction
        h = res.history
        sub = h["depth_m"] > 0.0
        rows["depth_m"] += h["depth_m"][sub].tolist()
        rows["force_z_N"] += h["force_z_N"][sub].tolist()
        rows["force_x_N"] += h["force_x_N"][sub].tolist()
        rows["angle"] += [math.degrees(theta)] * int(sub.sum())
        rows["dir"] += [math.degrees(gamma)] * int(sub.sum())
        forces = {key: res.summary[key] for key in ("force_x_N", "force_z_N", "torque_y_Nm")}
        out_cases.append({"angle_deg": math.degrees(theta), "direction_deg": math.degrees(gamma), **forces})
    data = PlateData(
        np.asarray(rows["depth_m"]),
        np.asarray(rows["force_z_N"]),
        np.asarray(rows["force_x_N"]),
        np.asarray(rows["angle"]),
        np.asarray(rows["dir"]),
    )
    return VirtualPlateTest(data, out_cases, sweep.bed)
