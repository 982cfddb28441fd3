"""3D granular resistive force theory (Agarwal, Goldman & Kamrin 2023) on triangle meshes.

The law
-------
A facet with outward unit normal n, moving with velocity v at depth d below the free surface, carries
the traction ``t = xi * alpha * d`` [Pa] (zero above the surface), with the media scale xi [N/m^3] and
the dimensionless stress per depth

    alpha = f1 n_hat + f2 v_hat - f3 z_hat,   f_i = sum_{k=1..20} c_i^k T_k(x1, x2, x3),

where T_k are the twenty monomials of :data:`AGARWAL2023_TERMS` in ``x1 = sin(gamma)``,
``x2 = cos(beta)`` and ``x3 = cos(psi) cos(gamma) sin(beta) + sin(gamma) cos(beta)``. The angles live in
the local frame (r_hat, theta_hat, z_hat): z_hat up, r_hat the horizontal direction of motion (for
vertical motion the horizontal direction of the normal, and if that is zero too any horizontal axis),
theta_hat = z_hat x r_hat; there ``n = (sin b cos psi, sin b sin psi, -cos b)`` and
``v_hat = (cos g, 0, -sin g)``. Written back in the world frame the three arguments are simply
``x1 = -v_hat_z``, ``x2 = -n_z`` and ``x3 = n . v_hat`` (with n the plate normal of the next section),
and alpha is already a world vector, so the kernels never build the frame and the
result cannot depend on the horizontal axis picked for vertical motion (:func:`agarwal2023_angles`
builds it only for reporting; :func:`agarwal2023_alpha_local` is the literal local-frame formula).

Conventions chosen here
-----------------------
* Upward-facing facets. The fit covers beta, gamma, psi in [-pi/2, pi/2], i.e. plates whose (chosen)
  normal points down or sideways (n_z <= 0); every direction of motion is covered. As in the plane law
  of Li et al. (alpha is pi-periodic in beta), alpha describes a *plate*, whichever face is outward:
  a facet whose outward normal points up (n_z > 1e-9, :data:`UPWARD_TOLERANCE`) is evaluated with its
  plate normal p = -n, which lies in the fitted domain; the leading-edge rule still uses the outward n.
  So the top of a buried box pulled up feels the fit of a horizontal plate pulled up. Vertical facets
  (|n_z| <= 1e-9) use n itself, with n_z taken as exactly 0. Both normals of a vertical plate are in
  the fitted domain and the fit is not exactly symmetric between them (alpha of a vertical plate moving
  broadside differs by 15-20 % between the two representations); the tolerance keeps round-off in
  n_z from switching a wall between them.
* Leading edge: only facets with n . v > 0 carry load (default; switchable). A facet at rest carries
  nothing (quasi-static RFT gives no force without motion), nor does a zero-area facet.
* Coefficient c_3^16 (term x2 x3^2): the two public transcriptions of the supplement's table disagree
  (-0.02730 and -0.20770; the other 59 agree). :attr:`Agarwal2023Fit.DEFAULT` uses -0.02730: with it a
  horizontal plate pushed straight down has alpha_z = 0.87574, which with the media scaling of medium
  sand (phi = 34 deg, rho_c = 1560 kg/m^3) gives 2.13 N/cm^3 against the plate value 2.02 N/cm^3 used
  with the plane law for that sand, while -0.20770 gives alpha_z = 1.05614 (2.57 N/cm^3); -0.20770
  also makes a downward-facing plate pulled up feel an upward push. :attr:`Agarwal2023Fit.ALTERNATIVE`
  selects -0.20770 for comparison. Neither has been checked against the PNAS supplement itself.
* Surface friction (optional): the tangential part of alpha (with respect to the facet normal) is
  capped at ``surface_friction`` times the magnitude of its normal part.

References
----------
S. Agarwal, D. I. Goldman, K. Kamrin, "Mechanistic framework for reduced-order models in soft
materials: application to three-dimensional granular intrusion", PNAS 120, e2214017120 (2023).
doi:10.1073/pnas.2214017120
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import Enum
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError, check_finite, check_positive, check_range
from ..geometry3d import Pose3D, TriangleMesh, Twist3D, Wrench3D
from ..materials import Material
from .forces import Backend

__all__ = [
    "AGARWAL2023_TERMS",
    "UPWARD_TOLERANCE",
    "Agarwal2023Fit",
    "RFT3DFacetForces",
    "RFT3DModel",
    "agarwal2023_alpha",
    "agarwal2023_alpha_local",
    "agarwal2023_angles",
    "agarwal2023_coefficients",
    "agarwal2023_fits",
    "agarwal2023_xi",
    "agarwal2023_xi_material",
    "rft3d_facet_forces",
    "rft3d_facet_tractions",
    "rft3d_medium_scale",
    "rft3d_wrench",
    "rft3d_wrench_many",
]

#: The twenty terms T_k of the fits, in the coefficient order.
AGARWAL2023_TERMS = (
    "1", "x1", "x2", "x3", "x1^2", "x2^2", "x3^2", "x1 x2", "x2 x3", "x3 x1",
    "x1^3", "x2^3", "x3^3", "x1 x2^2", "x2 x1^2", "x2 x3^2", "x3 x2^2", "x3 x1^2", "x1 x3^2", "x1 x2 x3",
)  # fmt: skip

#: A facet with n_z above this counts as upward-facing and is evaluated with its plate normal -n.
UPWARD_TOLERANCE = 1e-9

# Rows c_1, c_2, c_3 of the fit table (PNAS 2023 supplement, as transcribed by public codes), columns in
# the order of AGARWAL2023_TERMS. Entry [2, 15] is the disputed c_3^16 (see Agarwal2023Fit).
_COEFFICIENTS = np.array(
    [
        [0.00212, -0.02320, -0.20890, -0.43083, -0.00259, 0.48872, -0.00415, 0.07204, -0.02750, -0.08772,
         0.01992, -0.45961, 0.40799, -0.10107, -0.06576, 0.05664, -0.09269, 0.01892, 0.01033, 0.15120],
        [-0.06796, -0.10941, 0.04725, -0.06914, -0.05835, -0.65880, -0.11985, -0.25739, -0.26834, 0.02692,
         -0.00736, 0.63758, 0.08997, 0.21069, 0.04748, 0.20406, 0.18519, 0.04934, 0.13527, -0.33207],
        [-0.02634, -0.03436, 0.45256, 0.00835, 0.02553, -1.31290, -0.05532, 0.06790, -0.16404, 0.02287,
         0.02927, 0.95406, -0.00131, -0.11028, 0.01487, -0.02730, 0.10911, -0.04097, 0.07881, -0.27519],
    ]
)  # fmt: skip


class Agarwal2023Fit(str, Enum):
    """Which transcription of the disputed coefficient c_3^16 (term x2 x3^2) to use.

    ``DEFAULT``: -0.02730 (reproduces alpha_z = 0.876 for a horizontal plate pushed down, consistent
    with measured plate data through the media scaling). ``ALTERNATIVE``: -0.20770.
    """

    DEFAULT = "default"
    ALTERNATIVE = "alternative"


def agarwal2023_coefficients(fit: Agarwal2023Fit | str = Agarwal2023Fit.DEFAULT) -> NDArray[np.float64]:
    """Fit coefficients c_i^k [-], shape (3, 20): rows f1, f2, f3, columns :data:`AGARWAL2023_TERMS`.

    References
    ----------
    Agarwal, Goldman & Kamrin, PNAS 120, e2214017120 (2023), supplement Table S1.
    doi:10.1073/pnas.2214017120
    """
    choice = _fit(fit)
    c = _COEFFICIENTS.copy()
    if choice is Agarwal2023Fit.ALTERNATIVE:
        c[2, 15] = -0.20770
    return c


def _fit(fit: Agarwal2023Fit | str) -> Agarwal2023Fit:
    try:
        return Agarwal2023Fit(fit)
    except ValueError:
        raise InputError("fit", fit, f"one of {[f.value for f in Agarwal2023Fit]}") from None


def agarwal2023_xi(critical_density: float, friction_coefficient: float, g: float = 9.81) -> float:
    """Media scale xi [N/m^3] of 3D RFT: ``rho_c g (894 mu^3 - 386 mu^2 + 89 mu)``.

    Parameters
    ----------
    critical_density : float
        Critical (close-packed) bulk density rho_c [kg/m^3] = packing fraction x grain density.
    friction_coefficient : float
        Internal friction coefficient mu = tan(phi) [-]. The scaling was calibrated for mu of about
        0.3 to 0.9; values in (0, 2] are accepted (the cubic is positive for every mu > 0).
    g : float
        Gravitational acceleration [m/s^2].

    Returns
    -------
    float
        xi [N/m^3]; the traction is ``xi * alpha * depth``.

    References
    ----------
    Agarwal, Goldman & Kamrin, PNAS 120, e2214017120 (2023). doi:10.1073/pnas.2214017120
    """
    rho = check_range("critical_density", critical_density, 1.0, 25000.0, unit="kg/m^3")
    mu = check_finite("friction_coefficient", friction_coefficient)
    if not 0.0 < mu <= 2.0:
        raise InputError("friction_coefficient", mu, "a number in (0, 2]", "calibrated for 0.3-0.9")
    return rho * check_positive("g", g) * (894.0 * mu**3 - 386.0 * mu**2 + 89.0 * mu)


def agarwal2023_xi_material(material: Material, *, g: float = 9.81) -> float:
    """:func:`agarwal2023_xi` [N/m^3] from a medium's ``critical_density`` and ``internal_friction_angle``."""
    missing = [n for n in ("critical_density", "internal_friction_angle") if getattr(material, n) is None]
    if missing:
        raise InputError(
            f"material {material.name!r}.{missing[0]}",
            None,
            "a value for the 3D-RFT media scaling",
            "give [density] critical_kg_m3 and [friction] internal_friction_angle_deg, or pass xi directly",
        )
    assert material.critical_density is not None and material.internal_friction_angle is not None
    return agarwal2023_xi(material.critical_density, math.tan(material.internal_friction_angle), g)


