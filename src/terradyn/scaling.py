"""Scaling laws of granular locomotion (Slonaker et al., PRE 2017; Agarwal et al. 2021).

If the medium's resistance scales as ``alpha ~ rho_c g f(beta, gamma; mu)`` (true of RFT when
``zeta ~ rho_c g``, and of a frictional continuum), the motion of geometrically similar bodies
depends only on the dimensionless groups below. A design of size L, mass M in gravity g maps to size
lambda_L L, gravity lambda_g g and medium density lambda_rho rho_c with

* mass, M -> lambda_rho lambda_L^3 M (plane bodies scale their width too); inertia -> x lambda_L^2 more;
* spin, omega -> omega sqrt(lambda_g / lambda_L); speed, V -> V sqrt(lambda_g lambda_L);
* time, t -> t sqrt(lambda_L / lambda_g); force -> lambda_rho lambda_g lambda_L^3; torque -> x lambda_L;
* power -> lambda_rho lambda_g^(3/2) lambda_L^(7/2); RFT scale zeta -> lambda_rho lambda_g zeta.

Slip and sinkage / L are unchanged. A low-gravity test therefore keeps the same mass (not the same
weight). Cohesion breaks the scaling (it does not scale with rho g).

References
----------
J. Slonaker, D. C. Motley, Q. Zhang, S. Townsend, C. Senatore, K. Iagnemma, K. Kamrin, "General
scaling relations for locomotion in granular media", Phys. Rev. E 95, 052901 (2017).
doi:10.1103/PhysRevE.95.052901
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .errors import InputError, check_positive
from .geometry import Body
from .materials import Material

__all__ = ["ScaleFactors", "WheelTest", "dimensionless_groups", "scale_body", "scale_test"]

_NOT_LENGTHS = {"grouser_count", "flap_count", "flap_angle", "sweep", "flat_side", "center"}


@dataclass(frozen=True)
class ScaleFactors:
    """Ratios new / old of length, gravity and medium density [-]."""

    length: float = 1.0
    gravity: float = 1.0
    density: float = 1.0

    def __post_init__(self) -> None:
        for name in ("length", "gravity", "density"):
            check_positive(f"scale.{name}", getattr(self, name))

    @property
    def mass(self) -> float:
        return self.density * self.length**3

    @property
    def inertia(self) -> float:
        return self.mass * self.length**2

    @property
    def time(self) -> float:
        return math.sqrt(self.length / self.gravity)

    @property
    def omega(self) -> float:
        return 1.0 / self.time

    @property
    def velocity(self) -> float:
        return math.sqrt(self.gravity * self.length)

    @property
    def force(self) -> float:
        return self.density * self.gravity * self.length**3

    @property
    def torque(self) -> float:
        return self.force * self.length

    @property
    def power(self) -> float:
        return self.density * self.gravity**1.5 * self.length**3.5


@dataclass(frozen=True)
class WheelTest:
    """A wheel design and its driving conditions (SI)."""

    body: Body
    material: Material
    mass: float
    omega: float
    gravity: float = 9.81
    inertia: float | None = None
    drawbar_load: float = 0.0

    @property
    def load(self) -> float:
        """Weight on the axle [N]."""
        return self.mass * self.gravity


def scale_body(body: Body, factor: float) -> Body:
    """A geometrically similar body, every length (including the width) times ``factor``."""
    check_positive("factor", factor)
    if not dataclasses.is_dataclass(body):
        raise InputError("body", type(body).__name__, "a terradyn body dataclass")
    changes: dict[str, Any] = {}
    for f in dataclasses.fields(body):
        value = getattr(body, f.name)
        if f.name in _NOT_LENGTHS or isinstance(value, bool | str) or value is None:
            continue
        if isinstance(value, Body):
            changes[f.name] = scale_body(value, factor)
        elif isinstance(value, tuple) and value and all(isinstance(v, Body) for v in value):
            changes[f.name] = tuple(scale_body(v, factor) for v in value)
        elif isinstance(value, float | int) and not isinstance(value, bool):
            if isinstance(value, int) and not isinstance(value, float):
                continue
            changes[f.name] = value * factor
        elif isinstance(value, np.ndarray):
            changes[f.name] = value * factor
    return dataclasses.replace(body, **changes)  # type: ignore[type-var,unused-ignore]


def scale_test(test: WheelTest, factors: ScaleFactors) -> WheelTest:
    """Map a wheel test to another size, gravity or medium density with the same dimensionless state.

    The medium's RFT scale is multiplied by density x gravity ratios (zeta ~ rho_c g). Cohesive media
    (Bekker cohesion > 0) are refused: cohesion does not follow the scaling.
    """
    mat = test.material
    if mat.bekker is not None and mat.bekker.cohesion > 0 and (factors.gravity != 1 or factors.density != 1):
        raise InputError(
            "material",
            mat.name,
            "a cohesionless medium for a gravity or density change",
            "cohesion does not scale with rho g",
        )
    new_mat = mat
    if mat.rft is not None:
        new_mat = mat.with_zeta(mat.zeta * factors.density * factors.gravity)
    for key in ("grain_density", "bulk_density", "critical_density"):
        value = getattr(new_mat, key)
        if value is not None and factors.density != 1:
            new_mat = new_mat.with_changes(**{key: value * factors.density})
    return WheelTest(
        body=scale_body(test.body, factors.length),
        material=new_mat,
        mass=test.mass * factors.mass,
        omega=test.omega * factors.omega,
        gravity=test.gravity * factors.gravity,
        inertia=None if test.inertia is None else test.inertia * factors.inertia,
        drawbar_load=test.drawbar_load * factors.force,
    )


def dimensionless_groups(
    *,
    length: float,
    mass: float,
    gravity: float,
    critical_density: float,
    width: float | None = None,
    omega: float | None = None,
    velocity: float | None = None,
    inertia: float | None = None,
    power: float | None = None,
) -> dict[str, float]:
    """The dimensionless groups of a granular-locomotion test.

    ``mass_ratio`` = M / (rho_c L^3), or M / (rho_c L^2 W) for a plane body of width W (about 6 for
    the wheels of Agarwal et al. 2021); ``omega_hat`` = omega sqrt(L / g); ``velocity_hat`` =
    V / sqrt(g L); ``inertia_hat`` = I / (M L^2); ``power_hat`` = P / (M g^(3/2) L^(1/2)).
    """
    for name, v in (
        ("length", length),
        ("mass", mass),
        ("gravity", gravity),
        ("critical_density", critical_density),
    ):
        check_positive(name, v)
    depth = width if width is not None else length
    if width is not None:
        check_positive("width", width)
    out = {"mass_ratio": mass / (critical_density * length**2 * depth)}
    if omega is not None:
        out["omega_hat"] = omega * math.sqrt(length / gravity)
    if velocity is not None:
        out["velocity_hat"] = velocity / math.sqrt(gravity * length)
    if inertia is not None:
        out["inertia_hat"] = inertia / (mass * length**2)
    if power is not None:
        out["power_hat"] = power / (mass * gravity**1.5 * math.sqrt(length))
    return out
