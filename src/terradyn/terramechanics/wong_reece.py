"""Wong-Reece rigid wheel on a Bekker soil (driving and skidding).

Angles are measured at the axle from the downward vertical, positive towards the front (the direction
of travel). A wheel of radius r and width b sinks z0 = r (1 - cos theta_1); it touches the soil from the
entry angle theta_1 (front) back to the exit angle theta_2 <= 0 (default 0; negative for a rear rebound
contact). With slip s = 1 - V_x / (omega r) and k = k_c / b + k_phi:

* normal stress, front region theta_m <= theta <= theta_1:
  sigma(theta) = k [r (cos theta - cos theta_1)]^n, with theta_m = (c1 + c2 s) theta_1;
* rear region theta_2 <= theta < theta_m: the same law at the mapped angle
  theta* = theta_1 - (theta - theta_2)(theta_1 - theta_m) / (theta_m - theta_2);
* shear displacement j(theta) = r [(theta_1 - theta) - (1 - s)(sin theta_1 - sin theta)] (j > 0 when
  the rim slides backwards over the soil, i.e. driving);
* shear stress (Janosi-Hanamoto, extended oddly): tau = sign(j)(c + sigma tan phi)(1 - exp(-|j| / K)).
  Skidding (s < 0) uses the same j; j turns negative and the shear stress on the wheel points backwards,
  so the soil brakes the wheel (negative drawbar pull and drive torque). This is terradyn's choice for
  the skid branch, not Wong & Reece's separate skid analysis.

The soil force on the wheel, with tau acting along the rim tangent (cos theta, sin theta) and sigma along
the inward normal (-sin theta, cos theta):

* vertical force  W  = r b  int (sigma cos theta + tau sin theta) dtheta,
* drawbar pull    DP = r b  int (tau cos theta - sigma sin theta) dtheta = thrust - compaction resistance,
* drive torque    T  = r^2 b int tau dtheta (the soil torque about +y about the axle is -T).

The normal stress has a kink at theta_m, and when skidding the shear stress flips sign where j does
(over a displacement ~ K, a near-kink), so the contact is cut at theta_m and at that sign change and each
piece is integrated by its own Gauss-Legendre rule (``node_count`` nodes per piece). The integrals run
in a compiled (numba) kernel over many entry angles at once, checked against a NumPy reference;
:func:`wong_reece_wheel` evaluates them on a grid of entry angles to bracket the one that carries the
load, then refines it with Brent's method.

References
----------
.. [1] J. Y. Wong, A. R. Reece, Prediction of rigid wheel performance based on the analysis of soil-wheel
   stresses, part I: performance of driven rigid wheels, *J. Terramechanics* 4(1), 81-98 (1967),
   doi:10.1016/0022-4898(67)90105-X.
.. [2] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley (2008), ch. 4, ISBN 978-0-470-17038-0.
"""

from __future__ import annotations

import math
from dataclasses import KW_ONLY, dataclass, field
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq

from ..errors import InputError, SolverError, check_finite, check_positive, check_range
from ..geometry import WheelCircular
from ..kinematics import Pose2D, Twist2D, Wrench2D
from ..materials import BekkerParameters, Material
from ..materials import get as get_material
from ._kernels import (
    _wong_reece_integrals_many,
)

__all__ = [
    "WongReeceModel",
    "WongReeceProfiles",
    "WongReeceResult",
    "wong_reece_wheel",
    "wong_reece_wheel_forces",
]

FloatArray = NDArray[np.float64]

DEFAULT_C1 = 0.43
DEFAULT_C2 = 0.32
DEFAULT_NODE_COUNT = 48
_HALF_PI = 0.5 * math.pi
_BRACKET_POINTS = 16


@dataclass(frozen=True, eq=False)
class WongReeceProfiles:
    """Stress profiles along the contact, from the exit angle to the entry angle.

    Attributes
    ----------
    angle : (P,) angle theta from the downward vertical, + to the front [rad]
    normal_stress : (P,) sigma [Pa]
    shear_stress : (P,) tau [Pa] (+ pushes the wheel forward along the rim)
    shear_displacement : (P,) j [m]
    """

    angle: FloatArray
    normal_stress: FloatArray
    shear_stress: FloatArray
    shear_displacement: FloatArray


