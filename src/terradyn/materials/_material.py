"""The :class:`Material` value type and its parameter groups (all SI)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields, replace

import numpy as np

from ..errors import InputError, check_finite, check_positive, check_range
from ._dem_parameters import DEMParameters

__all__ = [
    "BekkerParameters",
    "ContinuumParameters",
    "DEMParameters",
    "LiCoefficients",
    "Material",
    "Provenance",
    "RFTParameters",
]

_LI_NAMES = ("A00", "A10", "B01", "B11", "Bm11", "C01", "C11", "Cm11", "D10")


@dataclass(frozen=True, slots=True)
class LiCoefficients:
    """The nine Fourier coefficients of the Li, Zhang & Goldman (2013) RFT fit.

    ``alpha_z = A00 + A10 cos 2b + B01 sin g + B11 sin(2b + g) + Bm11 sin(-2b + g)`` and
    ``alpha_x = C01 cos g + C11 cos(2b + g) + Cm11 cos(-2b + g) + D10 sin 2b`` (``Bm11`` and ``Cm11`` are
    the m = -1 terms). Dimensionless; :class:`RFTParameters` multiplies them by a scale [N/m^3].
    """

    A00: float
    A10: float
    B01: float
    B11: float
    Bm11: float
    C01: float
    C11: float
    Cm11: float
    D10: float

    def __post_init__(self) -> None:
        for name in _LI_NAMES:
            object.__setattr__(self, name, check_finite(f"rft.coefficients.{name}", getattr(self, name)))

    @classmethod
    def generic(cls) -> LiCoefficients:
        """The generic set of Li et al. (2013), normalised so that alpha_z(0, pi/2) = 1."""
        return cls(0.206, 0.169, 0.358, 0.212, 0.055, 0.253, -0.124, 0.007, 0.088)

    def as_array(self) -> np.ndarray:
        """Coefficients in the kernel order (A00, A10, B01, B11, Bm11, C01, C11, Cm11, D10)."""
        return np.array([getattr(self, n) for n in _LI_NAMES], dtype=np.float64)

    def alpha_z_plate_down(self) -> float:
        """alpha_z(beta=0, gamma=pi/2) of the bare coefficients: A00 + A10 + B01 + B11 + Bm11."""
        return self.A00 + self.A10 + self.B01 + self.B11 + self.Bm11

    @staticmethod
    def names() -> tuple[str, ...]:
        return _LI_NAMES


@dataclass(frozen=True, slots=True)
class RFTParameters:
    """RFT parameters of a medium: ``alpha = scale * alpha_fit(beta, gamma)``.

    Attributes
    ----------
    coefficients : LiCoefficients
        Shape of the alpha map.
    scale : float
        Multiplier [N/m^3]. For the generic set (alpha_z(0, pi/2) = 1) this is the RFT scale zeta.
    """

    coefficients: LiCoefficients
    scale: float

    def __post_init__(self) -> None:
        check_positive("rft.scale", self.scale)
        if self.zeta <= 0:
            raise InputError(
                "rft.coefficients",
                self.coefficients,
                "a set with alpha_z(beta=0, gamma=90 deg) > 0",
                "a plate pushed straight down must be resisted",
            )

    @property
    def zeta(self) -> float:
        """Vertical stress per depth of a horizontal plate pushed straight down [N/m^3]."""
        return self.scale * self.coefficients.alpha_z_plate_down()


@dataclass(frozen=True, slots=True)
class BekkerParameters:
    """Bekker pressure-sinkage and Janosi-Hanamoto shear parameters.

    Attributes
    ----------
    k_c : float  cohesive modulus [N/m^(n+1)]
    k_phi : float  frictional modulus [N/m^(n+2)]
    n : float  sinkage exponent [-]
    cohesion : float  c [Pa]
    friction_angle : float  phi [rad]
    shear_modulus : float  Janosi-Hanamoto shear deformation modulus K [m]
    """

    k_c: float
    k_phi: float
    n: float
    cohesion: float
    friction_angle: float
    shear_modulus: float

    def __post_init__(self) -> None:
        check_finite("bekker.k_c", self.k_c)
        check_positive("bekker.k_phi", self.k_phi)
        check_range("bekker.n", self.n, 0.1, 3.0)
        check_positive("bekker.cohesion", self.cohesion, allow_zero=True)
        check_range("bekker.friction_angle", self.friction_angle, 0.0, math.radians(89.0), unit="rad")
        check_positive("bekker.shear_modulus", self.shear_modulus)


@dataclass(frozen=True, slots=True)
class ContinuumParameters:
    """Parameters of the Dunatunga-Kamrin granular continuum (plane-strain MPM).

    Attributes
    ----------
    youngs_modulus : float  E [Pa] (often softened to keep explicit steps affordable)
    poisson_ratio : float  nu [-]
    friction_coefficient : float  static internal friction mu_s [-] (Drucker-Prager slope)
    friction_coefficient_2 : float  mu_2 of mu(I) [-]; equal to mu_s for the rate-independent model
    inertial_number_0 : float  I_0 of mu(I) [-]
    grain_diameter : float  d [m]
    surface_friction : float  body-grain Coulomb friction coefficient [-]
    """

    youngs_modulus: float
    poisson_ratio: float
    friction_coefficient: float
    friction_coefficient_2: float
    inertial_number_0: float = 0.278
    grain_diameter: float = 1.0e-3
    surface_friction: float = 0.4

    def __post_init__(self) -> None:
        check_positive("continuum.youngs_modulus", self.youngs_modulus)
        check_range("continuum.poisson_ratio", self.poisson_ratio, 0.0, 0.499)
        check_range("continuum.friction_coefficient", self.friction_coefficient, 0.0, 2.0)
        check_range("continuum.friction_coefficient_2", self.friction_coefficient_2, 0.0, 4.0)
        if self.friction_coefficient_2 < self.friction_coefficient:
            raise InputError(
                "continuum.friction_coefficient_2",
                self.friction_coefficient_2,
                f"a number >= friction_coefficient ({self.friction_coefficient})",
            )
        check_positive("continuum.inertial_number_0", self.inertial_number_0)
        check_positive("continuum.grain_diameter", self.grain_diameter)
        check_range("continuum.surface_friction", self.surface_friction, 0.0, 2.0)


@dataclass(frozen=True, slots=True)
class Provenance:
    """Where a parameter set comes from."""

    citation: str = ""
    doi: str = ""
    table: str = ""
    notes: str = ""


@dataclass(frozen=True, slots=True)
class Material:
    """A dry granular medium.

    Parameter groups are optional: a medium known only by its RFT fit has ``bekker=None``, and a model
    that needs a missing group raises :class:`~terradyn.errors.InputError` naming it.

    Attributes
    ----------
    name : str
    description : str
    rft : RFTParameters or None
    bekker : BekkerParameters or None
    continuum : ContinuumParameters or None
    grain_density, bulk_density, critical_density : float or None  [kg/m^3]
    internal_friction_angle : float or None  [rad] (3D-RFT media scaling, MPM mu_s mapping)
    surface_friction : float or None  body-medium friction coefficient [-] (3D-RFT tangential cap)
    dem : DEMParameters or None  grain and contact parameters of the DEM reference (``[dem]`` table)
    drft_lambda : float or None  inertial coefficient of dynamic RFT [-]
    provenance : Provenance
    """

    name: str
    description: str = ""
    rft: RFTParameters | None = None
    bekker: BekkerParameters | None = None
    continuum: ContinuumParameters | None = None
    grain_density: float | None = None
    bulk_density: float | None = None
    critical_density: float | None = None
    internal_friction_angle: float | None = None
    drft_lambda: float | None = None
    surface_friction: float | None = None
    dem: DEMParameters | None = None
    provenance: Provenance = field(default_factory=Provenance)

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.strip():
            raise InputError("material.name", self.name, "a non-empty string")
        for name in ("grain_density", "bulk_density", "critical_density"):
            value = getattr(self, name)
            if value is not None:
                check_range(f"material.{name}", value, 1.0, 25000.0, unit="kg/m^3")
        if self.internal_friction_angle is not None:
            check_range(
                "material.internal_friction_angle",
                self.internal_friction_angle,
                0.0,
                math.radians(89.0),
                unit="rad",
            )
        if self.drft_lambda is not None:
            check_positive("material.drft_lambda", self.drft_lambda, allow_zero=True)
        if self.surface_friction is not None:
            check_range("material.surface_friction", self.surface_friction, 0.0, 10.0)
        if (
            self.grain_density is not None
            and self.critical_density is not None
            and self.critical_density > self.grain_density
        ):
            raise InputError(
                "material.critical_density",
                self.critical_density,
                f"a density <= grain_density ({self.grain_density} kg/m^3)",
            )

    @property
    def zeta(self) -> float:
        """RFT scale [N/m^3] (alpha_z of a horizontal plate pushed straight down)."""
        return self.require_rft().zeta

    def require_rft(self) -> RFTParameters:
        if self.rft is None:
            raise InputError(f"material {self.name!r}.rft", None, "RFT parameters for this model")
        return self.rft

    def require_bekker(self) -> BekkerParameters:
        if self.bekker is None:
            raise InputError(
                f"material {self.name!r}.bekker", None, "Bekker/Wong-Reece parameters for this model"
            )
        return self.bekker

    def require_continuum(self) -> ContinuumParameters:
        if self.continuum is None:
            raise InputError(
                f"material {self.name!r}.continuum", None, "continuum (MPM) parameters for this model"
            )
        return self.continuum

    def require_dem(self) -> DEMParameters:
        if self.dem is None:
            raise InputError(
                f"material {self.name!r}.dem", None, "DEM parameters (a [dem] table) for this model"
            )
        return self.dem

    def with_zeta(self, zeta: float) -> Material:
        """A copy whose RFT alpha map is rescaled so that alpha_z(0, pi/2) = ``zeta`` [N/m^3]."""
        rft = self.require_rft()
        check_positive("zeta", zeta)
        scale = zeta / rft.coefficients.alpha_z_plate_down()
        return replace(self, rft=RFTParameters(rft.coefficients, scale))

    def with_changes(self, **changes: object) -> Material:
        """A validated copy with some fields replaced."""
        known = {f.name for f in fields(self)}
        for key in changes:
            if key not in known:
                raise InputError("material field", key, f"one of {sorted(known)}")
        return replace(self, **changes)  # type: ignore[arg-type]
