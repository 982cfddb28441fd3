"""MPM configuration: the granular model from a :class:`~terradyn.materials.Material`, walls, bed, solver.

Friction mapping
----------------
terradyn matches the Drucker-Prager cone ``tau <= mu p`` to cohesionless Mohr-Coulomb in plane strain:
at isochoric plastic flow the out-of-plane deviatoric stress vanishes, so ``tau`` is the in-plane
maximum shear ``(sigma_1 - sigma_3)/2`` and ``p = (sigma_1 + sigma_3)/2``, giving **mu = sin(phi)**
(:func:`friction_coefficient_from_angle`). The shipped media TOMLs store ``friction_coefficient`` with
this mapping from their friction angle. (``mu = tan(phi)`` is a common alternative; it corresponds to a
plane-strain angle ``asin(tan(phi))``.)

Bed stability
-------------
An elastically settled bed under uniaxial strain has ``sigma_h = nu/(1-nu) sigma_v`` (also out of
plane), so ``tau/p = sqrt(3)(1 - 2 nu)/(1 + nu)``. If ``mu_s`` is below that ratio the bed yields under
gravity alone; :func:`bed_stability_ratio` gives it and :meth:`GranularModel.check_bed_stability` raises.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields, replace
from enum import Enum
from typing import Any

from ..errors import InputError, check_positive, check_range
from ..materials import Material

__all__ = [
    "LOOSE_DENSITY_RATIO",
    "MAX_DILATANCY",
    "BedPacking",
    "GranularModel",
    "Wall",
    "WallKind",
    "Walls",
    "bed_stability_ratio",
    "default_settle_time",
    "friction_coefficient_from_angle",
    "resolve_model",
]


#: With dilatancy on and no ``loose_density``, a point is disconnected below this fraction of the
#: critical density. A choice: random loose packings of frictional spheres are near phi = 0.55-0.57
#: and their critical states near 0.58-0.60, a ratio of about 0.95 (continuum.md section 7.4 quotes
#: an onset of dilatancy at phi_c = 0.605 for glass beads prepared from 0.585).
LOOSE_DENSITY_RATIO = 0.95

#: Largest accepted dilatancy coefficient K [-].
MAX_DILATANCY = 50.0


def friction_coefficient_from_angle(friction_angle: float) -> float:
    """Plane-strain Drucker-Prager slope matching Mohr-Coulomb: ``mu = sin(phi)`` (phi [rad])."""
    check_range("friction_angle", friction_angle, 0.0, math.radians(89.0), unit="rad")
    return math.sin(friction_angle)


def bed_stability_ratio(poisson_ratio: float) -> float:
    """``tau/p`` of a bed settled elastically under uniaxial strain: sqrt(3)(1 - 2 nu)/(1 + nu) [-]."""
    return math.sqrt(3.0) * (1.0 - 2.0 * poisson_ratio) / (1.0 + poisson_ratio)


class WallKind(str, Enum):
    """Boundary condition of a box wall on the grains."""

    FREE_SLIP = "free-slip"
    NO_SLIP = "no-slip"
    FRICTIONAL = "frictional"


@dataclass(frozen=True, slots=True)
class Wall:
    """One wall: ``kind`` and, for :attr:`WallKind.FRICTIONAL`, the Coulomb ``friction`` [-]."""

    kind: WallKind = WallKind.FREE_SLIP
    friction: float = 0.0

    def __post_init__(self) -> None:
        try:
            object.__setattr__(self, "kind", WallKind(self.kind))
        except ValueError:
            raise InputError("wall.kind", self.kind, f"one of {[k.value for k in WallKind]}") from None
        check_range("wall.friction", self.friction, 0.0, 2.0)

    @property
    def code(self) -> int:
        return {WallKind.FREE_SLIP: 0, WallKind.NO_SLIP: 1, WallKind.FRICTIONAL: 2}[self.kind]


@dataclass(frozen=True, slots=True)
class Walls:
    """The three walls of the bed box (the top is open)."""

    left: Wall = field(default_factory=Wall)
    right: Wall = field(default_factory=Wall)
    bottom: Wall = field(default_factory=Wall)

    @classmethod
    def coerce(cls, walls: Walls | Wall | WallKind | str | None) -> Walls:
        """Accept a :class:`Walls`, one :class:`Wall`/kind for all sides, or None (free-slip)."""
        if walls is None:
            return cls()
        if isinstance(walls, Walls):
            return walls
        if isinstance(walls, Wall):
            return cls(walls, walls, walls)
        if isinstance(walls, str | WallKind):
            w = Wall(WallKind(walls) if walls in {k.value for k in WallKind} else walls)  # type: ignore[arg-type]
            return cls(w, w, w)
        raise InputError("walls", walls, "a Walls, a Wall or one of 'free-slip', 'no-slip', 'frictional'")


class BedPacking(str, Enum):
    """Initial packing of the bed relative to the critical density.

    CONSOLIDATED: density above critical with a geostatic stress (immediate frictional resistance).
    UNCONSOLIDATED: density just below critical and stress-free; it compacts under gravity while settling.
    With dilatancy on (:attr:`GranularModel.dilatancy`) a bed at or above the model's
    :attr:`~GranularModel.disconnection_density` is connected: it gets the geostatic stress of a
    consolidated bed, stays loose while it settles and compacts only where it is sheared.
    """

    CONSOLIDATED = "consolidated"
    UNCONSOLIDATED = "unconsolidated"


@dataclass(frozen=True, slots=True)
class GranularModel:
    """Parameters of the Dunatunga-Kamrin model in SI (see module doc for the mu mapping).

    Attributes
    ----------
    youngs_modulus : float  E [Pa]
    poisson_ratio : float  nu [-]
    friction_coefficient : float  mu_s [-]
    friction_coefficient_2 : float  mu_2 [-] (= mu_s: rate-independent)
    inertial_number_0 : float  I_0 [-]
    grain_diameter : float  d [m]
    grain_density : float  rho_s [kg/m^3]
    critical_density : float  rho_c [kg/m^3]
    bulk_density : float  nominal bed density [kg/m^3]
    surface_friction : float  body-grain Coulomb friction [-]
    dilatancy : float  K [-] of ``tan(psi) = K (phi - phi_c)`` (0: off, the isochoric model; see
        :mod:`terradyn.mpm.constitutive`)
    loose_density : float or None  with dilatancy on, the density [kg/m^3] below which a point is
        disconnected (stress-free); None: :data:`LOOSE_DENSITY_RATIO` x critical. Off, the critical
        density is the threshold.

    ``dilatancy`` and ``loose_density`` are left out of a run's fingerprint at their defaults, so the
    checkpoints of runs without dilatancy are the same as before they existed.
    """

    youngs_modulus: float
    poisson_ratio: float
    friction_coefficient: float
    friction_coefficient_2: float
    inertial_number_0: float
    grain_diameter: float
    grain_density: float
    critical_density: float
    bulk_density: float
    surface_friction: float
    dilatancy: float = field(default=0.0, metadata={"omit_default": True})
    loose_density: float | None = field(default=None, metadata={"omit_default": True})

    def __post_init__(self) -> None:
        check_positive("youngs_modulus", self.youngs_modulus)
        check_range("poisson_ratio", self.poisson_ratio, 0.0, 0.49)
        check_range("friction_coefficient", self.friction_coefficient, 0.0, 2.0)
        check_range("friction_coefficient_2", self.friction_coefficient_2, self.friction_coefficient, 4.0)
        check_positive("inertial_number_0", self.inertial_number_0)
        check_positive("grain_diameter", self.grain_diameter)
        check_range("grain_density", self.grain_density, 1.0, 25000.0, unit="kg/m^3")
        check_range("critical_density", self.critical_density, 1.0, self.grain_density, unit="kg/m^3")
        check_range("bulk_density", self.bulk_density, 1.0, self.grain_density, unit="kg/m^3")
        check_range("surface_friction", self.surface_friction, 0.0, 2.0)
        check_range("dilatancy", self.dilatancy, 0.0, MAX_DILATANCY)
        if self.loose_density is not None:
            if self.dilatancy == 0.0:
                raise InputError(
                    "loose_density", self.loose_density, "None when dilatancy is 0", "set dilatancy > 0"
                )
            check_range("loose_density", self.loose_density, 0.5 * self.critical_density,
                        self.critical_density, unit="kg/m^3")  # fmt: skip

    def __repr__(self) -> str:
        """The dataclass repr without the dilatancy fields at their defaults (results' metadata of
        runs without dilatancy read as before)."""
        shown = [
            f"{f.name}={getattr(self, f.name)!r}"
            for f in fields(self)
            if not (f.metadata.get("omit_default") and getattr(self, f.name) == f.default)
        ]
        return f"{type(self).__name__}({', '.join(shown)})"

    @classmethod
    def from_material(
        cls,
        material: Material,
        *,
        youngs_modulus: float | None = None,
        poisson_ratio: float | None = None,
        friction_coefficient: float | None = None,
        surface_friction: float | None = None,
        rate_dependent: bool = False,
        dilatancy: float | None = None,
        loose_density: float | None = None,
    ) -> GranularModel:
        """Model of a medium; keyword overrides replace single parameters.

        With ``rate_dependent=False`` (default) mu_2 is set to mu_s (constant friction, the RFT-comparison
        model); ``True`` keeps the material's mu(I) parameters. Missing densities fall back as follows:
        critical = bulk, grain = bulk / 0.6. ``dilatancy`` (K [-]) and ``loose_density`` [kg/m^3] are off
        unless given (the shipped media carry no dilatancy).
        """
        if not isinstance(material, Material):
            raise InputError("material", material, "a terradyn Material (materials.get(name))")
        c = material.require_continuum()
        bulk = material.bulk_density or material.critical_density
        if bulk is None:
            raise InputError(
                f"material {material.name!r}.bulk_density", None, "a bulk or critical density for MPM"
            )
        crit = material.critical_density or bulk
        grain = material.grain_density or max(bulk, crit) / 0.6
        mu_s = c.friction_coefficient if friction_coefficient is None else friction_coefficient
        mu_2 = max(c.friction_coefficient_2, mu_s) if rate_dependent else mu_s
        return cls(
            youngs_modulus=c.youngs_modulus if youngs_modulus is None else youngs_modulus,
            poisson_ratio=c.poisson_ratio if poisson_ratio is None else poisson_ratio,
            friction_coefficient=mu_s,
            friction_coefficient_2=mu_2,
            inertial_number_0=c.inertial_number_0,
            grain_diameter=c.grain_diameter,
            grain_density=grain,
            critical_density=crit,
            bulk_density=bulk,
            surface_friction=c.surface_friction if surface_friction is None else surface_friction,
            dilatancy=0.0 if dilatancy is None else dilatancy,
            loose_density=loose_density,
        )

    def with_changes(self, **changes: Any) -> GranularModel:
        """A validated copy with some parameters replaced."""
        known = {f.name for f in fields(self)}
        for key in changes:
            if key not in known:
                raise InputError("granular model field", key, f"one of {sorted(known)}")
        return replace(self, **changes)

    @property
    def disconnection_density(self) -> float:
        """Density [kg/m^3] below which a point is stress-free: critical, or with dilatancy on the
        loose density."""
        if self.dilatancy == 0.0:
            return self.critical_density
        if self.loose_density is None:
            return LOOSE_DENSITY_RATIO * self.critical_density
        return self.loose_density

    @property
    def shear_modulus(self) -> float:
        """G = E / (2 (1 + nu)) [Pa]."""
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    @property
    def bulk_modulus(self) -> float:
        """K = E / (3 (1 - 2 nu)) [Pa]."""
        return self.youngs_modulus / (3.0 * (1.0 - 2.0 * self.poisson_ratio))

    @property
    def lame_lambda(self) -> float:
        """lambda = K - 2G/3 [Pa]."""
        return self.bulk_modulus - 2.0 * self.shear_modulus / 3.0

    @property
    def earth_pressure_at_rest(self) -> float:
        """K_0 = nu / (1 - nu) [-], the elastic uniaxial-strain stress ratio used for geostatic stress."""
        return self.poisson_ratio / (1.0 - self.poisson_ratio)

    @property
    def friction_angle(self) -> float:
        """Plane-strain Mohr-Coulomb angle of the cone, asin(mu_s) [rad]."""
        return math.asin(min(1.0, self.friction_coefficient))

    def wave_speed(self, density: float | None = None) -> float:
        """P-wave speed sqrt((K + 4G/3)/rho) [m/s] at ``density`` (default: critical density)."""
        rho = self.critical_density if density is None else density
        return math.sqrt((self.bulk_modulus + 4.0 * self.shear_modulus / 3.0) / rho)

    def check_bed_stability(self) -> None:
        """Raise :class:`InputError` if a resting bed would yield under gravity (mu_s too small for nu)."""
        need = bed_stability_ratio(self.poisson_ratio)
        if self.friction_coefficient <= need:
            raise InputError(
                "friction_coefficient",
                self.friction_coefficient,
                f"a value above sqrt(3)(1-2nu)/(1+nu) = {need:.3f} for nu = {self.poisson_ratio}",
                "raise poisson_ratio or the bed creeps under its own weight",
            )

    def as_kernel_array(self):  # -> NDArray
        """(G, lambda, mu_s, mu_2, I_0, d, rho_s, rho_c) for :func:`terradyn.mpm._kernels.advance`,
        followed with dilatancy on by (K, loose density)."""
        import numpy as np

        values = [
            self.shear_modulus,
            self.lame_lambda,
            self.friction_coefficient,
            self.friction_coefficient_2,
            self.inertial_number_0,
            self.grain_diameter,
            self.grain_density,
            self.critical_density,
        ]
        if self.dilatancy > 0.0:
            values += [self.dilatancy, self.disconnection_density]
        return np.array(values)


def resolve_model(material: Any, *, rate_dependent: bool = False, **overrides: float | None) -> GranularModel:
    """The granular model of a :class:`Material` (its ``[continuum]`` table) or a given
    :class:`GranularModel`, with non-None ``overrides`` replacing single parameters; checked for bed
    stability."""
    changes = {k: v for k, v in overrides.items() if v is not None}
    if isinstance(material, GranularModel):
        model = material.with_changes(**changes)
    elif isinstance(material, Material):
        model = GranularModel.from_material(material, rate_dependent=rate_dependent, **changes)
    else:
        raise InputError("material", material, "a terradyn Material or an mpm.GranularModel")
    model.check_bed_stability()
    return model


def default_settle_time(model: GranularModel, depth: float, packing: BedPacking, gravity: float) -> float:
    """Settling time [s] of a bed ``depth`` [m] deep: 40 P-wave transits (damped), plus a free-fall
    time for an unconsolidated bed to compact."""
    t = 40.0 * depth / model.wave_speed()
    if packing is BedPacking.UNCONSOLIDATED:
        t += 4.0 * math.sqrt(0.05 * depth / gravity)
    return t
