"""Fitting Bekker and Janosi-Hanamoto parameters to plate-sinkage and shear tests.

* :func:`fit_bekker` - k_c, k_phi, n of ``p = (k_c / b + k_phi) z^n`` from plate pressure-sinkage curves at
  two or more plate widths b. For a fixed n the law is linear in (k_c, k_phi), so the fit is a linear
  least-squares problem in relative residuals ``(p_model - p) / p`` (close to a fit in log space, and
  fair to every depth) inside a one-dimensional search over n.
* :func:`fit_shear` - c, phi and K of ``tau = (c + sigma tan phi)(1 - exp(-j / K))`` from shear-box
  curves (shear stress against shear displacement) at two or more normal stresses. For a fixed K the law
  is linear in (c, tan phi) >= 0 (non-negative least squares), inside a one-dimensional search over
  log K. The Mohr-Coulomb line ``c + sigma tan phi`` is thus fitted to the strength each curve tends to,
  using every point of every curve rather than only the peaks.
* :func:`read_plate_sinkage_csv`, :func:`read_shear_csv` - the CSV files of those tests;
  :func:`write_material_toml` - a material file that :func:`terradyn.materials.load` reads back.

CSV columns (a header row is required; lines starting with ``#`` are comments):

* plate tests: ``plate_width_m``, ``sinkage_m``, ``pressure_Pa`` (one row per measurement; rows of all
  widths in one file);
* shear tests: ``normal_stress_Pa``, ``shear_displacement_m``, ``shear_stress_Pa``.

References
----------
.. [1] M. G. Bekker, *Theory of Land Locomotion*, University of Michigan Press (1956) (no DOI).
.. [2] Z. Janosi, B. Hanamoto, Proc. 1st Int. Conf. Terrain-Vehicle Systems, Turin (1961) (no DOI).
.. [3] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley (2008), ch. 2, ISBN 978-0-470-17038-0.
"""

from __future__ import annotations

import csv
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import minimize_scalar, nnls

from ..errors import InputError, SolverError
from ..materials import BekkerParameters

__all__ = [
    "BekkerFit",
    "PlateSinkageData",
    "ShearData",
    "ShearFit",
    "combine_fits",
    "fit_bekker",
    "fit_shear",
    "read_plate_sinkage_csv",
    "read_shear_csv",
    "write_material_toml",
]

FloatArray = NDArray[np.float64]

PLATE_COLUMNS = ("plate_width_m", "sinkage_m", "pressure_Pa")
SHEAR_COLUMNS = ("normal_stress_Pa", "shear_displacement_m", "shear_stress_Pa")


# --------------------------------------------------------------------------------------------------
# Data
# --------------------------------------------------------------------------------------------------


