"""The 3D wheel's inputs: its motion (slip, slip angle to 90 deg, rim and carriage speeds), the
3D-RFT scale of a medium, and the facets the medium can reach.

Used by :mod:`terradyn.locomotion.steady3d` (and re-exported there); frames and signs as in its notes.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError, check_finite, check_positive, check_range
from ..geometry3d import TriangleMesh
from ..kinematics import SlipDefinition, as_slip_definition, slip_from_speeds, speeds_from_slip
from ..materials import Material

__all__ = [
    "WheelKinematics3D",
    "rft3d_medium",
    "wheel_contact_directions",
    "wheel_contact_mesh",
    "wheel_kinematics_3d",
    "xi_from_zeta",
]


def _slip_angle(slip_angle: float) -> float:
    slip_angle = check_finite("slip_angle", slip_angle)
    if not abs(slip_angle) <= 0.5 * math.pi + 1e-12:
        raise InputError(
            "slip_angle", slip_angle, "an angle in [-pi/2, pi/2] [rad], i.e. |slip angle| <= 90 deg"
        )
    return max(-0.5 * math.pi, min(0.5 * math.pi, slip_angle))


# cos(slip angle) used at |slip angle| = 90 deg: the one-sided limit from below (wheel_kinematics_3d).
_SIDEWAYS = 1e-9


@dataclass(frozen=True)
class WheelKinematics3D:
    """Axle velocity and spin of a wheel in the wheel frame, and its slip.

    longitudinal_velocity, lateral_velocity : V_x, V_y [m/s]; omega : spin [rad/s] (>= 0);
    slip : longitudinal slip [-] in ``slip_definition`` ("classic" or "bounded").
    """

    longitudinal_velocity: float
    lateral_velocity: float
    omega: float
    slip: float
    slip_definition: str


def wheel_kinematics_3d(
    radius: float,
    slip: float | None = None,
    *,
    slip_angle: float = 0.0,
    omega: float = 1.0,
    slip_definition: SlipDefinition | str = SlipDefinition.CLASSIC,
    rim_speed: float | None = None,
    carriage_speed: float | None = None,
) -> WheelKinematics3D:
    """The wheel's motion from a slip and a slip angle [rad], or from the rim and carriage speeds.

    With ``slip``: the speeds of :func:`terradyn.kinematics.speeds_from_slip` at scale omega r,
    V_y = V_x tan(slip_angle); needs |slip_angle| < pi/2 (at 90 deg V_x = 0 and the slip no longer
    fixes the motion). With ``rim_speed`` U = omega r [m/s] (>= 0) and ``carriage_speed`` V [m/s]
    (> 0, the axle's speed over the ground): V_x = V cos(slip_angle), V_y = V sin(slip_angle),
    omega = U / r, any slip angle in [-pi/2, pi/2] and a locked wheel (U = 0) included.

    At |slip_angle| = pi/2 the rim moves tangentially to itself (n . v = 0 on every rim facet), the
    point where the leading-edge rule of RFT switches: the wheel is taken as the limit |slip angle| ->
    90 deg from below, V_x = 1e-9 V (so the slip there is 1 when spinning, -1 when locked).
    """
    radius = check_positive("nominal_radius", radius)
    angle = _slip_angle(slip_angle)
    definition = as_slip_definition(slip_definition)
    given = (rim_speed is not None, carriage_speed is not None)
    if slip is not None and any(given):
        raise InputError("slip", slip, "either a slip or rim_speed and carriage_speed, not both")
    if slip is None:
        if not all(given):
            missing = "rim_speed" if rim_speed is None else "carriage_speed"
            raise InputError(missing, None, "a speed [m/s] (give slip, or rim_speed and carriage_speed)")
        assert rim_speed is not None and carriage_speed is not None
        u = check_finite("rim_speed", rim_speed)
        if u < 0.0:
            raise InputError("rim_speed", rim_speed, "a rim speed omega r >= 0 [m/s]")
        v = check_finite("carriage_speed", carriage_speed)
        if not v > 0.0:
            raise InputError("carriage_speed", carriage_speed, "a speed > 0 [m/s]")
        vx, vy = v * max(math.cos(angle), _SIDEWAYS), v * math.sin(angle)
        if definition is SlipDefinition.CLASSIC and not u > 0.0:
            raise InputError(
                "rim_speed", rim_speed, "a rim speed > 0 [m/s] for the classic slip",
                "use slip_definition='bounded' for a locked wheel",
            )  # fmt: skip
        s = slip_from_speeds(u, vx, definition=definition)
        return WheelKinematics3D(vx, vy, u / radius, s, definition.value)
    classic = definition is SlipDefinition.CLASSIC
    hint = "s = 1 - V_x/(omega r)" if classic else "s = (omega r - V_x)/max(omega r, V_x)"
    s = check_range("slip", slip, -1.0, 1.0, hint=hint)
    omega = check_finite("omega", omega)
    if not omega > 0.0:
        raise InputError("omega", omega, "a spin rate > 0 [rad/s]", "slip is undefined when omega <= 0")
    if not abs(angle) < 0.5 * math.pi:
        raise InputError(
            "slip_angle", slip_angle, "an angle in (-pi/2, pi/2) [rad] with a slip",
            "at 90 deg the longitudinal slip does not fix the motion: give rim_speed and carriage_speed",
        )  # fmt: skip
    u, vx = speeds_from_slip(s, definition=definition, speed=omega * radius)
    return WheelKinematics3D(vx, vx * math.tan(angle), u / radius, s, definition.value)


def xi_from_zeta(zeta: float) -> float:
    """3D-RFT media scale xi [N/m^3] matching a plane-RFT scale zeta [N/m^3] (alpha_z(0, pi/2)).

    Both laws are matched where the calibration experiment measures them: a horizontal plate pushed
    straight down, whose stress per depth is zeta in the plane law and xi alpha_z in 3D RFT
    (alpha_z = 0.87574 with the default fit), so xi = zeta / alpha_z.
    """
    from ..rft.rft3d import agarwal2023_alpha

    z = check_positive("zeta", zeta)
    down = np.array([[0.0, 0.0, -1.0]])
    return z / float(agarwal2023_alpha(down, down)[0, 2])


def rft3d_medium(material: Material) -> tuple[Material | float, str]:
    """The 3D-RFT medium of a material and how its scale was found.

    The media scaling of Agarwal et al. (2023) from ``critical_density`` and ``internal_friction_angle``
    when the material has both; else :func:`xi_from_zeta` of its plane RFT scale (e.g. a TOML written by
    ``terradyn calibrate rft``). Returns (the Material or xi [N/m^3], a one-line note).
    """
    from ..rft.rft3d import agarwal2023_xi_material

    if not isinstance(material, Material):
        raise InputError("material", type(material).__name__, "a terradyn Material")
    if material.critical_density is not None and material.internal_friction_angle is not None:
        xi = agarwal2023_xi_material(material)
        return material, f"xi = {xi:.6g} N/m^3 from the density and friction angle of {material.name}"
    if material.rft is not None:
        zeta = material.rft.zeta
        xi = xi_from_zeta(zeta)
        return xi, (
            f"xi = {xi:.6g} N/m^3 from the plane RFT scale zeta = {zeta:.6g} N/m^3 of {material.name} "
            "(matched on a horizontal plate pushed down)"
        )
    return material, ""


def wheel_contact_directions(slip_angle: float = 0.0, *, count: int = 24) -> NDArray[np.float64]:
    """Body-frame directions (D, 3) from which the medium can meet a wheel over one turn.

    Over a turn the world's downward (penetration) direction and the in-plane part of every facet's
    motion sweep the wheel plane: ``count`` directions (cos phi, 0, sin phi). With a slip angle the
    facets also move sideways, the lateral tilt of their velocity ranging from that of the axle to
    90 deg at the instantaneous centre: the same circle tilted by 15, 30, ..., 75 deg towards the
    side the wheel moves to, and that side's axle direction itself.
    """
    angle = _slip_angle(slip_angle)
    phi = 2.0 * math.pi * np.arange(count) / count
    tilts = [0.0] if angle == 0.0 else [math.radians(t) for t in (0.0, 15.0, 30.0, 45.0, 60.0, 75.0)]
    side = math.copysign(1.0, angle)
    rows = [
        np.column_stack(
            (math.cos(t) * np.cos(phi), np.full(count, side * math.sin(t)), math.cos(t) * np.sin(phi))
        )
        for t in tilts
    ]
    if angle != 0.0:
        rows.append(np.array([[0.0, side, 0.0]]))
    return np.vstack(rows)


def wheel_contact_mesh(
    mesh: TriangleMesh, *, slip_angle: float | Sequence[float] = 0.0, count: int = 24
) -> TriangleMesh:
    """The facets of a wheel the medium can reach: those visible from outside along
    :func:`wheel_contact_directions` (:func:`terradyn.geometry3d.visibility.visible_facets`) of the
    slip angle [rad], or of every one of several slip angles (for a sweep).

    Drops enclosed faces (a hub inside a closed tyre, inner rim surfaces); keeps every facet of a closed
    convex wheel that faces one of the directions, so there the RFT answer is unchanged. Raises
    InputError if nothing is left.
    """
    from ..geometry3d.visibility import visible_facets

    if not isinstance(mesh, TriangleMesh):
        raise InputError("mesh", type(mesh).__name__, "a terradyn.geometry3d.TriangleMesh")
    angles = np.atleast_1d(np.asarray(slip_angle, dtype=np.float64))
    signs = sorted({float(np.sign(a)) for a in angles})  # the directions depend on the sign only
    directions = np.vstack([wheel_contact_directions(0.1 * sg, count=count) for sg in signs])
    for a in angles:
        _slip_angle(float(a))
    keep = visible_facets(mesh, directions)
    if not np.any(keep):
        raise InputError("mesh", "no facet visible from outside", "a wheel surface the medium can reach")
    return TriangleMesh(mesh.vertices, mesh.faces[keep])
