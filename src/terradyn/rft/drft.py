"""Dynamic RFT (DRFT): quasi-static RFT plus an inertial and a structural correction.

The traction on a leading surface element (outward normal n, velocity v, n . v > 0) is

    t = alpha(beta, gamma) * H(d_eff) * d_eff - n * lambda * rho * v_n**2,

with alpha the Li et al. (2013) stress per depth, ``v_n = n . v`` the normal speed, rho the critical
(close-packed) density of the medium and lambda an O(1) inertial coefficient. The element force is the
traction times the element area. ``d_eff`` is the depth below the *effective* free surface:

* the undisturbed surface for every element of a body that is not a wheel, and for the front half of a
  wheel's contact zone;
* for the rear half of a wheel's contact zone, a surface lowered by the structural correction
  ``delta_h = r (r omega**2 / g)`` (r the wheel's nominal radius, omega its spin, g gravity): a fast
  wheel throws grains out behind it and the pressure head behind the axle drops.

The contact zone is the loaded arc of plain RFT (leading elements below the undisturbed surface); it is
split at its mid-angle seen from the axle (an element exactly at the mid-angle counts as front).
Elements above their effective surface carry nothing (neither term). With lambda = 0 and omega -> 0
the model is quasi-static RFT.

References
----------
S. Agarwal, A. Karsai, D. I. Goldman, K. Kamrin, "Surprising simplicity in the modeling of dynamic
granular intrusion", Sci. Adv. 7, eabe0631 (2021). doi:10.1126/sciadv.abe0631
C. Li, T. Zhang, D. I. Goldman, Science 339, 1408-1412 (2013). doi:10.1126/science.1229163
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError, check_finite, check_positive
from ..geometry import Body, SurfaceElements
from ..kinematics import Pose2D, Twist2D, Wrench2D, rotation_matrix
from ..materials import Material
from ._kernels_drft import SPLIT_TIE
from .forces import Backend, as_elements
from .li2013 import MIN_SPEED, leading_share, li2013_alpha_from_directions

__all__ = [
    "DRFTElementForces",
    "DRFTModel",
    "drft_element_forces",
    "drft_structural_drop",
    "drft_wrench",
]


def drft_structural_drop(radius: float, omega: float, gravity: float = 9.81) -> float:
    """Structural correction delta_h = r (r omega^2 / g) [m] of a wheel.

    Parameters
    ----------
    radius : float
        Nominal (outer) wheel radius r [m].
    omega : float
        Spin rate [rad/s] (sign irrelevant).
    gravity : float
        Gravitational acceleration g [m/s^2].

    References
    ----------
    Agarwal et al., Sci. Adv. 7, eabe0631 (2021), doi:10.1126/sciadv.abe0631 (fit of MPM data).
    """
    r = check_positive("radius", radius)
    g = check_positive("gravity", gravity)
    w = check_finite("omega", omega)
    return r * (r * w * w / g)


def _wheel_radius(body: Body | SurfaceElements) -> float | None:
    """Nominal radius [m] of a wheel body (one with ``outer_radius``), else None."""
    r = getattr(body, "outer_radius", None)
    return None if r is None else float(r)


@dataclass(frozen=True)
class DRFTModel:
    """Dynamic RFT as a terrain model (``name = "drft"``): ``wrench(body, pose, twist)``.

    Parameters
    ----------
    material : Material
        Medium with RFT parameters (and ``critical_density`` [kg/m^3] when lambda > 0).
    inertial_coefficient : float, optional
        lambda [-] >= 0; default ``material.drft_lambda``, or 1 if the medium has none.
    density : float, optional
        rho [kg/m^3] of the inertial term; default ``material.critical_density``.
    structural_correction : bool
        Lower the free surface behind wheels (bodies with ``outer_radius``) by r (r omega^2 / g).
    gravity : float
        g [m/s^2] of the structural correction.
    surface_level : float
        Undisturbed free-surface height [m].
    element_size : float or None
        Discretisation of Body arguments [m] (None: the body's default).

    References
    ----------
    Agarwal, Karsai, Goldman, Kamrin, Sci. Adv. 7, eabe0631 (2021), doi:10.1126/sciadv.abe0631.
    """

    material: Material
    inertial_coefficient: float | None = None
    density: float | None = None
    structural_correction: bool = True
    gravity: float = 9.81
    surface_level: float = 0.0
    element_size: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.material, Material):
            raise InputError("material", type(self.material).__name__, "a terradyn Material")
        self.material.require_rft()
        lam = self.inertial_coefficient
        if lam is None:
            lam = self.material.drft_lambda if self.material.drft_lambda is not None else 1.0
        lam = check_positive("inertial_coefficient", lam, allow_zero=True)
        rho = self.density if self.density is not None else self.material.critical_density
        if rho is None:
            if lam > 0:
                raise InputError(
                    "density",
                    None,
                    "a density > 0 [kg/m^3]",
                    f"material {self.material.name!r} has no critical_density; give density= or set "
                    "inertial_coefficient=0",
                )
            rho = 0.0
        else:
            rho = check_positive("density", rho)
        object.__setattr__(self, "inertial_coefficient", lam)
        object.__setattr__(self, "density", rho)
        if not isinstance(self.structural_correction, bool):
            raise InputError("structural_correction", self.structural_correction, "True or False")
        check_positive("gravity", self.gravity)
        check_finite("surface_level", self.surface_level)

    @property
    def name(self) -> str:
        return "drft"

    @property
    def inertial_density(self) -> float:
        """lambda * rho [kg/m^3], the factor of v_n^2 in the inertial stress."""
        return float(self.inertial_coefficient) * float(self.density)  # type: ignore[arg-type]

    def structural_drop(self, body: Body | SurfaceElements, omega: float) -> float:
        """Surface lowering [m] behind ``body`` spinning at ``omega`` [rad/s] (0 if not a wheel)."""
        radius = _wheel_radius(body)
        if not self.structural_correction or radius is None:
            return 0.0
        return drft_structural_drop(radius, omega, self.gravity)

    def wrench(
        self,
        body: Body,
        pose: Pose2D,
        twist: Twist2D,
        *,
        about: tuple[float, float] | None = None,
    ) -> Wrench2D:
        return drft_wrench(body, self, pose, twist, about=about)

    def contact_angles(self, body: Body, pose: Pose2D, twist: Twist2D) -> tuple[float, float]:
        """Front and rear angles [rad] of the loaded contact, from the downward vertical (+ front)."""
        el = drft_element_forces(body, self, pose, twist)
        if not np.any(el.active):
            return 0.0, 0.0
        rel = el.positions[el.active] - np.array([pose.x, pose.z])
        ang = np.arctan2(rel[:, 0], -rel[:, 1])
        return float(ang.max()), float(ang.min())


@dataclass(frozen=True, eq=False)
class DRFTElementForces:
    """Per-element DRFT state of a body at one pose and twist (arrays (N,) or (N, 2)).

    Attributes
    ----------
    positions : world midpoints [m]; normals : world outward normals [-]; velocities [m/s];
    depth : depth below the element's effective surface [m] (<= 0 above it);
    rear : bool, element in the rear half of the contact arc (sees the lowered surface, in full or, with
    a ``leading_band``, in part);
    active : bool, leading element below its effective surface;
    quasi_static_forces, inertial_forces, forces : (N, 2) [N]; areas [m^2];
    drop : structural surface lowering [m]; wrench : Wrench2D sum, torque about ``about``.
    """

    positions: NDArray[np.float64]
    normals: NDArray[np.float64]
    velocities: NDArray[np.float64]
    depth: NDArray[np.float64]
    rear: NDArray[np.bool_]
    active: NDArray[np.bool_]
    quasi_static_forces: NDArray[np.float64]
    inertial_forces: NDArray[np.float64]
    forces: NDArray[np.float64]
    areas: NDArray[np.float64]
    drop: float
    wrench: Wrench2D
    about: tuple[float, float]

    def to_dataframe(self) -> Any:
        """Per-element table with unit-suffixed columns."""
        import pandas as pd

        return pd.DataFrame(
            {
                "x_m": self.positions[:, 0],
                "z_m": self.positions[:, 1],
                "depth_m": self.depth,
                "rear": self.rear,
                "active": self.active,
                "force_x_N": self.forces[:, 0],
                "force_z_N": self.forces[:, 1],
                "inertial_force_x_N": self.inertial_forces[:, 0],
                "inertial_force_z_N": self.inertial_forces[:, 1],
            }
        )


def _about(pose: Pose2D, about: tuple[float, float] | None) -> tuple[float, float]:
    if about is None:
        return (pose.x, pose.z)
    if len(about) != 2:
        raise InputError("about", about, "a point (x, z) [m]")
    return (check_finite("about[0]", about[0]), check_finite("about[1]", about[1]))


def _as_model(model: DRFTModel | Material) -> DRFTModel:
    if isinstance(model, DRFTModel):
        return model
    if isinstance(model, Material):
        return DRFTModel(model)
    raise InputError("model", type(model).__name__, "a DRFTModel or a Material")


def drft_element_forces(
    body: Body | SurfaceElements,
    model: DRFTModel | Material,
    pose: Pose2D,
    twist: Twist2D,
    *,
    about: tuple[float, float] | None = None,
    leading_band: float = 0.0,
) -> DRFTElementForces:
    """Per-element DRFT forces on a body (pure NumPy; the reference of the numba kernel).

    Parameters
    ----------
    body : Body or SurfaceElements
        The body (discretised at ``model.element_size``) or its elements. The structural correction
        applies only to wheels (bodies with ``outer_radius``).
    model : DRFTModel or Material
        Model options (a Material means DRFT with its defaults).
    pose : Pose2D
        Body position [m] and rotation [rad] about +y.
    twist : Twist2D
        Body velocity [m/s] and spin [rad/s] about +y.
    about : (float, float), optional
        Point (x, z) [m] for the torque; default the body origin.
    leading_band : float
        Smoothing of the leading-edge switch used by the time integrator [-]: an element with
        ``n . v / |v|`` in [-band, band] carries ``1/2 + n . v / (2 band |v|)`` of its force. 0 (default)
        is the rule of quasi-static RFT (:func:`terradyn.rft.li2013.leading_share`).
    """
    m = _as_model(model)
    band = check_positive("leading_band", leading_band, allow_zero=True)
    elems = as_elements(body, None if isinstance(body, SurfaceElements) else m.element_size)
    rft = m.material.require_rft()
    surface = float(m.surface_level)
    point = _about(pose, about)
    rot = rotation_matrix(pose.theta)
    offsets = elems.midpoints @ rot.T
    positions = offsets + np.array([pose.x, pose.z])
    normals = elems.normals @ rot.T
    velocities = np.column_stack(
        (twist.vx + twist.omega * offsets[:, 1], twist.vz - twist.omega * offsets[:, 0])
    )
    vn = np.einsum("ij,ij->i", normals, velocities)
    depth0 = surface - positions[:, 1]
    share = _leading_share(normals, vn, velocities, band)
    share = np.where(np.max(np.abs(velocities), axis=1) >= MIN_SPEED, share, 0.0)
    leading = share > 0
    drop = m.structural_drop(body, twist.omega)
    loaded = (depth0 > 0) & leading
    rear = (
        _rear_share(offsets, normals, elems.lengths, depth0, share, loaded, band)
        if drop > 0
        else np.zeros(len(vn))
    )
    depth = depth0 - drop * rear
    active = (depth > 0) & leading
    ax, az = li2013_alpha_from_directions(normals, velocities, rft.coefficients.as_array(), rft.scale)
    d = np.where(active, depth, 0.0)
    areas = elems.areas
    quasi = np.column_stack((-ax * d, az * d)) * areas[:, None]
    quasi[~active] = 0.0
    pressure = np.where(active & (vn > 0), m.inertial_density * vn * vn, 0.0)
    inertial = -normals * (pressure * areas)[:, None]
    forces = (quasi + inertial) * np.where(active, share, 0.0)[:, None]
    r = positions - np.array(point)
    wrench = Wrench2D(
        float(forces[:, 0].sum()),
        float(forces[:, 1].sum()),
        float(np.sum(r[:, 1] * forces[:, 0] - r[:, 0] * forces[:, 1])),
    )
    return DRFTElementForces(
        positions,
        normals,
        velocities,
        depth,
        rear > 0,
        active,
        quasi,
        inertial,
        forces,
        areas,
        drop,
        wrench,
        point,
    )


def _rear_share(
    offsets: NDArray[np.float64],
    normals: NDArray[np.float64],
    lengths: NDArray[np.float64],
    depth0: NDArray[np.float64],
    share: NDArray[np.float64],
    loaded: NDArray[np.bool_],
    band: float,
) -> NDArray[np.float64]:
    """Share [0, 1] of the structural drop each element sees (see the kernel for the smoothed rule)."""
    rear = np.zeros(len(depth0))
    if not np.any(loaded):
        return rear
    phi = np.arctan2(offsets[:, 0], -offsets[:, 1])
    if band == 0:
        split = 0.5 * (phi[loaded].min() + phi[loaded].max())
        return np.where(loaded & (phi < split - SPLIT_TIE), 1.0, 0.0)
    rad = np.hypot(offsets[:, 0], offsets[:, 1])
    dphi = np.where(rad > 0, lengths / np.where(rad > 0, rad, 1.0), 0.0)
    extent = lengths * np.abs(normals[:, 0])
    inside = share * np.where(extent > 0, np.minimum(1.0, depth0 / np.where(extent > 0, extent, 1.0)), 1.0)
    lo = np.min((phi + dphi * (1 - inside))[loaded])
    hi = np.max((phi - dphi * (1 - inside))[loaded])
    split = 0.5 * (lo + hi)
    ramp = np.clip(0.5 - (phi - split) / np.where(dphi > 0, dphi, 1.0), 0.0, 1.0)
    return np.where(loaded, np.where(dphi > 0, ramp, (phi < split).astype(float)), 0.0)


def _leading_share(
    normals: NDArray[np.float64], vn: NDArray[np.float64], velocities: NDArray[np.float64], band: float
) -> NDArray[np.float64]:
    """Share [0, 1] of each element's force under the leading-edge rule of RFT (``band`` 0:
    :func:`terradyn.rft.li2013.leading_share`) or its odd smoothing for time stepping."""
    if band == 0:
        return leading_share(normals, velocities)
    edge = band * np.hypot(velocities[:, 0], velocities[:, 1])
    safe = np.where(edge > 0, edge, 1.0)
    return np.where(edge > 0, np.clip(0.5 + 0.5 * vn / safe, 0.0, 1.0), (vn > 0).astype(np.float64))


def drft_wrench(
    body: Body | SurfaceElements,
    model: DRFTModel | Material,
    pose: Pose2D,
    twist: Twist2D,
    *,
    about: tuple[float, float] | None = None,
    leading_band: float = 0.0,
    backend: Backend | str = Backend.NUMBA,
) -> Wrench2D:
    """Total DRFT force [N] and torque about +y [N m] (about ``about``, default the body origin).

    Same arguments as :func:`drft_element_forces`; ``backend`` picks the numba kernel (default) or the
    NumPy reference.
    """
    try:
        backend = Backend(backend)
    except ValueError:
        raise InputError("backend", backend, f"one of {[b.value for b in Backend]}") from None
    m = _as_model(model)
    if backend is Backend.NUMPY:
        return drft_element_forces(body, m, pose, twist, about=about, leading_band=leading_band).wrench
    from ._kernels_drft import drft_wrench_kernel

    elems = as_elements(body, None if isinstance(body, SurfaceElements) else m.element_size)
    rft = m.material.require_rft()
    point = _about(pose, about)
    fx, fz, ty = drft_wrench_kernel(
        elems.midpoints,
        elems.normals,
        elems.lengths,
        elems.width,
        pose.x,
        pose.z,
        pose.theta,
        twist.vx,
        twist.vz,
        twist.omega,
        rft.coefficients.as_array(),
        rft.scale,
        float(m.surface_level),
        point[0],
        point[1],
        m.inertial_density,
        m.structural_drop(body, twist.omega),
        check_positive("leading_band", leading_band, allow_zero=True),
    )
    if not (math.isfinite(fx) and math.isfinite(fz) and math.isfinite(ty)):
        raise InputError("pose/twist", (pose, twist), "a state with finite DRFT forces")
    return Wrench2D(fx, fz, ty)