@dataclass(frozen=True)
class WongReeceResult:
    """Operating point of a Wong-Reece rigid wheel (SI).

    Attributes
    ----------
    sinkage : depth of the wheel's lowest point below the undisturbed surface [m]
    entry_angle : theta_1 [rad]; exit_angle : theta_2 [rad]; max_stress_angle : theta_m [rad]
    drawbar_pull : horizontal soil force on the wheel, + forward [N]
    drive_torque : torque the motor applies, + driving forward [N m]
    load : vertical soil force on the wheel W (= the axle load at equilibrium) [N]
    slip : s [-]
    thrust : r b int tau cos(theta) [N]; compaction_resistance : r b int sigma sin(theta) [N]
    profiles : stress profiles, when asked for
    """

    sinkage: float
    entry_angle: float
    exit_angle: float
    max_stress_angle: float
    drawbar_pull: float
    drive_torque: float
    load: float
    slip: float
    thrust: float
    compaction_resistance: float
    profiles: WongReeceProfiles | None = field(default=None, compare=False, repr=False)

    @property
    def soil_torque(self) -> float:
        """Torque of the soil on the wheel about +y about the axle [N m] (= -drive_torque)."""
        return -self.drive_torque

    def to_dict(self) -> dict[str, float]:
        """Scalars with unit-suffixed keys (``sinkage_m``, ``drawbar_pull_N``...)."""
        return {
            "slip": self.slip,
            "load_N": self.load,
            "sinkage_m": self.sinkage,
            "drawbar_pull_N": self.drawbar_pull,
            "drive_torque_Nm": self.drive_torque,
            "entry_angle_rad": self.entry_angle,
            "exit_angle_rad": self.exit_angle,
            "max_stress_angle_rad": self.max_stress_angle,
            "thrust_N": self.thrust,
            "compaction_resistance_N": self.compaction_resistance,
        }


# --------------------------------------------------------------------------------------------------
# Validation shared by the public functions and the terrain model
# --------------------------------------------------------------------------------------------------


class _Soil(NamedTuple):
    """Checked soil constants of the kernel for one wheel width (in the kernel's argument order)."""

    modulus: float
    n: float
    cohesion: float
    tan_phi: float
    shear_modulus: float


def _bekker_of(soil: BekkerParameters | Material | str) -> BekkerParameters:
    if isinstance(soil, BekkerParameters):
        return soil
    if isinstance(soil, Material | str):
        return get_material(soil).require_bekker()
    raise InputError("soil", type(soil).__name__, "BekkerParameters, a Material or a material name")


def _soil_for_width(bekker: BekkerParameters, width: float) -> _Soil:
    modulus = bekker.k_c / width + bekker.k_phi
    if not modulus > 0:
        raise InputError(
            "k_c / width + k_phi",
            modulus,
            "a pressure-sinkage modulus > 0 [N/m^(n+2)]",
            f"k_c = {bekker.k_c:g} is too negative for a wheel {width:g} m wide",
        )
    return _Soil(modulus, bekker.n, bekker.cohesion, math.tan(bekker.friction_angle), bekker.shear_modulus)


def _checked(
    radius: float,
    width: float,
    soil: BekkerParameters | Material | str,
    slip: float,
    exit_angle: float,
    node_count: int,
) -> tuple[float, float, float, _Soil, float, int]:
    """Checked (radius, width, slip, soil constants, exit angle, node count) of the public functions."""
    radius = check_positive("radius", radius)
    width = check_positive("width", width)
    slip = check_range("slip", slip, -1.0, 1.0, hint="s = 1 - V/(omega r)")
    ground = _soil_for_width(_bekker_of(soil), width)
    return radius, width, slip, ground, _check_exit_angle(exit_angle), _check_node_count(node_count)


def _check_node_count(node_count: Any) -> int:
    if isinstance(node_count, bool) or not isinstance(node_count, int | np.integer):
        raise InputError("node_count", node_count, "an integer in [4, 4096]")
    if not 4 <= int(node_count) <= 4096:
        raise InputError("node_count", node_count, "an integer in [4, 4096]")
    return int(node_count)


def _check_exit_angle(exit_angle: float) -> float:
    return check_range(
        "exit_angle",
        exit_angle,
        -_HALF_PI,
        0.0,
        unit="rad",
        hint="signed from the downward vertical, + to the front; a rear (rebound) contact is negative",
    )