def _column(name: str, values: ArrayLike, length: int | None) -> FloatArray:
    try:
        arr = np.asarray(values, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        raise InputError(name, values, "a 1-D array of numbers") from None
    bad = np.nonzero(~np.isfinite(arr))[0]
    if bad.size:
        raise InputError(f"{name}[{int(bad[0])}]", float(arr[bad[0]]), "a finite number")
    if length is not None and arr.size != length:
        raise InputError(name, f"{arr.size} values", f"{length} values (one per measurement)")
    return arr


def _check_nonnegative(name: str, arr: FloatArray, *, strict: bool = False) -> None:
    bad = np.nonzero(arr <= 0 if strict else arr < 0)[0]
    if bad.size:
        raise InputError(f"{name}[{int(bad[0])}]", float(arr[bad[0]]), "> 0" if strict else ">= 0")


@dataclass(frozen=True, eq=False)
class PlateSinkageData:
    """Plate pressure-sinkage measurements, one entry per measurement (SI).

    Attributes
    ----------
    plate_width : (N,) smaller plate dimension b [m], > 0
    sinkage : (N,) sinkage z [m], >= 0
    pressure : (N,) pressure p [Pa], >= 0
    source : where the data come from (a file name, for messages and provenance)
    """

    plate_width: FloatArray
    sinkage: FloatArray
    pressure: FloatArray
    source: str = ""

    def __post_init__(self) -> None:
        b = _column("plate_width", self.plate_width, None)
        z = _column("sinkage", self.sinkage, b.size)
        p = _column("pressure", self.pressure, b.size)
        _check_nonnegative("plate_width", b, strict=True)
        _check_nonnegative("sinkage", z)
        _check_nonnegative("pressure", p)
        for name, arr in (("plate_width", b), ("sinkage", z), ("pressure", p)):
            object.__setattr__(self, name, arr)

    @classmethod
    def from_tests(
        cls, tests: Mapping[float, tuple[ArrayLike, ArrayLike]], *, source: str = ""
    ) -> PlateSinkageData:
        """From ``{plate_width [m]: (sinkage [m], pressure [Pa])}``, one curve per plate."""
        widths, sinks, pressures = [], [], []
        for width, (z, p) in tests.items():
            z_arr = _column(f"tests[{width!r}] sinkage", z, None)
            widths.append(np.full(z_arr.size, float(width)))
            sinks.append(z_arr)
            pressures.append(_column(f"tests[{width!r}] pressure", p, z_arr.size))
        if not widths:
            raise InputError("plate_tests", tests, "at least one plate curve")
        return cls(np.concatenate(widths), np.concatenate(sinks), np.concatenate(pressures), source)


@dataclass(frozen=True, eq=False)
class ShearData:
    """Shear-box measurements, one entry per point of the shear curves (SI).

    Attributes
    ----------
    normal_stress : (N,) normal stress sigma of the test [Pa], >= 0
    shear_displacement : (N,) shear displacement j [m]
    shear_stress : (N,) shear stress tau [Pa]
    source : where the data come from
    """

    normal_stress: FloatArray
    shear_displacement: FloatArray
    shear_stress: FloatArray
    source: str = ""

    def __post_init__(self) -> None:
        s = _column("normal_stress", self.normal_stress, None)
        j = _column("shear_displacement", self.shear_displacement, s.size)
        t = _column("shear_stress", self.shear_stress, s.size)
        _check_nonnegative("normal_stress", s)
        for name, arr in (("normal_stress", s), ("shear_displacement", j), ("shear_stress", t)):
            object.__setattr__(self, name, arr)

    @classmethod
    def from_tests(cls, tests: Mapping[float, tuple[ArrayLike, ArrayLike]], *, source: str = "") -> ShearData:
        """From ``{normal_stress [Pa]: (shear_displacement [m], shear_stress [Pa])}``."""
        sig, disp, tau = [], [], []
        for sigma, (j, t) in tests.items():
            j_arr = _column(f"tests[{sigma!r}] shear_displacement", j, None)
            sig.append(np.full(j_arr.size, float(sigma)))
            disp.append(j_arr)
            tau.append(_column(f"tests[{sigma!r}] shear_stress", t, j_arr.size))
        if not sig:
            raise InputError("shear_tests", tests, "at least one shear curve")
        return cls(np.concatenate(sig), np.concatenate(disp), np.concatenate(tau), source)


# --------------------------------------------------------------------------------------------------
# Fits
# --------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class BekkerFit:
    """Bekker pressure-sinkage fit.

    Attributes
    ----------
    k_c : cohesive modulus [N/m^(n+1)]; k_phi : frictional modulus [N/m^(n+2)]; n : exponent [-]
    r_squared : coefficient of determination of the pressures [-]
    rms_residual : RMS pressure residual [Pa]; rms_relative_residual : RMS of (p_fit - p) / p [-]
    point_count : measurements used (rows with sinkage > 0); plate_widths : distinct widths [m]
    """

    k_c: float
    k_phi: float
    n: float
    r_squared: float
    rms_residual: float
    rms_relative_residual: float
    point_count: int
    plate_widths: tuple[float, ...]

    def pressure(self, sinkage: ArrayLike, plate_width: ArrayLike) -> FloatArray:
        """Fitted pressure [Pa] at sinkage [m] under a plate of width [m]."""
        z = np.maximum(np.asarray(sinkage, dtype=np.float64), 0.0)
        return (self.k_c / np.asarray(plate_width, dtype=np.float64) + self.k_phi) * z**self.n

    def to_bekker_parameters(self, shear: ShearFit) -> BekkerParameters:
        """Complete parameter set with the cohesion, friction angle and K of a shear fit."""
        return combine_fits(self, shear)


@dataclass(frozen=True)
class ShearFit:
    """Janosi-Hanamoto shear fit.

    Attributes
    ----------
    cohesion : c [Pa]; friction_angle : phi [rad]; shear_modulus : K [m]
    r_squared : coefficient of determination of the shear stresses [-]
    rms_residual : RMS shear-stress residual [Pa]
    point_count : points used; normal_stresses : distinct normal stresses of the tests [Pa]
    """

    cohesion: float
    friction_angle: float
    shear_modulus: float
    r_squared: float
    rms_residual: float
    point_count: int
    normal_stresses: tuple[float, ...]

    def shear_stress(self, shear_displacement: ArrayLike, normal_stress: ArrayLike) -> FloatArray:
        """Fitted shear stress [Pa] at a displacement [m] and normal stress [Pa]."""
        j = np.asarray(shear_displacement, dtype=np.float64)
        strength = self.cohesion + np.asarray(normal_stress, dtype=np.float64) * math.tan(self.friction_angle)
        return np.sign(j) * strength * -np.expm1(-np.abs(j) / self.shear_modulus)

    def to_bekker_parameters(self, pressure_sinkage: BekkerFit) -> BekkerParameters:
        """Complete parameter set with the k_c, k_phi, n of a pressure-sinkage fit."""
        return combine_fits(pressure_sinkage, self)


def combine_fits(pressure_sinkage: BekkerFit, shear: ShearFit) -> BekkerParameters:
    """One :class:`~terradyn.materials.BekkerParameters` from a plate fit and a shear fit."""
    return BekkerParameters(
        k_c=pressure_sinkage.k_c,
        k_phi=pressure_sinkage.k_phi,
        n=pressure_sinkage.n,
        cohesion=shear.cohesion,
        friction_angle=shear.friction_angle,
        shear_modulus=shear.shear_modulus,
    )


def _r_squared(observed: FloatArray, residual: FloatArray) -> float:
    ss_tot = float(np.sum((observed - observed.mean()) ** 2))
    return 1.0 - float(residual @ residual) / ss_tot if ss_tot > 0 else 1.0


def _minimise_on_grid(objective: Callable[[float], float], grid: FloatArray) -> float:
    """Minimise a 1-D function: best grid point, then bounded Brent search between its neighbours."""
    values = np.array([objective(x) for x in grid])
    i = int(np.argmin(values))
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
    res = minimize_scalar(objective, bounds=(lo, hi), method="bounded", options={"xatol": 1e-12})
    return float(res.x) if res.fun <= values[i] else float(grid[i])


def fit_bekker(plate_tests: PlateSinkageData | Mapping[float, tuple[ArrayLike, ArrayLike]]) -> BekkerFit:
    """Fit Bekker's k_c, k_phi and n to plate pressure-sinkage curves at two or more widths.

    Parameters
    ----------
    plate_tests : PlateSinkageData or mapping
        Measurements (see :class:`PlateSinkageData`), or ``{plate_width [m]: (sinkage [m],
        pressure [Pa])}``. Rows with zero sinkage carry no information and are skipped.

    Returns
    -------
    BekkerFit
        Parameters in SI and the fit quality.

    Raises
    ------
    InputError
        Fewer than two plate widths, fewer than three usable rows, a single sinkage, or a row with
        sinkage > 0 but pressure <= 0.
    SolverError
        The best fit has k_phi <= 0 or a non-positive modulus at a tested width.
    """
    data = (
        plate_tests if isinstance(plate_tests, PlateSinkageData) else PlateSinkageData.from_tests(plate_tests)
    )
    use = data.sinkage > 0
    b, z, p = data.plate_width[use], data.sinkage[use], data.pressure[use]
    bad = np.nonzero(p <= 0)[0]
    if bad.size:
        row = int(np.nonzero(use)[0][bad[0]])
        raise InputError(f"pressure[{row}]", float(p[bad[0]]), "> 0 where the sinkage is > 0")
    widths = tuple(float(w) for w in np.unique(b))
    if len(widths) < 2:
        raise InputError(
            "plate_width", widths, "two or more distinct plate widths", "k_c and k_phi separate only by width"
        )
    if z.size < 3 or np.unique(z).size < 2:
        raise InputError("sinkage", f"{z.size} rows", "three or more rows at two or more sinkages (> 0)")
    log_z = np.log(z)

    def solve(n: float) -> tuple[FloatArray, FloatArray]:
        zn = np.exp(n * log_z)
        design = np.column_stack((zn / b, zn)) / p[:, None]
        coef = np.linalg.lstsq(design, np.ones_like(p), rcond=None)[0].astype(np.float64)
        return coef, design @ coef - 1.0

    def objective(n: float) -> float:
        rel = solve(n)[1]
        return float(rel @ rel)

    n = _minimise_on_grid(objective, np.linspace(0.1, 3.0, 59))
    (k_c, k_phi), rel = solve(n)
    modulus = k_c / np.array(widths) + k_phi
    if not (k_phi > 0 and np.all(modulus > 0)):
        raise SolverError(
            f"plate data{' in ' + data.source if data.source else ''}: the best fit (k_c = {k_c:.4g}, "
            f"k_phi = {k_phi:.4g}, n = {n:.4g}) is not a valid Bekker soil (k_phi and k_c/b + k_phi must "
            "be > 0); check the units and the plate widths"
        )
    residual = rel * p
    return BekkerFit(
        k_c=float(k_c),
        k_phi=float(k_phi),
        n=n,
        r_squared=_r_squared(p, residual),
        rms_residual=float(np.sqrt(np.mean(residual**2))),
        rms_relative_residual=float(np.sqrt(np.mean(rel**2))),
        point_count=int(p.size),
        plate_widths=widths,
    )


def fit_shear(shear_tests: ShearData | Mapping[float, tuple[ArrayLike, ArrayLike]]) -> ShearFit:
    """Fit the Janosi-Hanamoto c, phi and K to shear-box curves at two or more normal stresses.

    Parameters
    ----------
    shear_tests : ShearData or mapping
        Measurements (see :class:`ShearData`), or ``{normal_stress [Pa]: (shear_displacement [m],
        shear_stress [Pa])}``.

    Returns
    -------
    ShearFit
        c [Pa] >= 0, phi [rad] in [0, 89 deg], K [m] and the fit quality.

    Raises
    ------
    InputError
        Fewer than two distinct normal stresses, fewer than four points, or no displacement != 0.
    SolverError
        The fit gives no positive strength or a friction angle above 89 deg.
    """
    data = shear_tests if isinstance(shear_tests, ShearData) else ShearData.from_tests(shear_tests)
    sigma, j, tau = data.normal_stress, data.shear_displacement, data.shear_stress
    stresses = tuple(float(s) for s in np.unique(sigma))
    if len(stresses) < 2:
        raise InputError(
            "normal_stress",
            stresses,
            "two or more distinct normal stresses",
            "c and phi separate only by sigma",
        )
    moved = np.abs(j[j != 0])
    if tau.size < 4 or moved.size == 0:
        raise InputError("shear_displacement", f"{tau.size} points", "four or more points, some with j != 0")

    def solve(log_k: float) -> tuple[FloatArray, FloatArray]:
        g = np.sign(j) * -np.expm1(-np.abs(j) / math.exp(log_k))
        design = np.column_stack((g, sigma * g))
        coef, _ = nnls(design, tau)
        return coef, design @ coef - tau

    def objective(log_k: float) -> float:
        res = solve(log_k)[1]
        return float(res @ res)

    grid = np.linspace(math.log(moved.min() * 1e-2), math.log(moved.max() * 1e2), 81)
    log_k = _minimise_on_grid(objective, grid)
    (c, tan_phi), residual = solve(log_k)
    phi = math.atan(tan_phi)
    if c + tan_phi * max(stresses) <= 0 or phi > math.radians(89.0):
        raise SolverError(
            f"shear data{' in ' + data.source if data.source else ''}: no valid Janosi-Hanamoto fit "
            f"(c = {c:.4g} Pa, phi = {math.degrees(phi):.4g} deg); check the signs and units"
        )
    return ShearFit(
        cohesion=float(c),
        friction_angle=phi,
        shear_modulus=math.exp(log_k),
        r_squared=_r_squared(tau, residual),
        rms_residual=float(np.sqrt(np.mean(residual**2))),
        point_count=int(tau.size),
        normal_stresses=stresses,
    )


# --------------------------------------------------------------------------------------------------
# Files
# --------------------------------------------------------------------------------------------------


def _read_columns(path: str | Path, columns: tuple[str, ...]) -> tuple[dict[str, FloatArray], str, list[int]]:
    """Columns of a CSV file as float arrays, the file name and each row's line number.

    Raises InputError naming the file, line and column of a bad value.
    """
    p = Path(path)
    if not p.is_file():
        raise InputError("data file", str(path), "an existing CSV file")
    try:
        text = p.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError("data file", str(path), "a readable UTF-8 CSV file", str(exc)) from None
    numbered = [(i + 1, line) for i, line in enumerate(text.splitlines())]
    numbered = [(i, line) for i, line in numbered if line.strip() and not line.lstrip().startswith("#")]
    if not numbered:
        raise InputError(p.name, "empty", f"a header row with {list(columns)} and data rows")
    rows = list(csv.reader([line for _, line in numbered]))
    header = [h.strip() for h in rows[0]]
    for col in columns:
        if col not in header:
            raise InputError(f"{p.name} column", col, f"present (found {header})")
    for col in header:
        if col not in columns:
            raise InputError(f"{p.name} column", col, f"one of {list(columns)}")
    if len(rows) < 2:
        raise InputError(p.name, "no data rows", "one or more measurements after the header")
    out = {col: np.empty(len(rows) - 1) for col in columns}
    for k, ((line_no, _), row) in enumerate(zip(numbered[1:], rows[1:], strict=True)):
        if len(row) != len(header):
            raise InputError(f"{p.name} line {line_no}", ",".join(row), f"{len(header)} values")
        for col, cell in zip(header, row, strict=True):
            try:
                value = float(cell)
            except ValueError:
                value = math.nan
            if not math.isfinite(value):
                raise InputError(f"{p.name} line {line_no} column {col}", cell.strip(), "a finite number")
            out[col][k] = value
    return out, p.name, [line_no for line_no, _ in numbered[1:]]


def _check_rows(name: str, lines: list[int], values: FloatArray, column: str, *, strict: bool) -> None:
    bad = np.nonzero(values <= 0 if strict else values < 0)[0]
    if bad.size:
        raise InputError(
            f"{name} line {lines[int(bad[0])]} column {column}",
            float(values[bad[0]]),
            "a number > 0" if strict else "a number >= 0",
        )


def read_plate_sinkage_csv(path: str | Path) -> PlateSinkageData:
    """Read plate tests: columns ``plate_width_m``, ``sinkage_m``, ``pressure_Pa`` (SI, any order).

    Raises
    ------
    InputError
        Missing file, missing or unknown column, or a bad value (named by file, line and column).
    """
    cols, name, lines = _read_columns(path, PLATE_COLUMNS)
    _check_rows(name, lines, cols["plate_width_m"], "plate_width_m", strict=True)
    _check_rows(name, lines, cols["sinkage_m"], "sinkage_m", strict=False)
    _check_rows(name, lines, cols["pressure_Pa"], "pressure_Pa", strict=False)
    return PlateSinkageData(cols["plate_width_m"], cols["sinkage_m"], cols["pressure_Pa"], name)


def read_shear_csv(path: str | Path) -> ShearData:
    """Read shear tests: columns ``normal_stress_Pa``, ``shear_displacement_m``, ``shear_stress_Pa``.

    Raises
    ------
    InputError
        Missing file, missing or unknown column, or a bad value (named by file, line and column).
    """
    cols, name, lines = _read_columns(path, SHEAR_COLUMNS)
    _check_rows(name, lines, cols["normal_stress_Pa"], "normal_stress_Pa", strict=False)
    return ShearData(cols["normal_stress_Pa"], cols["shear_displacement_m"], cols["shear_stress_Pa"], name)


def _toml_string(text: str) -> str:
    """A TOML basic string."""
    out = ['"']
    for ch in text:
        if ch == "\\":
            out.append("\\\\")
        elif ch == '"':
            out.append('\\"')
        elif ch == "\n":
            out.append("\\n")
        elif ch == "\t":
            out.append("\\t")
        elif ch == "\r":
            out.append("\\r")
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04X}")
        else:
            out.append(ch)
    out.append('"')
    return "".join(out)


