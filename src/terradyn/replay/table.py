"""The runs table of :mod:`terradyn.replay`: its columns, and reading and checking one CSV file.

One row is one single-wheel run. Column names carry their unit (``load_N``, ``slip_angle_deg``); the
full list with meanings is in ``docs/replay.md`` and in :data:`COLUMNS`. Every cell is checked when
the table is read; a bad cell raises one :class:`~terradyn.errors.InputError` naming the file, the row
(1 = first data row, the header is not counted), the column, the value and what is allowed.

Slip is the rig definition ``s = (omega r - V) / max(omega r, V)`` in [-1, 1] (V the carriage speed
along the wheel's heading, r the nominal radius): it covers a locked wheel (omega = 0, s = -1) and
every skid. A row gives either ``slip`` or the two speeds ``rim_speed_m_s`` (omega r) and
``carriage_speed_m_s`` (V, the speed of the axle along its direction of travel, which makes the slip
angle with the heading).
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import InputError

__all__ = [
    "COLUMNS",
    "QUANTITIES",
    "RunRow",
    "RunsTable",
    "WheelSpec",
    "read_runs",
    "rig_slip",
    "runs_from_records",
]

#: measured (and predicted) quantities: column name -> (standard-deviation column, meaning)
QUANTITIES: dict[str, tuple[str, str]] = {
    "drawbar_pull_N": ("drawbar_pull_std_N", "horizontal soil force along the heading [N], + forward"),
    "drive_torque_Nm": ("drive_torque_std_Nm", "motor torque [N m], + driving forward"),
    "sinkage_m": ("sinkage_std_m", "depth of the wheel's lowest point below the undisturbed surface [m]"),
    "side_force_N": ("side_force_std_N", "lateral soil force [N], + to the wheel's left (3D models)"),
}

#: every column terradyn reads: name -> meaning (with unit)
COLUMNS: dict[str, str] = {
    "run_id": "name of the run (text; default 'row N')",
    "medium": "medium name (see 'terradyn materials list') or a TOML file, relative to the table",
    "shape": "primitive wheel: circular (default) or grousered",
    "radius_m": "rim radius [m] (primitive wheels)",
    "width_m": "wheel width [m] (primitive wheels)",
    "grouser_count": "number of grousers (lugs) [-] (grousered wheels)",
    "grouser_height_m": "grouser height above the rim [m]",
    "grouser_thickness_m": "grouser thickness [m]",
    "mesh_file": "wheel mesh (STL/OBJ/PLY), closed; path relative to the table",
    "mesh_units": "units of the mesh file coordinates: m (default), cm or mm",
    "mesh_axle": "file axis the wheel turns about: x, y (default) or z (axle centre fitted)",
    "load_N": "vertical load on the axle [N] (load control)",
    "prescribed_sinkage_m": "period-mean depth of the wheel's lowest point [m] (sinkage control)",
    "slip": "rig slip (omega r - V) / max(omega r, V) [-], in [-1, 1]",
    "rim_speed_m_s": "rim speed omega r [m/s] (>= 0), with carriage_speed_m_s instead of slip",
    "carriage_speed_m_s": "speed of the axle over the ground [m/s] (>= 0)",
    "slip_angle_deg": "angle from the heading to the direction of travel [deg], + to the left, in [-90, 90]",
    **{q: f"measured {meaning}" for q, (_, meaning) in QUANTITIES.items()},
    **{std: f"standard deviation of {q} (>= 0, same unit)" for q, (std, _) in QUANTITIES.items()},
}

_UNIT_SUFFIXES = ("_N", "_Nm", "_m", "_m_s", "_deg", "_rad", "_kg", "_Pa", "_s")


@dataclass(frozen=True)
class WheelSpec:
    """The wheel of a run: a primitive (shape, sizes [m]) or a mesh file (path, units)."""

    shape: str = "circular"
    radius: float | None = None
    width: float | None = None
    grouser_count: int = 0
    grouser_height: float = 0.0
    grouser_thickness: float = 0.0
    mesh_file: str | None = None
    mesh_units: str = "m"
    mesh_axle: str = "y"

    @property
    def is_mesh(self) -> bool:
        return self.mesh_file is not None


@dataclass(frozen=True)
class RunRow:
    """One checked run (SI).

    ``omega_r`` and ``travel_speed`` are the rim speed and the axle speed over the ground [m/s] (from
    the two speed columns, or a unit pair of the same ratio when the row gives ``slip``, then
    ``speeds_given`` is False and models run at omega = 1 rad/s); ``slip`` is
    the rig slip; ``slip_angle`` [rad]. Exactly one of ``load`` [N] and ``prescribed_sinkage`` [m].
    ``measured`` and ``std`` map quantity names (:data:`QUANTITIES`) to values; ``extra`` holds the
    other columns as text (group and flag columns).
    """

    index: int
    run_id: str
    medium: str
    wheel: WheelSpec
    load: float | None
    prescribed_sinkage: float | None
    slip: float
    omega_r: float
    travel_speed: float
    slip_angle: float
    measured: dict[str, float] = field(default_factory=dict)
    std: dict[str, float] = field(default_factory=dict)
    extra: dict[str, str] = field(default_factory=dict)
    speeds_given: bool = False


@dataclass(frozen=True)
class RunsTable:
    """A checked runs table: its rows, the extra (non-standard) column names and the source path."""

    rows: tuple[RunRow, ...]
    extra_columns: tuple[str, ...]
    source: str

    def __len__(self) -> int:
        return len(self.rows)

    def column_values(self, column: str) -> list[str]:
        """Text of an extra column (or of a standard one, as written) in row order."""
        if column in self.extra_columns:
            return [r.extra.get(column, "") for r in self.rows]
        if column in ("run_id", "medium"):
            return [getattr(r, column) for r in self.rows]
        if column == "shape":
            return [r.wheel.shape if not r.wheel.is_mesh else "mesh" for r in self.rows]
        if column == "mesh_file":
            return [r.wheel.mesh_file or "" for r in self.rows]
        raise InputError(
            "column",
            column,
            f"a column of the table: {sorted((*self.extra_columns, 'run_id', 'medium', 'shape'))}",
        )


def rig_slip(omega_r: float, travel_speed: float) -> float:
    """Rig slip (omega r - V) / max(omega r, V) [-] of a rim speed and a travel speed [m/s]: the bounded
    definition of :func:`terradyn.kinematics.slip_from_speeds`."""
    from ..kinematics import slip_from_speeds

    return slip_from_speeds(omega_r, travel_speed, definition="bounded")


class _Cells:
    """Typed access to one row's cells with one-line errors naming file, row and column."""

    def __init__(self, where: str, index: int, cells: dict[str, str]) -> None:
        self.where, self.index, self.cells = where, index, cells

    def fail(self, column: str, value: Any, allowed: str, hint: str = "") -> InputError:
        return InputError(f"{self.where} row {self.index} column {column}", value, allowed, hint)

    def text(self, column: str) -> str | None:
        raw = self.cells.get(column)
        if raw is None:
            return None
        raw = raw.strip()
        return raw or None

    def number(
        self, column: str, *, low: float | None = None, high: float | None = None, strict_low: bool = False,
        unit: str = "",
    ) -> float | None:  # fmt: skip
        raw = self.text(column)
        if raw is None:
            return None
        what = _allowed(low, high, strict_low, unit)
        try:
            value = float(raw)
        except ValueError:
            raise self.fail(column, raw, what) from None
        if not math.isfinite(value):
            raise self.fail(column, raw, what)
        if low is not None and (value < low or (strict_low and value == low)):
            raise self.fail(column, raw, what)
        if high is not None and value > high:
            raise self.fail(column, raw, what)
        return value

    def integer(self, column: str, *, low: int = 0) -> int | None:
        raw = self.text(column)
        if raw is None:
            return None
        try:
            value = float(raw)
        except ValueError:
            raise self.fail(column, raw, f"a whole number >= {low}") from None
        if not (math.isfinite(value) and value == int(value) and value >= low):
            raise self.fail(column, raw, f"a whole number >= {low}")
        return int(value)

    def choice(self, column: str, options: tuple[str, ...], default: str) -> str:
        raw = self.text(column)
        if raw is None:
            return default
        if raw.lower() not in options:
            raise self.fail(column, raw, f"one of {list(options)}")
        return raw.lower()