def _check_theta_m_ratio(c1: float, c2: float, slip: float, exit_angle: float, entry_angle: float) -> float:
    """c1 + c2 s, if theta_m = (c1 + c2 s) theta_1 lies in [theta_2, theta_1] at ``entry_angle``."""
    c1 = check_finite("c1", c1)
    c2 = check_finite("c2", c2)
    ratio = c1 + c2 * slip
    theta_m = ratio * entry_angle
    if ratio > 1.0 or theta_m < exit_angle:
        raise InputError(
            "c1 + c2 * slip",
            ratio,
            f"a value giving theta_m = (c1 + c2 s) theta_1 in [theta_2, theta_1] = "
            f"[{exit_angle:.4g}, {entry_angle:.4g}] rad",
            f"c1 = {c1:g}, c2 = {c2:g}, slip = {slip:g}",
        )
    return ratio


def _result(
    integrals: FloatArray,
    entry_angle: float,
    exit_angle: float,
    ratio: float,
    radius: float,
    slip: float,
    profiles: WongReeceProfiles | None,
) -> WongReeceResult:
    w, dp, torque, thrust, resistance = (float(v) for v in integrals[:, 0])
    return WongReeceResult(
        sinkage=radius * (1.0 - math.cos(entry_angle)),
        entry_angle=entry_angle,
        exit_angle=exit_angle,
        max_stress_angle=ratio * entry_angle,
        drawbar_pull=dp,
        drive_torque=torque,
        load=w,
        slip=slip,
        thrust=thrust,
        compaction_resistance=resistance,
        profiles=profiles,
    )


def _profiles(
    entry_angle: float,
    exit_angle: float,
    ratio: float,
    radius: float,
    soil: _Soil,
    slip: float,
    point_count: int,
) -> WongReeceProfiles:
    if isinstance(point_count, bool) or not isinstance(point_count, int | np.integer) or point_count < 2:
        raise InputError("profile_points", point_count, "an integer >= 2")
    t1, t2 = entry_angle, exit_angle
    tm = ratio * t1
    theta = np.linspace(t2, t1, int(point_count))
    if tm > t2:
        mapped = t1 - (theta - t2) * (t1 - tm) / (tm - t2)
    else:
        mapped = theta
    stress_angle = np.where(theta < tm, mapped, theta)
    sigma = soil.modulus * np.power(np.maximum(radius * (np.cos(stress_angle) - math.cos(t1)), 0.0), soil.n)
    j = radius * ((t1 - theta) - (1.0 - slip) * (math.sin(t1) - np.sin(theta)))
    tau = np.sign(j) * (soil.cohesion + sigma * soil.tan_phi) * -np.expm1(-np.abs(j) / soil.shear_modulus)
    return WongReeceProfiles(theta, sigma, tau, j)


# --------------------------------------------------------------------------------------------------
# Public functions
# --------------------------------------------------------------------------------------------------


