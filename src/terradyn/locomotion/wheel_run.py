"""One wheel-run contract for every engine: a frozen case, engine settings as their own specs, one result.

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
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from enum import Enum
from typing import Any

import numpy as np

from ..errors import InputError, check_finite, check_positive
from ..kinematics import SlipDefinition, as_slip_definition, slip_from_speeds
from ..materials import Material
from ..models import ModelKind, as_terrain_model, model_entry

__all__ = [
    "HISTORY_KEYS",
    "SUMMARY_KEYS",
    "DEMSettings",
    "Dynamics",
    "Engine",
    "MPMSettings",
    "QuasiStatic",
    "WheelCase",
    "WheelRun",
    "compare_models",
    "run_wheel",
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


def run_wheel(
    case: WheelCase,
    model: Any = "rft",
    *,
    settings: Settings | None = None,
    progress: Callable[[float, float], None] | None = None,
) -> WheelRun:
    """Run ``case`` through ``model`` (a model-table name or a user's terrain model) with ``settings``
    (:class:`QuasiStatic` by default for force laws; :class:`MPMSettings` / :class:`DEMSettings` for
    the engines). ``progress(simulated_time, fraction)`` reports time-stepped runs. A model that
    cannot run the case (a 2D law with a slip angle, a torque in a steady solve, a free wheel in the
    DEM...) raises :class:`~terradyn.errors.InputError` naming the field."""
    if not isinstance(case, WheelCase):
        raise InputError("case", type(case).__name__, "a terradyn.locomotion.WheelCase")
    name = model.strip().lower() if isinstance(model, str) else None
    entry = model_entry(model, use="run-wheel") if name is not None else None
    if entry is not None and entry.kind is ModelKind.ENGINE:
        from . import _wheel_engines as engines

        if entry.name == "mpm":
            return engines.run_mpm(case, _settings(settings, MPMSettings, "mpm"), progress)
        return engines.run_dem(case, _settings(settings, DEMSettings, "dem"), progress)
    if isinstance(settings, Dynamics):
        from ._wheel_engines import run_dynamics

        return run_dynamics(case, model, entry, settings, progress)
    return _run_quasi_static(case, model, entry, _settings(settings, QuasiStatic, "a force law"))


def _settings(settings: Any, kind: type, what: str) -> Any:
    if settings is None:
        return kind()
    if not isinstance(settings, kind):
        raise InputError("settings", type(settings).__name__, f"a {kind.__name__} (or None) for {what}")
    return settings


def _force_law(model: Any, entry: Any, material: Material, element_size: float | None) -> Any:
    """The terrain model object: a named model built on the medium, or the user's as it is."""
    if entry is None:
        return as_terrain_model(model)
    options: dict[str, Any] = {}
    if entry.name in ("rft", "drft", "rft-ss") and element_size is not None:
        options["element_size"] = element_size
    return entry.build(material, **options)


def _run_quasi_static(case: WheelCase, model: Any, entry: Any, s: QuasiStatic) -> WheelRun:
    if case.drive_torque is not None:
        raise InputError(
            "drive_torque",
            case.drive_torque,
            "unset for a quasi-static solve",
            "a torque-driven wheel needs settings=Dynamics() or the MPM",
        )
    if entry is not None and entry.dimension == 3:
        return _run_3d(case, entry.name, s)
    if case.slip_angle != 0.0:
        raise InputError("slip_angle", case.slip_angle, "0 for a plane model", "use model='rft3d'")
    from ..geometry import Body

    if not isinstance(case.wheel, Body):
        raise InputError(
            "wheel", type(case.wheel).__name__, "a plane Body for a 2D model (a mesh needs rft3d)"
        )
    material = case.material
    terrain = _force_law(model, entry, material, s.element_size)
    slip, omega = case.drive()
    label = entry.name if entry is not None else str(getattr(terrain, "name", "user model"))
    if case.sinkage is not None:
        from .prescribed import wheel_at_sinkage

        if slip is None:
            raise InputError("slip", None, "a slip with a prescribed sinkage (a free wheel needs a load)")
        res = wheel_at_sinkage(
            case.wheel,
            terrain,
            case.sinkage,
            slip,
            omega=omega,
            phase_count=s.phase_count,
            slip_definition=case.slip_definition,
        )
        vertical = res.load_N
    elif slip is None:
        from .steady import wheel_self_propelled

        assert case.load is not None
        res = wheel_self_propelled(
            case.wheel,
            terrain,
            case.load,
            drawbar_load=case.drawbar_load,
            omega=omega,
            phase_count=s.phase_count,
        )
        vertical = case.load
    else:
        from .steady import wheel_steady

        assert case.load is not None
        res = wheel_steady(
            case.wheel,
            terrain,
            case.load,
            slip,
            omega=omega,
            phase_count=s.phase_count,
            slip_definition=case.slip_definition,
        )
        vertical = case.load
    summary = _summary(
        sinkage_m=res.sinkage_m,
        drawbar_pull_N=res.drawbar_pull_N,
        drive_torque_Nm=res.drive_torque_Nm,
        vertical_force_N=vertical,
        slip=res.slip,
        omega_rad_s=res.omega_rad_s,
        forward_velocity_m_s=res.forward_velocity_m_s,
        load_N=res.load_N,
        power_W=res.power_W,
    )
    meta = {"phase_count": res.phase_count, "axle_height_m": res.axle_height_m}
    return WheelRun(label, Engine.QUASI_STATIC, case, summary, {}, meta, res)


def _mesh(wheel: Any) -> Any:
    """A 3D wheel: a mesh as it is, a plane circular or grousered wheel extruded across its width."""
    from ..geometry import WheelCircular, WheelGrousered
    from ..geometry3d import TriangleMesh, wheel_cylinder, wheel_grousered

    if isinstance(wheel, TriangleMesh):
        return wheel
    if isinstance(wheel, WheelGrousered):
        return wheel_grousered(
            wheel.radius,
            wheel.width,
            grouser_count=wheel.grouser_count,
            grouser_height=wheel.grouser_height,
            grouser_thickness=wheel.grouser_thickness,
            circumferential_resolution=360,
            axial_resolution=2,
        )
    if isinstance(wheel, WheelCircular):
        return wheel_cylinder(wheel.radius, wheel.width, circumferential_resolution=360, axial_resolution=2)
    raise InputError(
        "wheel", type(wheel).__name__, "a TriangleMesh, WheelCircular or WheelGrousered for rft3d"
    )


def _run_3d(case: WheelCase, name: str, s: QuasiStatic) -> WheelRun:
    from .steady3d import steady3d_record, wheel_at_sinkage_3d, wheel_steady_3d
    from .wheel3d import rft3d_medium, wheel_contact_mesh

    slip, omega = case.drive()
    if slip is None:
        raise InputError("slip", None, "a slip for rft3d (it has no free-rolling solve)")
    mesh = _mesh(case.wheel)
    if s.cull:
        mesh = wheel_contact_mesh(mesh, slip_angle=case.slip_angle)
    medium, note = rft3d_medium(case.material)
    options: dict[str, Any] = {
        "slip_angle": case.slip_angle,
        "omega": omega,
        "slip_definition": case.slip_definition,
        "phase_count": s.phase_count,
    }
    if case.sinkage is not None:
        res = wheel_at_sinkage_3d(mesh, medium, case.sinkage, slip, **options)
    else:
        assert case.load is not None
        res = wheel_steady_3d(mesh, medium, case.load, slip, **options)
    rec = steady3d_record(res)
    summary = _summary(
        sinkage_m=rec["sinkage_m"],
        drawbar_pull_N=rec["drawbar_pull_N"],
        drive_torque_Nm=rec["drive_torque_Nm"],
        vertical_force_N=rec["vertical_force_N"],
        side_force_N=rec["side_force_N"],
        slip=rec["slip"],
        omega_rad_s=res.omega_rad_s,
        forward_velocity_m_s=res.longitudinal_velocity_m_s,
        load_N=res.load_N,
        power_W=rec["power_W"],
    )
    meta = {"facet_count": res.facet_count, "medium_note": note, "slip_angle_rad": case.slip_angle}
    return WheelRun(name, Engine.QUASI_STATIC, case, summary, {}, meta, res)


def compare_models(
    case: WheelCase,
    models: Any,
    *,
    settings: dict[str, Settings] | None = None,
    progress: Callable[[str, int, int], None] | None = None,
) -> list[WheelRun]:
    """:func:`run_wheel` of one case through each of ``models`` (names or model objects), with the
    settings ``settings[name]`` where given; ``progress(name, done, total)`` after each."""
    models = list(models)
    settings = dict(settings or {})
    out = []
    for k, m in enumerate(models):
        key = m if isinstance(m, str) else str(getattr(m, "name", k))
        out.append(run_wheel(case, m, settings=settings.get(key)))
        if progress is not None:
            progress(key, k + 1, len(models))
    return out


def with_duration(case: WheelCase, duration: float) -> WheelCase:
    """The case with another simulated time [s]."""
    return replace(case, duration=duration)
