"""Frozen, validated specs of an MPM run: the bed, the resolution, the outputs and the run length.

A case (:func:`~terradyn.mpm.run_intrusion`, :func:`~terradyn.mpm.run_wheel`,
:class:`~terradyn.mpm.MPMTerrain`, the verification studies) takes its settings as a few specs rather
than thirty keywords, so a new case reuses them instead of copying a signature::

    from terradyn.mpm import Bed, Outputs, Resolution, Stroke, run_intrusion

    bed = Bed(packing="unconsolidated", depth=0.2)          # None sizes = the case's sizing rule
    fine = Resolution(cell_size=0.002, particles_per_cell=3)
    res = run_intrusion(plate, ms, depth=0.03, bed=bed, resolution=fine, stroke=Stroke(0.004))

Each spec checks its fields when it is made and raises :class:`~terradyn.errors.InputError` naming the
field as the run functions always have (``cell_size``, ``bed_depth``, ``record_interval``...), so the
CLI maps a bad value back to the flag the user typed. Specs are immutable and hashable; ``replace``
returns a changed copy, and the repr lists only the fields that differ from the defaults.

The run functions still take the old flat keywords (``cell_size=``, ``bed_depth=``...): each maps
through the one table :data:`LEGACY` to a spec field.
"""

from __future__ import annotations

import dataclasses
import numbers
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from enum import Enum
from pathlib import Path
from typing import Any, ClassVar, TypeVar

from ..errors import InputError, check_positive, check_range
from .bodies import ContactScheme
from .model import BedPacking, Wall, Walls

__all__ = [
    "LEGACY",
    "MODEL_OVERRIDES",
    "Bed",
    "Drive",
    "Outputs",
    "Resolution",
    "Stroke",
    "apply_legacy",
]

S = TypeVar("S", bound="_Spec")


class _Spec:
    """Shared behaviour: a short repr, ``replace`` and the message name of each field."""

    #: field -> the name error messages (and the legacy keywords) use for it
    _NAMES: ClassVar[dict[str, str]] = {}

    def replace(self: S, **changes: Any) -> S:
        """A copy with ``changes`` (checked like a new spec)."""
        return dataclasses.replace(self, **changes)  # type: ignore[type-var]

    @classmethod
    def message_name(cls, name: str) -> str:
        return cls._NAMES.get(name, name)

    def __repr__(self) -> str:
        default = type(self)()
        parts = [
            f"{f.name}={_show(getattr(self, f.name))}"
            for f in dataclasses.fields(self)  # type: ignore[arg-type]
            if getattr(self, f.name) != getattr(default, f.name)
        ]
        return f"{type(self).__name__}({', '.join(parts)})"


def _show(value: Any) -> str:
    """A field value as one would type it (enums by value, paths as strings)."""
    if isinstance(value, Enum):
        return repr(value.value)
    if isinstance(value, Path):
        return repr(str(value))
    return repr(value)


def _set(spec: object, name: str, value: Any) -> None:
    object.__setattr__(spec, name, value)


def _optional_positive(name: str, value: Any, *, allow_zero: bool = False) -> None:
    if value is not None:
        check_positive(name, value, allow_zero=allow_zero)


def _path(name: str, value: Any) -> Path | None:
    if value is None:
        return None
    if not isinstance(value, str | Path) or str(value) == "":
        raise InputError(name, value, "a file system path (str or pathlib.Path) or None")
    return Path(value)


def _integer(name: str, value: Any, low: int, high: int | None, allowed: str) -> int:
    whole = isinstance(value, numbers.Integral) or (isinstance(value, float) and value.is_integer())
    if isinstance(value, bool) or not whole:
        raise InputError(name, value, allowed)
    v = int(value)
    if v < low or (high is not None and v > high):
        raise InputError(name, value, allowed)
    return v


