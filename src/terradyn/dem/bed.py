"""Granular beds in LAMMPS: polydisperse Hertz-Mindlin spheres poured, settled and checked at rest.

A bed is a box of grains under gravity on a frictional floor between two frictional end walls (x).
Out of plane it is either a *slab* (quasi-2D: periodic in y, a few grain diameters thick; bodies span
the whole thickness and results compare with plane models times that width) or *3d* (walls in y; a body
of finite width in the middle). Grains start on a jittered lattice in a tall region (no overlaps), fall
under gravity and settle; the packing is set by the grain friction during settling (``dense``: a
tenth of the grain friction and no rolling resistance, then the material's values; ``loose``: the
material's values throughout). Every LAMMPS command is issued through its Python module; nothing
is written by hand.

Contact law (LAMMPS ``pair_style granular``): Hertz normal force from the grains' Young's modulus and
Poisson ratio (``hertz/material``) with viscous damping set by the coefficient of restitution
(``damping coeff_restitution``), Mindlin tangential force capped by Coulomb friction, and ``sds``
rolling resistance capped by the rolling-friction coefficient.
"""

from __future__ import annotations

import json
import math
import os
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass
from enum import Enum
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError, SolverError, check_finite, check_positive, check_range
from ..materials import DEMParameters, Material
from ._lammps import is_root, new_lammps

__all__ = [
    "Bed",
    "BedKind",
    "BedSpec",
    "Packing",
    "load_bed",
    "prepare_bed",
    "save_bed",
]

GRAIN_TYPE = 1
BODY_TYPE = 2
#: largest bed accepted (grains): far above what one machine runs in reasonable time
MAX_GRAINS = 5_000_000
#: time step as a fraction of the Rayleigh time of the smallest grain
RAYLEIGH_FRACTION = 0.15
#: grain friction during the settling of a dense bed, as a fraction of the material's (low friction
#: lets grains slide into a dense packing; zero would take far longer to come to rest)
DENSE_SETTLE_FRICTION = 0.1
#: a bed is at rest when the mean kinetic energy per grain is below this fraction of m g d
REST_KINETIC = 1e-5
#: ... and its mean coordination number (grains with two or more contacts) at least this
REST_COORDINATION = 3.0


class Packing(str, Enum):
    """How the bed is prepared: dense (frictionless settling) or loose (frictional settling)."""

    DENSE = "dense"
    LOOSE = "loose"

    @classmethod
    def coerce(cls, value: Packing | str) -> Packing:
        try:
            return cls(value)
        except ValueError:
            raise InputError("packing", value, "'dense' or 'loose'") from None


class BedKind(str, Enum):
    """Quasi-2D slab (periodic out of plane) or a full 3D bed (walls out of plane)."""

    SLAB = "slab"
    THREE_D = "3d"

    @classmethod
    def coerce(cls, value: BedKind | str) -> BedKind:
        try:
            return cls(value)
        except ValueError:
            raise InputError("kind", value, "'slab' or '3d'") from None


@dataclass(frozen=True)
class BedSpec:
    """Size and preparation of a bed (SI).

    Attributes
    ----------
    length : float  bed extent along x [m]
    depth : float  settled bed height [m] (grains are counted for this height at the expected packing)
    thickness : float or None  out-of-plane extent [m]; default 4 grain diameters (slab) or 12 (3d)
    kind : BedKind  slab or 3d
    packing : Packing  dense or loose
    headroom : float or None  empty height above the bed [m] for bodies to start in (default = depth)
    grain_diameter : float or None  overrides the material's [dem] grain diameter (coarse graining)
    seed : int  random seed of the grain positions and sizes
    max_settle_time : float  simulated time [s] allowed for settling before the bed is refused
    gravity : float  gravitational acceleration [m/s^2] (the bed settles and is tested under it)
    """

    length: float
    depth: float
    thickness: float | None = None
    kind: BedKind = BedKind.SLAB
    packing: Packing = Packing.DENSE
    headroom: float | None = None
    grain_diameter: float | None = None
    seed: int = 12345
    max_settle_time: float | None = None
    gravity: float = 9.81

    def __post_init__(self) -> None:
        object.__setattr__(self, "kind", BedKind.coerce(self.kind))
        object.__setattr__(self, "packing", Packing.coerce(self.packing))
        check_positive("length", self.length)
        check_positive("depth", self.depth)
        for name in ("thickness", "headroom", "grain_diameter", "max_settle_time"):
            if getattr(self, name) is not None:
                check_positive(name, getattr(self, name))
        check_range("gravity", self.gravity, 0.01, 100.0, unit="m/s^2")
        if not isinstance(self.seed, int) or not 1 <= self.seed < 2**31:
            raise InputError("seed", self.seed, "an integer in [1, 2^31)")


