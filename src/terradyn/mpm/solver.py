"""MPM orchestration: the stable time step and a phase runner around the kernels (the grid and the
bed's initial particles are :mod:`terradyn.mpm.grid`, re-exported here).

Nothing here computes physics per particle; it sizes arrays, chooses ``dt``, calls
:func:`terradyn.mpm._kernels.advance` in chunks of steps, checks each chunk for instability, records
the force on the body, and writes snapshots and checkpoints.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numba
import numpy as np

from ..errors import InputError, SolverError, check_positive, check_range
from . import _kernels as K
from .bodies import BodyState, body_segments_world
from .checkpoint import load_checkpoint, save_checkpoint, write_snapshot
from .grid import GRID_PAD, BedGrid, ParticleState, check_surface_offset, initial_density, make_bed
from .interrupts import RunInterrupted, _HeldInterrupts
from .model import GranularModel
from .window import heap_toe, window_cells

__all__ = [
    "GRID_PAD",
    "BedGrid",
    "MPMInstabilityError",
    "ParticleState",
    "Phase",
    "RunInterrupted",
    "Runner",
    "check_surface_offset",
    "initial_density",
    "make_bed",
    "stable_time_step",
]

#: Largest allowed CFL number (c + |v|) dt / h checked at run time.
CFL_LIMIT = 0.6
#: Below this many particles the step loop runs on one thread (the parallel regions of a step cost
#: about as much as they save). From this size up, a runner given several threads times its chunks
#: and keeps the faster of one thread and all of them, trying the other every
#: :data:`THREAD_PROBE_EVERY` chunks: on a machine whose cores other processes keep busy the kernel
#: gives the run a fixed share of the CPU (per session), a second thread then adds only its
#: synchronisation cost, and one thread wins. Results do not depend on the thread count beyond
#: rounding (benchmarks/bench_mpm.py has the figures).
PARALLEL_MIN_PARTICLES = 10_000
#: Chunks between two timed trials of the thread count not in use (see PARALLEL_MIN_PARTICLES).
THREAD_PROBE_EVERY = 8
#: levels of a phase's twist ramp (:attr:`Phase.ramp_steps`): the prescribed twist rises in this many
#: equal steps, each held for an equal share of the ramp's time steps
RAMP_LEVELS = 100

ProgressCallback = Callable[[float, float], None]


class MPMInstabilityError(SolverError):
    """The MPM run became unstable (NaN, CFL violation or runaway kinetic energy)."""


def stable_time_step(
    model: GranularModel, cell_size: float, *, cfl: float = 0.3, speed: float = 0.0
) -> float:
    """``dt = cfl h / (c_p + speed)`` [s] with c_p the P-wave speed at the critical density [m/s]."""
    check_range("cfl", cfl, 1e-3, 0.5)
    check_positive("cell_size", cell_size)
    return cfl * cell_size / (model.wave_speed() + abs(speed))


@dataclass(frozen=True, slots=True)
class Phase:
    """A stretch of the run: ``n_steps`` with grid ``damping`` [1/s]; at its start the body gets
    ``twist`` (vx, vz, omega) and ``free`` flags, (x, z) or (x, z, spin) (None: keep).

    ``ramp_steps`` > 0 (with a ``twist``) ramps the prescribed (not free) components of the twist
    from 0 to ``twist`` over the phase's first ``ramp_steps`` steps: a staircase of
    :data:`RAMP_LEVELS` equal rises (fewer if the ramp has fewer steps), level k of L holding k/L of
    the twist; a function of the step number alone, so the run does not depend on how it is chunked
    for recording or resumed. The free components start from ``twist`` as without a ramp."""

    name: str
    n_steps: int
    damping: float = 0.0
    twist: tuple[float, float, float] | None = None
    free: tuple[bool, ...] | None = None
    ramp_steps: int = 0

    def ramp_pieces(self, first: int, n: int) -> list[tuple[int, int, float]]:
        """Steps ``first .. first + n - 1`` of this phase (counted from its start) split where the
        ramp level changes: ``(offset, count, fraction of the twist)``; fraction 1 after the ramp."""
        if self.ramp_steps <= 0:
            return [(0, n, 1.0)]
        levels = min(RAMP_LEVELS, self.ramp_steps)
        pieces, k = [], first
        while k < first + n:
            if k >= self.ramp_steps:
                pieces.append((k - first, first + n - k, 1.0))
                break
            level = k * levels // self.ramp_steps + 1  # the level holding step k, 1..levels
            end = min(first + n, -(-level * self.ramp_steps // levels))  # first step of the next level
            pieces.append((k - first, end - k, level / levels))
            k = end
        return pieces


@dataclass
class Runner:
    """Advances particles and one body through a list of phases; records, checks, saves.

    ``record_every`` steps form one recorded row (forces averaged over those steps). Output paths are
    optional; ``checkpoint_interval`` is wall-clock seconds between checkpoints. ``fingerprint`` holds
    the inputs that identify the run (a JSON-able mapping, see
    :func:`~terradyn.mpm.checkpoint.plain`; a string is an opaque key): a checkpoint is only resumed
    by a runner with the same fingerprint.

    State is consistent (and checkpointed) at the end of a chunk of ``record_every`` steps: the
    particles, the body, the step counter, the rows and the animation frames. Interrupts that arrive
    inside a chunk are held until it ends (:class:`_HeldInterrupts`); :meth:`run` then writes a
    checkpoint of that state and raises :class:`RunInterrupted`. Resuming it is bit-identical to an
    uninterrupted run.

    ``window`` [m] > 0 makes a moving window: only the grains within ``window`` of bed length centred
    on the body (snapped to whole cells, kept inside the bed) are stepped, on a grid over the window
    alone whose edges act as the bed's side walls; the rest of the bed is held as it is (the undisturbed
    bed ahead of a wheel, its rut behind). At the end of each chunk the window is re-centred on the
    body, so a body that travels far pays for the window, not for the bed. ``particles`` always holds
    the whole bed. With ``window_clearance`` [m] > 0 the leading edge keeps that clearance beyond the
    bow wave, growing with it (:mod:`~terradyn.mpm.window`). The window is a function of the state at
    the end of a chunk, so a resumed run rebuilds the same one.
    """

    model: GranularModel
    grid: BedGrid
    particles: ParticleState
    body: BodyState
    dt: float
    phases: list[Phase]
    gravity: float = 9.81
    record_every: int = 50
    has_body: bool = True
    reference_speed: float = 0.0
    fingerprint: Mapping[str, Any] | str = ""
    checkpoint_path: Path | None = None
    checkpoint_interval: float = 60.0
    snapshot_dir: Path | None = None
    snapshot_every: int = 0
    progress: ProgressCallback | None = None
    frame_every: int = 0
    window: float = 0.0
    window_clearance: float = 0.0
    averaged_divergence: bool = False  # Resolution.volumetric == "patch"
    flip: float = 0.0  # Resolution.flip
    step: int = 0
    rows: list[list[float]] = field(default_factory=list)
    frames: list[dict[str, np.ndarray]] = field(default_factory=list)
    _last_checkpoint: float = field(default=0.0, repr=False)
    _saved_step: int = field(default=-1, repr=False)  # step of the checkpoint on disk (-1: none)
    _step_seconds: dict[int, float] = field(default_factory=dict, repr=False)  # by thread count
    _chunks_timed: int = field(default=-1, repr=False)  # -1: the first (warm-up) chunk is not timed
    _bed: BedGrid | None = field(default=None, repr=False)  # the whole bed when a window is in use
    _index: np.ndarray | None = field(default=None, repr=False)  # bed particles in the window
    _active: ParticleState | None = field(default=None, repr=False)  # their stepped copy

    ROW = (
        "phase",
        "step",
        "time_s",
        "x_m",
        "z_m",
        "theta_rad",
        "vx_m_s",
        "vz_m_s",
        "omega_rad_s",
        "fx_per_width",
        "fz_per_width",
        "ty_per_width",
    )

    @property
    def total_steps(self) -> int:
        return sum(p.n_steps for p in self.phases)

    #: Arrays every run checkpoint holds (besides the particles ``p_*``).
    CHECKPOINT_KEYS = ("b_pose", "b_twist", "b_free", "step", "rows", "frame_count")

    def resume(self) -> None:
        """Load the state of ``checkpoint_path``.

        Raises :class:`~terradyn.errors.InputError` (field ``checkpoint_path``) if there is none, if it
        is unreadable, or if it was written by a run with other inputs (the message names them).
        """
        path = self.checkpoint_path
        if path is None:
            raise InputError("resume", True, "resume together with checkpoint_path", "give the file")
        names = [f"p_{k}" for k in ParticleState.NAMES]
        data = load_checkpoint(path, self.fingerprint, required=(*names, *self.CHECKPOINT_KEYS))
        try:
            particles = ParticleState.from_arrays(data)
            rows = np.asarray(data["rows"], dtype=float).reshape(-1, len(self.ROW))
            frames = _unstack_frames(data)
            step = int(data["step"])
            if len(particles) != len(self.particles) or not 0 <= step <= self.total_steps:
                raise ValueError("the particles or the step do not fit this run")
            self.body.pose[:] = data["b_pose"]
            self.body.twist[:] = data["b_twist"]
            self.body.free[: len(data["b_free"])] = data["b_free"]
        except (KeyError, ValueError, IndexError) as exc:
            raise InputError(
                "checkpoint_path",
                str(path),
                "a readable terradyn checkpoint (.npz)",
                f"the file is not a readable terradyn checkpoint: its arrays do not fit this run "
                f"({type(exc).__name__}); remove it or give another path",
            ) from None
        self.particles = particles
        self._index = self._active = None  # rebuilt from the restored pose by prepare()
        if self._bed is not None:
            self.grid = self._window_grid(self.body.pose[0])
        self.step = step
        self.rows = [list(r) for r in rows]
        self.frames = frames
        self._saved_step = step

    def save_checkpoint(self) -> None:
        """Write the current (consistent) state to ``checkpoint_path`` atomically, if one is set."""
        if self.checkpoint_path is None:
            return
        arrays = self.particles.arrays()
        arrays.update(
            b_pose=self.body.pose,
            b_twist=self.body.twist,
            b_free=self.body.free,
            step=np.array(self.step),
            rows=np.array(self.rows, dtype=float).reshape(-1, len(self.ROW)),
            **_stack_frames(self.frames),
        )
        save_checkpoint(self.checkpoint_path, arrays, self.fingerprint)
        self._last_checkpoint = time.monotonic()
        self._saved_step = self.step

    def prepare(self) -> None:
        """Allocate the grid and scratch buffers, and place the window (idempotent)."""
        if self.window > 0.0 and self._bed is None:
            check_positive("window", self.window)
            self._bed = self.grid
            h = self._bed.cell_size
            cells = math.ceil(self.window / h - 1e-9)
            if cells < round(self._bed.width / h):
                if cells < 8:
                    raise InputError("window", self.window, f"at least 8 cells ({8 * h:g} m)")
                self.grid = self._window_grid(self.body.pose[0])
            else:  # a window as long as the bed is the bed
                self._bed = None
                self.window = 0.0
        if self._bed is not None and self._active is None:
            self._gather()
        self._allocate()

    def _allocate(self) -> None:
        """Grid and scratch buffers for the current grid (again when a growing window changed it)."""
        nx, nz = self.grid.shape
        grid: tuple[np.ndarray, np.ndarray] | None = getattr(self, "_grid", None)
        if grid is None or grid[0].shape != (nx, nz):
            self._grid = (np.zeros((nx, nz)), np.zeros((nx, nz, 2)))
            self._buf = K.make_buffer(nx, nz, len(self.particles))
            self._scratch = K.make_scratch(nx, nz, len(self.particles))  # sized for the whole bed

    @property
    def bed_grid(self) -> BedGrid:
        """The whole bed (``grid`` is the window's grid when a window is in use)."""
        return self.grid if self._bed is None else self._bed

    @property
    def stepped_particles(self) -> int:
        """Particles stepped per step: the window's (after :meth:`prepare`) or the whole bed's."""
        return len(self.particles) if self._active is None else len(self._active)

    def _window_grid(self, x_body: float) -> BedGrid:
        """The window's grid around ``x_body`` [m] (:func:`~terradyn.mpm.window.window_cells`)."""
        bed = self._bed
        assert bed is not None
        h, toe = bed.cell_size, self.heap_toe(x_body)
        left, right = window_cells(bed.x_left, bed.width, h, self.window, x_body, toe, self.window_clearance)
        return BedGrid((right - left) * h, bed.depth, bed.air, h, left * h, bed.walls, bed.surface_offset)

    def heap_toe(self, x_body: float) -> float | None:
        """The bow wave's toe ahead of ``x_body`` [m] as the body moves (:func:`~.window.heap_toe`)."""
        return heap_toe(self.particles.pos, float(self.body.twist[0]), x_body)

    def _gather(self) -> None:
        """Take the bed particles within the window as the stepped set. Stepped particles stay inside
        the window (the grid clamps them to its walls) and held ones never move, so this set is the
        one the window held before it moved, plus the grains it now covers, minus those it left."""
        lo_x, hi_x = self.grid.bounds[:2]
        x = self.particles.pos[:, 0]
        self._index = np.flatnonzero((x >= lo_x) & (x <= hi_x))
        p = self.particles
        self._active = ParticleState(
            **{k: np.ascontiguousarray(getattr(p, k)[self._index]) for k in ParticleState.NAMES}
        )

    def _scatter_and_move(self) -> None:
        """Copy the stepped particles back into the bed, and re-centre the window on the body."""
        if self._active is None or self._index is None:
            return
        for k in ParticleState.NAMES:
            getattr(self.particles, k)[self._index] = getattr(self._active, k)
        grid = self._window_grid(self.body.pose[0])
        if grid.x_left != self.grid.x_left or grid.width != self.grid.width:
            self.grid = grid
            self._gather()
            self._allocate()

    def advance_steps(
        self, n: int, damping: float = 0.0, ramp: tuple[Phase, int] | None = None
    ) -> np.ndarray:
        """Advance ``n`` steps (no recording) and check stability; returns the per-step body forces
        (n, 3) per unit width [N/m, N/m, N m/m]. ``ramp`` (phase, steps of it done) applies that
        phase's twist ramp (:attr:`Phase.ramp_steps`)."""
        self.prepare()
        forces = np.zeros((n, 3))
        threads = numba.get_num_threads()
        use = self._thread_count(threads)
        numba.set_num_threads(use)
        start = time.perf_counter()
        target, pieces = None, [(0, n, 1.0)]
        if ramp is not None and ramp[0].twist is not None:
            target = np.asarray(ramp[0].twist, dtype=float)
            pieces = ramp[0].ramp_pieces(ramp[1], n)
        held = ~self.body.free[:3]  # the prescribed components
        try:
            for offset, count, fraction in pieces:
                if target is not None:
                    self.body.twist[held] = fraction * target[held]
                self._advance(count, damping, forces[offset : offset + count])
        finally:
            numba.set_num_threads(threads)
        self._time_chunk(use, (time.perf_counter() - start) / max(1, n))
        self.step += n
        self._scatter_and_move()
        self._check(n)
        return forces

    def _thread_count(self, threads: int) -> int:
        """Threads for the next chunk: 1 below :data:`PARALLEL_MIN_PARTICLES`, else the faster so far
        of 1 and ``threads`` (each is tried first; the slower one again every THREAD_PROBE_EVERY)."""
        if threads <= 1 or self.stepped_particles < PARALLEL_MIN_PARTICLES:
            return 1
        seen = self._step_seconds
        for count in (threads, 1):
            if count not in seen:
                return count
        best, other = (1, threads) if seen[1] <= seen[threads] else (threads, 1)
        return other if self._chunks_timed % THREAD_PROBE_EVERY == THREAD_PROBE_EVERY - 1 else best

    def _time_chunk(self, threads: int, seconds_per_step: float) -> None:
        """Record the wall time per step of a chunk run on ``threads`` (the first chunk compiles)."""
        self._chunks_timed += 1
        if self._chunks_timed == 0:
            return
        old = self._step_seconds.get(threads)
        self._step_seconds[threads] = seconds_per_step if old is None else 0.5 * (old + seconds_per_step)

    def run(self) -> None:
        """Run all phases from the current step to the end; the last state is checkpointed.

        A run resumed at its end does no step and leaves its checkpoint as it is. On an interrupt
        (KeyboardInterrupt) the state at the end of the last completed chunk is checkpointed (if
        ``checkpoint_path`` is set; further interrupts wait until the file is written) and
        :class:`RunInterrupted` is raised.
        """
        self._last_checkpoint = time.monotonic()
        try:
            self.prepare()
            self._run_phases()
        except RunInterrupted:
            raise
        except KeyboardInterrupt as exc:
            raise self._interrupted() from exc
        if self._saved_step != self.step:
            self.save_checkpoint()

    def _run_phases(self) -> None:
        start = 0
        for index, phase in enumerate(self.phases):
            stop = start + phase.n_steps
            if self.step == start:
                if phase.twist is not None:
                    self.body.twist[:] = phase.twist
                if phase.free is not None:
                    self.body.free[:] = False
                    self.body.free[: len(phase.free)] = phase.free
            while start <= self.step < stop:
                n = min(self.record_every, stop - self.step)
                self._chunk(index, phase, n, self.step - start)
            start = stop

    def _interrupted(self) -> RunInterrupted:
        """Checkpoint the consistent state after an interrupt; the exception to raise."""
        written, failure = None, ""
        if self.checkpoint_path is not None:
            try:
                with _HeldInterrupts(deliver=False):
                    if self._saved_step != self.step:
                        self.save_checkpoint()
                written = self.checkpoint_path
            except KeyboardInterrupt:
                failure = "a second interrupt stopped the checkpoint write"
            except OSError as exc:
                failure = f"the checkpoint could not be written ({exc.strerror or type(exc).__name__})"
        return RunInterrupted(self.step * self.dt, self.step, self.total_steps, written, failure)

    def _chunk(self, index: int, phase: Phase, n: int, done: int = 0) -> None:
        """Advance ``n`` steps (``done`` of the phase are done) and record them; the state is
        consistent again when this returns."""
        b = self.body
        ramp = (phase, done) if phase.ramp_steps > 0 and done < phase.ramp_steps else None
        with _HeldInterrupts():
            f = self.advance_steps(n, phase.damping, ramp).mean(axis=0)
            t = self.step * self.dt
            self.rows.append([index, self.step, t, *b.pose, *b.twist, *f])
            if self.frame_every > 0 and (self.step // self.record_every) % self.frame_every == 0:
                self.frames.append(self.frame())
        if self.snapshot_dir is not None and self.snapshot_every > 0:
            if (self.step // self.record_every) % self.snapshot_every == 0:
                self.write_snapshot()
        if self.checkpoint_path is not None:
            if time.monotonic() - self._last_checkpoint >= self.checkpoint_interval:
                self.save_checkpoint()
        if self.progress is not None:
            self.progress(t, self.step / max(1, self.total_steps))

    def _advance(self, n: int, damping: float, forces: np.ndarray) -> None:
        p = self.particles if self._active is None else self._active
        b, (gm, gv) = self.body, self._grid
        x0, z0 = self.grid.origin
        walls = self.grid.walls
        kinds = np.array([walls.left.code, walls.right.code, walls.bottom.code], dtype=np.int64)
        mus = np.array([walls.left.friction, walls.right.friction, walls.bottom.friction])
        K.advance(
            n,
            p.pos,
            p.vel,
            p.aff,
            p.stress,
            p.mass,
            p.vol,
            p.gdot,
            self._buf,
            gm,
            gv,
            x0,
            z0,
            self.grid.cell_size,
            self.dt,
            self.gravity,
            damping,
            GRID_PAD,
            kinds,
            mus,
            self.grid.bounds,
            self.model.as_kernel_array(),
            self.has_body,
            b.contact.code,
            b.seg,
            b.pose,
            b.twist,
            b.mass,
            b.inertia,
            b.free,
            b.load,
            b.reach + 2.0 * self.grid.cell_size,
            b.friction,
            forces,
            *self._scratch,
            self.averaged_divergence,
            self.flip,
        )

    def frame(self) -> dict[str, np.ndarray]:
        """A light copy of the state for animations: time, body pose and outline, particle x, z,
        speed and pressure (float32)."""
        p, b = self.particles, self.body
        st = p.stress
        return {
            "time_s": np.array(self.step * self.dt),
            "step": np.array(self.step),
            "segments": body_segments_world(b.seg, b.pose) if self.has_body else np.zeros((0, 2, 2)),
            "x": p.pos[:, 0].astype(np.float32),
            "z": p.pos[:, 1].astype(np.float32),
            "speed": np.hypot(p.vel[:, 0], p.vel[:, 1]).astype(np.float32),
            "pressure": (-(st[:, 0] + st[:, 1] + st[:, 3]) / 3.0).astype(np.float32),
        }

    def write_snapshot(self) -> Path | None:
        if self.snapshot_dir is None:
            return None
        path = self.snapshot_dir / f"particles_{self.step:09d}.nc"
        attrs = {
            "time_s": self.step * self.dt,
            "step": self.step,
            "body_x_m": self.body.pose[0],
            "body_z_m": self.body.pose[1],
            "body_theta_rad": self.body.pose[2],
            "per_unit_width": "mass and volume are per metre of out-of-plane width",
        }
        return write_snapshot(path, self.particles.fields(), attrs)

    def _check(self, n: int) -> None:
        """Raise :class:`MPMInstabilityError` on NaN, a CFL violation or runaway kinetic energy."""
        p, h, t = self.particles, self.grid.cell_size, self.step * self.dt
        where = f"at t = {t:.4g} s (step {self.step})"
        keep = f"; last good checkpoint kept at {self.checkpoint_path}" if self.checkpoint_path else ""
        if not (
            np.isfinite(p.vel).all() and np.isfinite(p.stress).all() and np.isfinite(self.body.pose).all()
        ):
            raise MPMInstabilityError(f"MPM run produced NaN/inf {where}{keep}; reduce cfl or cell_size")
        vmax = float(np.sqrt((p.vel**2).sum(axis=1).max()))
        cfl = (self.model.wave_speed() + vmax) * self.dt / h
        if cfl > CFL_LIMIT:
            raise MPMInstabilityError(
                f"CFL violation {where}: (c + |v|max) dt / h = {cfl:.3f} > {CFL_LIMIT} "
                f"(|v|max = {vmax:.3g} m/s){keep}; reduce cfl"
            )
        if self.has_body:
            r = self.body.reach
            x, z = self.body.pose[0], self.body.pose[1]
            if not self.grid.holds(x, z, r):
                raise MPMInstabilityError(
                    f"the body left the grid {where}: origin at ({x:.4g}, {z:.4g}) m, reach {r:.4g} m, "
                    f"grid {self.grid.describe_bounds()}{keep}; enlarge the bed"
                )
        if self.has_body and self.reference_speed > 0:
            b = self.body
            speed = math.hypot(b.twist[0], b.twist[1]) + abs(b.twist[2]) * b.reach
            if speed > 1.5 * self.reference_speed:
                raise MPMInstabilityError(
                    f"the body runs away {where}: point speed {speed:.3g} m/s is beyond 1.5 x the "
                    f"{self.reference_speed:.3g} m/s the time step was sized for (a free spin or "
                    f"translation under a load the bed cannot resist){keep}"
                )
        v_ref = self.reference_speed + math.sqrt(self.gravity * self.grid.depth)
        ke = 0.5 * float(np.sum(p.mass * (p.vel**2).sum(axis=1))) / float(np.sum(p.mass))
        if ke > 50.0 * v_ref**2:
            raise MPMInstabilityError(
                f"runaway kinetic energy {where}: mean v^2/2 = {ke:.3g} m^2/s^2 > {50 * v_ref**2:.3g}{keep}"
            )

    def table(self) -> dict[str, np.ndarray]:
        """Recorded rows as columns (forces still per unit width)."""
        arr = np.array(self.rows, dtype=float).reshape(-1, len(self.ROW))
        return {name: arr[:, k] for k, name in enumerate(self.ROW)}


def _stack_frames(frames: list[dict[str, np.ndarray]]) -> dict[str, np.ndarray]:
    """Animation frames as checkpoint arrays: ``frame_count`` and one stacked ``f_<key>`` per key."""
    out = {"frame_count": np.array(len(frames))}
    if frames:
        for key in frames[0]:
            out[f"f_{key}"] = np.stack([np.asarray(fr[key]) for fr in frames])
    return out


def _unstack_frames(data: Mapping[str, np.ndarray]) -> list[dict[str, np.ndarray]]:
    """Inverse of :func:`_stack_frames`."""
    count = int(data["frame_count"])
    keys = [k for k in data if k.startswith("f_")]
    if count and not keys:
        raise KeyError("f_time_s")
    for k in keys:
        if data[k].shape[0] != count:
            raise ValueError(f"{k} holds {data[k].shape[0]} frames, not {count}")
    return [{k[2:]: data[k][i, ...].copy() for k in keys} for i in range(count)]
