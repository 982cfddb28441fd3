"""Fitting RFT parameters to plate intrusion measurements.

The RFT force on a plate is linear in the nine Fourier coefficients (and in the scale), so both fits
are linear least squares: the scale ``zeta`` with the generic shape of the alpha map, or the full
coefficient set when the data span several plate angles and directions.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import InputError, check_positive
from ..geometry import Plate
from ..materials import LiCoefficients, Material, RFTParameters

__all__ = ["PlateData", "RFTFit", "fit_rft", "read_plate_force_csv", "write_rft_material_toml"]

_REQUIRED = ("depth_m", "force_z_N")
_OPTIONAL = ("force_x_N", "angle_deg", "direction_deg")


@dataclass(frozen=True, eq=False)
class PlateData:
    """Plate intrusion measurements: one row per depth (SI; angles in degrees as in the CSV).

    ``depth_m`` is the depth of the plate centre; ``angle_deg`` the plate rotation about +y
    (clockwise), ``direction_deg`` the motion direction below +x (90 = straight down).
    """

    depth_m: np.ndarray
    force_z_N: np.ndarray
    force_x_N: np.ndarray | None
    angle_deg: np.ndarray
    direction_deg: np.ndarray


@dataclass(frozen=True)
class RFTFit:
    """Result of an RFT fit: parameters and fit quality."""

    rft: RFTParameters
    full: bool
    r_squared: float
    rms_residual_N: float
    point_count: int

    @property
    def zeta(self) -> float:
        return self.rft.zeta


def read_plate_force_csv(path: str | Path) -> PlateData:
    """Read a CSV with columns depth_m, force_z_N and optional force_x_N, angle_deg, direction_deg."""
    import pandas as pd

    p = Path(path)
    if not p.is_file():
        raise InputError("data file", str(path), "an existing CSV file")
    try:
        df = pd.read_csv(p)
    except (ValueError, pd.errors.ParserError) as exc:
        raise InputError("data file", str(path), "a readable CSV", str(exc)) from None
    for col in _REQUIRED:
        if col not in df.columns:
            raise InputError(f"{p.name} column", col, f"present; found {list(df.columns)}")
    unknown = [c for c in df.columns if c not in _REQUIRED + _OPTIONAL]
    if unknown:
        raise InputError(f"{p.name} column", unknown[0], f"one of {list(_REQUIRED + _OPTIONAL)}")
    arrays = {}
    for col in df.columns:
        values = pd.to_numeric(df[col], errors="coerce").to_numpy(dtype=float)
        bad = np.nonzero(~np.isfinite(values))[0]
        if bad.size:
            row = int(bad[0]) + 2
            raise InputError(f"{p.name} row {row} column {col}", df[col].iloc[bad[0]], "a number")
        arrays[col] = values
    n = len(df)
    if n < 1:
        raise InputError(p.name, "no rows", "at least one measurement")
    return PlateData(
        arrays["depth_m"],
        arrays["force_z_N"],
        arrays.get("force_x_N"),
        arrays.get("angle_deg", np.zeros(n)),
        arrays.get("direction_deg", np.full(n, 90.0)),
    )


def _basis(plate: Plate, data: PlateData, element_size: float | None) -> np.ndarray:
    """Forces (rows, 2, 9): (F_x, F_z) of each row with one unit coefficient at unit scale."""
    theta = np.radians(data.angle_deg)
    gamma = np.radians(data.direction_deg)
    poses = np.column_stack((np.zeros_like(theta), -data.depth_m, theta))
    twists = np.column_stack((np.cos(gamma), -np.sin(gamma), np.zeros_like(gamma)))
    from ._kernels import rft_wrench_many_kernel

    el = plate.discretize(element_size)
    about = np.ascontiguousarray(poses[:, :2])
    out = np.empty((len(theta), 2, 9))
    for k in range(9):
        unit = np.zeros(9)
        unit[k] = 1.0
        w = rft_wrench_many_kernel(
            el.midpoints, el.normals, el.lengths, el.width, poses, twists, unit, 1.0, 0.0, about
        )
        out[:, 0, k] = w[:, 0]
        out[:, 1, k] = w[:, 1]
    return out


def fit_rft(
    data: PlateData,
    *,
    plate_length: float,
    plate_width: float,
    full: bool = False,
    element_size: float | None = None,
) -> RFTFit:
    """Fit the RFT scale zeta [N/m^3] (generic alpha shape), or all nine coefficients with ``full``.

    Parameters
    ----------
    data : PlateData
        Measured plate forces [N] at depths [m] (and angles/directions [deg]).
    plate_length, plate_width : float
        Plate size [m].
    full : bool
        Fit the full coefficient set; needs several distinct (angle, direction) pairs.
    """
    check_positive("plate_length", plate_length)
    check_positive("plate_width", plate_width)
    plate = Plate(plate_length, plate_width)
    basis = _basis(plate, data, element_size)
    has_x = data.force_x_N is not None
    rows_z = basis[:, 1, :]
    target = [data.force_z_N]
    design = [rows_z]
    if has_x:
        assert data.force_x_N is not None
        design.append(basis[:, 0, :])
        target.append(data.force_x_N)
    a = np.vstack(design)
    b = np.concatenate(target)
    if full:
        pairs = {(round(t, 6), round(g, 6)) for t, g in zip(data.angle_deg, data.direction_deg, strict=True)}
        if len(pairs) < 5:
            raise InputError(
                "full",
                True,
                "data at 5 or more distinct (angle, direction) pairs",
                f"found {len(pairs)}; fit zeta only",
            )
        coef, *_ = np.linalg.lstsq(a, b, rcond=None)
        coeffs = LiCoefficients(*coef.tolist())
        if coeffs.alpha_z_plate_down() <= 0:
            raise InputError("data", "fit", "data that give alpha_z(0, 90 deg) > 0")
        rft = RFTParameters(coeffs, 1.0)
    else:
        g = a @ LiCoefficients.generic().as_array()
        denom = float(g @ g)
        if denom == 0:
            raise InputError("depth_m", "all rows", "at least one row with the plate below the surface")
        zeta = float(g @ b) / denom
        if not (zeta > 0 and math.isfinite(zeta)):
            raise InputError("force_z_N", "fit", "forces that resist the motion (zeta > 0)")
        rft = RFTParameters(LiCoefficients.generic(), zeta)
        coef = LiCoefficients.generic().as_array() * zeta
    pred = a @ coef
    resid = b - pred
    ss_tot = float(np.sum((b - b.mean()) ** 2))
    r2 = 1.0 - float(resid @ resid) / ss_tot if ss_tot > 0 else 1.0
    return RFTFit(rft, full, r2, float(np.sqrt(np.mean(resid**2))), len(b))


def write_rft_material_toml(
    path: str | Path, name: str, fit: RFTFit, *, source: str = "", base: Material | None = None
) -> Path:
    """Write a material TOML with the fitted RFT parameters (atomically) and return its path."""
    from ..io import atomic_write_text

    if not name.strip():
        raise InputError("name", name, "a non-empty material name")
    notes = (
        f"RFT parameters fitted by terradyn calibrate rft to {source or 'plate data'}: "
        f"{'full coefficient set' if fit.full else 'zeta with the generic alpha shape'}, "
        f"R^2 = {fit.r_squared:.4f}, RMS residual = {fit.rms_residual_N:.4g} N over "
        f"{fit.point_count} values."
    )
    lines = [
        "[meta]",
        f"name = {_q(name)}",
        f"description = {_q('RFT fit to plate intrusion data')}",
        f"citation = {_q(base.provenance.citation if base else 'user measurements')}",
        f"notes = {_q(notes)}",
        "",
        "[rft]",
    ]
    if fit.full:
        lines.append(f"scale_N_per_m3 = {fit.rft.scale!r}")
        lines.append("[rft.coefficients]")
        for key, value in zip(LiCoefficients.names(), fit.rft.coefficients.as_array(), strict=True):
            lines.append(f"{key} = {float(value)!r}")
    else:
        lines.append('coefficients = "generic"')
        lines.append(f"zeta_N_per_m3 = {fit.rft.zeta!r}")
    return atomic_write_text(path, "\n".join(lines) + "\n")


def _q(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'
