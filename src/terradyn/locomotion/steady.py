"""Implicit quasi-static wheel solves ("implicit RFT"): sinkage for a load at a slip, and free rolling.

A wheel of nominal (outer) radius r spins at omega about +y and translates at V_x = (1 - s) omega r.
The solver finds the axle height at which the vertical soil force equals the load W. Non-circular
wheels (grousered, flapped, C-leg) are periodic in the wheel angle: forces are averaged over
``phase_count`` evenly spaced angles of one period at each axle height, the average vertical force
balances W, and the minimum and maximum over the period are reported too.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from functools import lru_cache
from typing import Any

import numpy as np

from ..errors import InputError, SolverError, check_positive, check_range
from ..geometry import Body, WheelCircular
from ..kinematics import Pose2D, SlipDefinition, Twist2D, Wrench2D, as_slip_definition, speeds_from_slip
from ..materials import Material
from ..models import as_terrain_model
from ..rft import RFTModel
from ..terrain import TerrainModel

__all__ = [
    "WheelSteadyResult",
    "wheel_nominal_radius",
    "wheel_rotation_period",
    "wheel_self_propelled",
    "wheel_steady",
]


@dataclass(frozen=True)
class WheelSteadyResult:
    """Steady operating point of a wheel (rotation-averaged for non-circular wheels).

    Attributes (SI)
    ---------------
    model : terrain model name; slip [-]; load_N; omega_rad_s; forward_velocity_m_s;
    sinkage_m : depth of the wheel's lowest point below the undisturbed surface (period average; a
    phase with the lowest point above the surface counts 0, so sinkage is never negative);
    axle_height_m : axle height above the surface; drawbar_pull_N : horizontal soil force, + forward;
    drive_torque_Nm : motor torque, + driving forward; power_W = drive_torque * omega;
    tractive_efficiency = drawbar_pull * V / power (0 when power <= 0);
    entry_angle_rad, exit_angle_rad : extent of the loaded contact, from the vertical below the axle,
    + towards the front (phase 0); min/max : extremes over one period (equal to the mean for
    circular wheels); phase_count.
    """

    model: str
    slip: float
    load_N: float
    omega_rad_s: float
    forward_velocity_m_s: float
    sinkage_m: float
    axle_height_m: float
    drawbar_pull_N: float
    drive_torque_Nm: float
    power_W: float
    tractive_efficiency: float
    entry_angle_rad: float
    exit_angle_rad: float
    drawbar_pull_min_N: float
    drawbar_pull_max_N: float
    drive_torque_min_Nm: float
    drive_torque_max_Nm: float
    vertical_force_min_N: float
    vertical_force_max_N: float
    sinkage_min_m: float
    sinkage_max_m: float
    phase_count: int
    extra: dict[str, Any] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d.pop("extra")
        d.update(self.extra)
        return d

    def summary(self) -> dict[str, float]:
        return {
            "sinkage_m": self.sinkage_m,
            "drawbar_pull_N": self.drawbar_pull_N,
            "drive_torque_Nm": self.drive_torque_Nm,
            "power_W": self.power_W,
        }


def wheel_nominal_radius(body: Body) -> float:
    """Nominal (outer) radius [m] used in the slip definition."""
    r = getattr(body, "outer_radius", None)
    return float(r) if r is not None else body.bounding_radius


def wheel_rotation_period(body: Body) -> float | None:
    """Angle [rad] after which the wheel repeats itself; None for an axisymmetric wheel."""
    if isinstance(body, WheelCircular) or type(body).__name__ == "Cylinder":
        return None
    for attr in ("grouser_count", "flap_count"):
        count = getattr(body, attr, None)
        if count:
            return 2.0 * math.pi / int(count)
    return 2.0 * math.pi


def _as_model(model: Any) -> TerrainModel:
    """A Material means RFT on it; a terrain model object (a user's included) is used as it is; a
    plain function ``wrench(body, pose, twist) -> Wrench2D`` is wrapped
    (:func:`terradyn.models.as_terrain_model`)."""
    if isinstance(model, Material):
        return RFTModel(model)
    if isinstance(model, TerrainModel):
        return model
    if callable(model):
        return as_terrain_model(model)
    raise InputError(
        "model",
        type(model).__name__,
        "a terrain model, a function wrench(body, pose, twist) or a Material (RFT)",
    )


class _ForceFunction:
    """Period-averaged wrench of a wheel at an axle height, for one twist (any terrain model).

    The generic path (Wong-Reece, DRFT, user models): one ``model.wrench`` call per phase and height.
    Quasi-static RFT takes the compiled path (:func:`_rft_point`) instead.
    """

    def __init__(self, model: TerrainModel, body: Body, twist: Twist2D, thetas: np.ndarray) -> None:
        self.model, self.body, self.twist, self.thetas = model, body, twist, thetas
        self.surface = float(getattr(model, "surface_level", 0.0))

    def phases(self, z: float) -> np.ndarray:
        """Wrenches (P, 3) over the phases at axle height ``z`` [m] (torque about the axle)."""
        tw = self.twist
        return np.array(
            [self.model.wrench(self.body, Pose2D(0.0, z, th), tw).as_array() for th in self.thetas]
        )

    def vertical_many(self, heights: np.ndarray) -> np.ndarray:
        """Period-averaged vertical force [N] at each axle height (H,) [m]."""
        return np.array([self.phases(float(z))[:, 1].mean() for z in heights])

    def vertical(self, z: float) -> float:
        return float(self.vertical_many(np.array([z]))[0])


def _lowest_points(body: Body, thetas: np.ndarray) -> np.ndarray:
    """Lowest body-frame z [m] of the outline rotated by each phase (relative to the axle)."""
    pts = np.concatenate(body.outline())
    c, s = np.cos(thetas)[:, None], np.sin(thetas)[:, None]
    z = -s * pts[None, :, 0] + c * pts[None, :, 1]
    return z.min(axis=1)


def _solve_height(fn: _ForceFunction, load: float, top: float, what: str) -> float:
    """Axle height [m] in [0, top] where the averaged vertical force equals ``load``."""
    grid = np.linspace(0.0, top, 17)
    fz = fn.vertical_many(grid)
    if fz[0] < load:
        raise SolverError(
            f"{what}: the medium carries at most {fz[0]:.4g} N before the axle reaches the surface, "
            f"less than the load {load:.4g} N (lower the load or use a wider or larger wheel)"
        )
    # Bracket on the coarse grid: last height with fz >= load, next with fz < load.
    above = np.nonzero(fz < load)[0]
    if above.size == 0:
        raise SolverError(f"{what}: the body carries the load even with no contact; check its geometry")
    j = int(above[0])
    if np.any(np.diff(fz[j - 1 :]) > 1e-9 * max(1.0, load)) and np.any(fz[j:] >= load):
        raise SolverError(f"{what}: vertical force is not monotonic in sinkage; no unique sinkage")
    from scipy.optimize import brentq

    g = lambda z: fn.vertical(z) - load  # noqa: E731
    return float(brentq(g, grid[j - 1], grid[j], xtol=1e-12 * top, rtol=1e-13, maxiter=200))


@lru_cache(maxsize=64)
def _rft_wheel_arrays(body: Body, element_size: float | None) -> tuple[Any, ...]:
    """(midpoints, normals, lengths, width, outline points (M, 2)) of a body, computed once per body."""
    el = body.discretize(element_size)
    return el.midpoints, el.normals, el.lengths, float(el.width), np.concatenate(body.outline())


def _rft_arrays(body: Body, element_size: float | None) -> tuple[Any, ...]:
    try:
        return _rft_wheel_arrays(body, element_size)
    except TypeError:  # an unhashable body: no cache
        return _rft_wheel_arrays.__wrapped__(body, element_size)


def _rft_point(
    model: RFTModel, body: Body, load: float, slip: float, omega: float, thetas: np.ndarray, twist: Twist2D
) -> WheelSteadyResult:
    """:func:`wheel_steady` for quasi-static RFT: the whole solve in one compiled call."""
    from . import _steady_kernels as k

    mid, nrm, lng, width, points = _rft_arrays(body, model.element_size)
    rft = model.material.require_rft()
    out = np.empty(16)
    surface = float(model.surface_level)
    status = k.rft_steady_kernel(
        mid, nrm, lng, width, points, thetas, twist.vx, twist.vz, twist.omega, _coefficients(rft),
        rft.scale, surface, load, 200, out,
    )  # fmt: skip
    if status != k.OK:
        _raise_status(status, f"load {load:g} N at slip {slip:g}", load, float(out[1]))
    (z, _, dp, drive, dp_lo, dp_hi, drive_lo, drive_hi, fz_lo, fz_hi, sink, sink_lo, sink_hi,
     entry, exit_, found) = out.tolist()  # fmt: skip
    power = drive * omega
    return WheelSteadyResult(
        model=model.name, slip=slip, load_N=load, omega_rad_s=omega, forward_velocity_m_s=twist.vx,
        sinkage_m=sink, axle_height_m=z - surface, drawbar_pull_N=dp, drive_torque_Nm=drive,
        power_W=power, tractive_efficiency=dp * twist.vx / power if power > 0 else 0.0,
        entry_angle_rad=entry if found else 0.0, exit_angle_rad=exit_ if found else 0.0,
        drawbar_pull_min_N=dp_lo, drawbar_pull_max_N=dp_hi, drive_torque_min_Nm=drive_lo,
        drive_torque_max_Nm=drive_hi, vertical_force_min_N=fz_lo, vertical_force_max_N=fz_hi,
        sinkage_min_m=sink_lo, sinkage_max_m=sink_hi, phase_count=len(thetas),
    )  # fmt: skip


def _coefficients(rft: Any) -> np.ndarray:
    """Kernel-order Li coefficients (read-only, cached per coefficient set)."""
    try:
        return _coefficient_array(rft.coefficients)
    except TypeError:  # unhashable
        return np.asarray(rft.coefficients.as_array(), dtype=np.float64)


@lru_cache(maxsize=64)
def _coefficient_array(coefficients: Any) -> np.ndarray:
    arr = np.asarray(coefficients.as_array(), dtype=np.float64)
    arr.setflags(write=False)
    return arr


def _raise_status(status: int, what: str, load: float, carried: float) -> None:
    """The SolverError of a failed compiled solve (messages as the generic path)."""
    from . import _steady_kernels as k

    if status == k.OVERLOADED:
        raise SolverError(
            f"{what}: the medium carries at most {carried:.4g} N before the axle reaches the surface, "
            f"less than the load {load:.4g} N (lower the load or use a wider or larger wheel)"
        )
    if status == k.NO_CONTACT:
        raise SolverError(f"{what}: the body carries the load even with no contact; check its geometry")
    if status == k.NOT_MONOTONIC:
        raise SolverError(f"{what}: vertical force is not monotonic in sinkage; no unique sinkage")
    raise SolverError(f"{what}: the sinkage did not converge in 200 iterations")


def wheel_steady(
    body: Body,
    model: TerrainModel | Material | Callable[..., Wrench2D],
    load: float,
    slip: float,
    *,
    omega: float = 1.0,
    phase_count: int = 16,
    slip_definition: SlipDefinition | str = SlipDefinition.CLASSIC,
) -> WheelSteadyResult:
    """Steady forced-slip state of a wheel: sinkage, drawbar pull, torque and power at a slip.

    Parameters
    ----------
    body : Body
        The wheel; origin at the axle. Nominal radius = ``outer_radius`` (or the bounding radius).
    model : TerrainModel, function or Material
        Terrain model: a terradyn model (:func:`terradyn.models.build_model`), a user's object with
        ``name`` and ``wrench(body, pose, twist, *, about=None)``, a plain function
        ``wrench(body, pose, twist) -> Wrench2D``, or a Material (quasi-static RFT on it).
    load : float
        Vertical load W on the axle [N] (> 0).
    slip : float
        In [-1, 1]; > 0 driving, < 0 skidding. Classic definition s = 1 - V_x / (omega r); with
        ``slip_definition="bounded"``, s = (omega r - V_x) / max(omega r, V_x), where -1 is a locked
        wheel (:class:`terradyn.kinematics.SlipDefinition`).
    omega : float
        Spin rate [rad/s] (> 0); for a bounded slip s < 0 it sets the carriage speed V_x = omega r and
        the spin is (1 + s) omega. Quasi-static RFT does not depend on it.
    phase_count : int
        Wheel angles sampled over one period for non-circular wheels (ignored for circular ones).
    slip_definition : SlipDefinition or str
        "classic" (default) or "bounded"; the result's ``slip`` is in the same definition.
    """
    model = _as_model(model)
    load = check_positive("load", load)
    definition = as_slip_definition(slip_definition)
    hint = (
        "s = 1 - V/(omega r)" if definition is SlipDefinition.CLASSIC else "s = (omega r - V)/max(omega r, V)"
    )
    slip = check_range("slip", slip, -1.0, 1.0, hint=hint)
    omega = check_positive("omega", omega, allow_zero=False) if omega != 0 else _zero_omega(omega)
    if not isinstance(phase_count, int | np.integer) or not (1 <= phase_count <= 4096):
        raise InputError("phase_count", phase_count, "an integer in [1, 4096]")
    radius = wheel_nominal_radius(body)
    period = wheel_rotation_period(body)
    thetas = np.zeros(1) if period is None else np.arange(phase_count) * period / phase_count
    rim, vx = speeds_from_slip(slip, definition=definition, speed=omega * radius)
    omega = rim / radius
    twist = Twist2D(vx, 0.0, omega)
    if isinstance(model, RFTModel):
        return _rft_point(model, body, load, slip, omega, thetas, twist)
    fn = _ForceFunction(model, body, twist, thetas)
    lowest = _lowest_points(body, thetas)
    surface = fn.surface
    top = surface - float(lowest.min())  # the deepest-reaching phase just touches: no contact
    z = _solve_height(fn, load, top, f"load {load:g} N at slip {slip:g}")
    w = fn.phases(z)
    dp, fz, tsoil = w[:, 0], w[:, 1], w[:, 2]
    drive = -tsoil
    # A phase whose lowest point is above the surface (a C-leg swinging over the hip) has sinkage 0,
    # not a negative depth: clamp before averaging.
    sink = np.maximum(surface - (z + lowest), 0.0)
    mean_dp, mean_drive = float(dp.mean()), float(drive.mean())
    power = mean_drive * omega
    eff = mean_dp * twist.vx / power if power > 0 else 0.0
    entry, exit_ = _contact_angles(model, body, Pose2D(0.0, z, float(thetas[0])), twist)
    return WheelSteadyResult(
        model=model.name,
        slip=slip,
        load_N=load,
        omega_rad_s=omega,
        forward_velocity_m_s=twist.vx,
        sinkage_m=float(sink.mean()),
        axle_height_m=z - surface,
        drawbar_pull_N=mean_dp,
        drive_torque_Nm=mean_drive,
        power_W=power,
        tractive_efficiency=eff,
        entry_angle_rad=entry,
        exit_angle_rad=exit_,
        drawbar_pull_min_N=float(dp.min()),
        drawbar_pull_max_N=float(dp.max()),
        drive_torque_min_Nm=float(drive.min()),
        drive_torque_max_Nm=float(drive.max()),
        vertical_force_min_N=float(fz.min()),
        vertical_force_max_N=float(fz.max()),
        sinkage_min_m=float(sink.min()),
        sinkage_max_m=float(sink.max()),
        phase_count=len(thetas),
    )


def _zero_omega(omega: float) -> float:
    raise InputError("omega", omega, "a spin rate > 0 [rad/s]", "slip is undefined when omega = 0")


def _contact_angles(model: TerrainModel, body: Body, pose: Pose2D, twist: Twist2D) -> tuple[float, float]:
    """Front (entry) and rear (exit) angles [rad] of the loaded contact, from the downward vertical."""
    if isinstance(model, RFTModel):
        from ..rft.kernels import rft_contact_angles_kernel

        el = body.discretize(model.element_size)
        hi, lo, found = rft_contact_angles_kernel(
            el.midpoints,
            el.normals,
            pose.x,
            pose.z,
            pose.theta,
            twist.vx,
            twist.vz,
            twist.omega,
            model.surface_level,
        )
        return (float(hi), float(lo)) if found else (0.0, 0.0)
    angles = getattr(model, "contact_angles", None)
    if callable(angles):
        entry, exit_ = angles(body, pose, twist)
        return float(entry), float(exit_)
    # Geometric contact: the arc of the outline below the surface (exit from the model if it has one).
    pts = np.concatenate(body.outline())
    c, s = math.cos(pose.theta), math.sin(pose.theta)
    rx = c * pts[:, 0] + s * pts[:, 1]
    rz = -s * pts[:, 0] + c * pts[:, 1]
    under = pose.z + rz < float(getattr(model, "surface_level", 0.0))
    if not np.any(under):
        return 0.0, 0.0
    ang = np.arctan2(rx[under], -rz[under])
    exit_angle = getattr(model, "exit_angle", None)
    return float(ang.max()), float(exit_angle) if exit_angle is not None else float(ang.min())


def wheel_self_propelled(
    body: Body,
    model: TerrainModel | Material,
    load: float,
    *,
    drawbar_load: float = 0.0,
    omega: float = 1.0,
    phase_count: int = 16,
) -> WheelSteadyResult:
    """Slip and sinkage at which the drawbar pull balances an applied rearward load [N].

    With ``drawbar_load`` = 0 this is the free-rolling (self-propelled) slip.
    """
    model = _as_model(model)
    drawbar_load = float(drawbar_load)
    if not math.isfinite(drawbar_load):
        raise InputError("drawbar_load", drawbar_load, "a finite force [N]")

    def excess(s: float) -> float:
        r = wheel_steady(body, model, load, s, omega=omega, phase_count=phase_count)
        return r.drawbar_pull_N - drawbar_load

    lo, hi = -0.99, 0.99
    f_hi = excess(hi)
    if f_hi < 0:
        raise SolverError(
            f"drawbar load {drawbar_load:g} N exceeds the pull the wheel develops even at slip {hi} "
            f"({f_hi + drawbar_load:.4g} N)"
        )
    f_lo = excess(lo)
    if f_lo > 0:
        raise SolverError(
            f"drawbar load {drawbar_load:g} N is below the pull at slip {lo} "
            f"({f_lo + drawbar_load:.4g} N): the wheel would be pushed"
        )
    from scipy.optimize import brentq

    s = float(brentq(excess, lo, hi, xtol=1e-10, maxiter=200))
    res = wheel_steady(body, model, load, s, omega=omega, phase_count=phase_count)
    return WheelSteadyResult(**{**asdict(res), "extra": {"drawbar_load_N": drawbar_load}})
