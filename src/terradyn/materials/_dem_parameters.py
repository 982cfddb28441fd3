"""Discrete-element (DEM) parameters of a medium: the optional ``[dem]`` table of a material TOML."""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import check_positive, check_range

__all__ = ["DEMParameters"]


@dataclass(frozen=True, slots=True)
class DEMParameters:
    """Grain and contact parameters of a Hertz-Mindlin DEM bed with rolling resistance (all SI).

    Attributes
    ----------
    grain_diameter : float  mean grain diameter d [m]
    diameter_spread : float  half-width of the uniform diameter distribution, d (1 +- spread) [-]
    grain_density : float  solid density of a grain [kg/m^3]
    youngs_modulus : float  grain Young's modulus E [Pa], usually softened far below the mineral's
    poisson_ratio : float  grain Poisson ratio nu [-]
    friction : float  grain-grain Coulomb friction coefficient [-]
    rolling_friction : float  grain-grain rolling-resistance coefficient mu_r [-]
    restitution : float  normal coefficient of restitution e [-]
    wall_friction : float  grain-body (intruder, container) friction coefficient [-]
    notes : str  sources of the values
    """

    grain_diameter: float
    diameter_spread: float
    grain_density: float
    youngs_modulus: float
    poisson_ratio: float
    friction: float
    rolling_friction: float
    restitution: float
    wall_friction: float
    notes: str = ""

    def __post_init__(self) -> None:
        check_range("dem.grain_diameter", self.grain_diameter, 1e-6, 0.1, unit="m")
        check_range("dem.diameter_spread", self.diameter_spread, 0.0, 0.5)
        check_range("dem.grain_density", self.grain_density, 1.0, 25000.0, unit="kg/m^3")
        check_positive("dem.youngs_modulus", self.youngs_modulus)
        check_range("dem.poisson_ratio", self.poisson_ratio, 0.0, 0.499)
        check_range("dem.friction", self.friction, 0.0, 2.0)
        check_range("dem.rolling_friction", self.rolling_friction, 0.0, 1.0)
        check_range("dem.restitution", self.restitution, 0.05, 1.0)
        check_range("dem.wall_friction", self.wall_friction, 0.0, 2.0)
