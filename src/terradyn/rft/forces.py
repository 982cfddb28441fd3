"""Force and torque of plane RFT on a body: per element (NumPy) and in total (numba)."""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError, check_finite
from ..geometry import Body, SurfaceElements
from ..kinematics import Pose2D, Twist2D, Wrench2D, rotation_matrix
from ..materials import Material, RFTParameters
from .li2013 import leading_share, li2013_alpha_from_directions, rft_angles

__all__ = [
    "Backend",
    "RFTElementForces",
    "RFTModel",
    "as_elements",
    "rft_element_forces",
    "rft_wrench",
    "rft_wrench_many",
]


class Backend(str, Enum):
    """Which implementation sums the element forces."""

    NUMBA = "numba"
    NUMPY = "numpy"


def as_elements(body: Body | SurfaceElements, element_size: float | None = None) -> SurfaceElements:
    """The surface elements of ``body`` (discretised at ``element_size`` [m] if it is a Body)."""
    if isinstance(body, SurfaceElements):
        if element_size is not None:
            raise InputError(
                "element_size", element_size, "None when elements are given", "discretise the body"
            )
        return body
    if isinstance(body, Body):
        return body.discretize(element_size)
    raise InputError("body", type(body).__name__, "a terradyn Body or SurfaceElements")


def _rft_params(material: Material | RFTParameters) -> RFTParameters:
    if isinstance(material, RFTParameters):
        return material
    if isinstance(material, Material):
        return material.require_rft()
    raise InputError("material", type(material).__name__, "a terradyn Material or RFTParameters")


@dataclass(frozen=True, eq=False)
class RFTElementForces:
    """Per-element RFT state of a body at one pose and twist (all arrays shape (N,) or (N, 2)).

    Attributes
    ----------
    positions : world midpoints [m]; normals : world outward normals [-]; velocities [m/s];
    depth : depth below the surface [m] (<= 0 above it); beta, gamma : RFT angles [rad];
    active : bool, element below the surface with a leading-edge share > 0;
    share : leading-edge share [0, 1] of the load the element carries (:data:`LEADING_BAND`: 1 when
    leading by more than 0.057 deg, 1/2 for a face moving along itself, linear in n . v / |v| between,
    0 when trailing by more than 0.057 deg or not below the surface);
    alpha_x, alpha_z : stress per depth of the law [N/m^3] (0 where not active);
    tractions : (N, 2) [Pa], ``share * (-alpha_x, alpha_z) * depth``; forces : (N, 2) [N]; areas : [m^2];
    wrench : Wrench2D, the sum, with torque about ``about``.
    """

    positions: NDArray[np.float64]
    normals: NDArray[np.float64]
    velocities: NDArray[np.float64]
    depth: NDArray[np.float64]
    beta: NDArray[np.float64]
    gamma: NDArray[np.float64]
    active: NDArray[np.bool_]
    share: NDArray[np.float64]
    alpha_x: NDArray[np.float64]
    alpha_z: NDArray[np.float64]
    tractions: NDArray[np.float64]
    forces: NDArray[np.float64]
    areas: NDArray[np.float64]
    wrench: Wrench2D
    about: tuple[float, float]

    def to_dataframe(self) -> Any:
        """Per-element table with unit-suffixed columns."""
        import pandas as pd

        return pd.DataFrame(
            {
                "x_m": self.positions[:, 0],
                "z_m": self.positions[:, 1],
                "normal_x": self.normals[:, 0],
                "normal_z": self.normals[:, 1],
                "velocity_x_m_s": self.velocities[:, 0],
                "velocity_z_m_s": self.velocities[:, 1],
                "depth_m": self.depth,
                "beta_rad": self.beta,
                "gamma_rad": self.gamma,
                "active": self.active,
                "leading_share": self.share,
                "alpha_x_N_per_m3": self.alpha_x,
                "alpha_z_N_per_m3": self.alpha_z,
                "force_x_N": self.forces[:, 0],
                "force_z_N": self.forces[:, 1],
            }
        )


def _about(pose: Pose2D, about: tuple[float, float] | None) -> tuple[float, float]:
    if about is None:
        return (pose.x, pose.z)
    if len(about) != 2:
        raise InputError("about", about, "a point (x, z) [m]")
    return (check_finite("about[0]", about[0]), check_finite("about[1]", about[1]))