def grain_parameters(material: Material, spec: BedSpec) -> DEMParameters:
    """The material's [dem] parameters, with the spec's grain diameter if it overrides it."""
    dem = material.require_dem()
    if spec.grain_diameter is not None:
        from dataclasses import replace

        dem = replace(dem, grain_diameter=spec.grain_diameter)
    return dem


def expected_packing(packing: Packing) -> float:
    """Packing fraction used to count the grains of a bed (random close / loose packing) [-]."""
    return 0.60 if packing is Packing.DENSE else 0.57


def time_step(dem: DEMParameters) -> float:
    """Explicit time step [s]: a fraction of the Rayleigh time of the smallest grain."""
    r_min = 0.5 * dem.grain_diameter * (1.0 - dem.diameter_spread)
    shear = dem.youngs_modulus / (2.0 * (1.0 + dem.poisson_ratio))
    rayleigh = math.pi * r_min * math.sqrt(dem.grain_density / shear) / (0.1631 * dem.poisson_ratio + 0.8766)
    return RAYLEIGH_FRACTION * rayleigh


def contact_coeffs(dem: DEMParameters, friction: float, rolling: float) -> str:
    """Arguments of ``pair_coeff`` / ``fix wall/gran granular`` for the Hertz-Mindlin law."""
    e, nu, mu, mu_r = dem.youngs_modulus, dem.poisson_ratio, friction, rolling
    # rolling spring and damping as in the LAMMPS granular examples, scaled with the normal stiffness
    d = dem.grain_diameter
    k_roll = 0.25 * e * d  # [N/m]
    g_roll = 0.5 * math.sqrt(k_roll * dem.grain_density * d**3)  # [N s/m]
    return (
        f"hertz/material {e:.12g} {dem.restitution:.12g} {nu:.12g} damping coeff_restitution "
        f"tangential mindlin NULL 1.0 {mu:.12g} rolling sds {k_roll:.12g} {g_roll:.12g} {mu_r:.12g}"
    )


@dataclass
class Bed:
    """A settled bed held in a live LAMMPS instance (coordinates: LAMMPS box, floor at z = 0).

    ``surface`` is the level [m] of the free surface in the box frame; terradyn's frame (surface at
    z = 0) is the box frame shifted down by it.
    """

    lmp: Any
    spec: BedSpec
    dem: DEMParameters
    dt: float
    box: tuple[float, float, float, float, float, float]
    grain_count: int
    surface: float
    packing_fraction: float
    coordination: float
    kinetic_per_grain: float
    settle_time: float

    @property
    def thickness(self) -> float:
        return self.box[3] - self.box[2]

    def summary(self) -> dict[str, Any]:
        return {
            "grain_count": self.grain_count,
            "grain_diameter_m": self.dem.grain_diameter,
            "bed_length_m": self.box[1] - self.box[0],
            "bed_depth_m": self.surface,
            "bed_thickness_m": self.thickness,
            "packing_fraction": self.packing_fraction,
            "coordination_number": self.coordination,
            "kinetic_energy_per_grain_mgd": self.kinetic_per_grain,
            "settle_time_s": self.settle_time,
            "time_step_s": self.dt,
        }

    def close(self) -> None:
        if self.lmp is not None:
            self.lmp.close()
            self.lmp = None

    # ------------------------------------------------------------------ measurements of the bed
    def grain_arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(positions (N, 3) [m], radii (N,) [m], types (N,)) of every atom, gathered on every rank."""
        return gather_arrays(self.lmp)

    def pressure_profile(self, bins: int = 8) -> tuple[np.ndarray, np.ndarray]:
        """(depth below the surface [m], vertical stress [Pa]) in horizontal layers of the bed's middle
        half (away from the end walls), from LAMMPS's per-atom stress (contact virial)."""
        return pressure_profile(self, bins)


