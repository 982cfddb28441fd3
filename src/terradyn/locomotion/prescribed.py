"""Plane wheel at a prescribed sinkage: the forces at a given depth (no load balance).

The counterpart of :func:`terradyn.locomotion.wheel_steady` for rigs that hold the axle height
(position control) instead of the load: the axle height is set so that the period-mean depth of the
lowest point equals the sinkage, and the vertical force the medium carries there is reported as the
load. Solving :func:`~terradyn.locomotion.wheel_steady` at that load returns the same state.
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError, check_finite, check_positive, check_range
from ..geometry import Body
from ..kinematics import Pose2D, SlipDefinition, Twist2D, as_slip_definition, speeds_from_slip
from ..materials import Material
from ..terrain import TerrainModel
from .steady import (
    WheelSteadyResult,
    _as_model,
    _contact_angles,
    _ForceFunction,
    _lowest_points,
    wheel_nominal_radius,
    wheel_rotation_period,
)

__all__ = ["axle_height_for_sinkage", "wheel_at_sinkage"]


def axle_height_for_sinkage(lowest: np.ndarray, sinkage: float, surface: float = 0.0) -> float:
    """Axle height [m] at which the mean over phases of max(surface - (z + lowest), 0) is ``sinkage``.

    ``lowest`` (P,) [m]: lowest body-frame z of each phase (negative: below the axle). Exact (the mean
    depth is piecewise linear and non-increasing in z). Raises InputError if the sinkage is negative
    or deeper than with the axle at the surface.
    """
    low = np.asarray(lowest, dtype=np.float64)
    depth = check_finite("sinkage", sinkage)
    deepest = float(np.maximum(-low, 0.0).mean())
    if depth < 0.0 or depth > deepest * (1.0 + 1e-12):
        raise InputError("sinkage", sinkage, f"a depth in [0, {deepest:.6g}] [m] (the axle at the surface)")
    if np.ptp(low) == 0.0:
        return surface - depth - float(low[0])
    top = surface - float(low.min())
    if depth == 0.0:
        return top
    from scipy.optimize import brentq

    def excess(h: float) -> float:
        return float(np.maximum(surface - (h + low), 0.0).mean()) - depth

    return float(brentq(excess, surface, top, xtol=1e-14, rtol=1e-15))


def wheel_at_sinkage(
    body: Body,
    model: TerrainModel | Material,
    sinkage: float,
    slip: float,
    *,
    omega: float = 1.0,
    phase_count: int = 16,
    slip_definition: SlipDefinition | str = SlipDefinition.CLASSIC,
) -> WheelSteadyResult:
    """Drawbar pull, torque and vertical force of a wheel held at ``sinkage`` [m] (>= 0) and a slip.

    Arguments as :func:`terradyn.locomotion.wheel_steady`, with the sinkage in place of the load;
    ``load_N`` of the result is the vertical force the medium carries there [N].
    """
    model = _as_model(model)
    definition = as_slip_definition(slip_definition)
    slip = check_range("slip", slip, -1.0, 1.0)
    omega = check_positive("omega", omega)
    if not isinstance(phase_count, int | np.integer) or not (1 <= phase_count <= 4096):
        raise InputError("phase_count", phase_count, "an integer in [1, 4096]")
    radius = wheel_nominal_radius(body)
    period = wheel_rotation_period(body)
    thetas = np.zeros(1) if period is None else np.arange(phase_count) * period / phase_count
    rim, vx = speeds_from_slip(slip, definition=definition, speed=omega * radius)
    twist = Twist2D(vx, 0.0, rim / radius)
    fn = _ForceFunction(model, body, twist, thetas)
    lowest = _lowest_points(body, thetas)
    surface = fn.surface
    z = axle_height_for_sinkage(lowest, sinkage, surface)
    w = fn.phases(z)
    dp, fz, drive = w[:, 0], w[:, 1], -w[:, 2]
    sink = np.maximum(surface - (z + lowest), 0.0)
    power = float(drive.mean()) * twist.omega
    entry, exit_ = _contact_angles(model, body, Pose2D(0.0, z, float(thetas[0])), twist)
    return WheelSteadyResult(
        model=model.name, slip=slip, load_N=float(fz.mean()), omega_rad_s=twist.omega,
        forward_velocity_m_s=vx, sinkage_m=float(sink.mean()), axle_height_m=z - surface,
        drawbar_pull_N=float(dp.mean()), drive_torque_Nm=float(drive.mean()), power_W=power,
        tractive_efficiency=float(dp.mean()) * vx / power if power > 0 else 0.0,
        entry_angle_rad=entry, exit_angle_rad=exit_,
        drawbar_pull_min_N=float(dp.min()), drawbar_pull_max_N=float(dp.max()),
        drive_torque_min_Nm=float(drive.min()), drive_torque_max_Nm=float(drive.max()),
        vertical_force_min_N=float(fz.min()), vertical_force_max_N=float(fz.max()),
        sinkage_min_m=float(sink.min()), sinkage_max_m=float(sink.max()), phase_count=len(thetas),
        extra={"prescribed": "sinkage", "slip_definition": definition.value},
    )  # fmt: skip