def wong_reece_wheel_forces(
    radius: float,
    width: float,
    soil: BekkerParameters | Material | str,
    slip: float,
    *,
    entry_angle: float | None = None,
    sinkage: float | None = None,
    c1: float = DEFAULT_C1,
    c2: float = DEFAULT_C2,
    exit_angle: float = 0.0,
    node_count: int = DEFAULT_NODE_COUNT,
    profiles: bool = False,
    profile_points: int = 181,
) -> WongReeceResult:
    """Soil forces on a Wong-Reece rigid wheel at a given entry angle (or sinkage).

    Parameters
    ----------
    radius : float
        Wheel radius r [m], > 0.
    width : float
        Wheel width b [m], > 0 (the plate width of the Bekker law).
    soil : BekkerParameters, Material or str
        Bekker/Janosi-Hanamoto parameters, or a medium that has them (``"MS"``, ``"LPS"``...).
    slip : float
        s = 1 - V_x / (omega r) in [-1, 1]; > 0 driving, < 0 skidding.
    entry_angle : float, optional
        theta_1 [rad] in (0, pi/2]. Give exactly one of ``entry_angle`` and ``sinkage``.
    sinkage : float, optional
        z0 = r (1 - cos theta_1) [m] in (0, r].
    c1, c2 : float
        theta_m = (c1 + c2 s) theta_1 [-]; must lie in [theta_2, theta_1]. Defaults 0.43 and 0.32 are the
        values a public Wong-Reece example uses for this 0.13 m MIT wheel; c1 = c2 = 0.5 also appears in
        the literature.
    exit_angle : float
        theta_2 [rad] in [-pi/2, 0]; 0 (default) ends the contact at the lowest point of the wheel.
    node_count : int
        Gauss-Legendre nodes per contact piece (the contact [theta_2, theta_1] is cut at theta_m and, when
        skidding, where j changes sign).
    profiles : bool
        Also return the stress profiles (``profile_points`` evenly spaced angles).

    Returns
    -------
    WongReeceResult
        ``load`` is the vertical soil force W [N] at this entry angle.

    Raises
    ------
    InputError
        Non-positive radius or width, slip outside [-1, 1], entry angle/sinkage out of range or both/
        neither given, theta_m outside [theta_2, theta_1], a non-positive Bekker modulus at this width.
    """
    radius, width, slip, ground, theta2, nodes = _checked(radius, width, soil, slip, exit_angle, node_count)
    if (entry_angle is None) == (sinkage is None):
        raise InputError("entry_angle / sinkage", (entry_angle, sinkage), "exactly one of the two")
    if entry_angle is not None:
        theta1 = check_range("entry_angle", entry_angle, 0.0, _HALF_PI, unit="rad")
        if theta1 == 0.0:
            raise InputError("entry_angle", entry_angle, "an angle in (0, pi/2] rad")
    else:
        assert sinkage is not None
        z0 = check_range(
            "sinkage", sinkage, 0.0, radius, unit="m", hint="Wong-Reece holds up to the axle at the surface"
        )
        if z0 == 0.0:
            raise InputError("sinkage", sinkage, f"a sinkage in (0, {radius:g}] m")
        theta1 = math.acos(max(-1.0, 1.0 - z0 / radius))
    ratio = _check_theta_m_ratio(c1, c2, slip, theta2, theta1)
    integrals = _integrals(np.array([theta1]), radius, width, ground, slip, ratio, theta2, nodes)
    prof = _profiles(theta1, theta2, ratio, radius, ground, slip, profile_points) if profiles else None
    return _result(integrals, theta1, theta2, ratio, radius, slip, prof)


def wong_reece_wheel(
    radius: float,
    width: float,
    soil: BekkerParameters | Material | str,
    slip: float,
    load: float,
    *,
    c1: float = DEFAULT_C1,
    c2: float = DEFAULT_C2,
    exit_angle: float = 0.0,
    node_count: int = DEFAULT_NODE_COUNT,
    profiles: bool = False,
    profile_points: int = 181,
) -> WongReeceResult:
    """Steady Wong-Reece rigid wheel: the sinkage at which the soil carries ``load``, and its forces.

    The entry angle theta_1 in (0, pi/2] solves W(theta_1) = load: W is evaluated on a grid of entry
    angles at once, the first grid interval where it reaches the load brackets the root, and Brent's
    method refines it (the solved W matches the load to about 1e-12 relative).

    Parameters
    ----------
    radius, width : float
        Wheel radius r and width b [m], > 0.
    soil : BekkerParameters, Material or str
        Soil parameters or a medium that has them.
    slip : float
        s in [-1, 1]; > 0 driving, < 0 skidding.
    load : float
        Vertical load W on the axle [N], > 0.
    c1, c2, exit_angle, node_count, profiles, profile_points
        As in :func:`wong_reece_wheel_forces`; theta_m = (c1 + c2 s) theta_1 must lie in
        [theta_2, theta_1] for every entry angle up to pi/2.

    Returns
    -------
    WongReeceResult

    Raises
    ------
    InputError
        Bad inputs (see :func:`wong_reece_wheel_forces`) or a non-positive load.
    SolverError
        The soil cannot carry the load before theta_1 reaches pi/2 (axle at the surface); the message
        gives the largest load it carries.
    """
    radius, width, slip, ground, theta2, nodes = _checked(radius, width, soil, slip, exit_angle, node_count)
    load = check_positive("load", load)
    # theta_m in [theta_2, theta_1] at theta_1 = pi/2 implies it for every smaller entry angle.
    ratio = _check_theta_m_ratio(c1, c2, slip, theta2, _HALF_PI)
    theta1 = _solve_entry_angle(radius, width, ground, slip, load, ratio, theta2, nodes)
    integrals = _integrals(np.array([theta1]), radius, width, ground, slip, ratio, theta2, nodes)
    prof = _profiles(theta1, theta2, ratio, radius, ground, slip, profile_points) if profiles else None
    return _result(integrals, theta1, theta2, ratio, radius, slip, prof)


