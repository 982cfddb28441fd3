"""Steady forced-slip state of a wheel on triangle meshes with 3D RFT, at a slip and a slip angle.

Frames and conventions
----------------------
The wheel mesh is given in its body frame with the origin on the axle and the axle along body y
(x forward, z up, DESIGN.md section 4). The solve works in the *wheel frame*: x along the wheel
heading (longitudinal), y along the axle (lateral, + to the wheel's left), z up; the undisturbed free
surface is horizontal at ``surface_level``. 3D RFT is isotropic about the vertical (its local frame is
built from the direction of motion), so where the wheel heads in the world does not change anything
reported in the wheel frame.

* Spin omega >= 0 about +y rolls the wheel forward. The longitudinal slip relates the rim speed
  omega r to V_x, the axle speed along the heading (r the nominal radius, default the largest
  distance of a vertex from the axle in the body x-z plane): classic ``s = 1 - V_x / (omega r)``, or
  bounded ``s = (omega r - V_x) / max(omega r, V_x)`` (-1: a locked wheel), see
  :class:`terradyn.kinematics.SlipDefinition`. The motion is given by a slip, or by the rim and
  carriage speeds (:func:`wheel_kinematics_3d`).
* Slip angle (ISO 8855 sign): ``slip_angle = (direction of the axle velocity) - (heading)``, measured
  counter-clockwise seen from above (about +z), in [-90, 90] deg. A positive slip angle means the
  wheel moves towards its left: with a slip ``V_y = V_x tan(slip_angle)``, with a carriage speed V
  ``(V_x, V_y) = V (cos, sin)(slip_angle)``; 90 deg (sideways) needs the speeds. Under this sign the
  soil's lateral force on a plain wheel opposes V_y, i.e. it is negative for a positive slip angle.
* Load control (:func:`wheel_steady_3d`) or a prescribed sinkage (:func:`wheel_at_sinkage_3d`).
* Facets the medium cannot reach (a hub inside a closed tyre) are dropped by
  :func:`wheel_contact_mesh` (visibility from outside along the motion and penetration directions).
* Outputs are soil forces and moments on the wheel, moments about the axle centre, in the wheel
  frame: drawbar pull = F_x (+ forward), side force = F_y (+ left), vertical force = F_z,
  drive torque = -M_y (the motor torque, + driving forward), overturning moment = M_x (about the
  longitudinal axis through the axle, right-hand rule), aligning moment = M_z (about the vertical
  through the axle, + counter-clockwise seen from above).
* Periodic wheels (grousers) are averaged over ``phase_count`` wheel angles spread evenly over one
  ``period``: the mean vertical force balances the load, and means, minima and maxima over the
  period are reported. By default the period is detected from the mesh
  (:func:`wheel_period_3d`: the smallest turn about the axle that maps the vertices onto themselves,
  e.g. 2 pi / lug count). An axisymmetric wheel needs ``phase_count = 1``.

References
----------
S. Agarwal, D. I. Goldman, K. Kamrin, "Mechanistic framework for reduced-order models in soft
materials: application to three-dimensional granular intrusion", PNAS 120, e2214017120 (2023).
doi:10.1073/pnas.2214017120
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError, SolverError, check_finite, check_positive, check_range
from ..geometry3d import TriangleMesh
from ..geometry3d.kinematics import rotations_y
from ..kinematics import SlipDefinition
from ..materials import Material
from ..results import TableResult
from .wheel3d import (
    WheelKinematics3D,
    rft3d_medium,
    wheel_contact_directions,
    wheel_contact_mesh,
    wheel_kinematics_3d,
    xi_from_zeta,
)

__all__ = [
    "WheelKinematics3D",
    "WheelSteady3DResult",
    "rft3d_medium",
    "steady3d_record",
    "sweep_3d",
    "wheel_at_sinkage_3d",
    "wheel_contact_directions",
    "wheel_contact_mesh",
    "wheel_kinematics_3d",
    "wheel_nominal_radius_3d",
    "wheel_period_3d",
    "wheel_steady_3d",
    "xi_from_zeta",
]

# Axle heights of the coarse scan that brackets the load (as _steady_kernels.SCAN_POINTS).
_SCAN_POINTS = 17

# Facet evaluations of the coarse scan below which it runs on one thread (a parallel launch costs more
# than it saves on small meshes, and on a shared machine a second thread may not get a core at all).
_MIN_PARALLEL_WORK = 200_000


@dataclass(frozen=True)
class WheelSteady3DResult:
    """Steady operating point of a wheel in 3D RFT (period-averaged for periodic wheels).

    Attributes (SI, wheel frame: x along the heading, y along the axle to the left, z up)
    -------------------------------------------------------------------------------------
    model : "rft3d"; slip [-]; slip_angle_rad [rad] (ISO sign, module notes); load_N [N];
    omega_rad_s [rad/s]; nominal_radius_m [m];
    longitudinal_velocity_m_s, lateral_velocity_m_s : axle velocity V_x, V_y [m/s];
    sinkage_m : depth of the wheel's lowest point below the undisturbed surface [m], 0 for a phase clear
        of it (period mean);
    axle_height_m : axle height above the surface [m] (negative when buried);
    drawbar_pull_N : F_x [N], + forward; side_force_N : F_y [N], + left; vertical_force_N : F_z [N]
    (equals the load); drive_torque_Nm : -M_y [N m], + driving forward; power_W : drive torque x omega
    [W]; tractive_efficiency : drawbar_pull x V_x / power [-] (0 when power <= 0);
    aligning_moment_Nm : M_z [N m]; overturning_moment_Nm : M_x [N m] (moments about the axle centre);
    contact_x_min_m, contact_x_max_m, contact_y_min_m, contact_y_max_m : extent of the loaded facets
    (centroids) relative to the axle, at phase 0 [m]; contact_length_m, contact_width_m : their spans;
    entry_angle_rad, exit_angle_rad : front and rear ends of the loaded contact in the x-z plane, from
    the downward vertical, + towards the front (phase 0) [rad];
    *_min_*, *_max_* : extremes over the period (equal to the mean for phase_count = 1);
    phase_count; period_rad : wheel angle spanned by the phases [rad] (0 for one phase); facet_count.
    """

    model: str
    slip: float
    slip_angle_rad: float
    load_N: float
    omega_rad_s: float
    nominal_radius_m: float
    longitudinal_velocity_m_s: float
    lateral_velocity_m_s: float
    sinkage_m: float
    axle_height_m: float
    drawbar_pull_N: float
    side_force_N: float
    vertical_force_N: float
    drive_torque_Nm: float
    power_W: float
    tractive_efficiency: float
    aligning_moment_Nm: float
    overturning_moment_Nm: float
    contact_x_min_m: float
    contact_x_max_m: float
    contact_y_min_m: float
    contact_y_max_m: float
    contact_length_m: float
    contact_width_m: float
    entry_angle_rad: float
    exit_angle_rad: float
    drawbar_pull_min_N: float
    drawbar_pull_max_N: float
    side_force_min_N: float
    side_force_max_N: float
    drive_torque_min_Nm: float
    drive_torque_max_Nm: float
    vertical_force_min_N: float
    vertical_force_max_N: float
    sinkage_min_m: float
    sinkage_max_m: float
    phase_count: int
    period_rad: float
    facet_count: int
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def slip_angle_deg(self) -> float:
        """Slip angle [deg]."""
        return math.degrees(self.slip_angle_rad)

    def to_dict(self) -> dict[str, Any]:
        """All fields (``extra`` merged in)."""
        d = asdict(self)
        d.pop("extra")
        d.update(self.extra)
        return d

    def summary(self) -> dict[str, float]:
        """The headline figures (as :func:`steady3d_record`)."""
        return steady3d_record(self)


def steady3d_record(result: WheelSteady3DResult) -> dict[str, float]:
    """JSON-ready record of a 3D steady solve (SI, unit-suffixed keys; slip angle in degrees).

    Keys: sinkage_m, drawbar_pull_N, drive_torque_Nm, power_W, side_force_N, aligning_moment_Nm,
    vertical_force_N, slip, slip_angle_deg.
    """
    if not isinstance(result, WheelSteady3DResult):
        raise InputError("result", type(result).__name__, "a WheelSteady3DResult")
    return {
        "sinkage_m": result.sinkage_m,
        "drawbar_pull_N": result.drawbar_pull_N,
        "drive_torque_Nm": result.drive_torque_Nm,
        "power_W": result.power_W,
        "side_force_N": result.side_force_N,
        "aligning_moment_Nm": result.aligning_moment_Nm,
        "vertical_force_N": result.vertical_force_N,
        "slip": result.slip,
        "slip_angle_deg": result.slip_angle_deg,
    }


def wheel_nominal_radius_3d(mesh: TriangleMesh) -> float:
    """Largest distance [m] of a vertex from the axle (body y axis), measured in the body x-z plane."""
    _check_mesh(mesh)
    v = mesh.vertices
    return float(np.sqrt(v[:, 0] ** 2 + v[:, 2] ** 2).max())


def wheel_period_3d(mesh: TriangleMesh, *, tolerance: float | None = None) -> float:
    """Smallest wheel angle [rad] after which the mesh repeats: 2 pi / k for the largest k found.

    A turn by 2 pi / k about the axle (body y) must map every vertex to within ``tolerance`` [m]
    (default 1e-5 x the nominal radius, loose enough for single-precision STL files) of a vertex.
    Candidates k are the divisors of the number of distinct angles of the outermost vertices.
    Returns 2 pi when the mesh has no rotational symmetry; a meshed cylinder of N rim quads gives
    2 pi / N.
    """
    _check_mesh(mesh)
    v = mesh.vertices
    rho = np.hypot(v[:, 0], v[:, 2])
    rmax = float(rho.max())
    tol = 1e-5 * rmax if tolerance is None else check_positive("tolerance", tolerance)
    outer = v[rho > rmax - tol]
    angles = np.sort(np.arctan2(outer[:, 2], outer[:, 0]))
    gaps = np.diff(np.concatenate((angles, angles[:1] + 2.0 * math.pi)))
    distinct = max(1, int(np.count_nonzero(gaps > tol / rmax)))
    grid = _PointGrid(v, tol)
    for k in sorted((d for d in range(2, distinct + 1) if distinct % d == 0), reverse=True):
        rot = rotations_y(np.array([2.0 * math.pi / k]))[0]
        if grid.all_near(v @ rot.T):
            return 2.0 * math.pi / k
    return 2.0 * math.pi


class _PointGrid:
    """Points hashed on a grid of cell ``tol``: does every query point lie within ``tol`` of one?

    NumPy only (scipy.spatial costs a quarter of a second to import in a CLI call). A point within tol
    of q lies in one of the 27 cells around q's; each cell is looked up by a sorted integer code. If
    some cell holds several points (points closer than tol), the first one found is checked and a
    miss falls back to a brute-force check of that query point.
    """

    def __init__(self, points: NDArray[np.float64], tol: float) -> None:
        self.points, self.tol = points, tol
        self.origin = points.min(axis=0) - 2.0 * tol
        cells = np.floor((points - self.origin) / tol).astype(np.int64)
        self.base = int(cells.max()) + 3
        codes = self._code(cells)
        self.order = np.argsort(codes, kind="stable")
        self.codes = codes[self.order]

    def _code(self, cells: NDArray[np.int64]) -> NDArray[np.int64]:
        b = self.base
        return (cells[:, 0] * b + cells[:, 1]) * b + cells[:, 2]

    def all_near(self, queries: NDArray[np.float64]) -> bool:
        cells = np.floor((queries - self.origin) / self.tol).astype(np.int64)
        if np.any(cells < 1) or np.any(cells > self.base - 2):
            return False
        found = np.zeros(queries.shape[0], dtype=bool)
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    todo = ~found
                    if not np.any(todo):
                        return True
                    code = self._code(cells[todo] + np.array([dx, dy, dz]))
                    at = np.minimum(np.searchsorted(self.codes, code), self.codes.size - 1)
                    hit = self.codes[at] == code
                    near = self.points[self.order[at]]
                    close = hit & (np.linalg.norm(near - queries[todo], axis=1) <= self.tol)
                    found[np.nonzero(todo)[0][close]] = True
        for i in np.nonzero(~found)[0]:  # a crowded cell: check the point against all
            if not np.any(np.linalg.norm(self.points - queries[i], axis=1) <= self.tol):
                return False
        return True


def _check_mesh(mesh: TriangleMesh) -> TriangleMesh:
    if not isinstance(mesh, TriangleMesh):
        raise InputError("mesh", type(mesh).__name__, "a terradyn.geometry3d.TriangleMesh")
    return mesh


@dataclass(frozen=True, eq=False)
class _Wheel3D:
    """A wheel at one twist: period-averaged wrenches at axle heights (vectorised over states)."""

    mesh: TriangleMesh
    medium: Material | float
    linear: NDArray[np.float64]
    angular: NDArray[np.float64]
    rotations: NDArray[np.float64]
    surface: float
    leading_edge: bool
    surface_friction: float | None
    period: float = 0.0

    def wrenches(self, heights: ArrayLike) -> NDArray[np.float64]:
        """Wrenches (H, P, 6) [N, N m] at axle heights (H,) [m] over the P phases, about the axle."""
        from ..rft.rft3d import rft3d_wrench_many

        h = np.atleast_1d(np.asarray(heights, dtype=np.float64))
        phases = self.rotations.shape[0]
        count = h.size * phases
        positions = np.zeros((count, 3))
        positions[:, 2] = np.repeat(h, phases)
        out = rft3d_wrench_many(
            self.mesh, self.medium, positions, np.tile(self.rotations, (h.size, 1, 1)),
            np.broadcast_to(self.linear, (count, 3)), np.broadcast_to(self.angular, (count, 3)),
            surface_level=self.surface, leading_edge=self.leading_edge,
            surface_friction=self.surface_friction,
        )  # fmt: skip
        return out.reshape(h.size, phases, 6)

    def vertical(self, heights: ArrayLike) -> NDArray[np.float64]:
        """Period-mean vertical force [N] at each axle height [m]."""
        return self.wrenches(heights)[..., 2].mean(axis=1)


def _solve_height(wheel: _Wheel3D, load: float, low: float, high: float, what: str) -> float:
    """Axle height [m] in [low, high] where the period-mean vertical force equals ``load`` [N].

    ``low`` puts the axle at the surface (the deepest state the solver accepts); at ``high`` the wheel
    only just touches, so the force there is zero.
    """
    grid = np.linspace(low, high, _SCAN_POINTS)
    fz = wheel.vertical(grid)
    if fz[0] < load:
        raise SolverError(
            f"{what}: the medium carries at most {fz[0]:.6g} N (maximum, with the axle at the surface), "
            f"less than the load {load:.6g} N (lower the load or use a wider or larger wheel)"
        )
    j = int(np.nonzero(fz < load)[0][0])
    if np.any(fz[j:] >= load):
        raise SolverError(f"{what}: vertical force is not monotonic in sinkage; no unique sinkage")

    def residual(z: float) -> float:
        return float(wheel.vertical([z])[0]) - load

    from scipy.optimize import brentq

    span = max(high - low, 1e-12)
    return float(brentq(residual, grid[j - 1], grid[j], xtol=1e-13 * span, rtol=1e-14, maxiter=200))


def _contact_patch(
    wheel: _Wheel3D, height: float, rotation: NDArray[np.float64]
) -> tuple[float, float, float, float, float, float]:
    """(x_min, x_max, y_min, y_max [m], entry, exit [rad]) of the loaded facets at one phase."""
    from ..rft.rft3d import rft3d_facet_tractions

    mesh = wheel.mesh
    offsets = mesh.centroids @ rotation.T
    velocities = wheel.linear + np.cross(wheel.angular, offsets)
    centroids = offsets + np.array([0.0, 0.0, height])
    xi = float(wheel.medium) if not isinstance(wheel.medium, Material) else _xi(wheel.medium)
    friction = wheel.surface_friction
    if friction is None and isinstance(wheel.medium, Material):
        friction = wheel.medium.surface_friction
    tractions = rft3d_facet_tractions(
        centroids, mesh.normals @ rotation.T, velocities, xi=xi, surface_level=wheel.surface,
        leading_edge=wheel.leading_edge, surface_friction=friction,
    )  # fmt: skip
    active = np.any(tractions != 0.0, axis=1) & (mesh.areas > 0.0)
    if not np.any(active):
        return (0.0,) * 6
    rel = offsets[active]
    angles = np.arctan2(rel[:, 0], -rel[:, 2])
    return (
        float(rel[:, 0].min()), float(rel[:, 0].max()), float(rel[:, 1].min()), float(rel[:, 1].max()),
        float(angles.max()), float(angles.min()),
    )  # fmt: skip


def _xi(material: Material) -> float:
    from ..rft.rft3d import agarwal2023_xi_material

    return agarwal2023_xi_material(material)


def _phases(phase_count: int, period: float | None) -> tuple[int, float]:
    if isinstance(phase_count, bool) or not isinstance(phase_count, int | np.integer):
        raise InputError("phase_count", phase_count, "an integer in [1, 4096]")
    if not 1 <= phase_count <= 4096:
        raise InputError("phase_count", phase_count, "an integer in [1, 4096]")
    span = math.nan if period is None else check_range("period", period, 1e-9, 2.0 * math.pi, unit="rad")
    return int(phase_count), span


def wheel_steady_3d(
    mesh: TriangleMesh,
    medium: Material | float,
    load: float,
    slip: float | None = None,
    *,
    slip_angle: float = 0.0,
    omega: float = 1.0,
    slip_definition: SlipDefinition | str = SlipDefinition.CLASSIC,
    rim_speed: float | None = None,
    carriage_speed: float | None = None,
    nominal_radius: float | None = None,
    phase_count: int = 1,
    period: float | None = None,
    surface_level: float = 0.0,
    leading_edge: bool = True,
    surface_friction: float | None = None,
) -> WheelSteady3DResult:
    """Steady forced-slip state of a 3D wheel in 3D RFT: the sinkage that carries the load, and the
    forces and moments there.

    Parameters
    ----------
    mesh : TriangleMesh
        Closed wheel surface, body origin on the axle, axle along body y.
    medium : Material or float
        A medium with ``critical_density`` and ``internal_friction_angle`` (MS, MMS, LPS, CPS ship
        both), or the 3D-RFT media scale xi [N/m^3].
    load : float
        Vertical load on the axle [N] (> 0).
    slip : float, optional
        Longitudinal slip in [-1, 1]; > 0 driving, < 0 skidding; classic s = 1 - V_x / (omega r) or,
        with ``slip_definition="bounded"``, s = (omega r - V_x) / max(omega r, V_x) (-1: locked wheel).
        Or give ``rim_speed`` and ``carriage_speed`` instead (:func:`wheel_kinematics_3d`).
    slip_angle : float
        Angle [rad] from the heading to the axle velocity, + counter-clockwise seen from above
        (ISO 8855; velocity towards the wheel's left); |slip_angle| <= pi/2 (= pi/2 only with the
        speeds). With a slip, V_y = V_x tan(slip_angle).
    omega : float
        Spin rate [rad/s] (> 0) with a slip (for a bounded s < 0: V_x = omega r, spin (1 + s) omega).
        Quasi-static RFT does not depend on it.
    slip_definition : SlipDefinition or str
        "classic" (default) or "bounded"; also the definition of the result's ``slip``.
    rim_speed, carriage_speed : float, optional
        omega r [m/s] (>= 0) and the axle's speed over the ground [m/s] (> 0), instead of ``slip``.
    nominal_radius : float, optional
        r [m] of the slip definition; default :func:`wheel_nominal_radius_3d`.
    phase_count : int
        Wheel angles averaged over one period (1 for an axisymmetric wheel).
    period : float, optional
        Wheel angle [rad] after which the mesh repeats (2 pi / lug count for a grousered wheel);
        default detected from the mesh (:func:`wheel_period_3d`). Used only when ``phase_count`` > 1.
    surface_level : float
        Height of the free surface [m].
    leading_edge : bool
        Load only facets moving into the medium (n . v > 0).
    surface_friction : float, optional
        Wheel-medium friction cap [-] (default the medium's, none if it has none).

    Returns
    -------
    WheelSteady3DResult

    Raises
    ------
    InputError
        A bad argument; the message names it.
    SolverError
        The medium cannot carry the load before the axle reaches the surface (the message gives the
        maximum it carries), or the vertical force is not monotonic in sinkage.
    """
    _check_mesh(mesh)
    load = check_positive("load", load)
    wheel, lowest, kin, radius = _setup(
        mesh, medium, slip, slip_angle=slip_angle, omega=omega, slip_definition=slip_definition,
        rim_speed=rim_speed, carriage_speed=carriage_speed, nominal_radius=nominal_radius,
        phase_count=phase_count, period=period, surface_level=surface_level,
        leading_edge=leading_edge, surface_friction=surface_friction,
    )  # fmt: skip
    what = f"load {load:g} N at slip {kin.slip:g}, slip angle {math.degrees(slip_angle):g} deg"
    state = _solve_state(wheel, lowest, load, what)
    return _result(wheel, kin, radius, load, float(slip_angle), state)


def _setup(
    mesh: TriangleMesh,
    medium: Material | float,
    slip: float | None,
    *,
    slip_angle: float,
    omega: float,
    slip_definition: SlipDefinition | str,
    rim_speed: float | None,
    carriage_speed: float | None,
    nominal_radius: float | None,
    phase_count: int,
    period: float | None,
    surface_level: float,
    leading_edge: bool,
    surface_friction: float | None,
) -> tuple[_Wheel3D, NDArray[np.float64], WheelKinematics3D, float]:
    """The wheel at its twist, the lowest body z of each phase, the kinematics and the radius."""
    phase_count, span = _phases(phase_count, period)
    radius = (
        wheel_nominal_radius_3d(mesh)
        if nominal_radius is None
        else check_positive("nominal_radius", nominal_radius)
    )
    kin = wheel_kinematics_3d(
        radius, slip, slip_angle=slip_angle, omega=omega, slip_definition=slip_definition,
        rim_speed=rim_speed, carriage_speed=carriage_speed,
    )  # fmt: skip
    surface = check_finite("surface_level", surface_level)
    if phase_count == 1:
        span = 0.0
    elif math.isnan(span):
        span = wheel_period_3d(mesh)
    thetas = np.arange(phase_count) * span / phase_count
    rotations = rotations_y(thetas)
    wheel = _Wheel3D(
        mesh, medium, np.array([kin.longitudinal_velocity, kin.lateral_velocity, 0.0]),
        np.array([0.0, kin.omega, 0.0]), rotations, surface, bool(leading_edge), surface_friction,
        span,
    )  # fmt: skip
    v = mesh.vertices
    lowest = np.min(
        -np.sin(thetas)[:, None] * v[None, :, 0] + np.cos(thetas)[:, None] * v[None, :, 2], axis=1
    )
    return wheel, lowest, kin, radius


def _result(
    wheel: _Wheel3D, kin: WheelKinematics3D, radius: float, load: float, slip_angle: float, state: _State
) -> WheelSteady3DResult:
    z, (fx, fy, fz, mx, drive, mz), (dp_lo, dp_hi, fy_lo, fy_hi, drive_lo, drive_hi, fz_lo, fz_hi) = state[:3]
    sink, sink_lo, sink_hi = state[3]
    x0, x1, y0, y1, entry, exit_ = state[4]
    omega, vx, vy, surface = kin.omega, kin.longitudinal_velocity, kin.lateral_velocity, wheel.surface
    power = drive * omega
    phase_count, span, mesh = wheel.rotations.shape[0], wheel.period, wheel.mesh
    return WheelSteady3DResult(
        model="rft3d", slip=kin.slip, slip_angle_rad=slip_angle, load_N=load, omega_rad_s=omega,
        nominal_radius_m=radius, longitudinal_velocity_m_s=vx, lateral_velocity_m_s=vy,
        sinkage_m=sink, axle_height_m=z - surface, drawbar_pull_N=fx, side_force_N=fy,
        vertical_force_N=fz, drive_torque_Nm=drive, power_W=power,
        tractive_efficiency=fx * vx / power if power > 0 else 0.0,
        aligning_moment_Nm=mz, overturning_moment_Nm=mx,
        contact_x_min_m=x0, contact_x_max_m=x1, contact_y_min_m=y0, contact_y_max_m=y1,
        contact_length_m=x1 - x0, contact_width_m=y1 - y0, entry_angle_rad=entry, exit_angle_rad=exit_,
        drawbar_pull_min_N=dp_lo, drawbar_pull_max_N=dp_hi, side_force_min_N=fy_lo, side_force_max_N=fy_hi,
        drive_torque_min_Nm=drive_lo, drive_torque_max_Nm=drive_hi,
        vertical_force_min_N=fz_lo, vertical_force_max_N=fz_hi,
        sinkage_min_m=sink_lo, sinkage_max_m=sink_hi, phase_count=phase_count,
        period_rad=span, facet_count=mesh.facet_count,
        extra={"slip_definition": kin.slip_definition},
    )  # fmt: skip


def wheel_at_sinkage_3d(
    mesh: TriangleMesh,
    medium: Material | float,
    sinkage: float,
    slip: float | None = None,
    *,
    slip_angle: float = 0.0,
    omega: float = 1.0,
    slip_definition: SlipDefinition | str = SlipDefinition.CLASSIC,
    rim_speed: float | None = None,
    carriage_speed: float | None = None,
    nominal_radius: float | None = None,
    phase_count: int = 1,
    period: float | None = None,
    surface_level: float = 0.0,
    leading_edge: bool = True,
    surface_friction: float | None = None,
) -> WheelSteady3DResult:
    """Forces and moments of a 3D wheel held at a prescribed sinkage (no load balance).

    ``sinkage`` [m] (>= 0) is the period-mean depth of the lowest point, as the ``sinkage_m`` a load
    solve reports; the axle height that gives it is found exactly (it is piecewise linear in the
    height). The result's ``load_N`` and ``vertical_force_N`` are the vertical force the medium
    carries there. Other arguments as :func:`wheel_steady_3d`; solving there at that load returns the
    same state.
    """
    _check_mesh(mesh)
    depth = check_finite("sinkage", sinkage)
    if depth < 0.0:
        raise InputError("sinkage", sinkage, "a depth >= 0 [m] of the lowest point below the surface")
    wheel, lowest, kin, radius = _setup(
        mesh, medium, slip, slip_angle=slip_angle, omega=omega, slip_definition=slip_definition,
        rim_speed=rim_speed, carriage_speed=carriage_speed, nominal_radius=nominal_radius,
        phase_count=phase_count, period=period, surface_level=surface_level,
        leading_edge=leading_edge, surface_friction=surface_friction,
    )  # fmt: skip
    from .prescribed import axle_height_for_sinkage

    z = axle_height_for_sinkage(lowest, depth, wheel.surface)
    state = _state_at(wheel, lowest, z)
    return _result(wheel, kin, radius, state[1][2], float(slip_angle), state)


def _state_at(wheel: _Wheel3D, lowest: NDArray[np.float64], z: float) -> _State:
    """The state tuple of :func:`_solve_compiled` at axle height ``z`` [m]."""
    surface = wheel.surface
    w = wheel.wrenches([z])[0]
    fx, fy, fz, mx, my, mz = (w[:, k] for k in range(6))
    drive = -my
    sink = np.maximum(surface - (z + lowest), 0.0)  # a phase clear of the surface sinks 0
    means = (float(fx.mean()), float(fy.mean()), float(fz.mean()), float(mx.mean()), float(drive.mean()),
             float(mz.mean()))  # fmt: skip
    extremes = tuple(float(f(a)) for a in (fx, fy, drive, fz) for f in (np.min, np.max))
    patch = _contact_patch(wheel, z, wheel.rotations[0])
    return z, means, extremes, (float(sink.mean()), float(sink.min()), float(sink.max())), patch  # type: ignore[return-value]


_State = tuple[
    float,
    tuple[float, float, float, float, float, float],
    tuple[float, float, float, float, float, float, float, float],
    tuple[float, float, float],
    tuple[float, float, float, float, float, float],
]


def _solve_compiled(wheel: _Wheel3D, lowest: NDArray[np.float64], load: float, what: str) -> _State:
    """(z, means (F_x, F_y, F_z, M_x, drive torque, M_z), min/max pairs (F_x, F_y, drive, F_z),
    sinkage (mean, min, max), contact patch) of the steady state: the whole solve compiled."""
    import numba

    from ..rft.rft3d import UPWARD_TOLERANCE, rft3d_medium_scale
    from . import _steady_kernels as k

    low, high = wheel.surface, wheel.surface - float(lowest.min())
    centroids, normals, areas = wheel.mesh.kernel_arrays
    order = k.rft3d_facet_order_kernel(centroids, normals, areas, wheel.rotations, wheel.surface, low, high)
    xi, mu = rft3d_medium_scale(wheel.medium, wheel.surface_friction, 9.81)
    out = np.zeros(30)
    with numba.parallel_chunksize(1):  # scan items differ in size: hand them out one at a time
        status = k.rft3d_steady_kernel(
            *order, wheel.rotations, lowest, wheel.linear, wheel.angular, _coefficients(), xi,
            wheel.surface, wheel.leading_edge, mu, UPWARD_TOLERANCE, low, high, load, 200,
            _MIN_PARALLEL_WORK, out,
        )  # fmt: skip
    if status == k.OVERLOADED:
        raise SolverError(
            f"{what}: the medium carries at most {out[1]:.6g} N (maximum, with the axle at the surface), "
            f"less than the load {load:.6g} N (lower the load or use a wider or larger wheel)"
        )
    if status == k.NOT_MONOTONIC:
        raise SolverError(f"{what}: vertical force is not monotonic in sinkage; no unique sinkage")
    if status == k.NO_CONTACT:
        raise SolverError(f"{what}: the wheel carries the load even with no contact; check its geometry")
    if status != k.OK:
        raise SolverError(f"{what}: the sinkage did not converge in 200 iterations")
    v = out.tolist()
    return v[0], tuple(v[2:8]), tuple(v[8:16]), tuple(v[16:19]), tuple(v[19:25])  # type: ignore[return-value]


def _solve_reference(wheel: _Wheel3D, lowest: NDArray[np.float64], load: float, what: str) -> _State:
    """:func:`_solve_compiled` from the batched wrench function and SciPy's brentq (the reference)."""
    surface = wheel.surface
    z = _solve_height(wheel, load, surface, surface - float(lowest.min()), what)
    return _state_at(wheel, lowest, z)


# The solver wheel_steady_3d uses (tests swap in _solve_reference).
_solve_state = _solve_compiled


def _coefficients() -> NDArray[np.float64]:
    from ..rft.rft3d import agarwal2023_coefficients

    return agarwal2023_coefficients()


_SWEEP_VALUES = (
    "sinkage_m",
    "drawbar_pull_N",
    "side_force_N",
    "vertical_force_N",
    "drive_torque_Nm",
    "power_W",
    "aligning_moment_Nm",
    "overturning_moment_Nm",
    "contact_length_m",
    "contact_width_m",
)


def sweep_3d(
    mesh: TriangleMesh,
    medium: Material | float,
    loads: Sequence[float] | NDArray[np.float64],
    slips: Sequence[float] | NDArray[np.float64],
    slip_angles: Sequence[float] | NDArray[np.float64],
    *,
    omega: float = 1.0,
    nominal_radius: float | None = None,
    phase_count: int = 1,
    period: float | None = None,
    surface_level: float = 0.0,
    leading_edge: bool = True,
    surface_friction: float | None = None,
    slip_definition: SlipDefinition | str = SlipDefinition.CLASSIC,
) -> TableResult:
    """:func:`wheel_steady_3d` over every load [N] x slip [-] x slip angle [rad] (|angle| < pi/2; slips
    in ``slip_definition``).

    Columns: load_N, slip, slip_angle_rad, solved, then sinkage_m, drawbar_pull_N, side_force_N,
    vertical_force_N, drive_torque_Nm, power_W, aligning_moment_Nm, overturning_moment_Nm,
    contact_length_m, contact_width_m. A point the medium cannot carry (:class:`SolverError`) is kept
    with ``solved = False`` and zeros, its reason in ``metadata["failures"]``. Bad inputs raise.
    """
    grids = []
    for name, values in (("loads", loads), ("slips", slips), ("slip_angles", slip_angles)):
        arr = np.atleast_1d(np.asarray(values, dtype=np.float64))
        if arr.ndim != 1 or arr.size == 0:
            raise InputError(name, values, "a non-empty 1D sequence of numbers")
        grids.append(arr)
    rows: list[tuple[Any, ...]] = []
    failures: list[str] = []
    for load in grids[0]:
        for slip in grids[1]:
            for angle in grids[2]:
                try:
                    r = wheel_steady_3d(
                        mesh, medium, float(load), float(slip), slip_angle=float(angle), omega=omega,
                        nominal_radius=nominal_radius, phase_count=phase_count, period=period,
                        surface_level=surface_level, leading_edge=leading_edge,
                        surface_friction=surface_friction, slip_definition=slip_definition,
                    )  # fmt: skip
                    vals: tuple[Any, ...] = (True, *(getattr(r, k) for k in _SWEEP_VALUES))
                except SolverError as exc:
                    failures.append(str(exc))
                    vals = (False, *([0.0] * len(_SWEEP_VALUES)))
                rows.append((float(load), float(slip), float(angle), *vals))
    names = ("load_N", "slip", "slip_angle_rad", "solved", *_SWEEP_VALUES)
    cols = {k: np.asarray([row[i] for row in rows]) for i, k in enumerate(names)}
    medium_name = medium.name if isinstance(medium, Material) else f"xi={float(medium):g} N/m^3"
    return TableResult(
        cols,
        {
            "model": "rft3d",
            "medium": medium_name,
            "facet_count": mesh.facet_count,
            "omega_rad_s": omega,
            "slip_angle_convention": "ISO 8855: velocity direction minus heading, + counter-clockwise",
            "failures": failures,
        },
    )
