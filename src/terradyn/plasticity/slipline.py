"""Prandtl-Reissner slip-line field of a strip footing (weightless Mohr-Coulomb soil), for overlays.

Under a footing of width ``B = 2 b`` the collapse mechanism of Prandtl (1921) has three zones on each
side (angles with ``mu = pi/4 - phi/2``):

* an active wedge under the footing whose sides leave the edges at ``pi/4 + phi/2`` below the
  horizontal and meet on the centre line at depth ``b tan(pi/4 + phi/2)``; a Rankine active zone
  (straight slip lines of both families) for a smooth base, a rigid wedge (no interior lines) for a
  rough one;
* a radial shear fan centred on the footing edge: straight radial lines and log spirals
  ``r(omega) = r_0 exp(omega' tan phi)``, ``omega'`` the angle turned from the active side, from
  ``r_0 = b / cos(pi/4 + phi/2)`` to ``r_1 = r_0 exp((pi/2) tan phi)``;
* a passive Rankine wedge with sides at ``pi/4 - phi/2`` to the horizontal reaching the surface at
  ``L = 2 r_1 cos(pi/4 - phi/2)`` beyond the edge (the heave extent).

:func:`prandtl_field` returns the lines as :class:`SlipLine` polylines in terradyn's frame (``x``
forward, ``z`` up, surface at ``surface_z``), mirrored about the footing centre, ready for
:func:`terradyn.plotting.slipline.plot_slip_lines`. The alpha family is the fan's radial lines and
their continuations, the beta family the log spirals and theirs (right half; the mirror swaps them).

References
----------
L. Prandtl, Z. angew. Math. Mech. 1(1), 15-20 (1921). doi:10.1002/zamm.19210010102
H. Reissner, Proc. 1st Int. Congress of Applied Mechanics, Delft, 295-311 (1924).
V. V. Sokolovskii, Statics of Granular Media (Pergamon, Oxford, 1965).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError, check_finite, check_length

__all__ = ["SlipLine", "prandtl_extent", "prandtl_field"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class SlipLine:
    """One slip line as a polyline: ``x``, ``z`` [m] (terradyn frame), its family and zone."""

    x: FloatArray
    z: FloatArray
    family: str  #: "alpha" or "beta"
    zone: str  #: "active", "fan", "passive", "boundary" or "moc"

    def __post_init__(self) -> None:
        x = np.asarray(self.x, dtype=np.float64)
        z = np.asarray(self.z, dtype=np.float64)
        if x.shape != z.shape or x.ndim != 1 or len(x) < 2:
            raise InputError("slip line", (x.shape, z.shape), "x and z as 1-D arrays of the same length >= 2")
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "z", z)


def _phi(friction_angle: float) -> float:
    phi = check_finite("friction_angle", friction_angle)
    if not (0.0 < phi <= math.radians(50.0)):
        raise InputError(
            "friction_angle", friction_angle, "an angle in (0, 50] deg, in radians", "use math.radians"
        )
    return phi


def prandtl_extent(width: float, friction_angle: float) -> dict[str, float]:
    """Closed-form size of the Prandtl mechanism of a footing of width ``B`` [m] at ``phi`` [rad].

    Returns (all [m]): ``r0`` (active wedge side), ``r1 = r0 exp((pi/2) tan phi)`` (passive wedge side),
    ``wedge_depth = (B/2) tan(pi/4 + phi/2)``, ``heave_extent = 2 r1 cos(pi/4 - phi/2)`` beyond each
    edge, ``half_extent = B/2 + heave_extent`` from the centre, ``max_depth`` (deepest point of the log
    spiral).
    """
    b = 0.5 * check_length("width", width)
    phi = _phi(friction_angle)
    mu = math.pi / 4 - phi / 2
    r0 = b / math.sin(mu)
    r1 = r0 * math.exp(0.5 * math.pi * math.tan(phi))
    omega = np.linspace(mu, math.pi / 2 + mu, 2001)
    r = r0 * np.exp((math.pi / 2 + mu - omega) * math.tan(phi))
    heave = 2.0 * r1 * math.cos(mu)
    return {
        "r0": r0,
        "r1": r1,
        "wedge_depth": b * math.tan(math.pi / 4 + phi / 2),
        "heave_extent": heave,
        "half_extent": b + heave,
        "max_depth": float(np.max(r * np.sin(omega))),
    }


def prandtl_field(
    width: float,
    friction_angle: float,
    *,
    base: str = "rough",
    center_x: float = 0.0,
    surface_z: float = 0.0,
    line_count: int = 6,
    points: int = 41,
) -> list[SlipLine]:
    """Slip lines of the Prandtl-Reissner mechanism under a strip footing, both sides.

    Parameters
    ----------
    width : footing width ``B`` [m]
    friction_angle : ``phi`` [rad], in (0, 50] deg
    base : ``"rough"`` (rigid active wedge, no interior lines) or ``"smooth"`` (Rankine active zone)
    center_x : footing centre [m]
    surface_z : level of the free surface and footing base [m]
    line_count : lines per family and zone (>= 1)
    points : points per curved line (>= 3)

    Returns
    -------
    list of :class:`SlipLine`, ``x``/``z`` in [m]; the mechanism boundary lines have zone
    ``"boundary"``.
    """
    b = 0.5 * check_length("width", width)
    phi = _phi(friction_angle)
    if base not in ("rough", "smooth"):
        raise InputError("base", base, "'rough' or 'smooth'")
    cx = check_finite("center_x", center_x)
    sz = check_finite("surface_z", surface_z)
    if not isinstance(line_count, int) or line_count < 1:
        raise InputError("line_count", line_count, "an integer >= 1")
    if not isinstance(points, int) or points < 3:
        raise InputError("points", points, "an integer >= 3")
    mu = math.pi / 4 - phi / 2
    tphi = math.tan(phi)
    r0 = b / math.sin(mu)
    grow = math.exp(0.5 * math.pi * tphi)
    omega_a = math.pi / 2 + mu  # direction of the active wedge side (solver frame, y down)

    def ray(omega: float, r: float) -> tuple[float, float]:
        return b + r * math.cos(omega), r * math.sin(omega)

    half: list[tuple[FloatArray, FloatArray, str, str]] = []  # (x from centre, depth, family, zone)

    def seg(p: tuple[float, float], q: tuple[float, float], family: str, zone: str) -> None:
        half.append((np.array([p[0], q[0]]), np.array([p[1], q[1]]), family, zone))

    def spiral(scale: float) -> tuple[FloatArray, FloatArray]:
        om = np.linspace(omega_a, mu, points)
        r = scale * r0 * np.exp((omega_a - om) * tphi)
        return b + r * np.cos(om), r * np.sin(om)

    edge = (b, 0.0)
    apex = ray(omega_a, r0)
    deep = ray(mu, r0 * grow)
    far = (b + 2.0 * r0 * grow * math.cos(mu), 0.0)
    # mechanism boundary: active side, outer spiral, passive side
    seg(edge, apex, "alpha", "boundary")
    sx, sy = spiral(1.0)
    half.append((sx, sy, "beta", "boundary"))
    seg(deep, far, "beta", "boundary")
    seg(edge, deep, "alpha", "boundary")
    fractions = [k / (line_count + 1) for k in range(1, line_count + 1)]
    for t in fractions:
        # fan: radial lines and inner spirals
        om = omega_a + t * (mu - omega_a)
        seg(edge, ray(om, r0 * math.exp((omega_a - om) * tphi)), "alpha", "fan")
        sx, sy = spiral(t)
        half.append((sx, sy, "beta", "fan"))
        # passive wedge: beta lines continue the inner spirals up to the surface (direction -mu) ...
        start = ray(mu, t * r0 * grow)
        seg(start, (start[0] + start[1] / math.tan(mu), 0.0), "beta", "passive")
        # ... alpha lines run from the surface parallel to the wedge side down to the outer side
        xs = b + t * (far[0] - b)
        length = (far[0] - xs) * math.sin(mu) / math.sin(2.0 * mu)
        seg((xs, 0.0), (xs + length * math.cos(mu), length * math.sin(mu)), "alpha", "passive")
        if base == "smooth":
            # Rankine active zone: straight beta lines from the inner spiral ends on the active side up
            # to the base (those from deep points cross the centre line); their mirror images are the
            # alpha lines, so both families cover the active triangle
            p = ray(omega_a, t * r0)
            seg(p, (p[0] - p[1] * math.tan(mu), 0.0), "beta", "active")
    out: list[SlipLine] = []
    for x, y, family, zone in half:
        out.append(SlipLine(cx + x, sz - y, family, zone))
        mirrored = family if zone == "boundary" else ("beta" if family == "alpha" else "alpha")
        out.append(SlipLine(cx - x, sz - y, mirrored, zone))
    return out
