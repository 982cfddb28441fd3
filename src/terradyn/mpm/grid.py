"""The MPM's background grid and the initial particles of a bed (sizes, packing, density): what a run is
built on before :mod:`terradyn.mpm.solver` steps it."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError, check_finite, check_positive, check_range
from .model import BedPacking, GranularModel, Walls

__all__ = ["GRID_PAD", "BedGrid", "ParticleState", "check_surface_offset", "initial_density", "make_bed"]

#: Grid nodes outside each wall (the quadratic B-spline stencil reaches 1.5 cells).
GRID_PAD = 2


@dataclass(frozen=True, slots=True)
class BedGrid:
    """A box of grains: bed ``width`` x ``depth`` [m] with its free surface at z = 0, and the grid over it.

    The left wall is at ``x_left`` [m]; ``air`` [m] of empty grid lies above the surface. Nodes are
    ``cell_size`` [m] apart with :data:`GRID_PAD` nodes outside each wall.

    The box is snapped outwards to the grid: the walls move to the nearest multiples of ``cell_size``
    that enclose the requested box and the depth is rounded up to whole cells, so that the nodes lie on
    x = k h and the free surface on the node line z = 0 whatever the bed size. (Without it a depth that
    is not a whole number of cells put the surface up to half a cell above z = 0, and a bed width change
    shifted the grid under the body by half a cell: each changed a 60 mm plate's force at 10 mm cells
    by 12 %, which had read as a wall effect.)

    ``surface_offset`` (a fraction of a cell in [0, 1), default 0) adds that fraction of a cell to the
    depth: the surface stays at z = 0 and the floor on a node line, and the node lines sit
    ``surface_offset`` cells below the surface and a whole number of cells below that. It moves the grid
    against the grains and the body by a known phase; a result that changes with it carries a
    discretisation error of that size (the grid-phase spread of
    :func:`terradyn.studies.mpm_verification.strip_footing`).
    """

    width: float
    depth: float
    air: float
    cell_size: float
    x_left: float = 0.0
    walls: Walls = field(default_factory=Walls)
    surface_offset: float = field(default=0.0, metadata={"omit_default": True})

    def __post_init__(self) -> None:
        check_positive("cell_size", self.cell_size)
        check_positive("bed_width", self.width)
        check_positive("bed_depth", self.depth)
        check_positive("air_height", self.air, allow_zero=True)
        off = check_surface_offset(self.surface_offset)
        h = self.cell_size
        left = math.floor(self.x_left / h + 1e-9)
        right = math.ceil((self.x_left + self.width) / h - 1e-9)
        object.__setattr__(self, "x_left", left * h)
        object.__setattr__(self, "width", (right - left) * h)
        # idempotent: a depth that already carries the offset keeps its whole cells
        deep = max(1, math.ceil(self.depth / h - off - 1e-9))
        object.__setattr__(self, "depth", (deep + off) * h)
        for name, value in (("bed_width", self.width), ("bed_depth", self.depth)):
            if value < 4 * self.cell_size:
                raise InputError(
                    name, value, f"at least 4 cells ({4 * self.cell_size:g} m)", "refine cell_size"
                )
        cells = (self.width / self.cell_size) * ((self.depth + self.air) / self.cell_size)
        if cells > 2.0e7:
            raise InputError("cell_size", self.cell_size, "a grid below 2e7 cells", "coarsen cell_size")

    @property
    def shape(self) -> tuple[int, int]:
        nx = round(self.width / self.cell_size) + 2 * GRID_PAD + 1
        nz = round((self.depth + self.air) / self.cell_size) + 2 * GRID_PAD + 3
        return nx, nz

    @property
    def origin(self) -> tuple[float, float]:
        """World (x, z) [m] of node (0, 0)."""
        return self.x_left - GRID_PAD * self.cell_size, -self.depth - GRID_PAD * self.cell_size

    @property
    def x_right(self) -> float:
        return self.x_left + (self.shape[0] - 1 - 2 * GRID_PAD) * self.cell_size

    def holds(self, x: float, z: float, reach: float) -> bool:
        """True if a body of ``reach`` [m] with its origin at (x, z) lies inside the particle bounds."""
        lo_x, hi_x, lo_z, hi_z = self.bounds
        return bool(lo_x + reach <= x <= hi_x - reach and lo_z + reach <= z <= hi_z - reach)

    def describe_bounds(self) -> str:
        lo_x, hi_x, lo_z, hi_z = self.bounds
        return f"[{lo_x:.4g}, {hi_x:.4g}] x [{lo_z:.4g}, {hi_z:.4g}] m"

    @property
    def bounds(self) -> np.ndarray:
        """(x_min, x_max, z_min, z_max) [m] that particles are kept within."""
        nz = self.shape[1]
        z_top = self.origin[1] + (nz - 1 - GRID_PAD) * self.cell_size
        return np.array([self.x_left, self.x_right, -self.depth, z_top])


def check_surface_offset(value: float) -> float:
    """``value`` as a grid surface offset: a fraction of a cell in [0, 1)."""
    value = check_finite("surface_offset", value)
    if not 0.0 <= value < 1.0:
        raise InputError("surface_offset", value, "a fraction of a cell in [0, 1)")
    return float(value)


@dataclass
class ParticleState:
    """Material points per unit out-of-plane width (see :mod:`terradyn.mpm._kernels` for shapes/units)."""

    pos: np.ndarray
    vel: np.ndarray
    aff: np.ndarray
    stress: np.ndarray
    mass: np.ndarray
    vol: np.ndarray
    gdot: np.ndarray

    NAMES = ("pos", "vel", "aff", "stress", "mass", "vol", "gdot")

    def __len__(self) -> int:
        return self.pos.shape[0]

    def arrays(self) -> dict[str, np.ndarray]:
        return {f"p_{k}": getattr(self, k) for k in self.NAMES}

    @classmethod
    def from_arrays(cls, data: dict[str, np.ndarray]) -> ParticleState:
        return cls(**{k: np.ascontiguousarray(data[f"p_{k}"]) for k in cls.NAMES})

    def fields(self) -> dict[str, np.ndarray]:
        """Per-particle output fields (unit names as in :func:`~terradyn.mpm.checkpoint.write_snapshot`)."""
        s = self.stress
        return {
            "x": self.pos[:, 0],
            "z": self.pos[:, 1],
            "vx": self.vel[:, 0],
            "vz": self.vel[:, 1],
            "stress_xx": s[:, 0],
            "stress_zz": s[:, 1],
            "stress_xz": s[:, 2],
            "stress_yy": s[:, 3],
            "pressure": -(s[:, 0] + s[:, 1] + s[:, 3]) / 3.0,
            "density": self.mass / self.vol,
            "plastic_shear_rate": self.gdot,
        }


def initial_density(bulk: float, critical: float, packing: BedPacking | str) -> float:
    """Default density [kg/m^3] of a fresh bed of ``packing`` (as :func:`make_bed` makes it): consolidated
    ``max(bulk, 1.02 critical)``, unconsolidated ``0.98 critical``."""
    if BedPacking(packing) is BedPacking.CONSOLIDATED:
        return max(float(bulk), 1.02 * float(critical))
    return 0.98 * float(critical)


def make_bed(
    model: GranularModel,
    grid: BedGrid,
    *,
    packing: BedPacking = BedPacking.CONSOLIDATED,
    density: float | None = None,
    particles_per_cell: int = 2,
    gravity: float = 9.81,
) -> ParticleState:
    """Fill the bed with ``particles_per_cell`` x ``particles_per_cell`` points per cell.

    Consolidated: density ``density`` (default ``max(bulk, 1.02 critical)``) and a geostatic stress
    ``sigma_zz = -rho g (0 - z)``, ``sigma_xx = sigma_yy = K_0 sigma_zz`` with ``K_0 = nu/(1 - nu)`` (the
    elastic equilibrium of a laterally confined layer). Unconsolidated: density (default
    ``0.98 critical``) at or below critical and no stress, so that it compacts to critical while it
    settles; with dilatancy on, a bed at or above ``model.disconnection_density`` is connected and
    gets the geostatic stress too, so it stays as loose as prepared (it compacts where it is sheared).
    """
    packing = BedPacking(packing)
    ppc = int(particles_per_cell)
    if ppc < 1 or ppc > 4:
        raise InputError("particles_per_cell", particles_per_cell, "1, 2, 3 or 4 per direction")
    rc = model.critical_density
    if packing is BedPacking.CONSOLIDATED:
        rho = initial_density(model.bulk_density, rc, packing) if density is None else density
        check_range(
            "bed_density",
            rho,
            rc * (1.0 + 1e-9),
            model.grain_density,
            unit="kg/m^3",
            hint="a consolidated bed is denser than the critical density",
        )
    else:
        rho = initial_density(model.bulk_density, rc, packing) if density is None else density
        check_range(
            "bed_density",
            rho,
            0.5 * rc,
            rc,
            unit="kg/m^3",
            hint="an unconsolidated bed is at or below the critical density",
        )
    h = grid.cell_size
    ncx = round(grid.width / h)
    # rows of points h / ppc apart from the floor up to the surface (whole cells plus the offset)
    rows = round(grid.depth * ppc / h)
    if abs(rows - grid.depth * ppc / h) > 1e-6:
        raise InputError(
            "surface_offset",
            grid.surface_offset,
            f"a multiple of 1 / particles_per_cell (1/{ppc})",
            "the points fill the bed in rows h / particles_per_cell apart",
        )
    off = (np.arange(ppc) + 0.5) / ppc
    cx = (np.arange(ncx)[:, None] + off[None, :]).ravel() * h + grid.x_left
    cz = ((np.arange(rows // ppc + 1)[:, None] + off[None, :]).ravel() * h - grid.depth)[:rows]
    zz, xx = np.meshgrid(cz, cx, indexing="ij")  # rows of constant z
    pos = np.ascontiguousarray(np.stack([xx.ravel(), zz.ravel()], axis=1))
    n = len(pos)
    vol = np.full(n, (h / ppc) ** 2)
    stress = np.zeros((n, 4))
    connected = model.dilatancy > 0.0 and rho >= model.disconnection_density
    if packing is BedPacking.CONSOLIDATED or connected:
        szz = rho * gravity * pos[:, 1]
        k0 = model.earth_pressure_at_rest
        stress[:, 0] = k0 * szz
        stress[:, 1] = szz
        stress[:, 3] = k0 * szz
    return ParticleState(
        pos=pos,
        vel=np.zeros((n, 2)),
        aff=np.zeros((n, 2, 2)),
        stress=stress,
        mass=vol * rho,
        vol=vol,
        gdot=np.zeros(n),
    )
