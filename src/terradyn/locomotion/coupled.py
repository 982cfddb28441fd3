"""A body under load driven through any terrain model, stateful (MPM) or stateless (RFT, DRFT...).

:func:`simulate_coupled` is the model-agnostic time integrator: the same call runs a wheel or an
intruder on MPM (:class:`terradyn.mpm.MPMTerrain`) or on RFT, so "RFT versus MPM on the same wheel" is
one call with a different ``terrain``. The body spins at a prescribed ``omega``; its horizontal motion is
prescribed (``vx``) or free; its vertical motion is free under the ``load``. Integration is
semi-implicit (symplectic) Euler with a fixed ``dt``: the terrain returns the wrench averaged over the
step, the free velocities are updated with it, then the pose moves with the new velocities.

For the RFT models the compiled :func:`terradyn.locomotion.simulate_wheel` is much faster; this driver
exists so that a stateful medium and a stateless one share one code path.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import InputError, SolverError, check_positive, check_range
from ..geometry import Body
from ..kinematics import Pose2D, Twist2D
from ..materials import Material
from ..rft import RFTModel
from ..terrain import StatefulTerrainModel, Stateless, TerrainModel

__all__ = ["CoupledResult", "simulate_coupled"]


@dataclass(frozen=True, eq=False)
class CoupledResult:
    """Time series (``series``, unit-suffixed columns) and a ``summary`` averaged over the end."""

    series: dict[str, np.ndarray]
    summary: dict[str, float]
    metadata: dict[str, Any] = field(default_factory=dict)

    def to_dataframe(self) -> Any:
        import pandas as pd

        df = pd.DataFrame(self.series)
        df.attrs.update(self.metadata)
        return df


def _as_stateful(terrain: Any) -> StatefulTerrainModel:
    if isinstance(terrain, StatefulTerrainModel):
        return terrain
    if isinstance(terrain, Material):
        return Stateless(RFTModel(terrain))
    if isinstance(terrain, TerrainModel):
        return Stateless(terrain)
    raise InputError(
        "terrain", type(terrain).__name__, "a terrain model (stateful or stateless) or a Material (RFT)"
    )


#: the series columns, in the order of the integrator's rows
_SERIES_NAMES = (
    "time_s",
    "x_m",
    "z_m",
    "theta_rad",
    "vx_m_s",
    "vz_m_s",
    "force_x_N",
    "force_z_N",
    "torque_y_Nm",
    "sinkage_m",
)


@dataclass(frozen=True)
class _Motion:
    """The checked drive: ``load`` [N], translational ``mass`` [kg], spin ``omega`` [rad/s], forward
    speed ``vx`` [m/s] (None: free), time step ``dt`` [s] and the number of ``steps``."""

    load: float
    mass: float
    omega: float
    vx: float | None
    dt: float
    steps: int


def _integrate(
    model: StatefulTerrainModel,
    outline: np.ndarray,
    pose: Pose2D,
    motion: _Motion,
    progress: Callable[[float, float], None] | None,
) -> np.ndarray:
    """Semi-implicit Euler from ``pose``: the terrain's step wrench updates the free velocities, then
    the pose moves with them. One row per step, the columns of :data:`_SERIES_NAMES` (the sinkage from
    the lowest ``outline`` point)."""
    dt, omega, vx, mass, load = motion.dt, motion.omega, motion.vx, motion.mass, motion.load
    x, z, theta = pose.x, pose.z, pose.theta
    vx_now = 0.0 if vx is None else float(vx)
    vz_now = 0.0
    cols = np.zeros((motion.steps, 10))
    for k in range(motion.steps):
        twist = Twist2D(vx_now, vz_now, omega)
        w = model.step(Pose2D(x, z, theta), twist, dt)
        if not (math.isfinite(w.fx) and math.isfinite(w.fz) and math.isfinite(w.torque_y)):
            raise SolverError(f"terrain {model.name!r} returned a non-finite wrench at t = {k * dt:.4g} s")
        if vx is None:
            vx_now += dt * w.fx / mass
        vz_now += dt * (w.fz - load) / mass
        x += dt * vx_now
        z += dt * vz_now
        theta += dt * omega
        c, s = math.cos(theta), math.sin(theta)
        low = z + float(np.min(-s * outline[:, 0] + c * outline[:, 1]))
        cols[k] = ((k + 1) * dt, x, z, theta, vx_now, vz_now, w.fx, w.fz, w.torque_y, -low)
        if progress is not None:
            progress((k + 1) * dt, (k + 1) / motion.steps)
    return cols


def _summary(
    series: dict[str, np.ndarray], motion: _Motion, average_fraction: float, body: Body
) -> dict[str, float]:
    """Means over the last ``average_fraction`` of the steps; the slip of a spinning body with a
    nominal radius."""
    steps, omega = motion.steps, motion.omega
    tail = slice(int(steps * (1.0 - average_fraction)), steps)
    summary = {
        "sinkage_m": float(series["sinkage_m"][tail].mean()),
        "force_x_N": float(series["force_x_N"][tail].mean()),
        "force_z_N": float(series["force_z_N"][tail].mean()),
        "drive_torque_Nm": float(-series["torque_y_Nm"][tail].mean()),
        "vx_m_s": float(series["vx_m_s"][tail].mean()),
        "load_N": float(motion.load),
        "omega_rad_s": float(omega),
    }
    radius = getattr(body, "outer_radius", None)
    if omega != 0 and radius is not None:
        summary["slip"] = 1.0 - summary["vx_m_s"] / (omega * float(radius))
    return summary


def simulate_coupled(
    body: Body,
    terrain: StatefulTerrainModel | TerrainModel | Material,
    *,
    load: float,
    pose: Pose2D,
    duration: float,
    dt: float,
    omega: float = 0.0,
    vx: float | None = 0.0,
    mass: float | None = None,
    gravity: float = 9.81,
    average_fraction: float = 0.5,
    initialize: bool = True,
    progress: Callable[[float, float], None] | None = None,
) -> CoupledResult:
    """Drive ``body`` from ``pose`` for ``duration`` [s] in steps of ``dt`` [s] through ``terrain``.

    Parameters
    ----------
    load : vertical load on the body [N] (its weight plus any payload), acting downwards.
    omega : prescribed spin about +y [rad/s] (a wheel rolls forward for omega > 0).
    vx : prescribed forward speed [m/s]; ``None`` leaves x free (self-propelled).
    mass : translational mass [kg] (default ``load / gravity``).
    initialize : call ``terrain.init(body, pose)`` first (False continues a terrain already in use).
    average_fraction : the summary averages the last fraction of the steps.

    The summary holds ``sinkage_m`` (depth of the lowest outline point below z = 0), ``force_x_N``
    (= drawbar pull, + forward), ``force_z_N``, ``drive_torque_Nm`` (= -soil torque about the origin),
    ``vx_m_s`` and, for a spinning body with a nominal radius, ``slip``.
    """
    model = _as_stateful(terrain)
    if not isinstance(body, Body):
        raise InputError("body", body, "a terradyn.geometry Body")
    if not isinstance(pose, Pose2D):
        raise InputError("pose", pose, "a terradyn.kinematics.Pose2D")
    load = check_positive("load", load)
    check_positive("duration", duration)
    check_positive("dt", dt)
    if dt > duration:
        raise InputError("dt", dt, f"at most duration = {duration:g} s")
    check_range("omega", omega, -1000.0, 1000.0, unit="rad/s")
    gravity = check_range("gravity", gravity, 0.01, 100.0, unit="m/s^2")
    mass = load / gravity if mass is None else check_positive("mass", mass)
    check_range("average_fraction", average_fraction, 0.01, 1.0)
    steps = math.ceil(duration / dt - 1e-9)
    if steps > 10_000_000:
        raise InputError("dt", dt, f"at least {duration / 1e7:.3g} s (at most 1e7 steps)")
    outline = np.vstack([np.asarray(p, dtype=float) for p in body.outline(body.size / 50.0)])
    motion = _Motion(load, mass, omega, vx, dt, steps)
    if initialize:
        model.init(body, pose)
    t0 = time.perf_counter()
    cols = _integrate(model, outline, pose, motion, progress)
    series = {n: cols[:, i] for i, n in enumerate(_SERIES_NAMES)}
    summary = _summary(series, motion, average_fraction, body)
    meta = {
        "terrain": model.name,
        "body": repr(body),
        "dt_s": dt,
        "steps": steps,
        "mass_kg": mass,
        "mode": "self-propelled" if vx is None else "prescribed vx",
        "wall_time_s": time.perf_counter() - t0,
    }
    return CoupledResult(series, summary, meta)
