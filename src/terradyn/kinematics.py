"""Plane kinematics: poses, twists, wrenches (DESIGN.md section 4 conventions).

Frame: x forward, z up, y = z x x (into the page when x points right and z up). Rotations (a pose's
``theta``, a spin ``omega``) are about +y: clockwise in the x-z view, the sense in which a wheel rolls
forward. A body-frame point ``p`` sits in the world at ``(x, z) + R(theta) p`` with
``R(theta) = [[cos, sin], [-sin, cos]]``; a body point at offset ``r`` from the origin moves with
``v = (vx + omega r_z, vz - omega r_x)``; a force ``F`` at offset ``r`` has torque about +y
``r_z F_x - r_x F_z``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .errors import check_finite

__all__ = [
    "Pose2D",
    "Twist2D",
    "Wrench2D",
    "point_velocities",
    "rotation_matrix",
    "to_world",
    "torque_about",
]


@dataclass(frozen=True, slots=True)
class Pose2D:
    """Position of a body's origin ``x, z`` [m] and its rotation ``theta`` [rad] about +y."""

    x: float = 0.0
    z: float = 0.0
    theta: float = 0.0

    def __post_init__(self) -> None:
        for name in ("x", "z", "theta"):
            object.__setattr__(self, name, check_finite(f"pose.{name}", getattr(self, name)))

    def as_array(self) -> NDArray[np.float64]:
        return np.array([self.x, self.z, self.theta])


@dataclass(frozen=True, slots=True)
class Twist2D:
    """Velocity of a body's origin ``vx, vz`` [m/s] and its spin ``omega`` [rad/s] about +y."""

    vx: float = 0.0
    vz: float = 0.0
    omega: float = 0.0

    def __post_init__(self) -> None:
        for name in ("vx", "vz", "omega"):
            object.__setattr__(self, name, check_finite(f"twist.{name}", getattr(self, name)))

    def as_array(self) -> NDArray[np.float64]:
        return np.array([self.vx, self.vz, self.omega])


@dataclass(frozen=True, slots=True)
class Wrench2D:
    """Force ``fx, fz`` [N] and torque ``torque_y`` [N m] about +y (about a stated point)."""

    fx: float = 0.0
    fz: float = 0.0
    torque_y: float = 0.0

    def __add__(self, other: Wrench2D) -> Wrench2D:
        return Wrench2D(self.fx + other.fx, self.fz + other.fz, self.torque_y + other.torque_y)

    def scaled(self, factor: float) -> Wrench2D:
        return Wrench2D(self.fx * factor, self.fz * factor, self.torque_y * factor)

    def as_array(self) -> NDArray[np.float64]:
        return np.array([self.fx, self.fz, self.torque_y])

    def to_dict(self) -> dict[str, float]:
        return {"force_x_N": self.fx, "force_z_N": self.fz, "torque_y_Nm": self.torque_y}


def rotation_matrix(theta: float) -> NDArray[np.float64]:
    """Matrix mapping body-frame (x, z) to world (x, z) for a rotation ``theta`` [rad] about +y."""
    c, s = np.cos(theta), np.sin(theta)
    return np.array([[c, s], [-s, c]])


def to_world(points: NDArray[np.float64], pose: Pose2D) -> NDArray[np.float64]:
    """Body-frame points, shape (N, 2) [m], to world coordinates, shape (N, 2) [m]."""
    rot = rotation_matrix(pose.theta)
    return np.asarray(points) @ rot.T + np.array([pose.x, pose.z])


def point_velocities(offsets: NDArray[np.float64], twist: Twist2D) -> NDArray[np.float64]:
    """Velocities [m/s], shape (N, 2), of body points at world-frame offsets ``r`` from the origin."""
    r = np.asarray(offsets)
    return np.column_stack((twist.vx + twist.omega * r[:, 1], twist.vz - twist.omega * r[:, 0]))


def torque_about(
    points: NDArray[np.float64], forces: NDArray[np.float64], about: tuple[float, float]
) -> float:
    """Total torque about +y [N m] of forces (N, 2) [N] applied at world points (N, 2) [m]."""
    r = np.asarray(points) - np.asarray(about)
    f = np.asarray(forces)
    return float(np.sum(r[:, 1] * f[:, 0] - r[:, 0] * f[:, 1]))