def _integrals(
    theta1: FloatArray,
    radius: float,
    width: float,
    soil: _Soil,
    slip: float,
    ratio: float,
    theta2: float,
    nodes: int,
) -> FloatArray:
    return _wong_reece_integrals_many(theta1, theta2, radius, width, *soil, slip, ratio, nodes)


def _solve_entry_angle(
    radius: float,
    width: float,
    soil: _Soil,
    slip: float,
    load: float,
    ratio: float,
    theta2: float,
    nodes: int,
) -> float:
    """Smallest entry angle in (0, pi/2] at which the vertical soil force reaches ``load``."""
    grid = np.linspace(0.0, _HALF_PI, _BRACKET_POINTS + 1)
    vertical = _integrals(grid, radius, width, soil, slip, ratio, theta2, nodes)[0]
    reached = np.nonzero(vertical >= load)[0]
    if reached.size == 0:
        raise SolverError(
            f"load = {load:.6g} N: the soil carries at most {float(vertical.max()):.4g} N before the entry "
            f"angle reaches pi/2 (axle at the surface) for this {radius:g} m x {width:g} m wheel at slip "
            f"{slip:g}; lower the load or use a larger or wider wheel"
        )
    i = int(reached[0])
    if i == 0:  # cannot happen for a positive load (W = 0 at theta_1 = 0 without cohesion)
        raise SolverError(f"load = {load:.6g} N: the vertical soil force is not zero at zero sinkage")

    def excess(t1: float) -> float:
        return float(_integrals(np.array([t1]), radius, width, soil, slip, ratio, theta2, nodes)[0, 0]) - load

    return float(brentq(excess, grid[i - 1], grid[i], xtol=1e-15, rtol=1e-14, maxiter=200))


