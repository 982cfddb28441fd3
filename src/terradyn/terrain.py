"""The terrain-model interface shared by RFT, dynamic RFT, Wong-Reece and MPM.

A *stateless* terrain model maps ``(body, pose, twist) -> Wrench2D``: the force [N] the medium exerts
on the body and its torque about +y [N m] about a point (default the body origin = ``(pose.x,
pose.z)``). Every driver (steady solves, sweeps, time integration) takes any object with this
interface, so comparing models is one call with a different ``model`` argument.
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

from .errors import InputError, check_positive
from .geometry import Body
from .kinematics import Pose2D, Twist2D, Wrench2D

__all__ = ["StatefulTerrainModel", "Stateless", "TerrainModel"]


@runtime_checkable
class TerrainModel(Protocol):
    """Anything that gives the soil wrench on a body at a pose and twist."""

    @property
    def name(self) -> str:
        """Short model name (``"rft"``, ``"drft"``, ``"wong-reece"``...)."""
        ...

    def wrench(
        self,
        body: Body,
        pose: Pose2D,
        twist: Twist2D,
        *,
        about: tuple[float, float] | None = None,
    ) -> Wrench2D:
        """Soil force [N] on the body and its torque about +y [N m] about ``about`` (default origin)."""
        ...


@runtime_checkable
class StatefulTerrainModel(Protocol):
    """A medium with memory, advanced in time around one body (see :class:`terradyn.mpm.MPMTerrain`)."""

    @property
    def name(self) -> str: ...

    def init(self, body: Body, pose: Pose2D) -> None:
        """Prepare the medium (e.g. settle a bed) with ``body`` placed at ``pose``."""
        ...

    def step(
        self,
        pose: Pose2D,
        twist: Twist2D,
        dt: float,
        *,
        about: tuple[float, float] | None = None,
    ) -> Wrench2D:
        """Advance by ``dt`` [s] with the body moving rigidly from ``pose`` at ``twist``; the
        interval-averaged soil wrench (torque about ``about``, default the body origin at ``pose``)."""
        ...


class Stateless:
    """A stateless :class:`TerrainModel` behind the stateful ``init``/``step`` interface.

    ``step`` evaluates the wrench at the middle of the interval (pose advanced by ``twist dt / 2``),
    which is second-order accurate for the interval average of a smooth force.
    """

    def __init__(self, model: TerrainModel) -> None:
        if not isinstance(model, TerrainModel):
            raise InputError("model", model, "a terrain model with a wrench(body, pose, twist) method")
        self.model = model
        self._body: Body | None = None

    @property
    def name(self) -> str:
        return self.model.name

    def init(self, body: Body, pose: Pose2D) -> None:
        self._body = body

    def step(
        self,
        pose: Pose2D,
        twist: Twist2D,
        dt: float,
        *,
        about: tuple[float, float] | None = None,
    ) -> Wrench2D:
        if self._body is None:
            raise InputError("terrain", "not initialised", "call init(body, pose) before stepping")
        check_positive("dt", dt)
        h = 0.5 * dt
        mid = Pose2D(pose.x + h * twist.vx, pose.z + h * twist.vz, pose.theta + h * twist.omega)
        ref = (pose.x, pose.z) if about is None else about
        return self.model.wrench(self._body, mid, twist, about=ref)
