"""Rigid-body kinematics in 3D: poses, twists, wrenches (DESIGN.md section 4 conventions).

Frame: x forward, z up, y = z x x (to the left when looking along +x with z up); right-handed. The
plane (2D) models live in the x-z plane, and their rotation ``theta`` about +y is the 3D pitch, so a
:class:`~terradyn.kinematics.Pose2D` maps to ``Pose3D.from_rpy(x, 0, z, pitch=theta)``.

A body-frame point ``p`` sits in the world at ``position + rotation @ p``. A twist holds the world
velocity of the body origin (the point at ``position``) and the world angular velocity ``omega``; a body
point at world offset ``r`` from the origin moves with ``linear + omega x r``. Moments are ``sum r x F``
about a stated point.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError, check_finite
from ..kinematics import Pose2D, Twist2D, Wrench2D

__all__ = [
    "Pose3D",
    "Twist3D",
    "Wrench3D",
    "rotation_from_rpy",
    "rotations_y",
    "rpy_from_rotation",
]


def rotations_y(thetas: NDArray[np.float64]) -> NDArray[np.float64]:
    """Rotation matrices (P, 3, 3) by the angles ``thetas`` (P,) [rad] about +y (a wheel's spin sense)."""
    c, s = np.cos(thetas), np.sin(thetas)
    r = np.zeros((thetas.size, 3, 3))
    r[:, 0, 0], r[:, 0, 2], r[:, 1, 1], r[:, 2, 0], r[:, 2, 2] = c, s, 1.0, -s, c
    return r


def _vector3(field: str, value: ArrayLike) -> NDArray[np.float64]:
    try:
        arr = np.array(value, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        raise InputError(field, value, "three finite numbers") from None
    if arr.shape != (3,) or not np.all(np.isfinite(arr)):
        raise InputError(field, value, "three finite numbers")
    arr.setflags(write=False)
    return arr


def rotation_from_rpy(roll: float, pitch: float, yaw: float) -> NDArray[np.float64]:
    """Body-to-world rotation matrix (3, 3) from roll, pitch, yaw [rad].

    ``R = R_z(yaw) @ R_y(pitch) @ R_x(roll)``, each a right-handed rotation about a world axis (yaw
    about +z, pitch about +y, roll about +x). Pitch is the plane models' ``theta``.
    """
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


def rpy_from_rotation(rotation: ArrayLike) -> tuple[float, float, float]:
    """Roll, pitch, yaw [rad] of a rotation matrix (the inverse of :func:`rotation_from_rpy`).

    Pitch is in [-pi/2, pi/2]; at pitch = +-pi/2 (gimbal lock) roll is set to 0.
    """
    r = np.asarray(rotation, dtype=np.float64)
    pitch = math.asin(max(-1.0, min(1.0, -r[2, 0])))
    if abs(r[2, 0]) > 1.0 - 1e-12:
        return 0.0, pitch, math.atan2(-r[0, 1], r[1, 1])
    return math.atan2(r[2, 1], r[2, 2]), pitch, math.atan2(r[1, 0], r[0, 0])


@dataclass(frozen=True, eq=False)
class Pose3D:
    """Position [m] of a body's origin and its body-to-world rotation matrix [-].

    Attributes
    ----------
    position : ndarray, shape (3,)
        World coordinates (x, y, z) of the body origin [m].
    rotation : ndarray, shape (3, 3)
        Proper orthogonal matrix mapping body-frame vectors to world vectors [-].
    """

    position: NDArray[np.float64]
    rotation: NDArray[np.float64]

    def __post_init__(self) -> None:
        object.__setattr__(self, "position", _vector3("pose.position", self.position))
        try:
            rot = np.array(self.rotation, dtype=np.float64)
        except (TypeError, ValueError):
            raise InputError("pose.rotation", self.rotation, "a 3 x 3 rotation matrix") from None
        if rot.shape != (3, 3) or not np.all(np.isfinite(rot)):
            raise InputError("pose.rotation", self.rotation, "a 3 x 3 rotation matrix of finite numbers")
        err = float(np.max(np.abs(rot @ rot.T - np.eye(3))))
        if err > 1e-9 or np.linalg.det(rot) < 0:
            raise InputError(
                "pose.rotation",
                "a matrix with |R R^T - I| = " + f"{err:.3g} and det {np.linalg.det(rot):.3g}",
                "a proper rotation (orthonormal, det = +1)",
                "build it with Pose3D.from_rpy",
            )
        rot.setflags(write=False)
        object.__setattr__(self, "rotation", rot)

    @classmethod
    def from_rpy(
        cls,
        x: float = 0.0,
        y: float = 0.0,
        z: float = 0.0,
        *,
        roll: float = 0.0,
        pitch: float = 0.0,
        yaw: float = 0.0,
    ) -> Pose3D:
        """Pose from a position [m] and roll, pitch, yaw [rad] (see :func:`rotation_from_rpy`)."""
        angles = [check_finite(n, v) for n, v in (("roll", roll), ("pitch", pitch), ("yaw", yaw))]
        return cls(np.array([x, y, z], dtype=np.float64), rotation_from_rpy(*angles))

    @classmethod
    def from_pose2d(cls, pose: Pose2D, *, y: float = 0.0) -> Pose3D:
        """The 3D pose of a plane pose: ``(x, y, z)`` and pitch = ``theta``."""
        return cls.from_rpy(pose.x, y, pose.z, pitch=pose.theta)

    def rpy(self) -> tuple[float, float, float]:
        """Roll, pitch, yaw [rad]."""
        return rpy_from_rotation(self.rotation)

    def to_world(self, points: ArrayLike) -> NDArray[np.float64]:
        """Body-frame points (N, 3) [m] in world coordinates (N, 3) [m]."""
        return np.asarray(points, dtype=np.float64) @ self.rotation.T + self.position


@dataclass(frozen=True, eq=False)
class Twist3D:
    """World velocity of a body's origin ``linear`` [m/s] and world angular velocity ``angular`` [rad/s]."""

    linear: NDArray[np.float64]
    angular: NDArray[np.float64]

    def __post_init__(self) -> None:
        object.__setattr__(self, "linear", _vector3("twist.linear", self.linear))
        object.__setattr__(self, "angular", _vector3("twist.angular", self.angular))

    @classmethod
    def from_components(
        cls,
        vx: float = 0.0,
        vy: float = 0.0,
        vz: float = 0.0,
        *,
        wx: float = 0.0,
        wy: float = 0.0,
        wz: float = 0.0,
    ) -> Twist3D:
        """Twist from velocity components [m/s] and angular velocity components [rad/s]."""
        return cls(np.array([vx, vy, vz], dtype=np.float64), np.array([wx, wy, wz], dtype=np.float64))

    @classmethod
    def from_twist2d(cls, twist: Twist2D) -> Twist3D:
        """The 3D twist of a plane twist: ``(vx, 0, vz)`` and spin ``omega`` about +y."""
        return cls.from_components(twist.vx, 0.0, twist.vz, wy=twist.omega)

    def point_velocities(self, offsets: ArrayLike) -> NDArray[np.float64]:
        """Velocities (N, 3) [m/s] of body points at world offsets (N, 3) [m] from the origin."""
        return self.linear + np.cross(self.angular, np.asarray(offsets, dtype=np.float64))


@dataclass(frozen=True, eq=False)
class Wrench3D:
    """Force ``force`` [N] and moment ``moment`` [N m] about the world point ``about`` [m]."""

    force: NDArray[np.float64]
    moment: NDArray[np.float64]
    about: NDArray[np.float64]

    def __post_init__(self) -> None:
        object.__setattr__(self, "force", _vector3("wrench.force", self.force))
        object.__setattr__(self, "moment", _vector3("wrench.moment", self.moment))
        object.__setattr__(self, "about", _vector3("wrench.about", self.about))

    def as_array(self) -> NDArray[np.float64]:
        """(F_x, F_y, F_z [N], M_x, M_y, M_z [N m])."""
        return np.concatenate((self.force, self.moment))

    def moved_to(self, point: ArrayLike) -> Wrench3D:
        """The same wrench with its moment taken about ``point`` [m]."""
        p = _vector3("point", point)
        return Wrench3D(self.force, self.moment + np.cross(self.about - p, self.force), p)

    def to_wrench2d(self) -> Wrench2D:
        """The plane part: (F_x, F_z, M_y)."""
        return Wrench2D(float(self.force[0]), float(self.force[2]), float(self.moment[1]))

    def to_dict(self) -> dict[str, float]:
        names = ("force_x_N", "force_y_N", "force_z_N", "moment_x_Nm", "moment_y_Nm", "moment_z_Nm")
        return dict(zip(names, (float(v) for v in self.as_array()), strict=True))
