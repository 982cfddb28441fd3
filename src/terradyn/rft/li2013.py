"""The Li, Zhang & Goldman (2013) granular resistive-force law (plane, quasi-static).

alpha = (alpha_x, alpha_z) is a stress per unit depth [N/m^3]. With beta the element orientation and
gamma its direction of motion (DESIGN.md section 4):

* ``beta = atan2(n_z, n_x) + pi/2`` from the outward unit normal n (beta = 0: horizontal plate),
* ``gamma = atan2(-v_z, v_x)`` from the velocity v (gamma = pi/2: straight down),

``alpha_z = A00 + A10 cos 2b + B01 sin g + B11 sin(2b + g) + Bm11 sin(-2b + g)`` and
``alpha_x = C01 cos g + C11 cos(2b + g) + Cm11 cos(-2b + g) + D10 sin 2b`` (times a scale), and the
traction on an element at depth d is ``(-alpha_x, alpha_z) * d`` (alpha_z > 0 pushes up, alpha_x > 0
pushes along -x). Both the m = -1 terms use the functions of the general Fourier series: the
``C_-11`` term multiplies a cosine, which makes the law mirror-symmetric without any re-mapping.

References
----------
C. Li, T. Zhang, D. I. Goldman, "A terradynamics of legged locomotion on granular media",
Science 339, 1408-1412 (2013). doi:10.1126/science.1229163
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..materials import LiCoefficients, Material, RFTParameters

#: Element speeds below this [m/s] count as rest: no direction of motion, no load.
MIN_SPEED = 1e-200

#: Half-width [-] of the leading-edge ramp in c = n . v / |v| (the cosine between the outward normal
#: and the direction of motion): an element carries the share ``clip(1/2 + c / (2 LEADING_BAND), 0, 1)``
#: of its load. Elements leading (trailing) by more than asin(1e-3) = 0.057 deg carry all (none) of it,
#: exactly as with the sharp rule n . v > 0; a face moving exactly along itself carries half, whichever
#: way rounding tips n . v. The ramp is odd about the switch (share(c) + share(-c) = 1), so a
#: zero-thickness plate (two faces, opposite normals) carries exactly the law's alpha in every
#: direction, and sums over a smooth surface differ from the sharp rule only at second order in the
#: band; forces are continuous in the direction of motion.
LEADING_BAND = 1e-3

__all__ = [
    "LEADING_BAND",
    "MIN_SPEED",
    "leading_share",
    "li2013_alpha",
    "li2013_alpha_from_directions",
    "li2013_alpha_material",
    "rft_angles",
]


def li2013_alpha(
    beta: ArrayLike, gamma: ArrayLike, coefficients: LiCoefficients, scale: float = 1.0
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Stress per unit depth (alpha_x, alpha_z) [N/m^3] of the Li et al. (2013) Fourier fit.

    Parameters
    ----------
    beta : array_like
        Element orientation [rad] (0 = horizontal; period pi).
    gamma : array_like
        Direction of motion [rad] (pi/2 = straight down, 0 = along +x).
    coefficients : LiCoefficients
        The nine fit coefficients [-].
    scale : float
        Multiplier [N/m^3] (the RFT scale zeta for the generic set).

    Returns
    -------
    alpha_x, alpha_z : ndarray
        Broadcast over ``beta`` and ``gamma`` [N/m^3].
    """
    b = np.asarray(beta, dtype=np.float64)
    g = np.asarray(gamma, dtype=np.float64)
    c = coefficients
    alpha_z = (
        c.A00
        + c.A10 * np.cos(2 * b)
        + c.B01 * np.sin(g)
        + c.B11 * np.sin(2 * b + g)
        + c.Bm11 * np.sin(-2 * b + g)
    )
    alpha_x = (
        c.C01 * np.cos(g) + c.C11 * np.cos(2 * b + g) + c.Cm11 * np.cos(-2 * b + g) + c.D10 * np.sin(2 * b)
    )
    return scale * alpha_x, scale * alpha_z


def li2013_alpha_material(
    beta: ArrayLike, gamma: ArrayLike, material: Material | RFTParameters
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """:func:`li2013_alpha` with the coefficients and scale of a medium [N/m^3]."""
    rft = material.require_rft() if isinstance(material, Material) else material
    return li2013_alpha(beta, gamma, rft.coefficients, rft.scale)


def leading_share(normals: ArrayLike, velocities: ArrayLike) -> NDArray[np.float64]:
    """Share [0, 1] of each element's load under the leading-edge rule (the NumPy reference).

    ``clip(1/2 + n . v / (2 |v| LEADING_BAND), 0, 1)`` from outward unit normals and velocities, both
    (N, 2) (or (N, 3)); 0 for elements at rest (speed below :data:`MIN_SPEED`). Continuous in n and v:
    a face parallel to its motion carries half its load whichever way rounding tips n . v, one leading
    by more than 0.057 deg all of it, one trailing by more than that nothing.
    """
    n = np.asarray(normals, dtype=np.float64)
    v = np.asarray(velocities, dtype=np.float64)
    big = np.max(np.abs(v), axis=-1)
    moving = big >= MIN_SPEED
    w = v / np.where(moving, big, 1.0)[..., None]  # scale first: tiny or huge speeds stay exact
    cos_nv = np.einsum("...i,...i->...", n, w) / np.where(
        moving, np.sqrt(np.einsum("...i,...i->...", w, w)), 1.0
    )
    return np.where(moving, np.clip(0.5 + 0.5 * cos_nv / LEADING_BAND, 0.0, 1.0), 0.0)


def rft_angles(normals: ArrayLike, velocities: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """RFT angles (beta, gamma) [rad] from outward normals and velocities, both shape (N, 2)."""
    n = np.asarray(normals, dtype=np.float64)
    v = np.asarray(velocities, dtype=np.float64)
    beta = np.arctan2(n[..., 1], n[..., 0]) + 0.5 * np.pi
    gamma = np.arctan2(-v[..., 1], v[..., 0])
    return beta, gamma


def li2013_alpha_from_directions(
    normals: NDArray[np.float64],
    velocities: NDArray[np.float64],
    coefficients: NDArray[np.float64],
    scale: float,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """alpha_x, alpha_z [N/m^3] straight from unit normals and velocities (N, 2), without trig.

    Uses cos 2beta = n_z^2 - n_x^2, sin 2beta = -2 n_x n_z, cos gamma = v_x/|v|, sin gamma = -v_z/|v|.
    ``coefficients`` is :meth:`LiCoefficients.as_array` order. Elements with zero speed get gamma = 0.
    This is the NumPy reference of the numba kernels.
    """
    a00, a10, b01, b11, bm11, c01, c11, cm11, d10 = coefficients
    nx, nz = normals[..., 0], normals[..., 1]
    vx, vz = velocities[..., 0], velocities[..., 1]
    speed = np.hypot(vx, vz)
    safe = np.where(speed > 0, speed, 1.0)
    cg = np.where(speed > 0, vx / safe, 1.0)
    sg = np.where(speed > 0, -vz / safe, 0.0)
    c2b = nz * nz - nx * nx
    s2b = -2.0 * nx * nz
    alpha_z = a00 + a10 * c2b + b01 * sg + b11 * (s2b * cg + c2b * sg) + bm11 * (c2b * sg - s2b * cg)
    alpha_x = c01 * cg + c11 * (c2b * cg - s2b * sg) + cm11 * (c2b * cg + s2b * sg) + d10 * s2b
    return scale * alpha_x, scale * alpha_z
