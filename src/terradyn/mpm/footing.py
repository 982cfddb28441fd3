"""The MPM strip footing whose base is a grid boundary condition: the continuum without the contact.

A rigid strip footing of width B on the free surface of a settled bed, pushed straight down; instead of
a contact body, the grid nodes under it (``|x| <= B/2`` on the surface node line and the
``base_rows - 1`` lines above it) take the footing's velocity after each grid update, as a
finite-element footing prescribes its footing nodes. The force of the grains on the footing is the
vertical impulse those nodes take from the grid per step. Everything else is the MPM of the intrusion
runs: the bed of :func:`terradyn.mpm.solver.make_bed` (consolidated, geostatic stress), its damped
settling (:func:`terradyn.mpm.model.default_settle_time`), the same compiled step
(:mod:`terradyn.mpm._footing_kernels`) and free-slip walls; a symmetry plane at x = 0 can halve the
grid. By default the grid follows the footing down, so the footing nodes stay on its base.

Settings come as frozen specs in the style of :mod:`terradyn.mpm.specs`: :class:`NodeFootingCase`
(the footing and its bed), :class:`FootingPush` (the loading) and the shared
:class:`~terradyn.mpm.specs.Resolution`. :func:`run_node_footing` returns the bearing pressure against
settlement (:class:`NodeFootingRun`); the bearing factor and its convergence study live in
:mod:`terradyn.studies.mpm_footing_nodes`.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from enum import Enum

import numpy as np

from ..errors import InputError, SolverError, check_length, check_positive, check_range
from ..materials import Material
from .model import BedPacking, GranularModel, default_settle_time, resolve_model
from .solver import GRID_PAD, BedGrid, initial_density, make_bed, stable_time_step
from .specs import Resolution, _integer, _set, _Spec

__all__ = ["FootingBase", "FootingPush", "NodeFootingCase", "NodeFootingRun", "run_node_footing"]


class FootingBase(str, Enum):
    """The footing's base: ``SMOOTH`` leaves the footing nodes' v_x free, ``ROUGH`` holds v_x = 0."""

    SMOOTH = "smooth"
    ROUGH = "rough"


@dataclass(frozen=True, repr=False)
class NodeFootingCase(_Spec):
    """The footing and its bed.

    width : footing width B [m].
    base : :class:`FootingBase` (``"smooth"`` or ``"rough"``).
    domain_widths : (half-width from the footing centre, depth) of the bed in footing widths,
        half-width in [1, 20], depth in [0.5, 10].
    symmetric : grid only x >= 0 with a symmetry plane (v_x = 0) at x = 0 (else both halves).
    follow : the grid moves down with the footing, so the footing nodes stay on its base (else the
        grid stays and the base stays on the surface node line while the grains move away from it:
        only settlements well under a cell read right).
    base_rows : node lines of the footing: the surface line and the ``base_rows - 1`` above it.
    gravity : [m/s^2].
    """

    width: float = 0.04
    base: FootingBase | str = FootingBase.SMOOTH
    domain_widths: tuple[float, float] = (6.0, 3.0)
    symmetric: bool = True
    follow: bool = True
    base_rows: int = 2
    gravity: float = 9.81

    def __post_init__(self) -> None:
        try:
            _set(self, "base", FootingBase(self.base))
        except ValueError:
            raise InputError("base", self.base, "'smooth' or 'rough'") from None
        _set(self, "width", check_length("width", self.width))
        allowed = "(half-width in [1, 20], depth in [0.5, 10]) footing widths"
        try:
            half, depth = (float(v) for v in self.domain_widths)
        except (TypeError, ValueError):
            raise InputError("domain_widths", self.domain_widths, allowed) from None
        if not (1.0 <= half <= 20.0 and 0.5 <= depth <= 10.0):
            raise InputError("domain_widths", self.domain_widths, allowed)
        _set(self, "domain_widths", (half, depth))
        for name in ("symmetric", "follow"):
            if not isinstance(getattr(self, name), bool):
                raise InputError(name, getattr(self, name), "True or False")
        _set(self, "base_rows", _integer("base_rows", self.base_rows, 1, 10, "an integer in [1, 10]"))
        _set(self, "gravity", check_range("gravity", self.gravity, 0.01, 100.0, unit="m/s^2"))


@dataclass(frozen=True, repr=False)
class FootingPush(_Spec):
    """The loading: the footing velocity rises from 0 to ``speed`` [m/s] over a half-cosine ramp of
    ``ramp_crossings`` P-wave transits of the bed depth (a sudden start sends a stress wave of about
    rho c v, as large as the collapse pressure at 0.02 m/s), then stays constant to the settlement
    ``settlement_ratio`` x B; the footing is then held still for ``hold_time`` [s]."""

    speed: float = 0.01
    ramp_crossings: float = 10.0
    settlement_ratio: float = 0.02
    hold_time: float = 0.0

    def __post_init__(self) -> None:
        _set(self, "settlement_ratio", check_range("settlement_ratio", self.settlement_ratio, 1e-3, 0.05))
        _set(self, "speed", check_positive("speed", self.speed))
        _set(self, "ramp_crossings", check_range("ramp_crossings", self.ramp_crossings, 0.0, 1e3))
        _set(self, "hold_time", check_range("hold_time", self.hold_time, 0.0, 10.0, unit="s"))


@dataclass(frozen=True, eq=False)
class NodeFootingRun:
    """What :func:`run_node_footing` measured.

    ``settlement_m`` [m] at the end of each recorded row of the push and ``pressure_Pa`` [Pa], the
    mean bearing pressure over the row (the grains' vertical force on the footing nodes over
    ``loaded_width_m``, B/2 with a symmetry plane, else B); ``held_time_s`` [s] since the push ended
    and ``held_pressure_Pa`` per row of the hold (empty without one). ``unit_weight_N_m3`` is the
    bed's as made, ``domain_m`` the grid's bed (width, depth) [m], ``push_time_s`` the push's
    duration, start-up ramp included, ``wall_s`` the run's wall time."""

    settlement_m: np.ndarray
    pressure_Pa: np.ndarray
    held_time_s: np.ndarray
    held_pressure_Pa: np.ndarray
    unit_weight_N_m3: float
    loaded_width_m: float
    cell_size_m: float
    time_step_s: float
    domain_m: tuple[float, float]
    particles: int
    steps: int
    push_time_s: float
    wall_s: float