def rft_element_forces(
    body: Body | SurfaceElements,
    material: Material | RFTParameters,
    pose: Pose2D,
    twist: Twist2D,
    *,
    surface_level: float = 0.0,
    about: tuple[float, float] | None = None,
    element_size: float | None = None,
) -> RFTElementForces:
    """Per-element RFT tractions and forces on a body (pure NumPy; the reference implementation).

    Parameters
    ----------
    body : Body or SurfaceElements
        The body (discretised at ``element_size`` [m], default the body's own) or its elements.
    material : Material or RFTParameters
        The medium.
    pose : Pose2D
        Body position [m] and rotation [rad] about +y.
    twist : Twist2D
        Body velocity [m/s] and spin [rad/s] about +y.
    surface_level : float
        Height of the free surface [m].
    about : (float, float), optional
        Point (x, z) [m] for the torque; default the body origin.
    """
    elems = as_elements(body, element_size)
    rft = _rft_params(material)
    surface = check_finite("surface_level", surface_level)
    point = _about(pose, about)
    rot = rotation_matrix(pose.theta)
    offsets = elems.midpoints @ rot.T
    positions = offsets + np.array([pose.x, pose.z])
    normals = elems.normals @ rot.T
    velocities = np.column_stack(
        (twist.vx + twist.omega * offsets[:, 1], twist.vz - twist.omega * offsets[:, 0])
    )
    depth = surface - positions[:, 1]
    share = leading_share(normals, velocities)
    active = (depth > 0) & (share > 0)
    share = np.where(active, share, 0.0)
    beta, gamma = rft_angles(normals, velocities)
    ax, az = li2013_alpha_from_directions(normals, velocities, rft.coefficients.as_array(), rft.scale)
    ax = np.where(active, ax, 0.0)
    az = np.where(active, az, 0.0)
    d = np.where(active, depth, 0.0)
    tractions = np.column_stack((-ax * d, az * d)) * share[:, None]
    areas = elems.areas
    forces = tractions * areas[:, None]
    r = positions - np.array(point)
    wrench = Wrench2D(
        float(forces[:, 0].sum()),
        float(forces[:, 1].sum()),
        float(np.sum(r[:, 1] * forces[:, 0] - r[:, 0] * forces[:, 1])),
    )
    return RFTElementForces(
        positions,
        normals,
        velocities,
        depth,
        beta,
        gamma,
        active,
        share,
        ax,
        az,
        tractions,
        forces,
        areas,
        wrench,
        point,
    )


def rft_wrench(
    body: Body | SurfaceElements,
    material: Material | RFTParameters,
    pose: Pose2D,
    twist: Twist2D,
    *,
    surface_level: float = 0.0,
    about: tuple[float, float] | None = None,
    element_size: float | None = None,
    backend: Backend | str = Backend.NUMBA,
) -> Wrench2D:
    """Total RFT force [N] and torque about +y [N m] (about ``about``, default the body origin).

    Same arguments as :func:`rft_element_forces`; ``backend`` picks the numba kernel (default) or the
    NumPy reference.
    """
    try:
        backend = Backend(backend)
    except ValueError:
        raise InputError("backend", backend, f"one of {[b.value for b in Backend]}") from None
    if backend is Backend.NUMPY:
        return rft_element_forces(
            body,
            material,
            pose,
            twist,
            surface_level=surface_level,
            about=about,
            element_size=element_size,
        ).wrench
    from ._kernels import rft_wrench_kernel

    elems = as_elements(body, element_size)
    rft = _rft_params(material)
    point = _about(pose, about)
    fx, fz, ty = rft_wrench_kernel(
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
        check_finite("surface_level", surface_level),
        point[0],
        point[1],
    )
    return Wrench2D(fx, fz, ty)


def rft_wrench_many(
    body: Body | SurfaceElements,
    material: Material | RFTParameters,
    poses: ArrayLike,
    twists: ArrayLike,
    *,
    surface_level: float = 0.0,
    about: ArrayLike | None = None,
    element_size: float | None = None,
) -> NDArray[np.float64]:
    """Wrenches (M, 3) = (F_x [N], F_z [N], torque_y [N m]) for M poses and twists, each (M, 3).

    Torques are about ``about`` (M, 2) [m], default each pose's origin. Runs in parallel over poses.
    """
    from ._kernels import rft_wrench_many_kernel

    p = np.ascontiguousarray(poses, dtype=np.float64)
    t = np.ascontiguousarray(twists, dtype=np.float64)
    if p.ndim != 2 or p.shape[1] != 3:
        raise InputError("poses", p.shape, "an array of shape (M, 3): x, z, theta")
    if t.shape != p.shape:
        raise InputError("twists", t.shape, f"an array of shape {p.shape}: vx, vz, omega")
    if not (np.all(np.isfinite(p)) and np.all(np.isfinite(t))):
        raise InputError("poses/twists", "non-finite values", "finite numbers")
    a = p[:, :2].copy() if about is None else np.ascontiguousarray(about, dtype=np.float64)
    if a.shape != (p.shape[0], 2):
        raise InputError("about", a.shape, f"an array of shape ({p.shape[0]}, 2)")
    elems = as_elements(body, element_size)
    rft = _rft_params(material)
    return rft_wrench_many_kernel(
        elems.midpoints,
        elems.normals,
        elems.lengths,
        elems.width,
        p,
        t,
        rft.coefficients.as_array(),
        rft.scale,
        check_finite("surface_level", surface_level),
        a,
    )


@dataclass(frozen=True)
class RFTModel:
    """Quasi-static plane RFT as a terrain model: ``wrench(body, pose, twist)``.

    Attributes
    ----------
    material : Material
    surface_level : float  free-surface height [m]
    element_size : float or None  discretisation of Body arguments [m] (None: the body's default)
    """

    material: Material
    surface_level: float = 0.0
    element_size: float | None = None

    def __post_init__(self) -> None:
        self.material.require_rft()
        check_finite("surface_level", self.surface_level)

    @property
    def name(self) -> str:
        return "rft"

    def wrench(
        self,
        body: Body,
        pose: Pose2D,
        twist: Twist2D,
        *,
        about: tuple[float, float] | None = None,
    ) -> Wrench2D:
        return rft_wrench(
            body,
            self.material,
            pose,
            twist,
            surface_level=self.surface_level,
            about=about,
            element_size=self.element_size,
        )