@dataclass(frozen=True, repr=False)
class Bed(_Spec):
    """The granular bed: initial state, walls, gravity and size.

    packing : :class:`BedPacking` (``"consolidated"`` or ``"unconsolidated"``).
    density : initial bulk density [kg/m^3] (None: the packing's default; checked against the
        material's critical density when the bed is made).
    walls : :class:`Walls`, one :class:`Wall` or a kind for all sides (default free-slip).
    gravity : [m/s^2].
    depth, width : depth of the grains and their extent along x [m] (a wheel run calls it the bed
        length); None = the case's sizing rule (see :func:`~terradyn.mpm.run_intrusion`,
        :func:`~terradyn.mpm.run_wheel`); :class:`~terradyn.mpm.MPMTerrain` needs both.
    settle_time : damped settling under gravity before the body moves [s] (None: 40 P-wave transits
        of the bed, plus a compaction time for an unconsolidated bed; 0 skips settling).
    window : length [m] of the moving window of grains that is stepped around the body (see
        :class:`~terradyn.mpm.solver.Runner`); 0 = the whole bed. None = the case's rule: a wheel
        run keeps the wheel and its bed margin on either side (the bed around its start), an
        intrusion steps the whole bed. A wheel's window (given or not) grows ahead of the heap the
        wheel pushes, keeping its margin clear of it. :class:`~terradyn.mpm.MPMTerrain` steps the
        whole bed.
    surface_offset : the grid's phase against the free surface, a fraction of a cell in [0, 1) and a
        multiple of 1 / ``particles_per_cell`` (default 0: the surface on a node line; see
        :class:`~terradyn.mpm.solver.BedGrid`). Runs at several offsets measure how much a result
        depends on where the grid lies.
    """

    packing: BedPacking | str = BedPacking.CONSOLIDATED
    density: float | None = None
    walls: Walls | Wall | str | None = field(default_factory=Walls)
    gravity: float = 9.81
    depth: float | None = None
    width: float | None = None
    settle_time: float | None = None
    window: float | None = None
    surface_offset: float = field(default=0.0, metadata={"omit_default": True})

    _NAMES: ClassVar[dict[str, str]] = {"density": "bed_density", "depth": "bed_depth", "width": "bed_width"}

    def __post_init__(self) -> None:
        try:
            _set(self, "packing", BedPacking(self.packing))
        except ValueError:
            raise InputError("packing", self.packing, "'consolidated' or 'unconsolidated'") from None
        _optional_positive("bed_density", self.density)
        try:
            _set(self, "walls", Walls.coerce(self.walls))
        except InputError:
            kinds = "a Walls, a Wall or one of 'free-slip', 'no-slip', 'frictional'"
            raise InputError("walls", self.walls, kinds) from None
        _set(self, "gravity", check_range("gravity", self.gravity, 0.01, 100.0, unit="m/s^2"))
        _optional_positive("bed_depth", self.depth)
        _optional_positive("bed_width", self.width)
        _optional_positive("settle_time", self.settle_time, allow_zero=True)
        _optional_positive("window", self.window, allow_zero=True)
        from .solver import check_surface_offset

        _set(self, "surface_offset", check_surface_offset(self.surface_offset))


#: the choices of :attr:`Resolution.volumetric`
VOLUMETRIC = ("point", "patch")


@dataclass(frozen=True, repr=False)
class Resolution(_Spec):
    """How finely the grains and the grid resolve the case.

    cell_size : grid spacing [m]; None = body diameter / 20 for intrusions, / 32 for wheels
        (terradyn.mpm.runs.INTRUSION_CELLS_ACROSS, terradyn.mpm.wheel_runs.WHEEL_CELLS_ACROSS).
    particles_per_cell : material points per cell along each axis (1-4).
    cfl : time step as a fraction of the cell crossing time of the fastest wave (<= 0.5). A smaller
        step is not more accurate: at coarse cells a moving body's force grows as cfl falls, most
        likely because each step's particle-grid transfer dissipates (60 mm plate, 6 cells across,
        0.05 m/s: +6 % at 0.15, +26 % at 0.075; 12 across: +0.9 % at 0.15; docs/mpm.md "Time step
        and loading speed").
    contact : grid contact scheme (:class:`~terradyn.mpm.bodies.ContactScheme`), ``"two-field"``
        (bodies need no thickness; a node behind the body surface is in contact), ``"two-field-gap"``
        (the same, in contact once the grains themselves reach the body: no compression at a distance,
        docs/mpm.md "Contact at a distance") or the legacy ``"cover"``.
    min_cells_across : the fewest cells accepted across the body's diameter (None: 6 for intrusions,
        8 for wheels).
    volumetric : the velocity divergence each point's volume and stress take: ``"point"`` (default)
        its own (the classical update, which locks) or ``"patch"`` the volume-weighted mean over the
        points of its nearest node's cell (B-bar, against volumetric locking of isochoric plastic
        flow; see docs/mpm.md "Volumetric locking"; not the default while a symmetric plate still
        feels a small torque with it).
    flip : FLIP fraction in [0, 1] of the grains' velocity update (0, the default: APIC alone). APIC
        drops the non-affine part of the grid velocity around each point every step, a numerical
        viscosity of order h^2 / dt whose force grows with speed / cfl and does not fade with
        refinement where the flow localises at the cell scale; 0.99 removes most of it (node strip
        footing, B/10, 0.01 m/s: 22.09 -> 16.34 against the slow-push 15.9-16.5; docs/mpm.md "What the
        rate error is"). Points next to a thin body's far-side grain field keep APIC.
    """

    cell_size: float | None = None
    particles_per_cell: int = 2
    cfl: float = 0.3
    contact: ContactScheme | str = ContactScheme.TWO_FIELD
    min_cells_across: int | None = None
    volumetric: str = "point"
    flip: float = 0.0

    def __post_init__(self) -> None:
        _optional_positive("cell_size", self.cell_size)
        _set(self, "flip", check_range("flip", self.flip, 0.0, 1.0))
        ppc = _integer("particles_per_cell", self.particles_per_cell, 1, 4, "1, 2, 3 or 4 per direction")
        _set(self, "particles_per_cell", ppc)
        hint = "explicit MPM is stable for cfl <= 0.5"
        _set(self, "cfl", check_range("cfl", self.cfl, 1e-3, 0.5, hint=hint))
        _set(self, "contact", ContactScheme.coerce(self.contact))
        if self.min_cells_across is not None:
            n = _integer("min_cells_across", self.min_cells_across, 2, None, "an integer >= 2")
            _set(self, "min_cells_across", n)
        if self.volumetric not in VOLUMETRIC:
            raise InputError("volumetric", self.volumetric, "'point' or 'patch'")


