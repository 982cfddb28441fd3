"""Predict one run of a runs table with a terrain model (2D or 3D), by name.

Models (:data:`REPLAY_MODELS`): ``rft`` (plane RFT, Li et al. 2013), ``drft`` (dynamic RFT), ``wong-reece``
(Wong-Reece rigid wheel), ``rft3d`` (3D RFT, Agarwal et al. 2023), and the slip-sinkage models of
:mod:`terradyn.rft.slip_sinkage`: ``rft-ss`` (2D) and ``rft3d-ss`` (3D). Plane models predict force per
width times the wheel width; they cannot take a slip angle or a mesh (such a run is reported as not
replayed, with the reason). Load-control runs of rft, drft, wong-reece, rft-ss and rft3d go through the
library's steady solvers (:func:`terradyn.locomotion.wheel_steady` with the bounded slip,
:func:`~terradyn.locomotion.steady3d.wheel_steady_3d` with the rim and carriage speeds); rft3d-ss runs
through the twist-based solver of :mod:`terradyn.replay.solve`. Sinkage control sets the axle height
with :func:`terradyn.locomotion.prescribed.axle_height_for_sinkage` (period-mean depth of the lowest
point, as the reported sinkage).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import lru_cache
from typing import Any

import numpy as np

from ..errors import InputError, TerradynError, check_range
from ..models import model_entry, model_names
from .table import QUANTITIES, RunRow, WheelSpec

__all__ = ["MODELS_2D", "MODELS_3D", "REPLAY_MODELS", "Prediction", "ReplayModel", "predict_run"]

MODELS_2D = model_names(use="replay", dimension=2)
MODELS_3D = model_names(use="replay", dimension=3)
REPLAY_MODELS = (*MODELS_2D, *MODELS_3D)
_SLIP_SINKAGE = ("rft-ss", "rft3d-ss")
# More rotational symmetry than this counts as axisymmetric (one phase): a meshed smooth rim.
_AXISYMMETRIC_ORDER = 90


@dataclass(frozen=True)
class ReplayModel:
    """A terrain model for replay, by name, with the parameters calibration may change.

    Attributes
    ----------
    name : one of :data:`REPLAY_MODELS` (``wr``/``wongreece`` accepted for wong-reece)
    scale : factor on the medium's RFT scale (zeta in 2D, xi in 3D) [-], > 0
    excavation, bulldozing, repose_angle : slip-sinkage parameters [-], [-], [rad] (None: the model's
        defaults, :class:`terradyn.rft.slip_sinkage.SlipSinkageParameters`); only for rft-ss/rft3d-ss
    phase_count : wheel angles averaged over one period of a non-circular wheel
    cull : drop the facets of a mesh wheel the medium cannot reach (hub, inner rim), as
        ``wheel steady --mesh`` does (:func:`terradyn.locomotion.wheel3d.wheel_contact_mesh`)
    terrain : a plane terrain model of the user's, replayed instead of a named one: an object with
        ``name`` and ``wrench(body, pose, twist, *, about=None)`` (used for every medium), or a function
        ``material -> terrain model`` (called with each run's medium); ``name`` is then free (it labels
        the results) and ``scale`` must be 1. Calibration fits nothing of a user's model.
    """

    name: str
    scale: float = 1.0
    excavation: float | None = None
    bulldozing: float | None = None
    repose_angle: float | None = None
    phase_count: int = 16
    cull: bool = True
    terrain: Any = field(default=None, compare=False)

    def __post_init__(self) -> None:
        if self.terrain is not None:
            self._check_user_model()
            return
        key = model_entry(self.name, use="replay").name
        object.__setattr__(self, "name", key)
        check_range("scale", self.scale, 1e-6, 1e6)
        if key == "wong-reece" and self.scale != 1.0:
            raise InputError("scale", self.scale, "1 for wong-reece (it has no RFT scale)")
        if key not in _SLIP_SINKAGE:
            for attr in ("excavation", "bulldozing", "repose_angle"):
                if getattr(self, attr) is not None:
                    raise InputError(attr, getattr(self, attr), f"unset for {key} (a slip-sinkage parameter)")
        if (
            isinstance(self.phase_count, bool)
            or not isinstance(self.phase_count, int)
            or not (1 <= self.phase_count <= 4096)
        ):
            raise InputError("phase_count", self.phase_count, "an integer in [1, 4096]")
        if key in _SLIP_SINKAGE:
            self.slip_sinkage()  # checks the slip-sinkage parameters now, not per run

    def _check_user_model(self) -> None:
        if not isinstance(self.name, str) or not self.name.strip():
            raise InputError("name", self.name, "a label for the user's model")
        if not callable(self.terrain) and not hasattr(self.terrain, "wrench"):
            raise InputError(
                "terrain",
                type(self.terrain).__name__,
                "a terrain model (wrench method) or a function material -> model",
            )
        if self.scale != 1.0:
            raise InputError("scale", self.scale, "1 for a user's model (terradyn cannot scale it)")
        for attr in ("excavation", "bulldozing", "repose_angle"):
            if getattr(self, attr) is not None:
                raise InputError(
                    attr, getattr(self, attr), "unset for a user's model (a slip-sinkage parameter)"
                )

    @property
    def is_3d(self) -> bool:
        return self.terrain is None and self.name in MODELS_3D

    @property
    def is_user_model(self) -> bool:
        return self.terrain is not None

    def slip_sinkage(self) -> Any:
        """The :class:`~terradyn.rft.slip_sinkage.SlipSinkageParameters` of this model."""
        from ..rft.slip_sinkage import SlipSinkageParameters

        base = SlipSinkageParameters()
        changes = {
            k: v
            for k, v in (
                ("excavation", self.excavation),
                ("bulldozing", self.bulldozing),
                ("repose_angle", self.repose_angle),
            )
            if v is not None
        }
        return replace(base, **changes)


@dataclass(frozen=True)
class Prediction:
    """Predicted quantities of one run (None where the model does not give one), or why it failed."""

    index: int
    solved: bool
    values: dict[str, float | None] = field(default_factory=dict)
    reason: str = ""


@lru_cache(maxsize=32)
def _material(name: str) -> Any:
    from .. import materials

    return materials.get(name)


@lru_cache(maxsize=8)
def _mesh(path: str, units: str, axle: str) -> Any:
    """A wheel mesh file in the body frame (:func:`terradyn.geometry3d.wheel.load_wheel_mesh`: units,
    axle to +y, axle centre fitted, plausibility checked)."""
    from ..geometry3d.wheel import load_wheel_mesh

    return load_wheel_mesh(path, units=units, axle=axle)[0]


def check_meshes(rows: Any, source: str = "runs") -> None:
    """Load every distinct mesh of the rows once; a bad one raises naming its first row and column."""
    seen: set[tuple[str, str, str]] = set()
    for row in rows:
        w = row.wheel
        if not w.is_mesh:
            continue
        key = (w.mesh_file, w.mesh_units, w.mesh_axle)
        if key in seen:
            continue
        seen.add(key)
        try:
            _mesh(*key)
        except InputError as exc:
            raise InputError(
                f"{source} row {row.index} column mesh_file", w.mesh_file, "a wheel mesh terradyn can place",
                " ".join(str(exc).split()),
            ) from None  # fmt: skip


@lru_cache(maxsize=64)
def _body_2d(wheel: WheelSpec) -> Any:
    from ..geometry import WheelCircular, WheelGrousered

    assert wheel.radius is not None and wheel.width is not None
    if wheel.shape == "circular":
        return WheelCircular(wheel.radius, wheel.width)
    return WheelGrousered(
        wheel.radius, wheel.width, wheel.grouser_count, wheel.grouser_height, wheel.grouser_thickness
    )


@lru_cache(maxsize=64)
def _mesh_3d(wheel: WheelSpec) -> Any:
    from ..geometry3d import wheel_cylinder, wheel_grousered

    if wheel.is_mesh:
        assert wheel.mesh_file is not None
        return _mesh(wheel.mesh_file, wheel.mesh_units, wheel.mesh_axle)
    assert wheel.radius is not None and wheel.width is not None
    if wheel.shape == "circular":
        return wheel_cylinder(wheel.radius, wheel.width, circumferential_resolution=360, axial_resolution=2)
    return wheel_grousered(
        wheel.radius, wheel.width, grouser_count=wheel.grouser_count, grouser_height=wheel.grouser_height,
        grouser_thickness=wheel.grouser_thickness, circumferential_resolution=360, axial_resolution=2,
    )  # fmt: skip


def _speeds(row: RunRow, radius: float) -> tuple[float, float]:
    """(rim speed U = omega r, travel speed V) [m/s] of a run; a run given by slip alone runs with
    max(U, V) = r x 1 rad/s (omega = 1 rad/s unless it skids)."""
    if row.speeds_given:
        return row.omega_r, row.travel_speed
    return row.omega_r * radius, row.travel_speed * radius


def predict_run(row: RunRow, model: ReplayModel) -> Prediction:
    """Predict one run; a run the model cannot replay (solver failure, unsupported case) is returned
    with ``solved = False`` and the reason."""
    try:
        values = _predict_3d(row, model) if model.is_3d else _predict_2d(row, model)
    except TerradynError as exc:
        return Prediction(row.index, False, {}, " ".join(str(exc).split()))
    for k, v in values.items():
        if v is not None and not math.isfinite(v):
            return Prediction(row.index, False, {}, f"the model gave a non-finite {k}")
    return Prediction(row.index, True, values)


def predict_task(task: tuple[RunRow, ReplayModel]) -> Prediction:
    """:func:`predict_run` of a (row, model) pair (module-level, for process pools and Dask)."""
    return predict_run(*task)


# ----------------------------------------------------------------------------------------------- 2D
def _model_2d(model: ReplayModel, material: Any) -> Any:
    if model.terrain is not None:
        from ..terrain import TerrainModel

        if isinstance(model.terrain, TerrainModel):
            return model.terrain
        built = model.terrain(material)
        if not isinstance(built, TerrainModel):
            raise InputError(
                "terrain(material)", type(built).__name__, "a terrain model (name and wrench method)"
            )
        return built
    if model.name == "wong-reece":
        from ..terramechanics import WongReeceModel

        return WongReeceModel(material)
    scaled = material.with_zeta(material.zeta * model.scale) if model.scale != 1.0 else material
    if model.name == "rft":
        from ..rft import RFTModel

        return RFTModel(scaled)
    if model.name == "drft":
        from ..rft import DRFTModel

        return DRFTModel(scaled)
    from ..rft.slip_sinkage import SlipSinkageRFTModel

    return SlipSinkageRFTModel(scaled, parameters=model.slip_sinkage())


def _predict_2d(row: RunRow, model: ReplayModel) -> dict[str, float | None]:
    from ..kinematics import Pose2D, Twist2D
    from ..locomotion import wheel_steady
    from ..locomotion.steady import wheel_nominal_radius, wheel_rotation_period

    if row.wheel.is_mesh:
        raise InputError("model", model.name, "a 3D model (rft3d, rft3d-ss) for a mesh wheel")
    if row.slip_angle != 0.0:
        raise InputError("model", model.name, "a 3D model (rft3d, rft3d-ss) for a run with a slip angle")
    body = _body_2d(row.wheel)
    terrain = _model_2d(model, _material(row.medium))
    radius = wheel_nominal_radius(body)
    rim, speed = _speeds(row, radius)
    period = wheel_rotation_period(body)
    phases = 1 if period is None else model.phase_count
    thetas = np.zeros(1) if period is None else np.arange(phases) * period / phases
    if row.load is not None:
        # bounded slip: the spin reference omega sets max(omega r, V) = omega_ref r
        res = wheel_steady(
            body, terrain, row.load, row.slip, omega=max(rim, speed) / radius, phase_count=phases,
            slip_definition="bounded",
        )  # fmt: skip
        return _values(res.drawbar_pull_N, res.drive_torque_Nm, res.sinkage_m, None, row.load)
    from ..locomotion.prescribed import axle_height_for_sinkage

    assert row.prescribed_sinkage is not None
    twist = Twist2D(speed, 0.0, rim / radius)
    surface = float(getattr(terrain, "surface_level", 0.0))

    def phase_wrench(z: float) -> np.ndarray:
        return np.array([terrain.wrench(body, Pose2D(0.0, z, float(t)), twist).as_array() for t in thetas])

    lowest = _lowest_2d(body, thetas)
    z = axle_height_for_sinkage(lowest, row.prescribed_sinkage, surface)
    from .solve import state_at_height

    w, sink = state_at_height(phase_wrench, lowest, z, surface)
    return _values(float(w[0]), float(-w[2]), sink, None, float(w[1]))


def _lowest_2d(body: Any, thetas: np.ndarray) -> np.ndarray:
    pts = np.concatenate(body.outline())
    c, s = np.cos(thetas)[:, None], np.sin(thetas)[:, None]
    return np.asarray((-s * pts[None, :, 0] + c * pts[None, :, 1]).min(axis=1))


def _what(row: RunRow) -> str:
    ctl = f"load {row.load:g} N" if row.load is not None else f"sinkage {row.prescribed_sinkage:g} m"
    return f"run {row.run_id!r} ({ctl} at slip {row.slip:g}, slip angle {math.degrees(row.slip_angle):g} deg)"


def _values(
    dp: float, torque: float, sinkage: float, side: float | None, vertical: float
) -> dict[str, float | None]:
    return {
        "drawbar_pull_N": dp,
        "drive_torque_Nm": torque,
        "sinkage_m": sinkage,
        "side_force_N": side,
        "vertical_force_N": vertical,
    }


# ----------------------------------------------------------------------------------------------- 3D
@lru_cache(maxsize=64)
def _contact_mesh(wheel: WheelSpec, side: float) -> Any:
    """The facets of a mesh wheel the medium can reach for slip angles of the sign ``side``."""
    from ..locomotion.wheel3d import wheel_contact_mesh

    return wheel_contact_mesh(_mesh_3d(wheel), slip_angle=0.1 * side)


@lru_cache(maxsize=64)
def _mesh_period(wheel: WheelSpec) -> float:
    """Rotational period [rad] of a mesh wheel, detected once per wheel (it costs more than a solve)."""
    from ..locomotion.steady3d import wheel_period_3d

    return wheel_period_3d(_mesh_3d(wheel))


def _phases_3d(mesh: Any, wheel: WheelSpec, model: ReplayModel) -> np.ndarray:
    if wheel.shape == "circular":
        return np.zeros(1)
    period = 2.0 * math.pi / wheel.grouser_count if wheel.shape == "grousered" else _mesh_period(wheel)
    if period <= 2.0 * math.pi / _AXISYMMETRIC_ORDER:
        return np.zeros(1)
    return np.arange(model.phase_count) * period / model.phase_count


def _predict_3d(row: RunRow, model: ReplayModel) -> dict[str, float | None]:
    from ..geometry3d.kinematics import rotations_y
    from ..locomotion.steady3d import (
        wheel_kinematics_3d,
        wheel_nominal_radius_3d,
        wheel_steady_3d,
    )
    from ..rft.rft3d import agarwal2023_xi_material

    mesh = _mesh_3d(row.wheel)
    if row.wheel.is_mesh and model.cull:
        mesh = _contact_mesh(row.wheel, float(np.sign(row.slip_angle)))
    material = _material(row.medium)
    xi = agarwal2023_xi_material(material) * model.scale
    friction = material.surface_friction
    friction = None if friction is None or friction == math.inf else float(friction)
    radius = wheel_nominal_radius_3d(mesh)
    rim, speed = _speeds(row, radius)
    omega = rim / radius
    if speed > 0.0:  # the kinematics of wheel_steady_3d (at 90 deg: the limit from below, V_x = 1e-9 V)
        kin = wheel_kinematics_3d(
            radius, rim_speed=rim, carriage_speed=speed, slip_angle=row.slip_angle, slip_definition="bounded"
        )
        vx, vy = kin.longitudinal_velocity, kin.lateral_velocity
    else:
        vx, vy = 0.0, 0.0
    thetas = _phases_3d(mesh, row.wheel, model)
    if model.name == "rft3d" and row.load is not None:
        kinematics: dict[str, Any] = (
            {
                "rim_speed": rim,
                "carriage_speed": speed,
                "slip_angle": row.slip_angle,
                "slip_definition": "bounded",
            }
            if speed > 0.0
            else {"slip": 1.0, "omega": omega}  # spinning in place: no travel, no slip angle
        )
        res = wheel_steady_3d(
            mesh, xi, row.load, nominal_radius=radius, phase_count=thetas.size,
            period=None if thetas.size == 1 else float(thetas[1] * thetas.size), surface_friction=friction,
            **kinematics,
        )  # fmt: skip
        return _values(res.drawbar_pull_N, res.drive_torque_Nm, res.sinkage_m, res.side_force_N, row.load)
    rotations = rotations_y(thetas)
    linear = np.array([vx, vy, 0.0])
    angular = np.array([0.0, omega, 0.0])
    v = mesh.vertices
    lowest = np.min(
        -np.sin(thetas)[:, None] * v[None, :, 0] + np.cos(thetas)[:, None] * v[None, :, 2], axis=1
    )
    if model.name == "rft3d":
        from ..rft.rft3d import rft3d_wrench_many

        def many(heights: np.ndarray) -> np.ndarray:
            n = heights.size * thetas.size
            pos = np.zeros((n, 3))
            pos[:, 2] = np.repeat(heights, thetas.size)
            out = rft3d_wrench_many(
                mesh, xi, pos, np.tile(rotations, (heights.size, 1, 1)), np.broadcast_to(linear, (n, 3)),
                np.broadcast_to(angular, (n, 3)), surface_friction=friction,
            )  # fmt: skip
            return np.asarray(out).reshape(heights.size, thetas.size, 6)
    else:
        from ..rft.slip_sinkage import SlipSinkageWheel3D

        state = SlipSinkageWheel3D(
            mesh, xi, rotations, linear, angular, model.slip_sinkage(), surface_friction=friction
        )

        def many(heights: np.ndarray) -> np.ndarray:
            return state.wrenches(heights)

    if row.load is not None:
        from .solve import solve_load

        z = solve_load(lambda h: many(h).mean(axis=1), 2, row.load, 0.0, -float(lowest.min()), _what(row))
    else:
        from ..locomotion.prescribed import axle_height_for_sinkage

        assert row.prescribed_sinkage is not None
        z = axle_height_for_sinkage(lowest, row.prescribed_sinkage, 0.0)
    from .solve import state_at_height

    w, sink = state_at_height(lambda h: many(np.array([h]))[0], lowest, z, 0.0)
    return _values(float(w[0]), float(-w[4]), sink, float(w[1]), float(w[2]))


def quantity_names() -> tuple[str, ...]:
    """The compared quantities, in table order."""
    return tuple(QUANTITIES)


def check_rows_for(model: ReplayModel, rows: Any) -> None:
    """Raise when a model can replay none of the rows at all (e.g. a 2D model on a mesh-only table)."""
    if model.is_3d:
        return
    if all(r.wheel.is_mesh for r in rows):
        raise InputError("model", model.name, "a 3D model (rft3d, rft3d-ss) for a table of mesh wheels")