def _allowed(low: float | None, high: float | None, strict_low: bool, unit: str) -> str:
    u = f" [{unit}]" if unit else ""
    if low is not None and high is not None:
        return f"a number in [{low:g}, {high:g}]{u}"
    if low is not None:
        return f"a number {'>' if strict_low else '>='} {low:g}{u}"
    return f"a finite number{u}"


def _check_header(where: str, header: list[str]) -> None:
    seen: set[str] = set()
    for col in header:
        name = col.strip()
        if not name:
            raise InputError(f"{where} header", header, "a name for every column", "a column has no name")
        if name in seen:
            raise InputError(f"{where} header column {name}", name, "each column once", "it appears twice")
        seen.add(name)
        if name not in COLUMNS and name.endswith(_UNIT_SUFFIXES):
            known = sorted(c for c in COLUMNS if c.endswith(_UNIT_SUFFIXES))
            raise InputError(
                f"{where} header column {name}", name, f"a known column with a unit: {known}",
                "other columns (without a unit suffix) are kept as text for --group-by / --calibrate-on",
            )  # fmt: skip
    for need in ("medium",):
        if need not in seen:
            raise InputError(f"{where} header", ",".join(header), f"a '{need}' column")
    if "load_N" not in seen and "prescribed_sinkage_m" not in seen:
        raise InputError(f"{where} header", ",".join(header), "a 'load_N' or a 'prescribed_sinkage_m' column")
    if "slip" not in seen and not {"rim_speed_m_s", "carriage_speed_m_s"} <= seen:
        raise InputError(
            f"{where} header",
            ",".join(header),
            "a 'slip' column or both 'rim_speed_m_s' and 'carriage_speed_m_s'",
        )
    if not (seen & set(QUANTITIES)):
        raise InputError(
            f"{where} header", ",".join(header), f"at least one measured column of {list(QUANTITIES)}"
        )


