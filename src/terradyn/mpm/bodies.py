"""Rigid intruders in MPM: outline segments, contact scheme, motion modes and the body state.

Contact (:class:`ContactScheme`). The default, ``"two-field"``, is a multi-velocity-field scheme
specialised to a rigid body (after Bardenhagen et al. 2000 and Huang et al. 2011, with the body
normal from its geometry instead of a mass gradient): on the grid nodes within two cells of the
body's surface the grains form two velocity fields, the particles on the node's side of the surface
and those across it (the far side of a body thinner than the B-spline stencil). Each field whose
particles' surface the node lies behind has its approach to the body removed, with Coulomb friction
on the tangential part; a particle whose step would cross the surface is put back on its side
(:func:`terradyn.mpm._kernels.body_contact_sides`, :func:`~terradyn.mpm._kernels.body_project_sides`).
A body therefore needs no thickness: a zero-thickness :class:`Plate` is a segment with two faces,
and composite and placed bodies take the same path as bare ones. The impulse taken from the grains
is the force on the body (two-way coupling).

``"two-field-gap"`` is the same scheme with another contact test: a field is in contact once its
grains (each reaching half its side beyond its centre) reach the body, rather than when the node
lies behind the body's surface. Under the node test a node inside the body holds the grains in its
stencil at the body's velocity while they are still up to a cell away, so a body compresses the top
grains before touching them and tears them off the grains below (docs/mpm.md "Contact at a distance").

``"cover"`` is the earlier scheme, kept for comparison: nodes inside the outline take the body
velocity, particles inside are pushed out, and a bare :class:`Plate` is thickened to
:data:`PLATE_MIN_CELLS` cells (thinner bands leak grains; other zero-thickness bodies get no force).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from enum import Enum

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..geometry import Body, Plate

__all__ = [
    "PLATE_MIN_CELLS",
    "BodyState",
    "ContactScheme",
    "DofMode",
    "body_segments",
    "body_segments_world",
    "check_footprint",
    "effective_body",
    "lowest_point",
]

#: Minimum plate thickness in MPM, in cells, under the legacy ``"cover"`` contact.
PLATE_MIN_CELLS = 3.0


class ContactScheme(str, Enum):
    """How a rigid body and the grains interact on the grid (see the module docstring)."""

    TWO_FIELD = "two-field"
    TWO_FIELD_GAP = "two-field-gap"
    COVER = "cover"

    @property
    def code(self) -> int:
        """The kernel code (:data:`terradyn.mpm._kernels.CONTACT_SIDES`, ``CONTACT_SIDES_GAP`` or
        ``CONTACT_COVER``)."""
        return {ContactScheme.COVER: 0, ContactScheme.TWO_FIELD: 1, ContactScheme.TWO_FIELD_GAP: 2}[self]

    @classmethod
    def coerce(cls, value: ContactScheme | str) -> ContactScheme:
        try:
            return cls(value)
        except ValueError:
            raise InputError("contact", value, "'two-field', 'two-field-gap' or 'cover'") from None


class DofMode(str, Enum):
    """How a translational degree of freedom of the body moves."""

    PRESCRIBED = "prescribed"
    FREE = "free"


def effective_body(
    body: Body, cell_size: float, contact: ContactScheme | str = ContactScheme.TWO_FIELD
) -> Body:
    """The body as MPM resolves it at ``cell_size`` [m].

    Under the two-field contact that is ``body`` itself, once :func:`check_footprint` has accepted it.
    Under ``"cover"`` a bare :class:`Plate` thinner than :data:`PLATE_MIN_CELLS` cells is thickened.
    """
    if not isinstance(body, Body):
        raise InputError("body", body, "a terradyn.geometry Body (Plate, WheelCircular, ...)")
    scheme = ContactScheme.coerce(contact)
    check_footprint(body, cell_size)
    if scheme is ContactScheme.COVER and isinstance(body, Plate):
        t = max(body.thickness, PLATE_MIN_CELLS * cell_size)
        if t >= body.length:
            raise InputError(
                "cell_size",
                cell_size,
                f"below {body.length / PLATE_MIN_CELLS:g} m for a plate of length {body.length:g} m",
                "the MPM plate is at least two cells thick",
            )
        if t != body.thickness:
            return replace(body, thickness=t)
    return body


def check_footprint(body: Body, cell_size: float) -> None:
    """Refuse a body the grid cannot resolve: every boundary loop (each part of a composite) must
    span at least one cell. Raises :class:`~terradyn.errors.InputError` naming the body, the part and
    the cell size."""
    loops = body.outline(min(0.5 * cell_size, body.size))
    for k, poly in enumerate(loops):
        p = np.asarray(poly, dtype=float)
        span = float(np.hypot(*np.ptp(p, axis=0))) if len(p) else 0.0  # bounding-box diagonal
        if not span >= cell_size:
            part = f"boundary loop {k} of {body!r}" if len(loops) > 1 else repr(body)
            raise InputError(
                "cell_size",
                cell_size,
                f"at most {span:.4g} m, the extent of {part}",
                "the body's footprint on the grid is degenerate (it spans less than one cell); refine "
                "cell_size or enlarge the body",
            )


def body_segments(body: Body, cell_size: float) -> NDArray[np.float64]:
    """Outline segments (S, 4) = (x1, z1, x2, z2) [m] in the body frame, about half a cell long."""
    loops = body.outline(min(0.5 * cell_size, body.size))
    segs = []
    for poly in loops:
        p = np.asarray(poly, dtype=float)
        if len(p) > 1 and np.allclose(p[0], p[-1]):
            p = p[:-1]
        q = np.roll(p, -1, axis=0)
        segs.append(np.hstack([p, q]))
    seg = np.vstack(segs)
    keep = np.hypot(seg[:, 2] - seg[:, 0], seg[:, 3] - seg[:, 1]) > 0
    return np.ascontiguousarray(seg[keep])


def body_segments_world(seg: NDArray[np.float64], pose: NDArray[np.float64]) -> NDArray[np.float64]:
    """Outline segments (S, 2, 2) [m] in the world at ``pose`` (x, z, theta): ``x + R(theta) p``."""
    c, s = math.cos(pose[2]), math.sin(pose[2])
    out = np.empty((len(seg), 2, 2))
    for k in (0, 1):
        px, pz = seg[:, 2 * k], seg[:, 2 * k + 1]
        out[:, k, 0] = pose[0] + c * px + s * pz
        out[:, k, 1] = pose[1] - s * px + c * pz
    return out


def lowest_point(seg: NDArray[np.float64], pose: NDArray[np.float64]) -> float:
    """World z [m] of the lowest outline vertex of a body at ``pose`` (x, z, theta)."""
    c, s = math.cos(pose[2]), math.sin(pose[2])
    z = pose[1] - s * seg[:, 0] + c * seg[:, 1]
    return float(z.min())


@dataclass
class BodyState:
    """Mutable state of a rigid body per unit out-of-plane width (kernels update the arrays in place).

    Attributes
    ----------
    seg : (S, 4) outline segments in the body frame [m]
    pose : (3,) x [m], z [m], theta [rad]
    twist : (3,) vx [m/s], vz [m/s], omega [rad/s]
    free : (3,) bool, x/z translation and spin free (else prescribed by ``twist``); a (2,) array is
        padded with a prescribed spin
    mass : float  [kg/m]
    load : (3,) external force incl. gravity [N/m] and torque about +y (a drive torque) [N m/m] on the
        body; a (2,) array is padded with zero torque
    friction : float  body-grain Coulomb coefficient [-]
    width : float  out-of-plane width [m] (results are per-width values times this)
    inertia : float  moment of inertia about the origin [kg m^2/m] (used when the spin is free)
    contact : :class:`ContactScheme`  grid contact scheme
    """

    seg: NDArray[np.float64]
    pose: NDArray[np.float64]
    twist: NDArray[np.float64]
    free: NDArray[np.bool_]
    mass: float
    load: NDArray[np.float64]
    friction: float
    width: float
    inertia: float = 1.0
    contact: ContactScheme = field(default=ContactScheme.TWO_FIELD)

    def __post_init__(self) -> None:
        self.contact = ContactScheme.coerce(self.contact)
        free = np.zeros(3, dtype=np.bool_)
        free[: len(self.free)] = np.asarray(self.free, dtype=np.bool_)[:3]
        load = np.zeros(3)
        load[: len(self.load)] = np.asarray(self.load, dtype=float)[:3]
        self.free, self.load = free, load
        for name in ("mass", "inertia"):
            if not (math.isfinite(getattr(self, name)) and getattr(self, name) > 0):
                raise InputError(name, getattr(self, name), "a positive finite value")

    @property
    def reach(self) -> float:
        """Largest distance [m] of the outline from the body origin."""
        return float(np.max(np.hypot(self.seg[:, :2][:, 0], self.seg[:, :2][:, 1])))

    @classmethod
    def empty(cls) -> BodyState:
        """A placeholder for runs without a body (bed preparation)."""
        return cls(
            seg=np.zeros((1, 4)),
            pose=np.zeros(3),
            twist=np.zeros(3),
            free=np.zeros(2, dtype=np.bool_),
            mass=1.0,
            load=np.zeros(2),
            friction=0.0,
            width=1.0,
        )

    def copy(self) -> BodyState:
        return BodyState(
            self.seg.copy(),
            self.pose.copy(),
            self.twist.copy(),
            self.free.copy(),
            self.mass,
            self.load.copy(),
            self.friction,
            self.width,
            self.inertia,
            self.contact,
        )