def gather_arrays(lmp: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    n = int(lmp.get_natoms())
    x = np.ctypeslib.as_array(lmp.gather_atoms("x", 1, 3), shape=(3 * n,)).reshape(n, 3).copy()
    r = np.ctypeslib.as_array(lmp.gather_atoms("radius", 1, 1), shape=(n,)).copy()
    t = np.ctypeslib.as_array(lmp.gather_atoms("type", 0, 1), shape=(n,)).copy()
    return x, r, t


def _commands(lmp: Any, lines: str) -> None:
    for line in lines.strip().splitlines():
        line = line.strip()
        if line:
            lmp.command(line)


def setup_interactions(lmp: Any, bed_box: tuple[float, ...], dem: DEMParameters, kind: BedKind,
                       *, friction: float, rolling: float, pair: bool = True,
                       gravity: float = 9.81) -> None:  # fmt: skip
    """Pair style, walls, gravity and integration of the grains. After a ``read_restart`` call it with
    ``pair=False``: the restart file holds the pair style, its coefficients and contact histories."""
    x0, x1, y0, y1 = bed_box[:4]
    grains = contact_coeffs(dem, friction, rolling)
    walls = contact_coeffs(dem, dem.wall_friction, rolling)
    d = dem.grain_diameter
    if pair:
        _commands(
            lmp,
            f"""
            pair_style granular
            pair_coeff * * {grains}
            pair_coeff {GRAIN_TYPE} {BODY_TYPE} {walls}
            pair_coeff {BODY_TYPE} {BODY_TYPE} {walls}
            """,
        )
    _commands(
        lmp,
        f"""
        neighbor {0.25 * d:.12g} bin
        neigh_modify delay 0 every 1 check yes exclude type {BODY_TYPE} {BODY_TYPE}
        comm_modify vel yes
        fix td_floor grains wall/gran granular {walls} zplane 0.0 NULL
        fix td_ends grains wall/gran granular {walls} xplane {x0:.12g} {x1:.12g}
        fix td_gravity grains gravity {gravity:.12g} vector 0 0 -1
        fix td_nve grains nve/sphere
        compute td_ke grains ke
        compute td_contacts grains contact/atom
        compute td_zsum grains reduce sum c_td_contacts
        thermo_style custom step time c_td_ke
        """,
    )
    if kind is BedKind.THREE_D:
        lmp.command(f"fix td_sides grains wall/gran granular {walls} yplane {y0:.12g} {y1:.12g}")


def _set_friction(lmp: Any, dem: DEMParameters, friction: float, rolling: float) -> None:
    lmp.command(f"pair_coeff {GRAIN_TYPE} {GRAIN_TYPE} {contact_coeffs(dem, friction, rolling)}")


@dataclass(frozen=True)
class _Pour:
    """How a bed is poured: its ``thickness`` [m] across, the ``n_grains`` to pour, the mean
    ``grain_volume`` [m^3], the largest grain ``dmax`` [m], the ``insert_height`` [m] of the start
    lattice and the simulation ``box`` (x0, x1, y0, y1, z0, z1) [m]."""

    thickness: float
    n_grains: int
    grain_volume: float
    dmax: float
    insert_height: float
    box: tuple[float, float, float, float, float, float]


def _pour(dem: DEMParameters, spec: BedSpec) -> _Pour:
    """The grain count and box of ``spec``'s bed; one :class:`InputError` line for a bed too small
    across or with too few or too many grains."""
    d = dem.grain_diameter
    kind = spec.kind
    thickness = spec.thickness if spec.thickness is not None else (4.0 if kind is BedKind.SLAB else 12.0) * d
    for name, value, low in (("length", spec.length, 8.0), ("depth", spec.depth, 4.0),
                             ("thickness", thickness, 2.0)):  # fmt: skip
        if value < low * d * (1.0 + dem.diameter_spread):
            raise InputError(
                name, value, f"at least {low:g} grain diameters ({low * d * (1 + dem.diameter_spread):.4g} m)"
            )
    phi = expected_packing(spec.packing)
    s = dem.diameter_spread
    mean_d3 = d**3 * (1.0 + s * s)  # <d^3> of d (1 + s U(-1, 1))
    grain_volume = math.pi / 6.0 * mean_d3
    n_grains = round(phi * spec.length * thickness * spec.depth / grain_volume)
    if n_grains > MAX_GRAINS:
        raise InputError(
            "grain count", n_grains, f"at most {MAX_GRAINS} grains", "coarsen the grains or shrink the bed"
        )
    if n_grains < 20:
        raise InputError("grain count", n_grains, "at least 20 grains", "enlarge the bed")
    dmax = d * (1.0 + s)
    # grains start on a jittered lattice of spacing 1.05 d_max (solid fraction about 0.4)
    a = 1.05 * dmax
    per_layer = max(1, int((spec.length - dmax) / a)) * max(1, int(thickness / a))
    insert_height = (math.ceil(n_grains / per_layer) + 1) * a
    headroom = spec.headroom if spec.headroom is not None else spec.depth
    top = max(insert_height, spec.depth + headroom) + 2 * dmax
    box = (-0.5 * spec.length, 0.5 * spec.length, 0.0, thickness, 0.0, top)
    return _Pour(thickness, n_grains, grain_volume, dmax, insert_height, box)


def _create_grains(lmp: Any, spec: BedSpec, dem: DEMParameters, pour: _Pour, dt: float) -> int:
    """The box and the grains on their start lattice (random diameters, the medium's density), and
    the time step; returns the number of atoms made."""
    x0, x1, y0, y1, _z0, top = pour.box
    n_grains, d, s = pour.n_grains, dem.grain_diameter, dem.diameter_spread
    boundary = "f p f" if spec.kind is BedKind.SLAB else "f f f"
    margin_y = 0.0 if spec.kind is BedKind.SLAB else 0.5 * pour.dmax
    _commands(
        lmp,
        f"""
        units si
        atom_style sphere
        dimension 3
        boundary {boundary}
        newton off
        atom_modify map array
        region td_box block {x0:.12g} {x1:.12g} {y0:.12g} {y1:.12g} 0 {top:.12g} units box
        create_box 2 td_box
        """,
    )
    positions = _lattice(n_grains, pour.box, pour.dmax, margin_y, spec.seed)
    lmp.create_atoms(n_grains, None, [GRAIN_TYPE] * n_grains, positions.ravel().tolist())
    made = int(lmp.get_natoms())
    _commands(
        lmp,
        f"""
        group grains type {GRAIN_TYPE}
        group body type {BODY_TYPE}
        variable td_d atom {d:.12g}*(1.0+{s:.12g}*(2.0*random(0,1,{spec.seed + 1})-1.0))
        set type {GRAIN_TYPE} diameter v_td_d
        set type {GRAIN_TYPE} density {dem.grain_density:.12g}
        timestep {dt:.12g}
        """,
    )
    return made


def _settle_grains(
    lmp: Any,
    spec: BedSpec,
    dem: DEMParameters,
    pour: _Pour,
    dt: float,
    progress: Callable[[float, float], None] | None,
) -> tuple[float, float]:
    """Let the grains fall and settle (a dense bed first with less friction, then with the medium's);
    returns the settled time [s] and the grain weight times diameter m g d [J] the rest test uses."""
    d = dem.grain_diameter
    settle_friction = DENSE_SETTLE_FRICTION * dem.friction if spec.packing is Packing.DENSE else dem.friction
    settle_rolling = 0.0 if spec.packing is Packing.DENSE else dem.rolling_friction
    setup_interactions(lmp, pour.box, dem, spec.kind, friction=settle_friction, rolling=settle_rolling,
                       gravity=spec.gravity)  # fmt: skip
    g = spec.gravity
    t_fall = math.sqrt(2.0 * pour.insert_height / g)
    t_max = (
        spec.max_settle_time if spec.max_settle_time is not None else 10.0 * t_fall + 200 * math.sqrt(d / g)
    )
    mgd = dem.grain_density * pour.grain_volume * g * d
    t_settled = _settle(lmp, dt, t_fall, t_max, pour.n_grains, mgd, progress, 0.0, 0.7)
    if spec.packing is Packing.DENSE:
        _set_friction(lmp, dem, dem.friction, dem.rolling_friction)
        t_settled = _settle(lmp, dt, 0.0, t_max, pour.n_grains, mgd, progress, t_settled, 1.0,
                            start=t_settled)  # fmt: skip
    return t_settled, mgd


def prepare_bed(
    material: Material,
    spec: BedSpec,
    *,
    progress: Callable[[float, float], None] | None = None,
    log: str | None = None,
) -> Bed:
    """Pour and settle a bed of ``material``'s grains; check it is at rest.

    Raises :class:`~terradyn.errors.InputError` for a bed that cannot be built (too few grains across,
    too many grains) and :class:`~terradyn.errors.SolverError` when it does not come to rest within
    ``spec.max_settle_time``. ``progress(time_s, fraction)`` is called as settling goes.
    """
    dem = grain_parameters(material, spec)
    pour = _pour(dem, spec)
    dt = time_step(dem)
    lmp = new_lammps(log)
    try:
        made = _create_grains(lmp, spec, dem, pour, dt)
        t_settled, mgd = _settle_grains(lmp, spec, dem, pour, dt, progress)
        bed = Bed(lmp, spec, dem, dt, pour.box, made, 0.0, 0.0, 0.0, 0.0, t_settled)
        measure_bed(bed, mgd)
    except BaseException:
        lmp.close()
        raise
    if bed.coordination < REST_COORDINATION:
        bed.close()
        raise SolverError(
            f"DEM bed not at rest after {t_settled:.3g} s: mean coordination number "
            f"{bed.coordination:.3g} < {REST_COORDINATION:g} (grains not jammed); enlarge the bed or "
            "allow more settling time"
        )
    return bed


def _lattice(n: int, box: tuple[float, ...], dmax: float, margin_y: float, seed: int) -> np.ndarray:
    """(n, 3) start positions [m]: a simple-cubic lattice of spacing >= 1.05 d_max filled from the
    floor up, jittered by up to 2% of the spacing (no two grains overlap)."""
    x0, x1, y0, y1 = box[:4]
    nx = max(1, int((x1 - x0 - dmax) / (1.05 * dmax)))
    ny = max(1, int((y1 - y0 - 2 * margin_y) / (1.05 * dmax)))
    ax = (x1 - x0 - dmax) / nx
    ay = (y1 - y0 - 2 * margin_y) / ny
    az = 1.05 * dmax
    k = np.arange(n)
    i, j, layer = k % nx, (k // nx) % ny, k // (nx * ny)
    rng = np.random.default_rng(seed)
    jitter = rng.uniform(-0.02, 0.02, size=(n, 3)) * np.array([ax, ay, az])
    pos = np.column_stack(
        (x0 + 0.5 * dmax + (i + 0.5) * ax, y0 + margin_y + (j + 0.5) * ay, dmax + layer * az)
    )
    return pos + jitter


def _settle(lmp: Any, dt: float, t_min: float, t_max: float, n: int, mgd: float,
            progress: Callable[[float, float], None] | None, t_done: float, frac_end: float,
            *, start: float = 0.0) -> float:  # fmt: skip
    """Run until the kinetic energy per grain is below REST_KINETIC m g d (after at least t_min);
    returns the simulated time reached [s]."""
    chunk = 200
    t = start
    first = True
    wall0 = time.perf_counter()
    while True:
        lmp.command(f"run {chunk}" + ("" if first else " pre no post no"))
        first = False
        t += chunk * dt
        ke = float(lmp.extract_compute("td_ke", 0, 0))
        if progress is not None:
            progress(t, min(frac_end, frac_end * (t - start) / max(t_max - start, 1e-30)))
        if t - start >= t_min and ke / n < REST_KINETIC * mgd:
            return t
        if t - start > t_max:
            raise SolverError(
                f"DEM bed did not settle within {t_max:.3g} s of simulated time: kinetic energy per "
                f"grain {ke / n / mgd:.3g} m g d > {REST_KINETIC:g} m g d (after "
                f"{time.perf_counter() - wall0:.0f} s wall time); allow more settling time"
            )


def measure_bed(bed: Bed, mgd: float | None = None) -> None:
    """Surface level, packing fraction, coordination and kinetic energy of a settled bed (in place)."""
    lmp = bed.lmp
    x, r, t = gather_arrays(lmp)
    grains = t == GRAIN_TYPE
    x, r = x[grains], r[grains]
    length = bed.box[1] - bed.box[0]
    area = length * bed.thickness
    vol = 4.0 / 3.0 * math.pi * r**3
    # packing fraction in the interior: middle half along x, between 2 d above the floor and 2 d
    # below the top of the grains (centres counted with their full volume)
    d = bed.dem.grain_diameter
    z_top_grain = float(np.quantile(x[:, 2], 0.99))
    lo, hi = 2.0 * d, z_top_grain - 3.0 * d
    inner = (np.abs(x[:, 0]) < 0.25 * length) & (x[:, 2] > lo) & (x[:, 2] < hi)
    if hi > lo:
        phi = float(vol[inner].sum() / (0.5 * length * bed.thickness * (hi - lo)))
    else:
        phi = float(vol.sum() / (area * (z_top_grain + r.mean())))
    bed.packing_fraction = phi
    bed.surface = float(vol.sum() / (area * phi))
    lmp.command("run 0 post no")
    z_atoms = np.asarray(lmp.numpy.extract_compute("td_contacts", 1, 1), dtype=float)
    # mean coordination of grains in contact (rattlers, with fewer than two contacts, left out)
    total = _gather_contacts(lmp, z_atoms)
    touching = total[total >= 2]
    bed.coordination = float(touching.mean()) if touching.size else 0.0
    n = bed.grain_count
    ke = float(lmp.extract_compute("td_ke", 0, 0))
    if mgd is None:
        mgd = bed.dem.grain_density * math.pi / 6.0 * d**3 * bed.spec.gravity * d
    bed.kinetic_per_grain = ke / n / mgd


def _gather_contacts(lmp: Any, local: np.ndarray) -> np.ndarray:
    """Per-grain contact counts of every rank (the compute is per owned atom)."""
    try:
        values = lmp.gather("c_td_contacts", 1, 1)
        n = int(lmp.get_natoms())
        arr = np.ctypeslib.as_array(values, shape=(n,)).copy()
        types = np.ctypeslib.as_array(lmp.gather_atoms("type", 0, 1), shape=(n,))
        return arr[types == GRAIN_TYPE]
    except Exception:  # older LAMMPS without gather of computes: this rank's grains only
        return local


def pressure_profile(bed: Bed, bins: int = 8) -> tuple[np.ndarray, np.ndarray]:
    lmp = bed.lmp
    bins = int(bins)
    if bins < 2:
        raise InputError("bins", bins, "an integer >= 2")
    try:
        lmp.command("compute td_stress grains stress/atom NULL pair fix")
    except Exception:
        lmp.command("compute td_stress grains stress/atom NULL pair")
    lmp.command("run 0 post no")
    n = int(lmp.get_natoms())
    s = np.ctypeslib.as_array(lmp.gather("c_td_stress", 1, 6), shape=(6 * n,)).reshape(n, 6).copy()
    lmp.command("uncompute td_stress")
    x, _r, t = gather_arrays(lmp)
    g = t == GRAIN_TYPE
    x, s = x[g], s[g]
    length = bed.box[1] - bed.box[0]
    middle = np.abs(x[:, 0]) < 0.25 * length
    edges = np.linspace(0.0, bed.surface, bins + 1)
    depth, sigma = [], []
    for k in range(bins):
        sel = middle & (x[:, 2] >= edges[k]) & (x[:, 2] < edges[k + 1])
        layer = 0.5 * length * bed.thickness * (edges[k + 1] - edges[k])
        # stress/atom is stress x volume (pressure-volume units), compressive negative
        sigma.append(-float(s[sel, 2].sum()) / layer)
        depth.append(bed.surface - 0.5 * (edges[k] + edges[k + 1]))
    return np.asarray(depth), np.asarray(sigma)


def check_speed(speed: float) -> float:
    speed = check_finite("speed", speed)
    if not speed > 0:
        raise InputError("speed", speed, "a speed > 0 [m/s]")
    return speed


def save_bed(bed: Bed, path: str | Path) -> Path:
    """Write a settled bed as a LAMMPS restart file ``path`` and its figures beside it (``.json``),
    each to a temporary name moved into place; :func:`load_bed` reads it back (for sweeps of runs
    from one bed)."""
    p = Path(path)
    tmp = p.with_name(f".{p.name}.tmp")
    bed.lmp.command(f"write_restart {tmp}")
    if is_root(bed.lmp):
        state = {"spec": _spec_dict(bed.spec), "dem": asdict(bed.dem), "box": list(bed.box),
                 "dt": bed.dt, "summary": bed.summary()}  # fmt: skip
        side = p.with_name(p.name + ".json")
        side_tmp = side.with_name(f".{side.name}.tmp")
        side_tmp.write_text(json.dumps(state), encoding="utf-8")
        os.replace(tmp, p)
        os.replace(side_tmp, side)
    return p


def _spec_dict(spec: BedSpec) -> dict[str, Any]:
    out = asdict(spec)
    out["kind"], out["packing"] = spec.kind.value, spec.packing.value
    return out


def load_bed(path: str | Path) -> Bed:
    """A bed written by :func:`save_bed`, live in a new LAMMPS instance."""
    p = Path(path)
    side = p.with_name(p.name + ".json")
    try:
        state = json.loads(side.read_text(encoding="utf-8"))
        spec = BedSpec(**state["spec"])
        dem = DEMParameters(**state["dem"])
        box = tuple(float(v) for v in state["box"])
        summary = state["summary"]
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise InputError("bed file", str(path), "a bed written by terradyn.dem.save_bed (with its .json)",
                         " ".join(str(exc).split())[:100]) from None  # fmt: skip
    lmp = new_lammps()
    try:
        lmp.command("atom_modify map array")
        lmp.command(f"read_restart {p}")
        setup_interactions(lmp, box, dem, spec.kind, friction=dem.friction, rolling=dem.rolling_friction,
                           gravity=spec.gravity)  # fmt: skip
        lmp.command("run 0 post no")  # restores the fixes' per-atom state (contact histories)
    except BaseException:
        lmp.close()
        raise
    return Bed(lmp, spec, dem, float(state["dt"]), box, int(summary["grain_count"]),  # type: ignore[arg-type]
               float(summary["bed_depth_m"]), float(summary["packing_fraction"]),
               float(summary["coordination_number"]), float(summary["kinetic_energy_per_grain_mgd"]),
               float(summary["settle_time_s"]))  # fmt: skip