def _wheel(c: _Cells, base: Path | None) -> WheelSpec:
    mesh = c.text("mesh_file")
    if mesh is not None:
        for col in ("radius_m", "width_m", "grouser_count", "grouser_height_m", "grouser_thickness_m"):
            if c.text(col) is not None:
                raise c.fail(col, c.text(col), "empty when mesh_file is given", "a row has one wheel")
        path = Path(mesh) if base is None or Path(mesh).is_absolute() else base / mesh
        if not path.is_file():
            raise c.fail("mesh_file", mesh, "an existing mesh file", f"{path} does not exist")
        units = c.choice("mesh_units", ("m", "cm", "mm"), "m")
        axle = c.choice("mesh_axle", ("x", "y", "z"), "y")
        return WheelSpec(shape="mesh", mesh_file=str(path), mesh_units=units, mesh_axle=axle)
    shape = c.choice("shape", ("circular", "grousered"), "circular")
    radius = c.number("radius_m", low=0.0, strict_low=True, unit="m")
    width = c.number("width_m", low=0.0, strict_low=True, unit="m")
    if radius is None:
        raise c.fail("radius_m", "", "a radius > 0 [m] (or a mesh_file)")
    if width is None:
        raise c.fail("width_m", "", "a width > 0 [m] (or a mesh_file)")
    if shape == "circular":
        for col in ("grouser_count", "grouser_height_m", "grouser_thickness_m"):
            raw = c.text(col)
            if raw is not None and raw not in ("0", "0.0"):
                raise c.fail(col, raw, "empty or 0 for a circular wheel", "set shape to grousered")
        return WheelSpec("circular", radius, width)
    count = c.integer("grouser_count", low=1)
    height = c.number("grouser_height_m", low=0.0, strict_low=True, unit="m")
    thick = c.number("grouser_thickness_m", low=0.0, strict_low=True, unit="m")
    for col, val in (("grouser_count", count), ("grouser_height_m", height), ("grouser_thickness_m", thick)):
        if val is None:
            raise c.fail(col, "", "a value (required for a grousered wheel)")
    assert count is not None and height is not None and thick is not None
    return WheelSpec("grousered", radius, width, count, height, thick)