def _terms(x1: NDArray[np.float64], x2: NDArray[np.float64], x3: NDArray[np.float64]) -> NDArray[np.float64]:
    """The monomials T_k, shape (..., 20)."""
    one = np.ones_like(x1)
    return np.stack(
        [one, x1, x2, x3, x1 * x1, x2 * x2, x3 * x3, x1 * x2, x2 * x3, x3 * x1,
         x1**3, x2**3, x3**3, x1 * x2 * x2, x2 * x1 * x1, x2 * x3 * x3, x3 * x2 * x2, x3 * x1 * x1,
         x1 * x3 * x3, x1 * x2 * x3],
        axis=-1,
    )  # fmt: skip


def agarwal2023_fits(
    x1: ArrayLike, x2: ArrayLike, x3: ArrayLike, *, fit: Agarwal2023Fit | str = Agarwal2023Fit.DEFAULT
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """The fits f1, f2, f3 [-] at ``x1 = sin g``, ``x2 = cos b``, ``x3 = cos psi cos g sin b + sin g cos b``.

    References
    ----------
    Agarwal, Goldman & Kamrin, PNAS 120, e2214017120 (2023). doi:10.1073/pnas.2214017120
    """
    a, b, c = np.broadcast_arrays(*(np.asarray(x, dtype=np.float64) for x in (x1, x2, x3)))
    f = _terms(a, b, c) @ agarwal2023_coefficients(fit).T
    return f[..., 0], f[..., 1], f[..., 2]


def agarwal2023_alpha_local(
    beta: ArrayLike, gamma: ArrayLike, psi: ArrayLike, *, fit: Agarwal2023Fit | str = Agarwal2023Fit.DEFAULT
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Generic alpha [-] in the local frame, (alpha_r, alpha_theta, alpha_z), from the angles [rad].

    The literal formula: ``alpha_r = f1 sin b cos psi + f2 cos g``, ``alpha_theta = f1 sin b sin psi``,
    ``alpha_z = -f1 cos b - f2 sin g - f3``. Fitted for beta, gamma, psi in [-pi/2, pi/2]; no leading-edge
    rule or friction cap. Multiply by xi [N/m^3] for a stress per depth.

    References
    ----------
    Agarwal, Goldman & Kamrin, PNAS 120, e2214017120 (2023). doi:10.1073/pnas.2214017120
    """
    b, g, p = np.broadcast_arrays(*(np.asarray(x, dtype=np.float64) for x in (beta, gamma, psi)))
    sb, cb, sg, cg = np.sin(b), np.cos(b), np.sin(g), np.cos(g)
    f1, f2, f3 = agarwal2023_fits(sg, cb, np.cos(p) * cg * sb + sg * cb, fit=fit)
    return f1 * sb * np.cos(p) + f2 * cg, f1 * sb * np.sin(p), -f1 * cb - f2 * sg - f3


def _unit_rows(field: str, value: ArrayLike) -> NDArray[np.float64]:
    arr = np.ascontiguousarray(value, dtype=np.float64)
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise InputError(field, arr.shape, "an array of shape (N, 3)")
    if not np.all(np.isfinite(arr)):
        raise InputError(field, "non-finite values", "finite numbers")
    return arr


def _directions(v: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Unit rows of ``v`` (scaled by the largest component first: exact for any magnitude) and a mask
    of the non-zero rows; zero rows stay zero."""
    vmax = np.abs(v).max(axis=1)
    moving = vmax > 0.0
    w = v / np.where(moving, vmax, 1.0)[:, None]
    norm = np.sqrt(np.einsum("ij,ij->i", w, w))
    return w / np.where(moving, norm, 1.0)[:, None], moving


def _normalised(normals: NDArray[np.float64]) -> NDArray[np.float64]:
    """Unit rows; zero rows (degenerate facets) stay exactly zero."""
    return _directions(normals)[0]


def _plate_normals(normals: NDArray[np.float64]) -> NDArray[np.float64]:
    """Normals folded into the fitted domain: -n where n_z > UPWARD_TOLERANCE; the n_z left in
    (0, UPWARD_TOLERANCE] is set to 0 (an exactly vertical plate)."""
    p = np.where((normals[:, 2] > UPWARD_TOLERANCE)[:, None], -normals, normals)
    p[:, 2] = np.minimum(p[:, 2], 0.0)
    return p


def agarwal2023_angles(
    normals: ArrayLike, velocities: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Local-frame angles (beta, gamma, psi) [rad], each (N,), of facets with normals and velocities (N, 3).

    The frame is r_hat = horizontal direction of v, else of the plate normal, else +x. Upward-facing
    normals are first folded to their plate normal -n (module notes). All angles lie in [-pi/2, pi/2];
    ``beta = sign(p_r) arccos(-p_z)``, ``psi = atan(p_theta / p_r)``, ``gamma = arcsin(-v_z / |v|)``
    (0 for a facet at rest). For reporting and plots; the force law does not need them.
    """
    p = _plate_normals(_normalised(_unit_rows("normals", normals)))
    v = _unit_rows("velocities", velocities)
    if v.shape != p.shape:
        raise InputError("velocities", v.shape, f"an array of shape {p.shape}")
    vh = np.hypot(v[:, 0], v[:, 1])
    ph = np.hypot(p[:, 0], p[:, 1])
    use_v = vh > 0.0
    use_p = ~use_v & (ph > 0.0)
    rx = np.where(
        use_v, v[:, 0] / np.where(use_v, vh, 1.0), np.where(use_p, p[:, 0] / np.where(use_p, ph, 1.0), 1.0)
    )
    ry = np.where(
        use_v, v[:, 1] / np.where(use_v, vh, 1.0), np.where(use_p, p[:, 1] / np.where(use_p, ph, 1.0), 0.0)
    )
    p_r = p[:, 0] * rx + p[:, 1] * ry
    p_t = -p[:, 0] * ry + p[:, 1] * rx
    sign = np.where(p_r >= 0.0, 1.0, -1.0)
    beta = sign * np.arccos(np.clip(-p[:, 2], 0.0, 1.0))
    psi = np.arctan2(sign * p_t, np.abs(p_r))
    gamma = np.arctan2(-v[:, 2], vh)
    return beta, gamma, psi


def agarwal2023_alpha(
    normals: ArrayLike,
    velocities: ArrayLike,
    *,
    fit: Agarwal2023Fit | str = Agarwal2023Fit.DEFAULT,
    leading_edge: bool = True,
    surface_friction: float | None = None,
) -> NDArray[np.float64]:
    """Generic alpha [-], shape (N, 3), in the world frame of facets with normals and velocities (N, 3).

    The pure-NumPy reference of the numba kernels. Normals are normalised (zero rows stay zero and give
    zero alpha); velocities may have any magnitude (only the direction matters; zero gives zero alpha).
    With ``leading_edge`` facets with n . v <= 0 give zero; ``surface_friction`` [-] caps the tangential
    part (module notes). Multiply by xi [N/m^3] and depth [m] for the traction [Pa].

    References
    ----------
    Agarwal, Goldman & Kamrin, PNAS 120, e2214017120 (2023). doi:10.1073/pnas.2214017120
    """
    n = _normalised(_unit_rows("normals", normals))
    v = _unit_rows("velocities", velocities)
    if v.shape != n.shape:
        raise InputError("velocities", v.shape, f"an array of shape {n.shape}")
    mu = _surface_friction(surface_friction)
    u, moving = _directions(v)
    p = _plate_normals(n)
    f1, f2, f3 = agarwal2023_fits(-u[:, 2], -p[:, 2], np.einsum("ij,ij->i", p, u), fit=fit)
    alpha = f1[:, None] * p + f2[:, None] * u
    alpha[:, 2] -= f3
    if mu >= 0.0:
        a_n = np.einsum("ij,ij->i", alpha, n)
        tangential = alpha - a_n[:, None] * n
        t_mag = np.linalg.norm(tangential, axis=1)
        limit = mu * np.abs(a_n)
        factor = np.where(t_mag > limit, limit / np.where(t_mag > limit, t_mag, 1.0), 1.0)
        alpha = a_n[:, None] * n + factor[:, None] * tangential
    carries = moving & (np.einsum("ij,ij->i", n, n) > 0.25)
    if leading_edge:
        carries &= np.einsum("ij,ij->i", n, u) > 0.0
    return np.where(carries[:, None], alpha, 0.0)


def _surface_friction(value: float | None) -> float:
    """Kernel form of the friction cap: -1 for none (None or inf), else the coefficient."""
    if value is None or value == math.inf:
        return -1.0
    return check_range("surface_friction", value, 0.0, 10.0)


def _backend(backend: Backend | str) -> Backend:
    try:
        return Backend(backend)
    except ValueError:
        raise InputError("backend", backend, f"one of {[b.value for b in Backend]}") from None


def rft3d_facet_tractions(
    centroids: ArrayLike,
    normals: ArrayLike,
    velocities: ArrayLike,
    *,
    xi: float,
    surface_level: float = 0.0,
    leading_edge: bool = True,
    surface_friction: float | None = None,
    fit: Agarwal2023Fit | str = Agarwal2023Fit.DEFAULT,
    backend: Backend | str = Backend.NUMBA,
) -> NDArray[np.float64]:
    """Tractions [Pa], shape (N, 3), on facets given in the world frame.

    Parameters
    ----------
    centroids : array_like, shape (N, 3)
        Facet centroids [m]; only those below ``surface_level`` [m] are loaded.
    normals : array_like, shape (N, 3)
        Outward normals [-] (normalised here; zero rows carry nothing).
    velocities : array_like, shape (N, 3)
        Facet velocities [m/s].
    xi : float
        Media scale [N/m^3] (:func:`agarwal2023_xi`).
    leading_edge, surface_friction, fit
        As :func:`agarwal2023_alpha`.
    backend : Backend
        ``numba`` (parallel over facets) or the ``numpy`` reference.

    References
    ----------
    Agarwal, Goldman & Kamrin, PNAS 120, e2214017120 (2023). doi:10.1073/pnas.2214017120
    """
    c = _unit_rows("centroids", centroids)
    n = _normalised(_unit_rows("normals", normals))
    v = _unit_rows("velocities", velocities)
    if n.shape != c.shape or v.shape != c.shape:
        raise InputError("normals/velocities", (n.shape, v.shape), f"arrays of shape {c.shape}")
    scale = check_positive("xi", xi)
    surface = check_finite("surface_level", surface_level)
    depth = np.maximum(surface - c[:, 2], 0.0)
    if _backend(backend) is Backend.NUMPY:
        alpha = agarwal2023_alpha(n, v, fit=fit, leading_edge=leading_edge, surface_friction=surface_friction)
        return scale * alpha * depth[:, None]
    from ._kernels3d import rft3d_tractions_kernel

    return rft3d_tractions_kernel(
        c, n, v, agarwal2023_coefficients(fit), scale, surface, bool(leading_edge),
        _surface_friction(surface_friction), UPWARD_TOLERANCE,
    )  # fmt: skip


@dataclass(frozen=True, eq=False)
class RFT3DFacetForces:
    """Per-facet 3D-RFT state of a body at one pose and twist (arrays (F,) or (F, 3), world frame).

    Attributes
    ----------
    centroids : [m]; normals : outward unit normals [-]; velocities : [m/s]; areas : [m^2];
    depth : below the surface [m] (<= 0 above it); beta, gamma, psi : local angles [rad];
    active : bool, below the surface, moving, non-degenerate and (with the rule) leading;
    alpha : generic stress per depth [-] (0 where not active); tractions : [Pa]; forces : [N];
    wrench : Wrench3D, the sum, with moments about ``wrench.about``.
    """

    centroids: NDArray[np.float64]
    normals: NDArray[np.float64]
    velocities: NDArray[np.float64]
    areas: NDArray[np.float64]
    depth: NDArray[np.float64]
    beta: NDArray[np.float64]
    gamma: NDArray[np.float64]
    psi: NDArray[np.float64]
    active: NDArray[np.bool_]
    alpha: NDArray[np.float64]
    tractions: NDArray[np.float64]
    forces: NDArray[np.float64]
    wrench: Wrench3D

    def to_dataframe(self) -> Any:
        """Per-facet table with unit-suffixed columns."""
        import pandas as pd

        cols: dict[str, Any] = {}
        for name, arr, unit in (
            ("centroid", self.centroids, "_m"),
            ("normal", self.normals, ""),
            ("velocity", self.velocities, "_m_s"),
            ("traction", self.tractions, "_Pa"),
            ("force", self.forces, "_N"),
        ):
            for k, axis in enumerate("xyz"):
                cols[f"{name}_{axis}{unit}"] = arr[:, k]
        cols.update(
            area_m2=self.areas, depth_m=self.depth, beta_rad=self.beta, gamma_rad=self.gamma,
            psi_rad=self.psi, active=self.active,
        )  # fmt: skip
        return pd.DataFrame(cols)


def rft3d_medium_scale(
    medium: Material | float, surface_friction: float | None, g: float
) -> tuple[float, float]:
    """(xi [N/m^3], kernel friction cap [-]) from a Material or a given xi; the cap is
    ``surface_friction`` (None: the medium's, and no cap for a bare xi), as the kernels take it."""
    if isinstance(medium, Material):
        xi = agarwal2023_xi_material(medium, g=g)
        if surface_friction is None:
            surface_friction = medium.surface_friction
    elif isinstance(medium, int | float) and not isinstance(medium, bool):
        xi = check_positive("xi", medium)
    else:
        raise InputError("medium", type(medium).__name__, "a terradyn Material or a media scale xi [N/m^3]")
    return xi, _surface_friction(surface_friction)


def _about(pose: Pose3D, about: ArrayLike | None) -> NDArray[np.float64]:
    if about is None:
        return np.array(pose.position)
    a = np.asarray(about, dtype=np.float64)
    if a.shape != (3,) or not np.all(np.isfinite(a)):
        raise InputError("about", about, "a point (x, y, z) [m]")
    return a


def _check_mesh(mesh: TriangleMesh) -> TriangleMesh:
    if not isinstance(mesh, TriangleMesh):
        raise InputError("mesh", type(mesh).__name__, "a terradyn.geometry3d.TriangleMesh")
    return mesh


def rft3d_facet_forces(
    mesh: TriangleMesh,
    medium: Material | float,
    pose: Pose3D,
    twist: Twist3D,
    *,
    surface_level: float = 0.0,
    about: ArrayLike | None = None,
    leading_edge: bool = True,
    surface_friction: float | None = None,
    fit: Agarwal2023Fit | str = Agarwal2023Fit.DEFAULT,
    g: float = 9.81,
) -> RFT3DFacetForces:
    """Per-facet 3D-RFT tractions and forces on a rigid body (pure NumPy; the reference).

    Parameters
    ----------
    mesh : TriangleMesh
        The body surface in its own frame.
    medium : Material or float
        A medium with ``critical_density`` and ``internal_friction_angle`` (xi from
        :func:`agarwal2023_xi_material`), or the media scale xi itself [N/m^3].
    pose : Pose3D
        Body position [m] and rotation.
    twist : Twist3D
        World velocity of the body origin [m/s] and angular velocity [rad/s].
    surface_level : float
        Height of the free surface [m].
    about : array_like (3,), optional
        Point [m] for the moments; default the body origin.
    leading_edge : bool
        Load only facets moving into the medium (n . v > 0).
    surface_friction : float, optional
        Body-medium friction cap [-]; default the medium's ``surface_friction`` (none if it has none);
        ``math.inf`` turns a medium's cap off.
    fit : Agarwal2023Fit
        Coefficient transcription (module notes).
    g : float
        Gravitational acceleration [m/s^2] for the media scaling.

    References
    ----------
    Agarwal, Goldman & Kamrin, PNAS 120, e2214017120 (2023). doi:10.1073/pnas.2214017120
    """
    m = _check_mesh(mesh)
    xi, mu = rft3d_medium_scale(medium, surface_friction, g)
    surface = check_finite("surface_level", surface_level)
    point = _about(pose, about)
    offsets = m.centroids @ pose.rotation.T
    centroids = offsets + pose.position
    normals = m.normals @ pose.rotation.T
    velocities = twist.point_velocities(offsets)
    depth = surface - centroids[:, 2]
    alpha = agarwal2023_alpha(
        normals, velocities, fit=fit, leading_edge=leading_edge, surface_friction=None if mu < 0 else mu
    )
    below = depth > 0.0
    alpha = np.where(below[:, None], alpha, 0.0)
    active = below & np.any(alpha != 0.0, axis=1)
    tractions = xi * alpha * np.where(below, depth, 0.0)[:, None]
    forces = tractions * m.areas[:, None]
    moment = np.cross(centroids - point, forces).sum(axis=0)
    beta, gamma, psi = agarwal2023_angles(normals, velocities)
    return RFT3DFacetForces(
        centroids, normals, velocities, np.array(m.areas), depth, beta, gamma, psi, active, alpha,
        tractions, forces, Wrench3D(forces.sum(axis=0), moment, point),
    )  # fmt: skip


def rft3d_wrench(
    mesh: TriangleMesh,
    medium: Material | float,
    pose: Pose3D,
    twist: Twist3D,
    *,
    surface_level: float = 0.0,
    about: ArrayLike | None = None,
    leading_edge: bool = True,
    surface_friction: float | None = None,
    fit: Agarwal2023Fit | str = Agarwal2023Fit.DEFAULT,
    g: float = 9.81,
    backend: Backend | str = Backend.NUMBA,
    parallel: bool | None = None,
) -> Wrench3D:
    """Total 3D-RFT force [N] and moment [N m] (about ``about``, default the body origin) on a body.

    Same arguments as :func:`rft3d_facet_forces`. ``backend`` picks the numba kernel (default) or the
    NumPy reference; ``parallel`` splits the facets over numba threads (default: for more than
    100 000 facets).
    """
    m = _check_mesh(mesh)
    if _backend(backend) is Backend.NUMPY:
        return rft3d_facet_forces(
            m, medium, pose, twist, surface_level=surface_level, about=about, leading_edge=leading_edge,
            surface_friction=surface_friction, fit=fit, g=g,
        ).wrench  # fmt: skip
    from ._kernels3d import rft3d_wrench_kernel, rft3d_wrench_parallel_kernel

    xi, mu = rft3d_medium_scale(medium, surface_friction, g)
    point = _about(pose, about)
    use_parallel = m.facet_count > 100_000 if parallel is None else bool(parallel)
    kernel = rft3d_wrench_parallel_kernel if use_parallel else rft3d_wrench_kernel
    out = kernel(
        *m.kernel_arrays, np.ascontiguousarray(pose.rotation), np.array(pose.position),
        np.array(twist.linear), np.array(twist.angular), agarwal2023_coefficients(fit), xi,
        check_finite("surface_level", surface_level), bool(leading_edge), mu, UPWARD_TOLERANCE, point,
    )  # fmt: skip
    return Wrench3D(out[:3], out[3:], point)


def _stack(field: str, value: ArrayLike, shape: tuple[int, ...]) -> NDArray[np.float64]:
    arr = np.ascontiguousarray(value, dtype=np.float64)
    if arr.shape != shape or not np.all(np.isfinite(arr)):
        raise InputError(field, arr.shape, f"a finite array of shape {shape}")
    return arr


def rft3d_wrench_many(
    mesh: TriangleMesh,
    medium: Material | float,
    positions: ArrayLike,
    rotations: ArrayLike,
    linear: ArrayLike,
    angular: ArrayLike,
    *,
    surface_level: float = 0.0,
    about: ArrayLike | None = None,
    leading_edge: bool = True,
    surface_friction: float | None = None,
    fit: Agarwal2023Fit | str = Agarwal2023Fit.DEFAULT,
    g: float = 9.81,
) -> NDArray[np.float64]:
    """Wrenches (M, 6) = (F [N], M [N m]) of one body in M states, in parallel over the states.

    ``positions`` (M, 3) [m] and ``rotations`` (M, 3, 3) place the body; ``linear`` (M, 3) [m/s] and
    ``angular`` (M, 3) [rad/s] are its world twists; moments about ``about`` (M, 3) [m], default each
    state's body origin. Rotations are trusted to be proper (build them with
    :func:`~terradyn.geometry3d.rotation_from_rpy`). Other arguments as :func:`rft3d_facet_forces`.
    """
    from ._kernels3d import rft3d_wrench_many_kernel

    m = _check_mesh(mesh)
    p = np.ascontiguousarray(positions, dtype=np.float64)
    if p.ndim != 2 or p.shape[1] != 3:
        raise InputError("positions", p.shape, "an array of shape (M, 3)")
    count = p.shape[0]
    p = _stack("positions", p, (count, 3))
    r = _stack("rotations", rotations, (count, 3, 3))
    v = _stack("linear", linear, (count, 3))
    w = _stack("angular", angular, (count, 3))
    a = p.copy() if about is None else _stack("about", about, (count, 3))
    xi, mu = rft3d_medium_scale(medium, surface_friction, g)
    return rft3d_wrench_many_kernel(
        *m.kernel_arrays, r, p, v, w, agarwal2023_coefficients(fit), xi,
        check_finite("surface_level", surface_level), bool(leading_edge), mu, UPWARD_TOLERANCE, a,
    )  # fmt: skip


@dataclass(frozen=True)
class RFT3DModel:
    """Quasi-static 3D RFT as a terrain model: ``wrench(mesh, pose, twist)``.

    Attributes
    ----------
    xi : float  media scale [N/m^3]
    surface_level : float  free-surface height [m]
    leading_edge : bool  load only leading facets
    surface_friction : float or None  friction cap [-] (None: no cap)
    fit : Agarwal2023Fit  coefficient transcription
    """

    xi: float
    surface_level: float = 0.0
    leading_edge: bool = True
    surface_friction: float | None = None
    fit: Agarwal2023Fit = Agarwal2023Fit.DEFAULT

    def __post_init__(self) -> None:
        object.__setattr__(self, "xi", check_positive("xi", self.xi))
        object.__setattr__(self, "surface_level", check_finite("surface_level", self.surface_level))
        _surface_friction(self.surface_friction)
        object.__setattr__(self, "fit", _fit(self.fit))

    @classmethod
    def from_material(
        cls,
        material: Material,
        *,
        surface_level: float = 0.0,
        leading_edge: bool = True,
        surface_friction: float | None = None,
        fit: Agarwal2023Fit | str = Agarwal2023Fit.DEFAULT,
        g: float = 9.81,
    ) -> RFT3DModel:
        """xi from the medium's density and friction angle; the cap from the argument or the medium."""
        mu = material.surface_friction if surface_friction is None else surface_friction
        return cls(
            agarwal2023_xi_material(material, g=g), surface_level, leading_edge,
            None if mu == math.inf else mu, _fit(fit),
        )  # fmt: skip

    @property
    def name(self) -> str:
        return "rft3d"

    def _options(self) -> dict[str, Any]:
        return {
            "surface_level": self.surface_level,
            "leading_edge": self.leading_edge,
            "surface_friction": self.surface_friction,
            "fit": self.fit,
        }

    def wrench(
        self, mesh: TriangleMesh, pose: Pose3D, twist: Twist3D, *, about: ArrayLike | None = None
    ) -> Wrench3D:
        """Force [N] and moment [N m] about ``about`` (default the body origin)."""
        return rft3d_wrench(mesh, self.xi, pose, twist, about=about, **self._options())

    def facet_forces(
        self, mesh: TriangleMesh, pose: Pose3D, twist: Twist3D, *, about: ArrayLike | None = None
    ) -> RFT3DFacetForces:
        """Per-facet state (NumPy reference) for plots and tables."""
        return rft3d_facet_forces(mesh, self.xi, pose, twist, about=about, **self._options())
