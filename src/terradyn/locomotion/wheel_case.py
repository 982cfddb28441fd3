"""The wheel-run contract's data: the case, the engines' settings and the one result type
(:func:`terradyn.locomotion.run_wheel` runs them; this module documents the contract).

One wheel-run contract for every engine: a frozen case, engine settings as their own specs, one result.

"RFT versus dynamic RFT versus MPM versus DEM on the same wheel" is one call with a different model::

    case = WheelCase(WheelCircular(0.13, 0.16), "MS", load=130.0, slip=0.3)
    runs = [run_wheel(case, m) for m in ("rft", "drft", "mpm", "dem")]

* :class:`WheelCase` says what is run: the wheel (a plane :class:`~terradyn.geometry.Body`, or a
  :class:`~terradyn.geometry3d.TriangleMesh` for 3D RFT), the medium (one
  :class:`~terradyn.materials.Material` for every model: each reads its own parameters), the vertical
  load (or a prescribed sinkage), the drive (a slip, the rim and carriage speeds, free rolling, or a
  motor torque), the slip angle and, for time-stepped engines, the simulated time.
* The model is a name of the model table (:mod:`terradyn.models`: ``rft``, ``drft``, ``rft-ss``,
  ``wong-reece``, ``rft3d``, ``mpm``, ``dem``) or a user's terrain model (an object with
  ``wrench(body, pose, twist)`` or a plain function).
* How it is run is a settings spec: :class:`QuasiStatic` (the default for force laws: the implicit
  steady solves), :class:`Dynamics` (time integration of the wheel's free motion through a force law),
  :class:`MPMSettings` and :class:`DEMSettings` (the engines' own beds, resolutions and outputs).
* :class:`WheelRun` has the same summary keys whatever ran (:data:`SUMMARY_KEYS`; None where an
  engine does not give a quantity, e.g. the side force of a plane model), the time series of the
  time-stepped engines under the same column names (:data:`HISTORY_KEYS`), the engine's metadata and
  its own result object (``raw``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from enum import Enum
from typing import Any

import numpy as np

from ..errors import InputError, check_finite, check_positive
from ..kinematics import SlipDefinition, as_slip_definition, slip_from_speeds
from ..materials import Material
from ..models import as_terrain_model

__all__ = [
    "HISTORY_KEYS",
    "SUMMARY_KEYS",
    "DEMSettings",
    "Dynamics",
    "Engine",
    "MPMSettings",
    "QuasiStatic",
    "Settings",
    "WheelCase",
    "WheelRun",
]

#: the summary every engine returns (SI, unit-suffixed; None where the engine gives no value)
SUMMARY_KEYS = (
    "sinkage_m",
    "drawbar_pull_N",
    "drive_torque_Nm",
    "vertical_force_N",
    "side_force_N",
    "slip",
    "omega_rad_s",
    "forward_velocity_m_s",
    "load_N",
    "power_W",
)
#: the time-series columns of time-stepped engines (those an engine records)
HISTORY_KEYS = (
    "time_s",
    "x_m",
    "sinkage_m",
    "drawbar_pull_N",
    "vertical_force_N",
    "drive_torque_Nm",
    "omega_rad_s",
    "forward_velocity_m_s",
)


class Engine(str, Enum):
    """How a case is computed."""

    QUASI_STATIC = "quasi-static"
    DYNAMICS = "dynamics"
    MPM = "mpm"
    DEM = "dem"


@dataclass(frozen=True)
class WheelCase:
    """What is run: one wheel on one medium under one drive (SI; angles in rad).

    Attributes
    ----------
    wheel : plane Body (origin at the axle; out-of-plane width its own) or, for 3D RFT, a TriangleMesh
        (axle along y through the origin). A plane WheelCircular / WheelGrousered runs in 3D RFT too.
    medium : a Material or a medium name (:func:`terradyn.materials.get`)
    load : vertical load on the axle [N] (the wheel's weight included), or None with ``sinkage``
    sinkage : prescribed sinkage [m] instead of a load (quasi-static force laws only)
    slip : longitudinal slip [-] (``slip_definition``); None: free rolling (self-propelled) unless
        ``rim_speed``/``carriage_speed`` give it
    slip_definition : "classic" s = 1 - V/(omega r) or "bounded" (U - V)/max(U, V) (locked wheels)
    rim_speed, carriage_speed : U = omega r and V [m/s] instead of ``slip`` and ``omega`` (both or none)
    omega : spin [rad/s] about +y (> 0), the spin reference of a bounded slip
    drive_torque : motor torque [N m] (+ forward) instead of a prescribed spin (time-stepped engines)
    drawbar_load : horizontal load resisting a free wheel [N] (+ backwards)
    slip_angle : angle between the wheel's heading and its travel [rad] (3D RFT)
    duration : simulated time of the drive [s] (time-stepped engines; None: the engine's default)
    """

    wheel: Any
    medium: Material | str
    load: float | None = None
    sinkage: float | None = None
    slip: float | None = None
    slip_definition: SlipDefinition | str = SlipDefinition.CLASSIC
    rim_speed: float | None = None
    carriage_speed: float | None = None
    omega: float = 1.0
    drive_torque: float | None = None
    drawbar_load: float = 0.0
    slip_angle: float = 0.0
    duration: float | None = None

    def __post_init__(self) -> None:
        if (self.load is None) == (self.sinkage is None):
            raise InputError("load", self.load, "a load [N] or a sinkage [m], exactly one of them")
        if self.load is not None:
            check_positive("load", self.load)
        if self.sinkage is not None:
            check_positive("sinkage", self.sinkage, allow_zero=True)
        object.__setattr__(self, "slip_definition", as_slip_definition(self.slip_definition))
        self._check_drive()
        check_finite("drawbar_load", self.drawbar_load)
        angle = check_finite("slip_angle", self.slip_angle)
        if not abs(angle) < math.pi / 2:
            raise InputError("slip_angle", self.slip_angle, "an angle in (-pi/2, pi/2) [rad]")
        if self.duration is not None:
            check_positive("duration", self.duration)

    def _check_drive(self) -> None:
        speeds = (self.rim_speed is not None, self.carriage_speed is not None)
        if any(speeds) and not all(speeds):
            raise InputError("rim_speed", self.rim_speed, "both rim_speed and carriage_speed, or neither")
        if all(speeds) and self.slip is not None:
            raise InputError("slip", self.slip, "unset with rim_speed and carriage_speed (they give it)")
        if self.drive_torque is not None and (self.slip is not None or all(speeds)):
            raise InputError(
                "drive_torque", self.drive_torque, "unset with a slip (a torque leaves the spin free)"
            )
        if self.drive_torque is not None:
            check_finite("drive_torque", self.drive_torque)
        if self.slip is not None:
            check_finite("slip", self.slip)
        check_positive("omega", self.omega)

    @property
    def material(self) -> Material:
        """The medium as a Material."""
        if isinstance(self.medium, Material):
            return self.medium
        from .. import materials

        return materials.get(self.medium)

    @property
    def radius(self) -> float:
        """Nominal (outer) radius [m] of the wheel."""
        r = getattr(self.wheel, "outer_radius", None)
        if r is not None:
            return float(r)
        from ..geometry import Body

        if isinstance(self.wheel, Body):
            return float(self.wheel.bounding_radius)
        from .steady3d import wheel_nominal_radius_3d

        return wheel_nominal_radius_3d(self.wheel)

    def drive(self) -> tuple[float | None, float]:
        """(slip in the case's definition or None for a free wheel, spin reference omega [rad/s])."""
        if self.rim_speed is None or self.carriage_speed is None:
            return self.slip, self.omega
        slip = slip_from_speeds(self.rim_speed, self.carriage_speed, definition=self.slip_definition)
        top = max(abs(self.rim_speed), abs(self.carriage_speed))
        return slip, top / self.radius

    def classic_slip(self) -> float | None:
        """The slip as s = 1 - V/(omega r) (what the time-stepped engines prescribe); None when free."""
        slip, _ = self.drive()
        if slip is None or self.slip_definition is SlipDefinition.CLASSIC:
            return slip
        from ..kinematics import slip_convert

        return slip_convert(slip, source=self.slip_definition, target=SlipDefinition.CLASSIC)


@dataclass(frozen=True)
class QuasiStatic:
    """Implicit steady solves of a force law: the sinkage that carries the load at the slip.

    ``phase_count``: wheel angles averaged over one period of a lugged wheel; ``element_size`` [m]:
    discretisation of plane bodies for named RFT models (None: the body's); ``cull``: 3D RFT drops
    the facets of a mesh the medium cannot reach."""

    phase_count: int = 16
    element_size: float | None = None
    cull: bool = True


@dataclass(frozen=True)
class Dynamics:
    """Time integration of the wheel's motion through a force law (x and z free under the load).

    ``dt`` [s] (None: the integrator's stable step); ``output_every``: record every N-th step;
    ``mass`` [kg] (None: load / g); ``element_size`` as :class:`QuasiStatic`. A free wheel through
    ``rft`` or ``drft`` runs in the compiled integrator (:func:`terradyn.locomotion.simulate_wheel`);
    a prescribed slip or another force law through :func:`terradyn.locomotion.simulate_coupled`."""

    dt: float | None = None
    output_every: int = 10
    mass: float | None = None
    element_size: float | None = None
    gravity: float = 9.81


@dataclass(frozen=True)
class MPMSettings:
    """The MPM engine's specs (:mod:`terradyn.mpm.specs`): bed, resolution, outputs and drive phases
    (None: the engine's defaults; the case's ``duration`` overrides ``drive.duration``)."""

    bed: Any = None
    resolution: Any = None
    outputs: Any = None
    drive: Any = None


@dataclass(frozen=True)
class DEMSettings:
    """The DEM engine's settings (:func:`terradyn.dem.run_wheel`): grain diameter [m] (None: the
    medium's), bed kind and packing, seed, a prepared ``bed`` (None: settle one), record interval [s],
    checkpoint path and resume."""

    grain_diameter: float | None = None
    kind: str = "slab"
    packing: str = "dense"
    seed: int = 12345
    bed: Any = None
    record_interval: float | None = None
    checkpoint_path: str | None = None
    resume: bool = False


Settings = QuasiStatic | Dynamics | MPMSettings | DEMSettings


@dataclass(frozen=True, eq=False)
class WheelRun:
    """The result of :func:`run_wheel`: the same keys whatever engine ran.

    ``summary``: :data:`SUMMARY_KEYS` (time-stepped engines: averaged over the end of the drive);
    ``history``: :data:`HISTORY_KEYS` columns a time-stepped engine recorded (empty for quasi-static
    solves); ``metadata``: the engine's own facts (bed, grains, averaging window...); ``raw``: the
    engine's own result object."""

    model: str
    engine: Engine
    case: WheelCase
    summary: dict[str, float | None]
    history: dict[str, np.ndarray] = field(default_factory=dict)
    metadata: dict[str, Any] = field(default_factory=dict)
    raw: Any = None

    def to_dict(self) -> dict[str, Any]:
        """One JSON-able record: model, engine and the summary."""
        return {"model": self.model, "engine": self.engine.value, **self.summary}

    def to_dataframe(self) -> Any:
        """The history as a pandas DataFrame."""
        import pandas as pd

        return pd.DataFrame({k: np.asarray(v) for k, v in self.history.items()})


def _summary(**values: Any) -> dict[str, float | None]:
    unknown = set(values) - set(SUMMARY_KEYS)
    assert not unknown, unknown
    return {k: (None if values.get(k) is None else float(values[k])) for k in SUMMARY_KEYS}


def _power(torque: float | None, omega: float | None) -> float | None:
    return None if torque is None or omega is None else torque * omega


def _force_law(model: Any, entry: Any, material: Material, element_size: float | None) -> Any:
    """The terrain model object: a named model built on the medium, or the user's as it is."""
    if entry is None:
        return as_terrain_model(model)
    options: dict[str, Any] = {}
    if entry.name in ("rft", "drft", "rft-ss") and element_size is not None:
        options["element_size"] = element_size
    return entry.build(material, **options)