@dataclass(frozen=True, repr=False)
class Outputs(_Spec):
    """What a run writes and reports besides its result; none of it changes the physics.

    record_interval : simulated time [s] per recorded row (forces are averaged over it); or, for
        intrusions, ``record_spacing`` [m] of travel per row (default a quarter cell of travel;
        wheels: duration / 200). Give at most one.
    snapshot_dir : folder for particle NetCDF snapshots (fields extra), written every
        ``snapshot_interval`` [s] (wheels, default duration / 20) or ``snapshot_spacing`` [m] of
        travel (intrusions, default 4 cells).
    checkpoint_path, checkpoint_interval, resume : checkpoint file (.npz), wall-clock seconds between
        checkpoints, and whether to continue the run saved there (it must exist).
    progress : callable ``(simulated_time_s, fraction_done)``.
    frame_count : light copies of the state kept during the motion (``result.frames``), 0-2000.
    """

    record_interval: float | None = None
    record_spacing: float | None = None
    snapshot_dir: Path | None = None
    snapshot_interval: float | None = None
    snapshot_spacing: float | None = None
    checkpoint_path: Path | None = None
    checkpoint_interval: float = 60.0
    resume: bool = False
    progress: Callable[[float, float], None] | None = None
    frame_count: int = 0

    def __post_init__(self) -> None:
        for name in ("record_interval", "record_spacing", "snapshot_interval", "snapshot_spacing"):
            _optional_positive(name, getattr(self, name))
        for a, b in (("record_spacing", "record_interval"), ("snapshot_spacing", "snapshot_interval")):
            if getattr(self, a) is not None and getattr(self, b) is not None:
                raise InputError(a, getattr(self, a), f"None when {b} is given", "give one of them")
        _set(self, "snapshot_dir", _path("snapshot_dir", self.snapshot_dir))
        _set(self, "checkpoint_path", _path("checkpoint_path", self.checkpoint_path))
        _set(self, "checkpoint_interval", check_positive("checkpoint_interval", self.checkpoint_interval))
        if not isinstance(self.resume, bool):
            raise InputError("resume", self.resume, "True or False")
        if self.resume and self.checkpoint_path is None:
            raise InputError("resume", True, "resume together with checkpoint_path", "give the file")
        if self.progress is not None and not callable(self.progress):
            raise InputError(
                "progress", self.progress, "a callable (simulated_time_s, fraction_done) or None"
            )
        _set(
            self, "frame_count", _integer("frame_count", self.frame_count, 0, 2000, "an integer in [0, 2000]")
        )


@dataclass(frozen=True, repr=False)
class Stroke(_Spec):
    """Run length of an intrusion: the body moves until its reference point has passed the
    ``averaging_window`` [m] centred on the report depth (the summary averages over it; None:
    ``max(4 cell_size, 0.2 depth)``)."""

    averaging_window: float | None = None

    def __post_init__(self) -> None:
        _optional_positive("averaging_window", self.averaging_window)


