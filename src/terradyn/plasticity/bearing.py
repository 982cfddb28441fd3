"""Closed-form bearing-capacity factors of a rigid strip footing on a Mohr-Coulomb half-space.

One function per published model (pvlib style). Angles in radians, lengths in m, stresses in Pa,
unit weight in N/m^3. Every function accepts floats or NumPy arrays (inputs broadcast).

The collapse pressure of a strip footing of width ``B`` founded at depth ``D`` is written, after
Terzaghi (1943), as the superposition

    q_u = c N_c + q N_q + 1/2 gamma B N_gamma,    q = gamma D,

which is exact for each term alone and conservative for their sum (up to ~30 %, Davis & Booker 1971).

* :func:`reissner1924_nq` and :func:`prandtl1921_nc` are exact (weightless soil, associated flow).
* ``N_gamma`` has no closed form; :func:`vesic1973_ngamma`, :func:`meyerhof1963_ngamma`,
  :func:`hansen1970_ngamma` and :func:`ec7_ngamma` are **approximations** fitted to or bounding
  characteristics / limit-analysis results, given for context. The exact (method of characteristics)
  value is :func:`terradyn.plasticity.moc.moc_n_gamma`.
* :func:`hansen1970_depth_factor_q` and :func:`hansen1970_strip_pressure` give the growth of the bearing
  pressure with the founding depth (the "deep plate" curve): it never saturates, because ``q = gamma D``
  grows linearly while ``d_q`` tends to a constant.
* :func:`davis1968_reduced_friction_angle` maps a non-associated soil (friction ``phi``, dilatancy
  ``psi``) to an associated one of lower friction angle (Davis 1968; Drescher & Detournay 1993).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError

__all__ = [
    "davis1968_reduced_friction_angle",
    "ec7_ngamma",
    "hansen1970_depth_factor_q",
    "hansen1970_ngamma",
    "hansen1970_strip_pressure",
    "meyerhof1963_ngamma",
    "passive_earth_pressure_coefficient",
    "prandtl1921_nc",
    "reissner1924_nq",
    "vesic1973_ngamma",
]

FloatArray = NDArray[np.float64]

#: largest friction angle accepted [rad] (60 deg; bearing factors explode beyond)
MAX_FRICTION_ANGLE = np.radians(60.0)


def _angle(
    field: str, value: ArrayLike, *, allow_zero: bool = True, high: float = MAX_FRICTION_ANGLE
) -> FloatArray:
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise InputError(field, value, "a finite angle in radians") from None
    low_ok = arr >= 0 if allow_zero else arr > 0
    if not np.all(np.isfinite(arr)) or not np.all(low_ok) or not np.all(arr <= high):
        low = "0 <=" if allow_zero else "0 <"
        raise InputError(
            field,
            value,
            f"an angle with {low} value <= {np.degrees(high):g} deg, in radians",
            "convert degrees with math.radians",
        )
    return arr


def _nonneg(field: str, value: ArrayLike) -> FloatArray:
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise InputError(field, value, "a finite number >= 0") from None
    if not np.all(np.isfinite(arr)) or not np.all(arr >= 0):
        raise InputError(field, value, "a finite number >= 0")
    return arr


def _out(arr: FloatArray) -> FloatArray | float:
    return float(arr) if arr.ndim == 0 else arr


def reissner1924_nq(friction_angle: ArrayLike) -> FloatArray | float:
    """Surcharge factor ``N_q = exp(pi tan phi) tan^2(pi/4 + phi/2)`` [-] (Prandtl-Reissner, exact).

    Parameters
    ----------
    friction_angle : float or array
        Friction angle ``phi`` [rad], 0 to 60 deg.

    Returns
    -------
    N_q [-]; 1 at ``phi = 0``.

    References
    ----------
    H. Reissner, Zum Erddruckproblem, Proc. 1st Int. Congress of Applied Mechanics, Delft, 295-311 (1924).
    """
    phi = _angle("friction_angle", friction_angle)
    return _out(np.exp(np.pi * np.tan(phi)) * np.tan(np.pi / 4 + phi / 2) ** 2)


def prandtl1921_nc(friction_angle: ArrayLike) -> FloatArray | float:
    """Cohesion factor ``N_c = (N_q - 1) cot phi`` [-] (Prandtl, exact); ``2 + pi`` at ``phi = 0``.

    Parameters
    ----------
    friction_angle : float or array
        Friction angle ``phi`` [rad], 0 to 60 deg.

    References
    ----------
    L. Prandtl, Ueber die Eindringungsfestigkeit (Haerte) plastischer Baustoffe und die Festigkeit von
    Schneiden, Z. angew. Math. Mech. 1(1), 15-20 (1921). doi:10.1002/zamm.19210010102
    """
    phi = _angle("friction_angle", friction_angle)
    nq = np.asarray(reissner1924_nq(phi))
    small = phi < 1e-6
    safe = np.where(small, 1.0, phi)
    nc = np.where(small, 2.0 + np.pi + 0.0 * phi, (nq - 1.0) / np.tan(safe))
    return _out(np.asarray(nc, dtype=np.float64))


def passive_earth_pressure_coefficient(friction_angle: ArrayLike) -> FloatArray | float:
    """Rankine passive coefficient ``K_p = tan^2(pi/4 + phi/2) = (1 + sin phi) / (1 - sin phi)`` [-].

    References
    ----------
    W. J. M. Rankine, On the stability of loose earth, Phil. Trans. R. Soc. 147, 9-27 (1857).
    doi:10.1098/rstl.1857.0003
    """
    phi = _angle("friction_angle", friction_angle)
    return _out(np.tan(np.pi / 4 + phi / 2) ** 2)


def vesic1973_ngamma(friction_angle: ArrayLike) -> FloatArray | float:
    """APPROXIMATE self-weight factor ``N_gamma = 2 (N_q + 1) tan phi`` [-] (Vesic 1973).

    A fit to Caquot & Kerisel's (1953) characteristics values for a rough base; above the exact value
    for associated flow by some 40-50 % at 30-35 deg (compare :func:`~terradyn.plasticity.moc.moc_n_gamma`).

    References
    ----------
    A. S. Vesic, Analysis of ultimate loads of shallow foundations, J. Soil Mech. Found. Div. ASCE 99(SM1),
    45-73 (1973). doi:10.1061/JSFEAQ.0001846
    """
    phi = _angle("friction_angle", friction_angle)
    return _out(2.0 * (np.asarray(reissner1924_nq(phi)) + 1.0) * np.tan(phi))


def meyerhof1963_ngamma(friction_angle: ArrayLike) -> FloatArray | float:
    """APPROXIMATE self-weight factor ``N_gamma = (N_q - 1) tan(1.4 phi)`` [-] (Meyerhof 1963).

    References
    ----------
    G. G. Meyerhof, Some recent research on the bearing capacity of foundations, Can. Geotech. J. 1(1),
    16-26 (1963). doi:10.1139/t63-003
    """
    phi = _angle("friction_angle", friction_angle)
    return _out((np.asarray(reissner1924_nq(phi)) - 1.0) * np.tan(1.4 * phi))


def hansen1970_ngamma(friction_angle: ArrayLike) -> FloatArray | float:
    """APPROXIMATE self-weight factor ``N_gamma = 1.5 (N_q - 1) tan phi`` [-] (Brinch Hansen 1970).

    References
    ----------
    J. Brinch Hansen, A revised and extended formula for bearing capacity, Danish Geotechnical Institute
    Bulletin 28, 5-11 (1970).
    """
    phi = _angle("friction_angle", friction_angle)
    return _out(1.5 * (np.asarray(reissner1924_nq(phi)) - 1.0) * np.tan(phi))


def ec7_ngamma(friction_angle: ArrayLike) -> FloatArray | float:
    """APPROXIMATE self-weight factor ``N_gamma = 2 (N_q - 1) tan phi`` [-] (Eurocode 7, Annex D).

    Chen's (1975) upper-bound fit for a rough base, adopted in EN 1997-1:2004 Annex D (drained
    conditions).

    References
    ----------
    EN 1997-1:2004 Eurocode 7: Geotechnical design - Part 1: General rules, Annex D.3 (CEN, 2004).
    W. F. Chen, Limit Analysis and Soil Plasticity (Elsevier, 1975). ISBN 0-444-41249-2
    """
    phi = _angle("friction_angle", friction_angle)
    return _out(2.0 * (np.asarray(reissner1924_nq(phi)) - 1.0) * np.tan(phi))


def hansen1970_depth_factor_q(
    friction_angle: ArrayLike, depth: ArrayLike, width: ArrayLike
) -> FloatArray | float:
    """Depth factor of the surcharge term, ``d_q = 1 + 2 tan phi (1 - sin phi)^2 k`` [-] (Brinch Hansen 1970).

    ``k = D / B`` for ``D <= B`` and ``k = arctan(D / B)`` [rad] beyond (Vesic 1973 uses the same factor);
    as published, ``k`` drops from 1 to ``pi/4`` at ``D = B``.
    ``d_gamma = 1``. The factor saturates at ``1 + pi tan phi (1 - sin phi)^2`` but ``q N_q d_q`` keeps
    growing linearly with depth through ``q = gamma D``.

    Parameters
    ----------
    friction_angle : friction angle ``phi`` [rad]
    depth : founding depth ``D`` [m], >= 0
    width : footing width ``B`` [m], > 0

    References
    ----------
    J. Brinch Hansen, A revised and extended formula for bearing capacity, Danish Geotechnical Institute
    Bulletin 28, 5-11 (1970).
    """
    phi = _angle("friction_angle", friction_angle)
    d = _nonneg("depth", depth)
    b = _nonneg("width", width)
    if np.any(b <= 0):
        raise InputError("width", width, "a finite number > 0 [m]")
    ratio = d / b
    k = np.where(ratio <= 1.0, ratio, np.arctan(ratio))
    return _out(np.asarray(1.0 + 2.0 * np.tan(phi) * (1.0 - np.sin(phi)) ** 2 * k, dtype=np.float64))


def hansen1970_strip_pressure(
    friction_angle: ArrayLike,
    width: ArrayLike,
    depth: ArrayLike,
    unit_weight: ArrayLike,
    *,
    n_gamma: ArrayLike | None = None,
) -> FloatArray | float:
    """Collapse pressure of a buried strip footing on cohesionless soil [Pa] (Brinch Hansen 1970 form).

    ``q_u = gamma D N_q d_q + 1/2 gamma B N_gamma`` with :func:`reissner1924_nq`,
    :func:`hansen1970_depth_factor_q` and ``N_gamma`` from :func:`hansen1970_ngamma` unless
    ``n_gamma`` is given (e.g. the exact method-of-characteristics value). Grows without bound with
    depth (no saturation), the trend deep-plate MPM runs are checked against.

    Parameters
    ----------
    friction_angle : ``phi`` [rad]
    width : footing width ``B`` [m]
    depth : founding depth ``D`` [m]
    unit_weight : ``gamma = rho g`` [N/m^3]
    n_gamma : optional self-weight factor [-] to use instead of Hansen's approximation

    References
    ----------
    J. Brinch Hansen, A revised and extended formula for bearing capacity, Danish Geotechnical Institute
    Bulletin 28, 5-11 (1970).
    """
    phi = _angle("friction_angle", friction_angle)
    b = _nonneg("width", width)
    d = _nonneg("depth", depth)
    g = _nonneg("unit_weight", unit_weight)
    ng = np.asarray(hansen1970_ngamma(phi)) if n_gamma is None else _nonneg("n_gamma", n_gamma)
    dq = np.asarray(hansen1970_depth_factor_q(phi, d, b))
    nq = np.asarray(reissner1924_nq(phi))
    return _out(np.asarray(g * d * nq * dq + 0.5 * g * b * ng, dtype=np.float64))


def davis1968_reduced_friction_angle(
    friction_angle: ArrayLike, dilatancy_angle: ArrayLike = 0.0
) -> FloatArray | float:
    """Associated friction angle equivalent to a non-associated soil (Davis 1968).

    ``tan phi* = sin phi cos psi / (1 - sin phi sin psi)``.

    For isochoric flow (``psi = 0``) ``tan phi* = sin phi``; for ``psi = phi`` it returns ``phi``. Exact
    for translational (velocity-discontinuity) mechanisms (Drescher & Detournay 1993), an estimate for
    bearing capacity: the characteristics solution at ``phi*`` approximates the non-associated collapse
    load.

    Parameters
    ----------
    friction_angle : ``phi`` [rad]
    dilatancy_angle : ``psi`` [rad], ``0 <= psi <= phi``

    Returns
    -------
    ``phi*`` [rad]

    References
    ----------
    E. H. Davis, Theories of plasticity and the failure of soil masses, in Soil Mechanics: Selected Topics
    (I. K. Lee, ed.), Butterworths, London, 341-380 (1968).
    A. Drescher, E. Detournay, Limit load in translational failure mechanisms for associative and
    non-associative materials, Geotechnique 43(3), 443-456 (1993). doi:10.1680/geot.1993.43.3.443
    """
    phi = _angle("friction_angle", friction_angle)
    psi = _angle("dilatancy_angle", dilatancy_angle)
    if np.any(psi > phi + 1e-12):
        raise InputError(
            "dilatancy_angle", dilatancy_angle, "an angle between 0 and the friction angle [rad]"
        )
    s = np.sin(phi)
    return _out(np.arctan(s * np.cos(psi) / (1.0 - s * np.sin(psi))))
