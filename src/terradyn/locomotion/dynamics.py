"""Free-body dynamics of a driven wheel in the plane through RFT or dynamic RFT.

A rigid wheel of mass m (and moment of inertia I about its axle) moves freely in x and z under gravity,
an applied rearward drawbar load and the soil wrench of a terrain model, while it is driven either by
a prescribed spin omega(t) (constant, step or ramp) or by a prescribed motor torque. The whole time loop
runs compiled (:mod:`terradyn.locomotion._dynamics_kernels`).

Integration scheme
------------------
Backward (implicit) Euler on the velocities and positions, solved each step by Newton's method with a
finite-difference Jacobian of the soil force (reused across steps while it keeps converging) and a
backtracking line search; a step whose iteration fails is retried as 2, 4, ... 32 substeps. Converged
means a force residual below ``tolerance * m g``. For the implicit solve the force law is made
continuous: the leading-edge switch of RFT is smoothed over ``|n . v| / |v| < 0.01`` (an odd ramp, so
sums over many elements change at second order) and the DRFT split of the contact arc moves
continuously as elements enter (see :func:`terradyn.rft.kernels.drft_wrench_kernel`). With the
sharp rules the implicit equations often have no root (it sits on a jump), steps end with force
residuals up to a quarter of m g and the steady state is biased (0.26 m MS wheel, 130 N, 5 rad/s: DRFT
slip 0.68, against 0.727 from the quasi-static DRFT solve and 0.726 with the smoothing). A body without
spin at rest is held by a plastic stick rule (see :mod:`._dynamics_kernels`).

Backward Euler is A-stable for the linearised system, so neither the vertical RFT stiffness
(k ~ zeta * contact length * width) nor the velocity-direction stiffness (~ F / |v|, large at low
speed for a rate-independent law) limits the step through stability; measured, the scheme stays
stable and converges at 5x the limits below. The limits enforced by :func:`simulate_wheel` are
resolution limits of what the scheme must follow:

* ``dt sqrt(k_max / m) <= 1`` with ``k_max = zeta * width * 2 r`` [N/m] (whole diameter in contact, an
  upper bound): the landing and bobbing of the wheel on the medium. At the limit the peak landing
  sinkage is ~9 % low (first-order numerical damping), at a quarter of it (the default step) ~3.5 %;
* ``|omega|max dt <= min(pitch / 8, facet / 2, 0.25 rad)``, pitch = 2 pi / grouser (flap) count and
  facet the angular size of the rim elements: the soil force of a wheel is periodic with the pitch and,
  through its discretisation, with the facet; sampling a facet once a step aliases it (a 1 % slip
  error for the 360-element circular wheel at 0.9 facet per step). The default step is half of this
  limit (a quarter for the stiffness limit).

Backward Euler dissipates ``(m/2) |u_{n+1} - u_n|^2`` per step (first order in dt): energy balances
and transients converge at first order (tests in ``tests/unit/test_dynamics.py``). Fixed points of
the scheme are exact equilibria, so a steady rolling state does not depend on dt.

References
----------
S. Agarwal, A. Karsai, D. I. Goldman, K. Kamrin, "Surprising simplicity in the modeling of dynamic
granular intrusion", Sci. Adv. 7, eabe0631 (2021). doi:10.1126/sciadv.abe0631
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError, SolverError, check_finite, check_positive
from ..geometry import Body, SurfaceElements
from ..kinematics import Pose2D
from ..materials import Material
from ..models import model_entry
from ..rft import RFTModel
from ..rft.drft import DRFTModel
from . import _dynamics_kernels as K
from .steady import wheel_nominal_radius, wheel_rotation_period

__all__ = ["WheelDynamicsResult", "simulate_wheel", "stable_time_step"]

_MAX_FAILED_FRACTION = 0.01  # share of steps allowed to end unconverged after all substeps
_LEADING_BAND = 1e-2  # smoothing of the leading-edge switch in n . v / |v| (see the module notes)

_COLUMNS = {
    "time_s": K.C_T,
    "x_m": K.C_X,
    "z_m": K.C_Z,
    "theta_rad": K.C_THETA,
    "vx_m_s": K.C_VX,
    "vz_m_s": K.C_VZ,
    "omega_rad_s": K.C_OMEGA,
    "force_x_N": K.C_FX,
    "force_z_N": K.C_FZ,
    "drive_torque_Nm": K.C_TORQUE,
    "slip": K.C_SLIP,
    "sinkage_m": K.C_SINKAGE,
    "power_W": K.C_POWER,
    "soil_torque_Nm": K.C_SOIL_TORQUE,
    "soil_work_J": K.C_WORK,
}


@dataclass(frozen=True, eq=False)
class WheelDynamicsResult:
    """Time series of a simulated wheel (all SI; arrays of equal length, row 0 = initial state).

    Attributes
    ----------
    t [s]; x, z [m] axle position; theta [rad] wheel angle about +y; vx, vz [m/s]; omega [rad/s];
    fx, fz [N] soil force on the wheel (fx = drawbar pull, + forward); torque [N m] motor (drive)
    torque, + driving forward; slip [-] 1 - vx / (omega r) (0 while omega r = 0); sinkage [m] depth of
    the lowest point below the undisturbed surface; power [W] = torque * omega; soil_torque [N m] soil
    torque about the axle (+y); soil_work [J] cumulative work of the soil wrench on the wheel.
    model : terrain model name; nominal_radius [m]; rotation_period [rad] or None; mass [kg];
    inertia [kg m^2]; gravity [m/s^2]; drawbar_load [N]; dt [s]; stats : solver counters;
    metadata : provenance.
    """

    t: NDArray[np.float64]
    x: NDArray[np.float64]
    z: NDArray[np.float64]
    theta: NDArray[np.float64]
    vx: NDArray[np.float64]
    vz: NDArray[np.float64]
    omega: NDArray[np.float64]
    fx: NDArray[np.float64]
    fz: NDArray[np.float64]
    torque: NDArray[np.float64]
    slip: NDArray[np.float64]
    sinkage: NDArray[np.float64]
    power: NDArray[np.float64]
    soil_torque: NDArray[np.float64]
    soil_work: NDArray[np.float64]
    model: str
    nominal_radius: float
    rotation_period: float | None
    mass: float
    inertia: float
    gravity: float
    drawbar_load: float
    dt: float
    stats: dict[str, float] = field(default_factory=dict)
    metadata: dict[str, Any] = field(default_factory=dict)

    def __len__(self) -> int:
        return int(self.t.shape[0])

    def columns(self) -> dict[str, NDArray[np.float64]]:
        """Unit-suffixed columns (``time_s``, ``x_m``, ... ``soil_work_J``)."""
        names = (
            "t",
            "x",
            "z",
            "theta",
            "vx",
            "vz",
            "omega",
            "fx",
            "fz",
            "torque",
            "slip",
            "sinkage",
            "power",
            "soil_torque",
            "soil_work",
        )
        return {key: getattr(self, n) for key, n in zip(_COLUMNS, names, strict=True)}

    def to_dataframe(self) -> Any:
        """The series as a pandas DataFrame (metadata in ``attrs``)."""
        import pandas as pd

        df = pd.DataFrame(self.columns())
        df.attrs.update(self._meta())
        return df

    def to_xarray(self) -> Any:
        """The series as an xarray Dataset on the ``time_s`` coordinate (needs xarray)."""
        try:
            import xarray as xr
        except ImportError as exc:  # pragma: no cover - optional extra
            raise InputError("format", "netcdf", "xarray installed", "pip install terradyn[fields]") from exc
        cols = self.columns()
        time = cols.pop("time_s")
        meta = {
            k: (json.dumps(v) if isinstance(v, dict | list | tuple | bool) or v is None else v)
            for k, v in self._meta().items()
        }
        return xr.Dataset({k: ("time_s", v) for k, v in cols.items()}, coords={"time_s": time}, attrs=meta)

    def save(self, path: str | Path) -> Path:
        """Write ``.csv``, ``.json`` or NetCDF (``.nc``, via xarray) and return the path."""
        p = Path(path)
        if p.suffix == ".csv":
            self.to_dataframe().to_csv(p, index=False)
        elif p.suffix == ".json":
            cols = {k: v.tolist() for k, v in self.columns().items()}
            p.write_text(json.dumps({"metadata": self._meta(), "columns": cols}))
        elif p.suffix == ".nc":
            self.to_xarray().to_netcdf(p, engine=self.netcdf_engine())
        else:
            raise InputError("path", str(path), "a file ending in .csv, .json or .nc")
        return p

    @staticmethod
    def netcdf_engine() -> str:
        """The xarray NetCDF engine used by :meth:`save`: netcdf4, h5netcdf (with h5py) or scipy."""
        from importlib.util import find_spec

        if find_spec("netCDF4") is not None:
            return "netcdf4"
        if find_spec("h5netcdf") is not None and find_spec("h5py") is not None:
            return "h5netcdf"
        return "scipy"

    def _meta(self) -> dict[str, Any]:
        return {
            "model": self.model,
            "nominal_radius_m": self.nominal_radius,
            "rotation_period_rad": self.rotation_period,
            "mass_kg": self.mass,
            "inertia_kg_m2": self.inertia,
            "gravity_m_s2": self.gravity,
            "drawbar_load_N": self.drawbar_load,
            "time_step_s": self.dt,
            **{f"solver_{k}": v for k, v in self.stats.items()},
            **self.metadata,
        }

    def averaging_window(self, revolutions: float | None = None) -> tuple[float, float]:
        """Start time [s] and number of revolutions of the window :meth:`steady_summary` averages over.

        Default: the largest whole number of revolutions within the last half of the run; if the wheel
        turns less than once there, the largest whole number of rotation periods (grouser pitches);
        if none, the whole last half (revolutions reported as the fraction turned).
        """
        t_end = float(self.t[-1])
        turned = self.theta - self.theta[-1]  # <= 0 going back in time for omega > 0
        if revolutions is not None:
            rev = check_positive("revolutions", revolutions)
            angle = 2.0 * math.pi * rev
            if abs(self.theta[-1] - self.theta[0]) < angle * (1 - 1e-9):
                raise InputError(
                    "revolutions",
                    revolutions,
                    f"at most {abs(self.theta[-1] - self.theta[0]) / (2 * math.pi):.3g} (turned in the run)",
                )
            return self._time_at_turn(turned, angle), rev
        half = np.searchsorted(self.t, 0.5 * t_end)
        available = abs(float(turned[half]))
        for unit in (2.0 * math.pi, self.rotation_period):
            if unit is not None and available >= unit:
                count = math.floor(available / unit + 1e-9)
                return self._time_at_turn(turned, count * unit), count * unit / (2.0 * math.pi)
        return float(self.t[half]), available / (2.0 * math.pi)

    def _time_at_turn(self, turned: NDArray[np.float64], angle: float) -> float:
        a = np.abs(turned)[::-1]
        return float(np.interp(angle, a, self.t[::-1]))

    def steady_summary(self, revolutions: float | None = None) -> dict[str, float]:
        """Time averages over the last whole revolutions (see :meth:`averaging_window`).

        Returns
        -------
        dict
            ``forward_velocity_m_s``, ``slip`` (1 - <vx> / (<omega> r)), ``sinkage_m``,
            ``drive_torque_Nm``, ``vertical_force_N``, ``drawbar_pull_N``, ``omega_rad_s``,
            ``power_W``, ``averaging_window_s``, ``revolutions``.
        """
        start, rev = self.averaging_window(revolutions)
        sel = self.t >= start - 1e-12
        if np.count_nonzero(sel) < 2:
            raise SolverError(
                "steady_summary: fewer than two samples in the averaging window; "
                "lower output_every or run longer"
            )
        t = self.t[sel]
        span = float(t[-1] - t[0])

        def mean(a: NDArray[np.float64]) -> float:
            return float(np.trapezoid(a[sel], t) / span)

        vx, w = mean(self.vx), mean(self.omega)
        wr = w * self.nominal_radius
        return {
            "forward_velocity_m_s": vx,
            "slip": 1.0 - vx / wr if abs(wr) > 1e-12 else 0.0,
            "sinkage_m": mean(self.sinkage),
            "drive_torque_Nm": mean(self.torque),
            "vertical_force_N": mean(self.fz),
            "drawbar_pull_N": mean(self.fx),
            "omega_rad_s": w,
            "power_W": mean(self.power),
            "averaging_window_s": span,
            "revolutions": rev,
        }


def _resolve_model(material: Material, model: str | RFTModel | DRFTModel, gravity: float) -> DRFTModel:
    """The model as DRFT options (RFT = DRFT with no inertial or structural term)."""
    if isinstance(model, str):
        key = model_entry(model, use="dynamics").name
        if key == "rft":
            return DRFTModel(material, inertial_coefficient=0.0, structural_correction=False, gravity=gravity)
        return DRFTModel(material, gravity=gravity)
    if isinstance(model, RFTModel):
        if model.material != material:
            raise InputError("model", model.name, f"a model on the same material ({material.name!r})")
        return DRFTModel(
            material,
            inertial_coefficient=0.0,
            structural_correction=False,
            gravity=gravity,
            surface_level=model.surface_level,
            element_size=model.element_size,
        )
    if isinstance(model, DRFTModel):
        if model.material != material:
            raise InputError("model", model.name, f"a model on the same material ({material.name!r})")
        if model.structural_correction and not math.isclose(model.gravity, gravity):
            raise InputError("model.gravity", model.gravity, f"the simulation gravity {gravity:g} m/s^2")
        return model
    raise InputError(
        "model", type(model).__name__, "'rft', 'drft', an RFTModel or a DRFTModel",
        "any other terrain model (a user's included) runs through terradyn.locomotion.simulate_coupled",
    )  # fmt: skip


def _geometry(
    body: Body | SurfaceElements,
    element_size: float | None,
    nominal_radius: float | None,
    elements: SurfaceElements | None = None,
) -> tuple[SurfaceElements, NDArray[np.float64], float, float | None]:
    """Elements, outline points, nominal radius [m] and rotation period [rad] of the body."""
    if isinstance(body, SurfaceElements):
        if elements is not None:
            raise InputError("elements", "SurfaceElements", "None when body is already SurfaceElements")
        outline = np.ascontiguousarray(body.midpoints)
        if nominal_radius is None:
            radius = float(np.max(np.hypot(outline[:, 0], outline[:, 1])))
        else:
            radius = check_positive("nominal_radius", nominal_radius)
        return body, outline, radius, 2.0 * math.pi
    if not isinstance(body, Body):
        raise InputError("body", type(body).__name__, "a terradyn Body or SurfaceElements")
    if elements is None:
        elems = body.discretize(element_size)
    elif isinstance(elements, SurfaceElements):
        if element_size is not None:
            raise InputError("element_size", element_size, "None when elements are given")
        elems = elements
    else:
        raise InputError("elements", type(elements).__name__, "SurfaceElements of the body or None")
    outline = np.ascontiguousarray(np.concatenate(body.outline()))
    if nominal_radius is None:
        radius = wheel_nominal_radius(body)
    else:
        radius = check_positive("nominal_radius", nominal_radius)
    return elems, outline, radius, wheel_rotation_period(body)


def stable_time_step(
    body: Body | SurfaceElements,
    material: Material,
    *,
    mass: float,
    omega_max: float,
    elements: SurfaceElements | None = None,
    nominal_radius: float | None = None,
) -> float:
    """Largest time step [s] :func:`simulate_wheel` accepts for a body, medium, mass and top spin.

    ``min(sqrt(m / k_max), 0.25 / w, pitch / (8 w), facet / (2 w))`` with ``w = omega_max`` [rad/s],
    ``k_max = zeta * width * 2 r`` [N/m], pitch = 2 pi / grouser (flap) count and facet the median
    angular size of the rim-like elements (see the module notes). The default step of
    :func:`simulate_wheel` is ``min(sqrt(m / k_max) / 4, rotation limits / 2)``.
    """
    elems, _, radius, period = _geometry(body, None, nominal_radius, elements)
    return _dt_limits(
        elems,
        material,
        check_positive("mass", mass),
        abs(check_finite("omega_max", omega_max)),
        radius,
        period,
    )[0]


def _facet_angle(elems: SurfaceElements) -> float | None:
    """Median angular size [rad] of the rim-like elements (normal within 45 deg of radial)."""
    mid, nrm = elems.midpoints, elems.normals
    rad = np.hypot(mid[:, 0], mid[:, 1])
    ok = rad > 0
    radial = np.zeros(len(rad), dtype=bool)
    radial[ok] = np.abs(np.einsum("ij,ij->i", mid[ok], nrm[ok])) / rad[ok] > math.sqrt(0.5)
    if not np.any(radial):
        return None
    return float(np.median(elems.lengths[radial] / rad[radial]))


def _dt_limits(
    elems: SurfaceElements,
    material: Material,
    mass: float,
    omega_max: float,
    radius: float,
    period: float | None,
) -> tuple[float, float]:
    """(largest accepted, default) time step [s]."""
    k_max = material.require_rft().zeta * elems.width * 2.0 * radius
    stiff = math.sqrt(mass / k_max)
    spin = math.inf
    if omega_max > 0:
        spin = 0.25 / omega_max
        if period is not None:
            spin = min(spin, period / 8.0 / omega_max)
        facet = _facet_angle(elems)
        if facet is not None:
            spin = min(spin, facet / 2.0 / omega_max)
    return min(stiff, spin), min(0.25 * stiff, 0.5 * spin)


@dataclass(frozen=True)
class _Drive:
    mode: int
    omega_initial: float
    omega_target: float
    ramp: float
    step_time: float
    torque: float
    omega_max: float


def _drive(
    omega: float | None, omega_initial: float, ramp: float | None, step_time: float, torque: float | None
) -> _Drive:
    if (omega is None) == (torque is None):
        raise InputError(
            "omega/torque",
            (omega, torque),
            "exactly one of omega= or torque=",
            "prescribe either the spin or the motor torque",
        )
    w0 = check_finite("omega_initial", omega_initial)
    t0 = check_positive("step_time", step_time, allow_zero=True)
    if torque is not None:
        if ramp is not None:
            raise InputError("ramp", ramp, "None with a prescribed torque", "ramps apply to omega")
        return _Drive(1, w0, w0, 0.0, 0.0, check_finite("torque", torque), abs(w0))
    assert omega is not None
    w1 = check_finite("omega", omega)
    rate = 0.0 if ramp is None else check_positive("ramp", ramp)
    if ramp is None and t0 == 0.0:
        w0 = w1  # constant spin from t = 0
    return _Drive(0, w0, w1, rate, t0, 0.0, max(abs(w0), abs(w1)))


def _initial_state(
    pose: Pose2D | None,
    velocity: float | tuple[float, float],
    outline: NDArray[np.float64],
    surface: float,
    omega0: float,
) -> NDArray[np.float64]:
    if pose is None:
        pose = Pose2D(0.0, surface - float(outline[:, 1].min()), 0.0)
    elif not isinstance(pose, Pose2D):
        raise InputError("initial_pose", pose, "a Pose2D(x, z, theta) or None (resting on the surface)")
    if isinstance(velocity, tuple | list):
        if len(velocity) != 2:
            raise InputError("initial_velocity", velocity, "vx or (vx, vz) [m/s]")
        vx, vz = (check_finite("initial_velocity", v) for v in velocity)
    else:
        vx, vz = check_finite("initial_velocity", velocity), 0.0
    return np.array([pose.x, pose.z, pose.theta, vx, vz, omega0])


@dataclass(frozen=True, eq=False)
class _Geometry:
    """A body as the integrator sees it: its elements, outline points [m] (body frame), nominal radius
    [m], rotation period [rad] (None: no symmetry) and whether it is a wheel (has an outer radius)."""

    elements: SurfaceElements
    outline: NDArray[np.float64]
    radius: float
    period: float | None
    is_wheel: bool


@dataclass(frozen=True)
class _Dynamics:
    """What moves the body besides its drive: the terrain model (DRFT options), the medium, mass m
    [kg], moment of inertia [kg m^2], g [m/s^2] and the drawbar load [N]."""

    drft: DRFTModel
    material: Material
    mass: float
    inertia: float
    gravity: float
    drawbar_load: float


@dataclass(frozen=True)
class _TimeGrid:
    """Time step [s], number of steps and the steps per output sample."""

    dt: float
    n_steps: int
    output_every: int


def _body_and_model(
    body: Body | SurfaceElements,
    material: Material,
    model: str | RFTModel | DRFTModel,
    gravity: float,
    element_size: float | None,
    elements: SurfaceElements | None,
    nominal_radius: float | None,
) -> tuple[DRFTModel, float, _Geometry]:
    """The checked medium and g [m/s^2], the model as DRFT options and the body discretised (by the
    model's element size unless one or the elements are given)."""
    if not isinstance(material, Material):
        raise InputError("material", type(material).__name__, "a terradyn Material")
    gravity = check_positive("gravity", gravity)
    drft = _resolve_model(material, model, gravity)
    size = element_size if (element_size is not None or elements is not None) else drft.element_size
    elems, outline, radius, period = _geometry(body, size, nominal_radius, elements)
    is_wheel = getattr(body, "outer_radius", None) is not None
    return drft, gravity, _Geometry(elems, outline, radius, period, is_wheel)


def _time_grid(
    geo: _Geometry,
    material: Material,
    mass: float,
    drive: _Drive,
    duration: float,
    dt: float | None,
    output_every: int,
) -> _TimeGrid:
    """The checked run length and step (default or at most the limit of :func:`_dt_limits`) and the
    output sampling."""
    duration = check_positive("duration", duration)
    limit, default = _dt_limits(geo.elements, material, mass, drive.omega_max, geo.radius, geo.period)
    dt = default if dt is None else check_positive("dt", dt)
    if dt > limit * (1 + 1e-12):
        raise InputError(
            "dt",
            dt,
            f"a step in (0, {limit:.4g}] s",
            "the limit of the implicit scheme for this body, mass and spin (stable_time_step)",
        )
    n_steps = round(duration / dt)
    if n_steps < 1 or n_steps > 50_000_000:
        raise InputError("duration", duration, f"between dt and {50_000_000 * dt:.3g} s")
    if not isinstance(output_every, int | np.integer) or not (1 <= output_every <= n_steps):
        raise InputError("output_every", output_every, f"an integer in [1, {n_steps}]")
    return _TimeGrid(dt, n_steps, output_every)


def _checked_tolerance(tolerance: float) -> float:
    """The Newton tolerance relative to m g: > 0 and at most 1e-3."""
    tolerance = check_positive("tolerance", tolerance)
    if tolerance > 1e-3:
        raise InputError("tolerance", tolerance, "at most 1e-3 (relative to m g)")
    return tolerance


def _integrate(
    geo: _Geometry,
    dyn: _Dynamics,
    drive: _Drive,
    tolerance: float,
    state0: NDArray[np.float64],
    grid: _TimeGrid,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The compiled time loop (:func:`._dynamics_kernels.integrate_wheel_kernel`): samples and stats."""
    rft = dyn.material.require_rft()
    params = _kernel_params(geo, dyn, drive, tolerance)
    elems = geo.elements
    return K.integrate_wheel_kernel(
        elems.midpoints,
        elems.normals,
        elems.lengths,
        rft.coefficients.as_array(),
        geo.outline,
        params,
        state0,
        grid.dt,
        grid.n_steps,
        int(grid.output_every),
    )


def simulate_wheel(
    body: Body | SurfaceElements,
    material: Material,
    *,
    model: str | RFTModel | DRFTModel = "rft",
    mass: float,
    inertia: float | None = None,
    omega: float | None = None,
    omega_initial: float = 0.0,
    ramp: float | None = None,
    step_time: float = 0.0,
    torque: float | None = None,
    duration: float,
    dt: float | None = None,
    initial_pose: Pose2D | None = None,
    initial_velocity: float | tuple[float, float] = 0.0,
    drawbar_load: float = 0.0,
    gravity: float = 9.81,
    output_every: int = 1,
    element_size: float | None = None,
    elements: SurfaceElements | None = None,
    nominal_radius: float | None = None,
    tolerance: float = 1e-5,
) -> WheelDynamicsResult:
    """Integrate a driven wheel moving freely in x and z through RFT or dynamic RFT.

    Parameters
    ----------
    body : Body or SurfaceElements
        The wheel, origin at the axle (elements: give ``nominal_radius``; they repeat every 2 pi).
    material : Material
        The medium.
    model : {"rft", "drft"} or RFTModel or DRFTModel
        Terrain model (a model instance carries its options; its material must be ``material``).
    mass : float
        Wheel (and carriage) mass m [kg] > 0.
    inertia : float, optional
        Moment of inertia about the axle [kg m^2]; default m r^2 / 2 (uniform disc).
    omega : float, optional
        Prescribed spin [rad/s] about +y: constant; after ``step_time`` when that is > 0 (a step from
        ``omega_initial``); or the target of a ramp.
    omega_initial : float
        Spin before the step or at the start of the ramp [rad/s]; initial spin with ``torque``.
    ramp : float, optional
        Ramp rate [rad/s^2] > 0 from ``omega_initial`` to ``omega`` starting at ``step_time``.
    step_time : float
        Time [s] of the step or of the start of the ramp.
    torque : float, optional
        Prescribed motor torque [N m] (+ driving forward) instead of ``omega``.
    duration : float
        Simulated time [s].
    dt : float, optional
        Time step [s], at most :func:`stable_time_step` (default: see there).
    initial_pose : Pose2D, optional
        Axle position [m] and wheel angle [rad]; default resting on the surface (lowest point at it).
    initial_velocity : float or (float, float)
        Initial axle velocity vx or (vx, vz) [m/s].
    drawbar_load : float
        Horizontal load on the axle [N], rearward positive.
    gravity : float
        g [m/s^2] (also used by the DRFT structural correction).
    output_every : int
        Sample every this many steps.
    element_size : float, optional
        Discretisation of a Body [m] (default: the model's, else the body's).
    elements : SurfaceElements, optional
        A discretisation of ``body`` to use instead (e.g. ``WheelGrousered.discretize_counts``).
    nominal_radius : float, optional
        Radius for the slip [m]; default the body's outer radius.
    tolerance : float
        Newton tolerance on the force residual relative to m g [-].

    Returns
    -------
    WheelDynamicsResult

    References
    ----------
    Agarwal, Karsai, Goldman, Kamrin, Sci. Adv. 7, eabe0631 (2021), doi:10.1126/sciadv.abe0631.
    """
    drft, gravity, geo = _body_and_model(
        body, material, model, gravity, element_size, elements, nominal_radius
    )
    mass = check_positive("mass", mass)
    inertia = 0.5 * mass * geo.radius**2 if inertia is None else check_positive("inertia", inertia)
    drive = _drive(omega, omega_initial, ramp, step_time, torque)
    grid = _time_grid(geo, material, mass, drive, duration, dt, output_every)
    tolerance = _checked_tolerance(tolerance)
    dyn = _Dynamics(drft, material, mass, inertia, gravity, check_finite("drawbar_load", drawbar_load))
    state0 = _initial_state(
        initial_pose, initial_velocity, geo.outline, drft.surface_level, drive.omega_initial
    )
    out, stats = _integrate(geo, dyn, drive, tolerance, state0, grid)
    return _result(out, stats, geo, dyn, grid.dt)


def _kernel_params(geo: _Geometry, dyn: _Dynamics, drive: _Drive, tolerance: float) -> NDArray[np.float64]:
    """The ``params`` array of :func:`._dynamics_kernels.integrate_wheel_kernel`."""
    drft, radius, gravity = dyn.drft, geo.radius, dyn.gravity
    params = np.zeros(K.N_PARAMS)
    params[[K.P_WIDTH, K.P_SCALE, K.P_SURFACE, K.P_LAM_RHO]] = (
        geo.elements.width,
        drft.material.require_rft().scale,
        drft.surface_level,
        drft.inertial_density,
    )
    params[K.P_DROP_COEFF] = radius**2 / gravity if (drft.structural_correction and geo.is_wheel) else 0.0
    params[[K.P_MASS, K.P_INERTIA, K.P_GRAVITY, K.P_DRAWBAR]] = (
        dyn.mass,
        dyn.inertia,
        gravity,
        dyn.drawbar_load,
    )
    params[[K.P_MODE, K.P_OMEGA0, K.P_OMEGA1, K.P_RAMP, K.P_STEP_TIME, K.P_TORQUE]] = (
        drive.mode,
        drive.omega_initial,
        drive.omega_target,
        drive.ramp,
        drive.step_time,
        drive.torque,
    )
    params[[K.P_RADIUS, K.P_RTOL, K.P_MAX_ITER, K.P_MAX_HALVINGS]] = (radius, tolerance, 25, 5)
    params[K.P_BAND] = _LEADING_BAND
    return params


def _result(
    out: NDArray[np.float64],
    stats: NDArray[np.float64],
    geo: _Geometry,
    dyn: _Dynamics,
    dt: float,
) -> WheelDynamicsResult:
    """The run's result from the kernel's samples and stats; a :class:`SolverError` for non-finite
    values or too many unconverged steps."""
    drft, is_wheel = dyn.drft, geo.is_wheel
    if not np.all(np.isfinite(out)):
        raise SolverError("simulate_wheel: the integration produced non-finite values; reduce dt")
    keys = (
        "force_evaluations",
        "jacobians",
        "steps",
        "substeps",
        "stuck_steps",
        "failed_steps",
        "max_jump_residual_rel",
        "jump_steps",
    )
    st = {k: float(v) for k, v in zip(keys, stats, strict=True)}
    if st["failed_steps"] > _MAX_FAILED_FRACTION * st["steps"]:
        raise SolverError(
            f"simulate_wheel: Newton failed on {st['failed_steps']:.0f} of {st['steps']:.0f} "
            "steps even with substeps; reduce dt"
        )
    name = "drft" if (drft.inertial_density > 0 or (drft.structural_correction and is_wheel)) else "rft"

    def col(j: int) -> NDArray[np.float64]:
        series = np.ascontiguousarray(out[:, j])
        series.setflags(write=False)
        return series

    meta = {
        "material": dyn.material.name,
        "inertial_coefficient": drft.inertial_coefficient,
        "density_kg_m3": drft.density,
        "structural_correction": drft.structural_correction and is_wheel,
        "citation": "Agarwal, Karsai, Goldman, Kamrin, Sci. Adv. 7, eabe0631 (2021)",
    }
    return WheelDynamicsResult(
        t=col(K.C_T),
        x=col(K.C_X),
        z=col(K.C_Z),
        theta=col(K.C_THETA),
        vx=col(K.C_VX),
        vz=col(K.C_VZ),
        omega=col(K.C_OMEGA),
        fx=col(K.C_FX),
        fz=col(K.C_FZ),
        torque=col(K.C_TORQUE),
        slip=col(K.C_SLIP),
        sinkage=col(K.C_SINKAGE),
        power=col(K.C_POWER),
        soil_torque=col(K.C_SOIL_TORQUE),
        soil_work=col(K.C_WORK),
        model=name,
        nominal_radius=geo.radius,
        rotation_period=geo.period,
        mass=dyn.mass,
        inertia=dyn.inertia,
        gravity=dyn.gravity,
        drawbar_load=dyn.drawbar_load,
        dt=dt,
        stats=st,
        metadata=meta,
    )