def _toml_float(value: float) -> str:
    """A TOML float (``repr`` of a finite float always has a '.' or an exponent)."""
    if not math.isfinite(value):
        raise InputError("bekker", value, "finite parameters")
    return repr(float(value))


def write_material_toml(
    path: str | Path,
    name: str,
    *,
    bekker: BekkerParameters,
    description: str = "",
    citation: str = "",
    doi: str = "",
    table: str = "",
    notes: str = "",
) -> Path:
    """Write a material TOML with Bekker parameters, readable by :func:`terradyn.materials.load`.

    The file is written to a temporary file in the same folder and moved into place
    (``os.replace``), so a reader never sees a partial file.

    Parameters
    ----------
    path : str or Path
        Output file; its folder must exist.
    name : str
        Material name ([meta].name).
    bekker : BekkerParameters
        Parameters to write (SI; the friction angle is written in degrees, ``friction_angle_deg``).
    description, citation, doi, table, notes : str
        Provenance written to [meta] (e.g. which tests, which fit, its R^2).

    Returns
    -------
    Path
        The written file.
    """
    if not isinstance(name, str) or not name.strip():
        raise InputError("name", name, "a non-empty material name")
    if not isinstance(bekker, BekkerParameters):
        raise InputError("bekker", type(bekker).__name__, "BekkerParameters")
    target = Path(path)
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        raise InputError("path", str(path), "a file in an existing folder")
    lines = ["# Written by terradyn.terramechanics.calibration.write_material_toml", "[meta]"]
    lines.append(f"name = {_toml_string(name.strip())}")
    for key, value in (
        ("description", description),
        ("citation", citation),
        ("doi", doi),
        ("table", table),
        ("notes", notes),
    ):
        if value:
            lines.append(f"{key} = {_toml_string(str(value))}")
    lines += [
        "",
        "[bekker]",
        f"k_c_N_per_m_n1 = {_toml_float(bekker.k_c)}",
        f"k_phi_N_per_m_n2 = {_toml_float(bekker.k_phi)}",
        f"n = {_toml_float(bekker.n)}",
        f"cohesion_Pa = {_toml_float(bekker.cohesion)}",
        f"friction_angle_deg = {_toml_float(math.degrees(bekker.friction_angle))}",
        f"shear_modulus_m = {_toml_float(bekker.shear_modulus)}",
        "",
    ]
    from ..io import atomic_write_text

    atomic_write_text(target, "\n".join(lines))
    return target