@dataclass(frozen=True, repr=False)
class Drive(_Spec):
    """Run length of a wheel: ``sink_time`` [s] sinking under the load (None: ``3 sqrt(reach / g)``),
    then ``duration`` [s] of driving (None: ``spin_up`` plus 4.5 rad of rotation, ``4.5 / |omega|``;
    torque-driven ``20 sqrt(reach / g)``); the summary averages the last ``average_fraction``
    (0.05-1) of the drive. ``spin_up`` [s] (0: the wheel starts at full spin) ramps the prescribed
    spin, and a prescribed forward speed with it (the slip stays as set), linearly from rest over the
    first ``spin_up`` of the drive (a rate of ``omega / spin_up``); it must end before the averaged
    part of the drive begins. ``initial_speed`` [m/s] is the forward velocity a wheel whose forward
    motion is free (self-propelled or towing) has when the drive starts (0: from rest)."""

    sink_time: float | None = None
    duration: float | None = None
    average_fraction: float = 0.5
    spin_up: float = 0.0
    initial_speed: float = 0.0

    def __post_init__(self) -> None:
        _optional_positive("sink_time", self.sink_time, allow_zero=True)
        _optional_positive("duration", self.duration)
        _set(self, "spin_up", check_positive("spin_up", self.spin_up, allow_zero=True))
        _set(
            self, "initial_speed", check_range("initial_speed", self.initial_speed, -100.0, 100.0, unit="m/s")
        )
        _set(self, "average_fraction", check_range("average_fraction", self.average_fraction, 0.05, 1.0))


#: the flat keywords of the run functions before specs: keyword -> (spec argument, field)
LEGACY: dict[str, tuple[str, str]] = {
    "packing": ("bed", "packing"),
    "bed_density": ("bed", "density"),
    "walls": ("bed", "walls"),
    "gravity": ("bed", "gravity"),
    "bed_depth": ("bed", "depth"),
    "bed_width": ("bed", "width"),
    "bed_length": ("bed", "width"),
    "settle_time": ("bed", "settle_time"),
    "cell_size": ("resolution", "cell_size"),
    "particles_per_cell": ("resolution", "particles_per_cell"),
    "cfl": ("resolution", "cfl"),
    "contact": ("resolution", "contact"),
    "min_cells_across": ("resolution", "min_cells_across"),
    "record_interval": ("outputs", "record_interval"),
    "record_spacing": ("outputs", "record_spacing"),
    "snapshot_dir": ("outputs", "snapshot_dir"),
    "snapshot_interval": ("outputs", "snapshot_interval"),
    "snapshot_spacing": ("outputs", "snapshot_spacing"),
    "checkpoint_path": ("outputs", "checkpoint_path"),
    "checkpoint_interval": ("outputs", "checkpoint_interval"),
    "resume": ("outputs", "resume"),
    "progress": ("outputs", "progress"),
    "frame_count": ("outputs", "frame_count"),
    "averaging_window": ("stroke", "averaging_window"),
    "sink_time": ("drive", "sink_time"),
    "duration": ("drive", "duration"),
    "average_fraction": ("drive", "average_fraction"),
    "spin_up": ("drive", "spin_up"),
    "initial_speed": ("drive", "initial_speed"),
}

#: keywords that override single parameters of the material's continuum model
MODEL_OVERRIDES = (
    "youngs_modulus",
    "poisson_ratio",
    "friction_coefficient",
    "surface_friction",
    "rate_dependent",
    "dilatancy",
)


def apply_legacy(
    function: str,
    legacy: Mapping[str, Any],
    specs: Mapping[str, Any],
    *,
    exclude: frozenset[str] = frozenset(),
) -> tuple[dict[str, Any], dict[str, Any]]:
    """Fold the flat keywords ``legacy`` of ``function`` into its ``specs`` (argument name -> spec).

    Returns the updated specs and the model overrides (:data:`MODEL_OVERRIDES`). A keyword that is
    neither, belongs to a spec ``function`` does not take, or is in ``exclude`` raises TypeError as
    Python does; so does a keyword given beside a non-default spec of its own (say ``cell_size=``
    with ``resolution=Resolution(...)``): give one or the other. A bad value raises
    :class:`InputError` naming the keyword.
    """
    overrides: dict[str, Any] = {}
    changes: dict[str, dict[str, tuple[str, Any]]] = {}
    for name, value in legacy.items():
        if name in MODEL_OVERRIDES:
            overrides[name] = value
            continue
        target = LEGACY.get(name)
        if target is None or target[0] not in specs or name in exclude:
            raise TypeError(f"{function}() got an unexpected keyword argument {name!r}")
        changes.setdefault(target[0], {})[target[1]] = (name, value)
    out = dict(specs)
    for arg, fields in changes.items():
        spec = specs[arg]
        if spec != type(spec)():
            names = ", ".join(repr(n) for n, _ in fields.values())
            raise TypeError(f"{function}() got {names} beside {arg}={spec!r}: set it in the spec instead")
        try:
            out[arg] = dataclasses.replace(spec, **{f: v for f, (_, v) in fields.items()})
        except InputError as exc:
            for f, (name, _) in fields.items():  # name the keyword the caller wrote
                if exc.field == spec.message_name(f) and name != exc.field:
                    raise InputError(name, exc.value, exc.allowed, exc.hint) from None
            raise
    return out, overrides
