"""Pressure-sinkage and shear-displacement laws of classical terramechanics.

One function per published model, each vectorised over NumPy arrays (inputs broadcast):

* :func:`bekker_pressure` - Bekker's plate pressure-sinkage law ``p = (k_c / b + k_phi) z^n``;
* :func:`reece_pressure` - Reece's dimensionless form ``p = (c k'_c + gamma_s b k'_phi) (z / b)^n``;
* :func:`janosi_hanamoto_shear` - Janosi-Hanamoto shear stress-displacement law
  ``tau = (c + sigma tan phi) (1 - exp(-j / K))``.

The public functions check their inputs and raise :class:`~terradyn.errors.InputError` naming the bad
field; the underscore kernels beside them take plain SI floats and arrays and check nothing (the
Wong-Reece wheel integrates them at thousands of points per solve).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError, check_finite, check_positive, check_range

__all__ = ["bekker_pressure", "janosi_hanamoto_shear", "reece_pressure"]

FloatArray = NDArray[np.float64]


def _array(field: str, value: ArrayLike) -> FloatArray:
    """``value`` as a float array, or InputError if any entry is not a finite number."""
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise InputError(field, value, "a finite number or array of finite numbers") from None
    if not np.all(np.isfinite(arr)):
        raise InputError(field, value, "finite numbers only")
    return arr


def _positive_array(field: str, value: ArrayLike, *, allow_zero: bool = False) -> FloatArray:
    arr = _array(field, value)
    bad = arr < 0 if allow_zero else arr <= 0
    if np.any(bad):
        first = arr[bad].flat[0] if arr.ndim else float(arr)
        raise InputError(field, float(first), "numbers >= 0" if allow_zero else "numbers > 0")
    return arr


def _result(value: FloatArray) -> FloatArray | float:
    """Return 0-d results as Python floats, arrays as arrays."""
    return float(value) if np.ndim(value) == 0 else value


def _power_law(sinkage: FloatArray, n: float) -> FloatArray:
    """``max(z, 0)^n``: a plate above the surface carries nothing."""
    return np.power(np.maximum(sinkage, 0.0), n)


def bekker_pressure(
    sinkage: ArrayLike, plate_width: ArrayLike, k_c: float, k_phi: float, n: float
) -> FloatArray | float:
    r"""Bekker pressure-sinkage law of a plate (or of a wheel's contact patch).

    .. math:: p = \left(\frac{k_c}{b} + k_\phi\right) z^n

    Parameters
    ----------
    sinkage : array_like
        Plate sinkage z below the undisturbed surface [m]. Negative values (plate above the
        surface) give zero pressure.
    plate_width : array_like
        Smaller dimension b of the plate (a wheel's width) [m], > 0. Broadcasts with ``sinkage``.
    k_c : float
        Cohesive modulus [N/m^(n+1)]; may be negative (fitted values for dry sand often are).
    k_phi : float
        Frictional modulus [N/m^(n+2)].
    n : float
        Sinkage exponent [-], in [0.1, 3].

    Returns
    -------
    float or numpy.ndarray
        Pressure p [Pa], with the broadcast shape of ``sinkage`` and ``plate_width``.

    Raises
    ------
    InputError
        Non-finite inputs, non-positive width, n outside [0.1, 3], or a width at which the modulus
        ``k_c / b + k_phi`` is not positive (the plate would be pulled into the soil).

    References
    ----------
    .. [1] M. G. Bekker, *Theory of Land Locomotion*, University of Michigan Press, Ann Arbor (1956)
       (no DOI).
    .. [2] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley (2008), ch. 2,
       ISBN 978-0-470-17038-0.
    """
    z = _array("sinkage", sinkage)
    b = _positive_array("plate_width", plate_width)
    k_c = check_finite("k_c", k_c)
    k_phi = check_finite("k_phi", k_phi)
    n = check_range("n", n, 0.1, 3.0)
    modulus = k_c / b + k_phi
    if np.any(modulus <= 0):
        raise InputError(
            "k_c / plate_width + k_phi",
            float(np.min(modulus)),
            "a modulus > 0 [N/m^(n+2)]",
            "with a negative k_c the plate must be wider than -k_c / k_phi",
        )
    return _result(_bekker_pressure_kernel(z, b, k_c, k_phi, n))


def _bekker_pressure_kernel(
    sinkage: FloatArray, plate_width: FloatArray | float, k_c: float, k_phi: float, n: float
) -> FloatArray:
    return (k_c / plate_width + k_phi) * _power_law(sinkage, n)


def reece_pressure(
    sinkage: ArrayLike,
    plate_width: ArrayLike,
    cohesion: float,
    unit_weight: float,
    k_c_prime: float,
    k_phi_prime: float,
    n: float,
) -> FloatArray | float:
    r"""Reece pressure-sinkage law (dimensionless moduli).

    .. math:: p = \left(c\,k'_c + \gamma_s\,b\,k'_\phi\right) \left(\frac{z}{b}\right)^n

    Reece's form makes the moduli dimensionless and puts the width dependence in ``z / b``; for a
    cohesionless soil the pressure at a given ``z / b`` grows linearly with the width.

    Parameters
    ----------
    sinkage : array_like
        Plate sinkage z [m]; negative values give zero pressure.
    plate_width : array_like
        Smaller plate dimension b [m], > 0.
    cohesion : float
        Soil cohesion c [Pa], >= 0.
    unit_weight : float
        Unit weight of the soil gamma_s = rho g [N/m^3], >= 0.
    k_c_prime : float
        Cohesive modulus k'_c [-].
    k_phi_prime : float
        Frictional modulus k'_phi [-].
    n : float
        Sinkage exponent [-], in [0.1, 3].

    Returns
    -------
    float or numpy.ndarray
        Pressure p [Pa].

    Raises
    ------
    InputError
        Non-finite inputs, non-positive width, negative cohesion or unit weight, n outside [0.1, 3],
        or a non-positive modulus ``c k'_c + gamma_s b k'_phi``.

    References
    ----------
    .. [1] A. R. Reece, Principles of soil-vehicle mechanics, *Proc. Inst. Mech. Eng.* 180 (Part 2A),
       45-66 (1965) (no DOI found).
    .. [2] J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley (2008), ch. 2,
       ISBN 978-0-470-17038-0.
    """
    z = _array("sinkage", sinkage)
    b = _positive_array("plate_width", plate_width)
    c = check_positive("cohesion", cohesion, allow_zero=True)
    gamma_s = check_positive("unit_weight", unit_weight, allow_zero=True)
    kc = check_finite("k_c_prime", k_c_prime)
    kphi = check_finite("k_phi_prime", k_phi_prime)
    n = check_range("n", n, 0.1, 3.0)
    modulus = c * kc + gamma_s * b * kphi
    if np.any(modulus <= 0):
        raise InputError(
            "cohesion * k_c_prime + unit_weight * plate_width * k_phi_prime",
            float(np.min(modulus)),
            "a modulus > 0 [Pa]",
        )
    return _result(modulus * _power_law(z / b, n))


def janosi_hanamoto_shear(
    shear_displacement: ArrayLike,
    normal_stress: ArrayLike,
    cohesion: float,
    friction_angle: float,
    shear_modulus: float,
) -> FloatArray | float:
    r"""Janosi-Hanamoto shear stress developed over a shear displacement.

    .. math:: \tau = \operatorname{sign}(j)\,(c + \sigma \tan\phi)\left(1 - e^{-|j|/K}\right)

    For ``j >= 0`` this is the published law; the stress rises from 0 at ``j = 0`` to the
    Mohr-Coulomb strength ``c + sigma tan(phi)`` as ``j -> infinity``. terradyn extends it oddly to
    ``j < 0`` (shearing the other way gives the opposite stress), which is what a skidding wheel needs.

    Parameters
    ----------
    shear_displacement : array_like
        Shear displacement j [m]; the sign gives the direction of the stress.
    normal_stress : array_like
        Normal stress sigma on the shear plane [Pa], >= 0. Broadcasts with ``shear_displacement``.
    cohesion : float
        Cohesion c [Pa], >= 0.
    friction_angle : float
        Internal friction angle phi [rad], in [0, 89 deg].
    shear_modulus : float
        Shear deformation modulus K [m], > 0.

    Returns
    -------
    float or numpy.ndarray
        Shear stress tau [Pa].

    References
    ----------
    .. [1] Z. Janosi, B. Hanamoto, The analytical determination of drawbar pull as a function of slip
       for tracked vehicles in deformable soils, *Proc. 1st Int. Conf. Terrain-Vehicle Systems*, Turin
       (1961) (no DOI).
    .. [2] J. Y. Wong, A. R. Reece, Prediction of rigid wheel performance based on the analysis of
       soil-wheel stresses, part I, *J. Terramechanics* 4(1), 81-98 (1967),
       doi:10.1016/0022-4898(67)90105-X.
    """
    j = _array("shear_displacement", shear_displacement)
    sigma = _positive_array("normal_stress", normal_stress, allow_zero=True)
    c = check_positive("cohesion", cohesion, allow_zero=True)
    phi = check_range("friction_angle", friction_angle, 0.0, np.radians(89.0), unit="rad")
    k = check_positive("shear_modulus", shear_modulus)
    return _result(_janosi_hanamoto_kernel(j, sigma, c, float(np.tan(phi)), k))


def _janosi_hanamoto_kernel(
    shear_displacement: FloatArray, normal_stress: FloatArray, cohesion: float, tan_phi: float, k: float
) -> FloatArray:
    """Odd Janosi-Hanamoto law with ``tan(phi)`` precomputed; no checks."""
    j = shear_displacement
    return np.sign(j) * (cohesion + normal_stress * tan_phi) * -np.expm1(-np.abs(j) / k)