# --------------------------------------------------------------------------------------------------
# Terrain model
# --------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class WongReeceModel:
    """Wong-Reece rigid-wheel terrain model (implements :class:`~terradyn.terrain.TerrainModel`).

    Only :class:`~terradyn.geometry.WheelCircular` bodies (origin at the axle) are supported. The wheel's
    sinkage is ``surface_level - (pose.z - radius)``; its slip comes from the twist,
    s = 1 - vx / (omega radius) (omega must be non-zero; vz and the pose angle do not enter). A wheel
    spinning backwards (omega < 0) is treated as the mirror image of one rolling forwards.

    Parameters
    ----------
    material : Material or str
        A medium with Bekker parameters.
    c1, c2 : float
        theta_m = (c1 + c2 s) theta_1 [-].
    exit_angle : float
        theta_2 [rad] in [-pi/2, 0].
    surface_level : float
        Height of the undisturbed surface [m].
    node_count : int
        Gauss-Legendre nodes per contact region.
    """

    material: Material | str
    _: KW_ONLY
    c1: float = DEFAULT_C1
    c2: float = DEFAULT_C2
    exit_angle: float = 0.0
    surface_level: float = 0.0
    node_count: int = DEFAULT_NODE_COUNT

    def __post_init__(self) -> None:
        object.__setattr__(self, "material", get_material(self.material))
        self.bekker  # noqa: B018 - raises InputError now if the medium has no Bekker parameters
        object.__setattr__(self, "c1", check_finite("c1", self.c1))
        object.__setattr__(self, "c2", check_finite("c2", self.c2))
        object.__setattr__(self, "exit_angle", _check_exit_angle(self.exit_angle))
        object.__setattr__(self, "surface_level", check_finite("surface_level", self.surface_level))
        object.__setattr__(self, "node_count", _check_node_count(self.node_count))

    @property
    def name(self) -> str:
        return "wong-reece"

    @property
    def bekker(self) -> BekkerParameters:
        assert isinstance(self.material, Material)
        return self.material.require_bekker()

    def _wheel(self, body: Any) -> WheelCircular:
        if not isinstance(body, WheelCircular):
            raise InputError(
                "body",
                type(body).__name__,
                "a WheelCircular",
                "Wong-Reece is a rigid circular wheel model; use RFT for other shapes",
            )
        return body

    def _state(self, body: Any, pose: Pose2D, twist: Twist2D) -> tuple[WheelCircular, float, float, float]:
        """(wheel, sinkage [m], slip [-], mirror sign) of a wheel at a pose and twist."""
        wheel = self._wheel(body)
        r = wheel.radius
        if twist.omega == 0.0:
            raise InputError("twist.omega", twist.omega, "a non-zero spin [rad/s]", "slip is undefined")
        slip = 1.0 - twist.vx / (twist.omega * r)
        if not -1.0 <= slip <= 1.0:
            raise InputError(
                "slip",
                slip,
                "a slip in [-1, 1]",
                f"s = 1 - vx / (omega r) with vx = {twist.vx:g} m/s, omega = {twist.omega:g} rad/s",
            )
        sinkage = self.surface_level - (pose.z - r)
        if sinkage > r:
            if sinkage > r * (1.0 + 1e-9):
                raise InputError(
                    "pose.z",
                    pose.z,
                    f"an axle height >= surface_level = {self.surface_level:g} m",
                    f"Wong-Reece holds for sinkage up to the radius; sinkage {sinkage:.4g} m > {r:g} m",
                )
            sinkage = r
        return wheel, sinkage, slip, math.copysign(1.0, twist.omega)

    def wheel_state(self, body: Any, pose: Pose2D, twist: Twist2D) -> WongReeceResult | None:
        """Full Wong-Reece result of a wheel at a pose and twist (None when it does not touch)."""
        wheel, sinkage, slip, _ = self._state(body, pose, twist)
        if sinkage <= 0.0:
            return None
        return wong_reece_wheel_forces(
            wheel.radius,
            wheel.width,
            self.bekker,
            slip,
            sinkage=sinkage,
            c1=self.c1,
            c2=self.c2,
            exit_angle=self.exit_angle,
            node_count=self.node_count,
        )

    def wrench(
        self,
        body: Any,
        pose: Pose2D,
        twist: Twist2D,
        *,
        about: tuple[float, float] | None = None,
    ) -> Wrench2D:
        """Soil force on the wheel [N] and its torque about +y [N m] about ``about`` (default the axle).

        fx is the drawbar pull, fz the vertical soil force W, torque_y the soil torque (= -drive torque
        about the axle). A wheel above the surface feels nothing.
        """
        wheel, sinkage, slip, mirror = self._state(body, pose, twist)
        if sinkage <= 0.0:
            return Wrench2D(0.0, 0.0, 0.0)
        r = wheel.radius
        theta1 = math.acos(max(-1.0, 1.0 - sinkage / r))
        ratio = _check_theta_m_ratio(self.c1, self.c2, slip, self.exit_angle, theta1)
        ground = _soil_for_width(self.bekker, wheel.width)
        w, dp, drive, _, _ = _integrals(
            np.array([theta1]), r, wheel.width, ground, slip, ratio, self.exit_angle, self.node_count
        )[:, 0]
        fx, fz, torque = mirror * float(dp), float(w), -mirror * float(drive)
        if about is not None:
            ax, az = float(about[0]), float(about[1])
            rx, rz = pose.x - ax, pose.z - az
            torque += rz * fx - rx * fz
        return Wrench2D(fx, fz, torque)

    def contact_angles(self, body: Any, pose: Pose2D, twist: Twist2D) -> tuple[float, float]:
        """Entry and exit angles [rad] of the contact, + to the front (zeros when not touching).

        For a wheel spinning backwards the contact is mirrored: entry -theta_1, exit -theta_2.
        """
        wheel, sinkage, _, mirror = self._state(body, pose, twist)
        if sinkage <= 0.0:
            return 0.0, 0.0
        theta1 = math.acos(max(-1.0, 1.0 - sinkage / wheel.radius))
        return mirror * theta1, mirror * self.exit_angle

    def wheel(self, body: Any, load: float, slip: float, *, profiles: bool = False) -> WongReeceResult:
        """Steady wheel at a load [N] and slip [-] (:func:`wong_reece_wheel` with this model's options)."""
        wheel = self._wheel(body)
        return wong_reece_wheel(
            wheel.radius,
            wheel.width,
            self.bekker,
            slip,
            load,
            c1=self.c1,
            c2=self.c2,
            exit_angle=self.exit_angle,
            node_count=self.node_count,
            profiles=profiles,
        )
