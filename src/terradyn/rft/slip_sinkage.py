"""Slip-sinkage RFT: RFT on a free surface reshaped by the slipping wheel (excavation and bulldozing).

Quasi-static RFT loads each leading element by its depth below a flat, undisturbed free surface. A
slipping wheel does not meet that surface: the contact drags grains along with it, so soil is dug out
from under the wheel and carried behind it (driving) or pushed ahead of it into a berm (skidding,
locked, or sliding sideways at a slip angle). This model keeps the RFT stress law and changes only the
surface height each element's depth is measured from, the height field being the steady state of the
surface along the wheel's path ("memory" of the surface the wheel has already worked):

* **Excavation (slip sinkage).** Soil under the contact is removed at a rate proportional to the slip
  speed |v_s| of the contact over the ground (v_s: horizontal velocity of the wheel's lowest point)
  and to the thickness of the sheared layer, taken proportional to the sinkage d (the failure zone of
  a rigid wheel scales with its contact, Lyasko 2010). A ground point spends L/V under a contact of
  length L passed at speed V, so by continuity the surface there drops by
  ``Delta = excavation x d x |v_s| / V``, linearly from zero at the front of the contact to Delta at the
  wheel's lowest point, and stays at Delta behind it. For a driving wheel ``|v_s|/V = s/(1 - s)``; for a
  skid ``-s``; a locked wheel gives 1 (rig slip, :func:`terradyn.replay.rig_slip`).
* **Angle of repose.** The front wall of that trough cannot be steeper than the angle of repose:
  grains avalanche back in (height-field terrain with repose relaxation, as in soil models such as
  Project Chrono's SCM and sand-pile height maps). The drop at distance x behind the front of the
  contact is at most ``x tan(repose_angle)``; this also bounds the sinkage of a wheel spinning in
  place (V = 0), where the excavation term alone would be unbounded.
* **Bulldozing.** When the contact pushes soil forward along the direction of travel (a skid, a
  locked wheel, or the side face of a wheel at a slip angle: Ding et al. 2010/2015 name this side
  flow and bulldozing), the material removed is heaped in front of the contact: a berm of height
  ``bulldozing x d x b`` (b = forward component of v_s over V, in [0, 1]) at the front of the
  contact, falling off ahead at the angle of repose. Elements in front then meet a higher surface.

With ``excavation = bulldozing = 0`` the surface is flat and the model is plane (or 3D) RFT, to
rounding (tests compare with :class:`~terradyn.rft.RFTModel` and 3D RFT). Sinkage then grows with slip
(Lyasko 2010; Ding et al. 2010 measure 3-7 times the static sinkage at slip 0.6 for lugged wheels),
and the drawbar pull saturates, because the rear of the contact, which gives the thrust, loses depth.

Parameters and defaults (:class:`SlipSinkageParameters`)
--------------------------------------------------------
excavation [-], default 0.5
    From the mechanism: the sheared layer is as thick as the sinkage (the failure zone under a rigid
    wheel reaches about its sinkage, Wong & Reece 1967) and its velocity falls linearly across it from
    the contact's slip speed to zero, so on average it carries soil at half the slip speed. With it,
    terradyn's example 125 mm wheels (20 N on MS, ``terradyn.replay.synthetic``) sink 2.5 (smooth) and
    2.0 (12 grousers) times deeper at slip 0.6 than at slip 0; Ding et al. (2010) measured 3-7 times
    for lugged wheels, whose lugs also dig, which this model does not describe. Fit it with
    ``terradyn replay --calibrate-on``.
bulldozing [-], default 1.0
    Berm height per excavated depth: the soil dug out by a pushing contact is heaped in front of it,
    as high as it was deep (continuity, no side spill). terradyn's choice; fit it with
    ``terradyn replay --calibrate-on``.
repose_angle [rad], default 32 deg
    Typical of dry sands (30-35 deg; Al-Hashemi & Al-Amoudi 2018).

References
----------
M. Lyasko, "Slip sinkage effect in soil-vehicle mechanics", J. Terramechanics 47(1), 21-31 (2010).
doi:10.1016/j.jterra.2009.08.005
L. Ding, H. Gao, Z. Deng, J. Tao, "Wheel slip-sinkage and its prediction model of lunar rover",
J. Cent. South Univ. Technol. 17, 129-135 (2010). doi:10.1007/s11771-010-0021-7
L. Ding, Z. Deng, H. Gao, J. Tao, K. Iagnemma, G. Liu, "Interaction mechanics model for rigid
driving wheels of planetary rovers moving on sandy terrain with consideration of multiple physical
effects", J. Field Robotics 32(6), 827-859 (2015)
H. M. Al-Hashemi, O. S. Al-Amoudi, "A review on the angle of repose of granular materials", Powder
Technology 330, 397-417 (2018)
J. Y. Wong, A. R. Reece, "Prediction of rigid wheel performance based on the analysis of soil-wheel
stresses, part I", J. Terramechanics 4(1), 81-98 (1967). doi:10.1016/0022-4898(67)90105-X
H. Li, Y. Zhang, D. I. Goldman, "A terradynamics of legged locomotion on granular media", Science 339,
1408-1412 (2013) (the RFT stress law); S. Agarwal, D. I. Goldman, K. Kamrin, PNAS 120, e2214017120
(2023) (3D RFT).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError, check_finite, check_range
from ..geometry import Body
from ..kinematics import Pose2D, Twist2D, Wrench2D, rotation_matrix
from ..materials import Material
from .li2013 import leading_share, li2013_alpha_from_directions

__all__ = [
    "SlipSinkageParameters",
    "SlipSinkageRFTModel",
    "SlipSinkageWheel3D",
    "slip_sinkage_surface",
    "slip_sinkage_wrench_3d",
]


@dataclass(frozen=True)
class SlipSinkageParameters:
    """Excavation [-] (>= 0), bulldozing [-] (>= 0) and angle of repose [rad] in (0, pi/2).

    Defaults and their sources: module notes. ``SlipSinkageParameters.off()`` switches the effect off
    (the model is then RFT).
    """

    excavation: float = 0.5
    bulldozing: float = 1.0
    repose_angle: float = math.radians(32.0)

    def __post_init__(self) -> None:
        check_range("excavation", self.excavation, 0.0, 100.0)
        check_range("bulldozing", self.bulldozing, 0.0, 100.0)
        angle = check_finite("repose_angle", self.repose_angle)
        if not 0.0 < angle < 0.5 * math.pi:
            raise InputError("repose_angle", angle, "an angle in (0, pi/2) [rad]")

    @classmethod
    def off(cls) -> SlipSinkageParameters:
        """No excavation and no bulldozing: plain RFT."""
        return cls(excavation=0.0, bulldozing=0.0)

    @property
    def is_off(self) -> bool:
        return self.excavation == 0.0 and self.bulldozing == 0.0


def slip_sinkage_surface(
    ahead: NDArray[np.float64],
    *,
    front: float,
    bottom: float,
    sinkage: float,
    excavation_ratio: float,
    push_ratio: float,
    parameters: SlipSinkageParameters,
) -> NDArray[np.float64]:
    """Free-surface height [m] (above the undisturbed level) at points ``ahead`` [m] along the travel.

    Parameters
    ----------
    ahead : array
        Distance of each point ahead of the axle along the direction of travel [m].
    front, bottom : float
        ``ahead`` of the front of the contact (the body's foremost point below the undisturbed
        surface) and of the body's lowest point [m].
    sinkage : float
        Depth d of the lowest point below the undisturbed surface [m] (>= 0).
    excavation_ratio : float
        |v_s| / V [-] (may be inf for a wheel spinning in place).
    push_ratio : float
        Forward component of v_s over V [-], clipped to [0, 1].
    parameters : SlipSinkageParameters
    """
    x = np.asarray(ahead, dtype=np.float64)
    h = np.zeros_like(x)
    if sinkage <= 0.0 or parameters.is_off:
        return h
    tan_r = math.tan(parameters.repose_angle)
    behind = front - x  # distance behind the front of the contact
    if parameters.excavation > 0.0 and excavation_ratio > 0.0:
        span = max(front - bottom, 1e-12)
        drop = (
            parameters.excavation * sinkage * excavation_ratio
            if math.isfinite(excavation_ratio)
            else math.inf
        )
        ramp = np.where(behind > 0.0, np.minimum(behind / span, 1.0), 0.0)
        trough = np.where(ramp > 0.0, ramp * drop if math.isfinite(drop) else np.inf, 0.0)
        trough = np.minimum(trough, np.maximum(behind, 0.0) * tan_r)
        h -= trough
    push = min(max(push_ratio, 0.0), 1.0)
    if parameters.bulldozing > 0.0 and push > 0.0:
        height = parameters.bulldozing * sinkage * push
        ahead_of_front = np.maximum(-behind, 0.0)
        berm = np.where(behind <= 0.0, np.maximum(height - ahead_of_front * tan_r, 0.0), 0.0)
        h += berm
    return h


def _ratios(
    slip_velocity: NDArray[np.float64], travel: NDArray[np.float64]
) -> tuple[float, float, NDArray[np.float64]]:
    """(|v_s|/V, forward component of v_s over V, unit direction of travel) from horizontal vectors."""
    speed = float(np.linalg.norm(travel))
    slip_speed = float(np.linalg.norm(slip_velocity))
    if speed <= 0.0:
        direction = np.zeros_like(travel)
        direction[0] = 1.0
        return (math.inf if slip_speed > 0.0 else 0.0), 0.0, direction
    direction = travel / speed
    return slip_speed / speed, float(np.dot(slip_velocity, direction)) / speed, direction


@dataclass(frozen=True)
class SlipSinkageRFTModel:
    """Plane slip-sinkage RFT as a terrain model (``name = "rft-ss"``): ``wrench(body, pose, twist)``.

    Attributes
    ----------
    material : Material  (with RFT parameters)
    parameters : SlipSinkageParameters  (module notes; ``SlipSinkageParameters.off()`` is RFT)
    surface_level : float  undisturbed free-surface height [m]
    element_size : float or None  discretisation of Body arguments [m]
    """

    material: Material
    parameters: SlipSinkageParameters = field(default_factory=SlipSinkageParameters)
    surface_level: float = 0.0
    element_size: float | None = None

    def __post_init__(self) -> None:
        self.material.require_rft()
        check_finite("surface_level", self.surface_level)
        if not isinstance(self.parameters, SlipSinkageParameters):
            raise InputError("parameters", type(self.parameters).__name__, "a SlipSinkageParameters")

    @property
    def name(self) -> str:
        return "rft-ss"

    def surface(
        self, body: Body, pose: Pose2D, twist: Twist2D, x: NDArray[np.float64]
    ) -> NDArray[np.float64]:
        """Free-surface height [m] at world x positions for the body at this pose and twist."""
        _, profile = self._profile(body, pose, twist)
        return self.surface_level + profile(np.asarray(x, dtype=np.float64) - pose.x)

    def _profile(self, body: Body, pose: Pose2D, twist: Twist2D) -> tuple[Any, Any]:
        pts = np.concatenate(body.outline()) @ rotation_matrix(pose.theta).T  # offsets from the axle
        world_z = pose.z + pts[:, 1]
        low = int(np.argmin(world_z))
        sinkage = self.surface_level - float(world_z[low])
        travel = np.array([twist.vx])
        slip_velocity = np.array([twist.vx + twist.omega * pts[low, 1]])
        ratio, push, direction = _ratios(slip_velocity, travel)
        along = pts[:, 0] * direction[0]
        under = world_z < self.surface_level
        front = float(along[under].max()) if np.any(under) else 0.0
        bottom = float(along[low])
        params = self.parameters

        def profile(offset_x: NDArray[np.float64]) -> NDArray[np.float64]:
            return slip_sinkage_surface(
                offset_x * direction[0], front=front, bottom=bottom, sinkage=max(sinkage, 0.0),
                excavation_ratio=ratio, push_ratio=push, parameters=params,
            )  # fmt: skip

        return along, profile

    def wrench(
        self, body: Body, pose: Pose2D, twist: Twist2D, *, about: tuple[float, float] | None = None
    ) -> Wrench2D:
        """Soil force [N] and torque about +y [N m] about ``about`` (default the body origin)."""
        elems = body.discretize(self.element_size)
        rft = self.material.require_rft()
        point = (pose.x, pose.z) if about is None else (float(about[0]), float(about[1]))
        rot = rotation_matrix(pose.theta)
        offsets = elems.midpoints @ rot.T
        positions = offsets + np.array([pose.x, pose.z])
        normals = elems.normals @ rot.T
        velocities = np.column_stack(
            (twist.vx + twist.omega * offsets[:, 1], twist.vz - twist.omega * offsets[:, 0])
        )
        _, profile = self._profile(body, pose, twist)
        depth = self.surface_level + profile(offsets[:, 0]) - positions[:, 1]
        share = leading_share(normals, velocities)
        active = (depth > 0) & (share > 0)
        share = np.where(active, share, 0.0)
        ax, az = li2013_alpha_from_directions(normals, velocities, rft.coefficients.as_array(), rft.scale)
        d = np.where(active, depth, 0.0)
        ax = np.where(active, ax, 0.0)
        az = np.where(active, az, 0.0)
        forces = np.column_stack((-ax * d, az * d)) * (share * elems.areas)[:, None]
        r = positions - np.array(point)
        return Wrench2D(
            float(forces[:, 0].sum()),
            float(forces[:, 1].sum()),
            float(np.sum(r[:, 1] * forces[:, 0] - r[:, 0] * forces[:, 1])),
        )


def slip_sinkage_wrench_3d(
    mesh: Any,
    xi: float,
    heights: NDArray[np.float64],
    rotations: NDArray[np.float64],
    linear: NDArray[np.float64],
    angular: NDArray[np.float64],
    parameters: SlipSinkageParameters,
    *,
    surface_friction: float | None = None,
) -> NDArray[np.float64]:
    """3D slip-sinkage RFT wrenches (H, P, 6) [N, N m] of a wheel at axle heights (H,) [m] over P phases.

    The wheel frame of :mod:`terradyn.locomotion.steady3d` (x heading, y axle, z up; undisturbed
    surface at z = 0); ``rotations`` (P, 3, 3) turn the mesh about its axle, ``linear`` (3,) [m/s] and
    ``angular`` (3,) [rad/s] are the axle velocity and spin. Moments about the axle. Each facet is
    loaded by the 3D-RFT traction (Agarwal et al. 2023, :func:`terradyn.rft.rft3d.rft3d_facet_tractions`)
    at its depth below the reshaped surface of :func:`slip_sinkage_surface`, measured along the
    horizontal direction of travel (so at a slip angle the berm builds against the wheel's side face).
    For many calls on one wheel state, build a :class:`SlipSinkageWheel3D` once.
    """
    wheel = SlipSinkageWheel3D(
        mesh, xi, rotations, linear, angular, parameters, surface_friction=surface_friction
    )
    return wheel.wrenches(heights)


class SlipSinkageWheel3D:
    """A wheel in one kinematic state for 3D slip-sinkage RFT: the per-phase geometry computed once,
    :meth:`wrenches` at any axle heights (arguments as :func:`slip_sinkage_wrench_3d`)."""

    def __init__(
        self,
        mesh: Any,
        xi: float,
        rotations: NDArray[np.float64],
        linear: NDArray[np.float64],
        angular: NDArray[np.float64],
        parameters: SlipSinkageParameters,
        *,
        surface_friction: float | None = None,
    ) -> None:
        lin = np.asarray(linear, dtype=np.float64)
        ang = np.asarray(angular, dtype=np.float64)
        self.mesh, self.xi, self.parameters, self.surface_friction = (
            mesh,
            float(xi),
            parameters,
            surface_friction,
        )
        self.phases = []
        for rot in np.asarray(rotations, dtype=np.float64):
            offsets = mesh.centroids @ rot.T
            verts = mesh.vertices @ rot.T
            low = int(np.argmin(verts[:, 2]))
            ratio, push, direction = _ratios((lin + np.cross(ang, verts[low]))[:2], lin[:2])
            self.phases.append(
                (offsets, mesh.normals @ rot.T, lin + np.cross(ang, offsets), verts[:, 2], low, ratio, push,
                 verts[:, :2] @ direction, offsets[:, :2] @ direction)
            )  # fmt: skip

    def wrenches(self, heights: NDArray[np.float64]) -> NDArray[np.float64]:
        """Wrenches (H, P, 6) [N, N m] about the axle at axle heights (H,) [m]."""
        from .rft3d import rft3d_facet_tractions

        params = self.parameters
        hs = np.atleast_1d(np.asarray(heights, dtype=np.float64))
        out = np.zeros((hs.size, len(self.phases), 6))
        for p, (offsets, normals, velocities, vz, low, ratio, push, along_v, along_c) in enumerate(
            self.phases
        ):
            for k, z in enumerate(hs):
                world_z = z + vz
                under = world_z < 0.0
                if not np.any(under):
                    continue
                sinkage = -float(world_z[low])
                # the surface is nowhere above the berm crest: facets higher than it carry nothing
                crest = params.bulldozing * sinkage * min(max(push, 0.0), 1.0)
                near = np.nonzero(offsets[:, 2] + z < crest)[0]
                h = slip_sinkage_surface(
                    along_c[near], front=float(along_v[under].max()), bottom=float(along_v[low]),
                    sinkage=sinkage, excavation_ratio=ratio, push_ratio=push, parameters=params,
                )  # fmt: skip
                shifted = offsets[near].copy()
                shifted[:, 2] += z - h  # depth below the reshaped surface = h - (z + offset_z)
                tractions = rft3d_facet_tractions(
                    shifted, normals[near], velocities[near], xi=self.xi, surface_level=0.0,
                    surface_friction=self.surface_friction,
                )  # fmt: skip
                forces = tractions * self.mesh.areas[near, None]
                out[k, p, :3] = forces.sum(axis=0)
                out[k, p, 3:] = np.cross(offsets[near], forces).sum(axis=0)
        return out