def _footing_grid(case: NodeFootingCase, h: float) -> tuple[BedGrid, np.ndarray, np.ndarray]:
    """The bed's grid at cell size ``h`` [m] and the footing nodes' (i, j) ranges (first, last)."""
    b = case.width
    n_half = round(0.5 * b / h)
    if n_half < 2 or abs(n_half * h - 0.5 * b) > 1e-6 * h:
        raise InputError(
            "cell_size", h, f"B/2 / k for a whole k >= 2 (B = {b:g} m)", "the footing edge is a node"
        )
    half_l, depth_b = case.domain_widths
    half_cells = max(n_half + 2, round(half_l * b / h))
    grid = BedGrid(
        width=(half_cells if case.symmetric else 2 * half_cells) * h,
        depth=depth_b * b,
        air=4.0 * h,
        cell_size=h,
        x_left=0.0 if case.symmetric else -half_cells * h,
    )
    x0, z0 = grid.origin
    i_centre = round(-x0 / h)
    j_surface = round(-z0 / h)
    first_i = i_centre if case.symmetric else i_centre - n_half
    foot_i = np.array([first_i, i_centre + n_half], dtype=np.int64)
    foot_j = np.array([j_surface, j_surface + case.base_rows - 1], dtype=np.int64)
    return grid, foot_i, foot_j


@dataclass(frozen=True)
class _Schedule:
    """The run's time step [s] and step counts: settling, start-up ramp, push and hold, and the
    steps per recorded row."""

    dt: float
    n_settle: int
    ramp_steps: int
    n_push: int
    n_hold: int
    record_every: int

    @property
    def total(self) -> int:
        return self.n_settle + self.n_push + self.n_hold


