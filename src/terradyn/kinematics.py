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
from enum import Enum

import numpy as np
from numpy.typing import NDArray

from .errors import InputError, check_finite

__all__ = [
    "Pose2D",
    "SlipDefinition",
    "Twist2D",
    "Wrench2D",
    "as_slip_definition",
    "point_velocities",
    "rotation_matrix",
    "slip_convert",
    "slip_from_speeds",
    "speeds_from_slip",
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


class SlipDefinition(str, Enum):
    """How a longitudinal slip s relates the rim speed U = omega r to the axle speed V.

    CLASSIC : s = 1 - V / U (DESIGN.md section 4; Wong's slip). Needs U > 0; s in (-inf, 1]; a locked
        wheel (U = 0) has no value.
    BOUNDED : s = (U - V) / max(U, V), the slip ratio single-wheel rigs report (Ishigami et al. 2007).
        s in [-1, 1] for U, V >= 0: 1 spinning in place, 0 free rolling, -1 a locked wheel dragged;
        it equals CLASSIC for s >= 0 and is continuous through U = 0 (with V > 0).

    References
    ----------
    G. Ishigami, A. Miwa, K. Nagatani, K. Yoshida, "Terramechanics-based model for steering maneuver of
    planetary exploration rovers on loose soil", J. Field Robotics 24(3), 233-250 (2007).
    doi:10.1002/rob.20187
    """

    CLASSIC = "classic"
    BOUNDED = "bounded"


def as_slip_definition(definition: SlipDefinition | str) -> SlipDefinition:
    """``definition`` as a :class:`SlipDefinition` (InputError naming ``slip_definition`` otherwise)."""
    try:
        return SlipDefinition(definition.strip().lower() if isinstance(definition, str) else definition)
    except ValueError:
        raise InputError(
            "slip_definition", definition, f"one of {[d.value for d in SlipDefinition]}"
        ) from None


def slip_from_speeds(
    rim_speed: float, carriage_speed: float, *, definition: SlipDefinition | str = SlipDefinition.BOUNDED
) -> float:
    """Longitudinal slip [-] from the rim speed U = omega r [m/s] and the axle speed V [m/s].

    ``bounded``: (U - V) / max(U, V), defined for V >= 0 and any U with max(U, V) > 0 (a wheel spun
    backwards, U < 0, gives s < -1). ``classic``: 1 - V / U, needs U > 0.
    """
    u = check_finite("rim_speed", rim_speed)
    v = check_finite("carriage_speed", carriage_speed)
    if as_slip_definition(definition) is SlipDefinition.CLASSIC:
        if not u > 0.0:
            raise InputError(
                "rim_speed", rim_speed, "a rim speed > 0 [m/s] for the classic slip 1 - V/(omega r)",
                "use the bounded definition (U - V)/max(U, V) for a locked wheel",
            )  # fmt: skip
        return 1.0 - v / u
    if v < 0.0:
        raise InputError("carriage_speed", carriage_speed, "a speed >= 0 [m/s]", "flip the x axis")
    top = max(u, v)
    if not top > 0.0:
        raise InputError(
            "rim_speed", rim_speed, "rim or carriage speed > 0 [m/s]", "slip is undefined at rest"
        )
    return (u - v) / top


def speeds_from_slip(
    slip: float, *, definition: SlipDefinition | str = SlipDefinition.CLASSIC, speed: float = 1.0
) -> tuple[float, float]:
    """(rim speed U, axle speed V) [m/s] of a slip; ``speed`` [m/s] (> 0) sets the scale.

    ``classic`` (s <= 1): U = speed, V = (1 - s) U. ``bounded`` (s in [-1, 1]): max(U, V) = speed,
    so V = (1 - s) U when s >= 0 and U = (1 + s) V when s < 0 (U = 0 at s = -1, a locked wheel).
    """
    scale = check_finite("speed", speed)
    if not scale > 0.0:
        raise InputError("speed", speed, "a speed > 0 [m/s]")
    s = check_finite("slip", slip)
    if as_slip_definition(definition) is SlipDefinition.CLASSIC:
        if s > 1.0:
            raise InputError("slip", slip, "a slip <= 1", "s = 1 - V/(omega r)")
        return scale, (1.0 - s) * scale
    if not -1.0 <= s <= 1.0:
        raise InputError("slip", slip, "a number in [-1, 1]", "s = (omega r - V)/max(omega r, V)")
    if s >= 0.0:
        return scale, (1.0 - s) * scale
    return (1.0 + s) * scale, scale


def slip_convert(slip: float, *, source: SlipDefinition | str, target: SlipDefinition | str) -> float:
    """The same wheel state's slip under another definition.

    classic -> bounded: s for s >= 0, s / (1 - s) for s < 0. bounded -> classic: s for s >= 0,
    s / (1 + s) for s < 0 (a locked wheel, bounded -1, has no classic value: InputError).
    """
    src, dst = as_slip_definition(source), as_slip_definition(target)
    s = check_finite("slip", slip)
    if src is dst:
        if src is SlipDefinition.BOUNDED and not -1.0 <= s <= 1.0:
            raise InputError("slip", slip, "a number in [-1, 1]", "s = (omega r - V)/max(omega r, V)")
        if src is SlipDefinition.CLASSIC and s > 1.0:
            raise InputError("slip", slip, "a slip <= 1", "s = 1 - V/(omega r)")
        return s
    u, v = speeds_from_slip(s, definition=src)
    if dst is SlipDefinition.CLASSIC and not u > 0.0:
        raise InputError(
            "slip", slip, "a bounded slip > -1 (the classic slip of a locked wheel is -infinity)"
        )
    return slip_from_speeds(u, v, definition=dst)