def _row(c: _Cells, base: Path | None, extra_columns: tuple[str, ...]) -> RunRow:
    medium = c.text("medium")
    if medium is None:
        raise c.fail("medium", "", "a medium name or TOML file")
    if medium.lower().endswith(".toml") and base is not None and not Path(medium).is_absolute():
        medium = str(base / medium)
    wheel = _wheel(c, base)
    load = c.number("load_N", low=0.0, strict_low=True, unit="N")
    sink = c.number("prescribed_sinkage_m", low=0.0, unit="m")
    if (load is None) == (sink is None):
        which = "load_N" if load is None else "prescribed_sinkage_m"
        raise c.fail(which, c.text(which) or "", "exactly one of load_N and prescribed_sinkage_m per row")
    slip = c.number("slip", low=-1.0, high=1.0)
    rim = c.number("rim_speed_m_s", low=0.0, unit="m/s")
    travel = c.number("carriage_speed_m_s", low=0.0, unit="m/s")
    speeds_given = slip is None
    if slip is not None:
        if rim is not None or travel is not None:
            col = "rim_speed_m_s" if rim is not None else "carriage_speed_m_s"
            raise c.fail(col, c.text(col), "empty when slip is given", "give slip or the two speeds")
        rim, travel = (1.0, 1.0 - slip) if slip >= 0 else (1.0 + slip, 1.0)
    else:
        if rim is None or travel is None:
            col = "rim_speed_m_s" if rim is None else "carriage_speed_m_s"
            raise c.fail(col, "", "a speed >= 0 [m/s] (or a slip)")
        if rim == 0.0 and travel == 0.0:
            raise c.fail(
                "carriage_speed_m_s", c.text("carriage_speed_m_s"), "a speed > 0 when the rim is at rest"
            )
        slip = rig_slip(rim, travel)
    angle = c.number("slip_angle_deg", low=-90.0, high=90.0, unit="deg") or 0.0
    measured: dict[str, float] = {}
    std: dict[str, float] = {}
    for q, (sd, _) in QUANTITIES.items():
        low = 0.0 if q == "sinkage_m" else None
        value = c.number(q, low=low)
        if value is not None:
            measured[q] = value
        spread = c.number(sd, low=0.0)
        if spread is not None:
            if value is None:
                raise c.fail(sd, c.text(sd), f"empty when {q} is empty")
            std[q] = spread
    if not measured:
        raise c.fail("/".join(QUANTITIES), "", "at least one measured value per row")
    run_id = c.text("run_id") or f"row {c.index}"
    extra = {k: (c.text(k) or "") for k in extra_columns}
    return RunRow(
        c.index, run_id, medium, wheel, load, sink, float(slip), float(rim), float(travel),
        math.radians(angle), measured, std, extra, speeds_given,
    )  # fmt: skip


def runs_from_records(
    records: list[dict[str, Any]], *, source: str = "runs", base: str | Path | None = None
) -> RunsTable:
    """A checked :class:`RunsTable` from dicts (column -> value; None or "" for an empty cell)."""
    if not records:
        raise InputError(source, "no rows", "a table with at least one run")
    header: list[str] = []
    for rec in records:
        header += [k for k in rec if k not in header]
    _check_header(source, header)
    extra = tuple(h.strip() for h in header if h.strip() not in COLUMNS)
    root = None if base is None else Path(base)
    rows = []
    for i, rec in enumerate(records, start=1):
        cells = {str(k).strip(): ("" if v is None else str(v)) for k, v in rec.items()}
        rows.append(_row(_Cells(source, i, cells), root, extra))
    ids = [r.run_id for r in rows]
    if len(set(ids)) != len(ids):
        dup = next(x for x in ids if ids.count(x) > 1)
        raise InputError(f"{source} column run_id", dup, "a distinct run_id per row", "it appears twice")
    return RunsTable(tuple(rows), extra, source)


def read_runs(path: str | Path) -> RunsTable:
    """Read and check a runs table (CSV with a header row; ``#`` lines are comments)."""
    p = Path(path)
    where = p.name
    if not p.is_file():
        raise InputError("runs table", str(path), "an existing CSV file", "no such file")
    try:
        text = p.read_text(encoding="utf-8-sig")
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError("runs table", str(path), "a readable UTF-8 CSV file", str(exc)) from None
    lines = [ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    if not lines:
        raise InputError(
            "runs table", str(path), "a CSV file with a header and at least one row", "it is empty"
        )
    reader = csv.reader(lines)
    header = [h.strip() for h in next(reader)]
    records = []
    for i, cells in enumerate(reader, start=1):
        if len(cells) != len(header):
            raise InputError(
                f"{where} row {i}", f"{len(cells)} cells", f"{len(header)} cells (one per header column)"
            )
        records.append(dict(zip(header, cells, strict=True)))
    if not records:
        raise InputError("runs table", str(path), "a CSV file with at least one row after the header")
    return runs_from_records(records, source=where, base=p.parent)