def _schedule(
    model: GranularModel, grid: BedGrid, case: NodeFootingCase, cfl: float, push: FootingPush
) -> _Schedule:
    """The steps of a run; the start-up ramp must end before the settlement is reached."""
    speed = push.speed
    dt = stable_time_step(model, grid.cell_size, cfl=cfl, speed=speed)
    settle_time = default_settle_time(model, grid.depth, BedPacking.CONSOLIDATED, case.gravity)
    n_settle = max(1, round(settle_time / dt))
    ramp_steps = round(push.ramp_crossings * grid.depth / model.wave_speed() / dt)
    settlement = push.settlement_ratio * case.width
    # the ramp covers half its duration x speed; the rest at constant speed
    ramp_travel = 0.5 * ramp_steps * dt * speed
    if ramp_travel >= settlement:
        raise InputError(
            "speed",
            speed,
            f"below {speed * settlement / ramp_travel:.3g} m/s",
            "the ramp must end before the reading",
        )
    n_push = ramp_steps + math.ceil((settlement - ramp_travel) / (speed * dt))
    n_hold = round(push.hold_time / dt)
    return _Schedule(dt, n_settle, ramp_steps, n_push, n_hold, max(1, n_push // 400))


def _settle_push_hold(
    chunk: Callable[[int, int, float, float, float], np.ndarray],
    plan: _Schedule,
    settle_damping: float,
    speed: float,
) -> tuple[np.ndarray, np.ndarray]:
    """Run the three stretches of a node footing with ``chunk(n, step0, damping, speed, settled)``
    (n steps from step ``step0`` of the stretch, the footing's settlement ``settled`` [m] before
    them; returns the per-step (F_x, F_z, footing velocity)): the damped settling with the footing
    held, the push at ``speed`` [m/s] and the hold. Returns the push's rows (settlement [m], mean
    F_z [N/m]) and the hold's (time since the push [s], mean F_z [N/m]), one per recorded row."""
    settle_chunk = max(1, plan.n_settle // 20)
    k = 0
    while k < plan.n_settle:
        n = min(settle_chunk, plan.n_settle - k)
        chunk(n, 0, settle_damping, 0.0, 0.0)
        k += n
    rows = []
    k = 0
    s = 0.0
    while k < plan.n_push:
        n = min(plan.record_every, plan.n_push - k)
        f = chunk(n, k, 0.0, speed, s)
        s += float(-np.sum(f[:, 2]) * plan.dt)
        rows.append((s, float(np.mean(f[:, 1]))))
        k += n
    held_rows = []
    k = 0
    while k < plan.n_hold:  # the footing nodes at rest (speed 0), the grid with them
        n = min(plan.record_every, plan.n_hold - k)
        f = chunk(n, plan.n_push + k, 0.0, 0.0, s)
        k += n
        held_rows.append((k * plan.dt, float(np.mean(f[:, 1]))))
    return np.array(rows), np.array(held_rows).reshape(-1, 2)


def run_node_footing(
    material: Material | GranularModel,
    case: NodeFootingCase = NodeFootingCase(),
    *,
    resolution: Resolution = Resolution(),
    push: FootingPush = FootingPush(),
    local_damping: float = 0.0,
    progress: Callable[[float, float], None] | None = None,
) -> NodeFootingRun:
    """Push the strip footing of ``case`` into a settled bed of ``material`` and record its bearing
    pressure against settlement (module docstring).

    ``material`` a :class:`~terradyn.materials.Material` with a ``[continuum]`` table or a
    :class:`~terradyn.mpm.GranularModel`. ``resolution``: ``cell_size`` [m] (default B/20; B/2 must
    be a whole number >= 2 of cells, so the footing edge is a node), ``particles_per_cell``, ``cfl``
    (at coarse cells the reading depends on ``speed / cfl``, docs/mpm.md), ``volumetric`` and
    ``flip`` (positions and affine matrices stay APIC's); ``contact`` and ``min_cells_across`` do not
    apply (no contact body). ``push``: the loading. ``local_damping`` alpha in [0, 0.95] adds the
    local damping of quasi-static explicit codes at the free nodes
    (:func:`terradyn.mpm._footing_kernels.local_damp`), a diagnostic. ``progress(done, total)`` gets
    the steps done. Raises :class:`~terradyn.errors.SolverError` if the run goes unstable.
    """
    from . import _footing_kernels as FK
    from . import _kernels as K

    local_damping = check_range("local_damping", local_damping, 0.0, 0.95)
    model = resolve_model(material)
    b, g = case.width, case.gravity
    h = b / 20.0 if resolution.cell_size is None else resolution.cell_size
    grid, foot_i, foot_j = _footing_grid(case, h)
    state = make_bed(model, grid, particles_per_cell=resolution.particles_per_cell, gravity=g)
    gamma = initial_density(model.bulk_density, model.critical_density, BedPacking.CONSOLIDATED) * g
    plan = _schedule(model, grid, case, resolution.cfl, push)
    dt = plan.dt
    nx, nz = grid.shape
    x0, z0 = grid.origin
    scratch, geo, _ = K.make_scratch(nx, nz, len(state.pos))
    arrays = (state.pos, state.vel, state.aff, state.stress, state.mass, state.vol, state.gdot,
              K.make_buffer(nx, nz, len(state.pos)), np.zeros((nx, nz)), np.zeros((nx, nz, 2)))  # fmt: skip
    free_slip = (np.zeros(3, dtype=np.int64), np.zeros(3))  # wall kinds and friction (left, right, bottom)
    mat = model.as_kernel_array()
    rough = case.base is FootingBase.ROUGH
    averaged = resolution.volumetric == "patch"
    t0 = time.perf_counter()
    done = 0

    def chunk(n: int, step0: int, damping: float, v: float, settled: float) -> np.ndarray:
        nonlocal done
        f = np.zeros((n, 3))
        FK.advance_footing(n, step0, *arrays, x0, z0, h, dt, g, damping, GRID_PAD, *free_slip, grid.bounds,
                           mat, foot_i, foot_j, rough, case.symmetric, v, plan.ramp_steps, settled,
                           case.follow, -grid.depth, scratch, geo, averaged, f, resolution.flip,
                           local_damping)  # fmt: skip
        if not np.all(np.isfinite(f)):
            raise SolverError(f"the node footing went unstable (cell {h:g} m); lower cfl")
        done += n
        if progress is not None:
            progress(float(done), float(plan.total))
        return f

    # the footing nodes held still while the bed settles, damped over a wave transit
    arr, held = _settle_push_hold(chunk, plan, model.wave_speed() / grid.depth, push.speed)
    wall = time.perf_counter() - t0
    loaded = (0.5 if case.symmetric else 1.0) * b
    return NodeFootingRun(
        settlement_m=arr[:, 0],
        pressure_Pa=arr[:, 1] / loaded,
        held_time_s=held[:, 0],
        held_pressure_Pa=held[:, 1] / loaded,
        unit_weight_N_m3=gamma,
        loaded_width_m=loaded,
        cell_size_m=h,
        time_step_s=dt,
        domain_m=(grid.width, grid.depth),
        particles=len(state.pos),
        steps=plan.total,
        push_time_s=plan.n_push * dt,
        wall_s=wall,
    )
