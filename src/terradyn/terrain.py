"""The terrain-model interface shared by RFT, dynamic RFT, Wong-Reece and MPM.

A *stateless* terrain model maps ``(body, pose, twist) -> Wrench2D``: the force [N] the medium exerts
on the body and its torque about +y [N m] about a point (default the body origin = ``(pose.x,
pose.z)``). Every driver (steady solves, sweeps, time integration) takes any object with this
interface, so comparing models is one call with a different ``model`` argument.
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

from .geometry import Body
from .kinematics import Pose2D, Twist2D, Wrench2D

__all__ = ["TerrainModel"]


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
