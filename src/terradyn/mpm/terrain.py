"""MPM as a *stateful* terrain model: ``init`` a settled bed around a body, then ``step`` it in time.

The stateless models (RFT, DRFT, Wong-Reece) map ``(body, pose, twist) -> Wrench2D``. A granular
continuum remembers where it has been pushed, so MPM is driven instead through
:class:`terradyn.terrain.StatefulTerrainModel`::

    terrain = MPMTerrain(materials.get("MS"), bed=Bed(width=0.4, depth=0.15),
                         resolution=Resolution(cell_size=0.005))
    terrain.init(plate, Pose2D(0.0, 0.01))          # builds and settles the bed, places the body
    for k in range(n):
        w = terrain.step(pose, twist, dt)            # grains advance by dt with the body moving rigidly
        ...                                          # the caller integrates its own body with w

During ``step`` the body moves kinematically from ``pose`` with the constant ``twist`` (it is the
caller's body: the caller owns its dynamics); the MPM sub-steps ``dt`` with its own stable time step and
returns the time-averaged wrench of the grains on the body over the interval. The medium's state
(particles, time) persists between calls and can be checkpointed and restored.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError, check_positive
from ..geometry import Body
from ..kinematics import Pose2D, Twist2D, Wrench2D
from ..materials import Material
from .bodies import BodyState, ContactScheme, body_segments, effective_body
from .checkpoint import load_checkpoint, save_checkpoint
from .model import BedPacking, GranularModel, Walls, resolve_model
from .runs import bed_particles, settle_time
from .solver import BedGrid, ParticleState, Phase, Runner, _HeldInterrupts, stable_time_step
from .specs import Bed, Resolution, apply_legacy

__all__ = ["MPMTerrain"]


class MPMTerrain:
    """A plane-strain MPM granular bed that one rigid body moves through, advanced step by step.

    Parameters
    ----------
    material : a terradyn :class:`~terradyn.materials.Material` (its ``[continuum]`` parameters) or a
        :class:`~terradyn.mpm.GranularModel`.
    bed : :class:`~terradyn.mpm.Bed`; its ``width`` and ``depth`` [m] are required (no sizing rule
        without a body path): the free surface is at z = 0 and the grains span
        ``x_left <= x <= x_left + width`` (default centred on x = 0). Packing, density, walls, gravity
        and settling time as in :func:`terradyn.mpm.run_intrusion`.
    resolution : :class:`~terradyn.mpm.Resolution`; its ``cell_size`` [m] is required; particles per
        cell, cfl and contact scheme as in :func:`terradyn.mpm.run_intrusion`.
    air : empty grid above the surface [m] (default the bed depth); the body must stay below its top.
    max_speed : the largest body-point speed [m/s] the caller will impose; it sets the MPM time step
        (``dt = cfl h / (c_p + max_speed)``) and a faster body stops :meth:`step` with an error.
    **legacy : the flat keywords ``bed_width=``, ``bed_depth=``, ``cell_size=``, ``packing=``...
        (fields of the two specs, :data:`terradyn.mpm.specs.LEGACY`) and the model overrides
        ``youngs_modulus``, ``poisson_ratio``, ``friction_coefficient``, ``surface_friction``,
        ``rate_dependent``.
    """

    name = "mpm"

    def __init__(
        self,
        material: Material | GranularModel,
        *,
        bed: Bed = Bed(),
        resolution: Resolution = Resolution(),
        x_left: float | None = None,
        air: float | None = None,
        max_speed: float = 0.5,
        **legacy: Any,
    ) -> None:
        for name, spec, kind in (("bed", bed, Bed), ("resolution", resolution, Resolution)):
            if not isinstance(spec, kind):
                raise InputError(name, spec, f"a terradyn.mpm.{kind.__name__}")
        specs, overrides = apply_legacy(
            "MPMTerrain", legacy, {"bed": bed, "resolution": resolution}, exclude=frozenset({"bed_length"})
        )
        bed, resolution = specs["bed"], specs["resolution"]
        width, depth, cell = bed.width, bed.depth, resolution.cell_size
        for name, value in (("bed_width", width), ("bed_depth", depth), ("cell_size", cell)):
            if value is None:
                hint = "MPMTerrain has no sizing rule: give the bed and the cell size"
                raise InputError(name, None, "a size [m]", hint)
        assert width is not None and depth is not None and cell is not None
        if bed.window:
            raise InputError("window", bed.window, "None or 0 for MPMTerrain", "it steps the whole bed")
        self.bed, self.resolution = bed, resolution
        self.contact = ContactScheme.coerce(resolution.contact)
        self.model = model = resolve_model(material, **overrides)
        air = depth if air is None else air
        x_left = -0.5 * width if x_left is None else float(x_left)
        self.grid = BedGrid(
            float(width),
            float(depth),
            float(air),
            float(cell),
            x_left,
            Walls.coerce(bed.walls),
            bed.surface_offset,
        )
        self.packing = BedPacking(bed.packing)
        self.bed_density = bed.density
        self.particles_per_cell = resolution.particles_per_cell
        self.volumetric = resolution.volumetric
        self.flip = resolution.flip
        self.gravity = bed.gravity
        self.cfl = resolution.cfl
        self.max_speed = check_positive("max_speed", max_speed)
        self.settle_time = bed.settle_time
        self.dt = stable_time_step(model, self.grid.cell_size, cfl=self.cfl, speed=self.max_speed)
        self._runner: Runner | None = None
        self._body: Body | None = None
        self._eff: Body | None = None
        self._time = 0.0

    # -- state ------------------------------------------------------------------------------------
    @property
    def initialized(self) -> bool:
        return self._runner is not None

    @property
    def time(self) -> float:
        """Simulated time [s] since the end of bed settling."""
        self._require()
        return self._time

    @property
    def body(self) -> Body:
        """The body given to :meth:`init` (under the legacy ``"cover"`` contact thin plates are
        thickened, see :attr:`mpm_body`)."""
        self._require()
        assert self._body is not None
        return self._body

    @property
    def mpm_body(self) -> Body:
        """The body as MPM resolves it."""
        self._require()
        assert self._eff is not None
        return self._eff

    @property
    def pose(self) -> Pose2D:
        """The body's pose at the end of the last step."""
        p = self._require().body.pose
        return Pose2D(float(p[0]), float(p[1]), float(p[2]))

    def fields(self) -> dict[str, np.ndarray]:
        """Per-particle fields now (positions, velocities, stresses, pressure, density...)."""
        return self._require().particles.fields()

    def _require(self) -> Runner:
        if self._runner is None:
            raise InputError("terrain", "not initialised", "call init(body, pose) before stepping")
        return self._runner

    # -- the stateful terrain interface -----------------------------------------------------------
    def init(self, body: Body, pose: Pose2D) -> None:
        """Build the bed, settle it under gravity to rest, and place ``body`` at ``pose``.

        The body takes no part in settling; the pose may put it in contact with the surface or (for a
        prescribed intrusion start) above it. Calling ``init`` again starts a fresh bed.
        """
        if not isinstance(pose, Pose2D):
            raise InputError("pose", pose, "a terradyn.kinematics.Pose2D")
        runner, eff, state = self._setup(body)
        self._check_inside(state, pose, "pose")
        depth = self.grid.depth
        wave = self.model.wave_speed()
        settle = settle_time(self.model, self.bed, depth)
        if settle > 0:
            runner.phases = [Phase("settle", max(1, round(settle / self.dt)), damping=wave / depth)]
            runner.run()
        runner.has_body = True
        state.pose[:] = pose.as_array()
        self._runner, self._body, self._eff, self._time = runner, body, eff, 0.0

    def _setup(self, body: Body) -> tuple[Runner, Body, BodyState]:
        """A runner over a fresh (unsettled) bed, with ``body`` not yet in contact."""
        if not isinstance(body, Body):
            raise InputError("body", body, "a terradyn.geometry Body")
        h = self.grid.cell_size
        eff = effective_body(body, h, self.contact)
        state = BodyState(
            seg=body_segments(eff, h),
            pose=np.zeros(3),
            twist=np.zeros(3),
            free=np.zeros(2, dtype=np.bool_),
            mass=1.0,
            load=np.zeros(2),
            friction=self.model.surface_friction,
            width=body.width,
            contact=self.contact,
        )
        runner = Runner(
            self.model,
            self.grid,
            bed_particles(self.model, self.grid, self.bed, self.resolution),
            state,
            self.dt,
            [],
            gravity=self.gravity,
            has_body=False,
            reference_speed=self.max_speed,
            averaged_divergence=self.volumetric == "patch",
            flip=self.flip,
        )
        return runner, eff, state

    def _check_inside(self, state: BodyState, pose: Pose2D, field: str) -> None:
        if not self.grid.holds(pose.x, pose.z, state.reach):
            raise InputError(
                field,
                f"(x={pose.x:.4g}, z={pose.z:.4g})",
                f"a body origin at least its reach {state.reach:.4g} m inside the grid "
                f"{self.grid.describe_bounds()}",
                "enlarge the bed or the air above it",
            )

    def step(
        self,
        pose: Pose2D,
        twist: Twist2D,
        dt: float,
        *,
        about: tuple[float, float] | None = None,
    ) -> Wrench2D:
        """Advance the medium by ``dt`` [s] with the body moving rigidly from ``pose`` at ``twist``.

        Returns the grains' force [N] on the body and torque about +y [N m] about ``about`` (default
        the body origin at ``pose``), averaged over the interval. ``dt`` is split into MPM steps of at
        most the stable time step.
        """
        runner = self._require()
        check_positive("dt", dt)
        if not isinstance(pose, Pose2D):
            raise InputError("pose", pose, "a terradyn.kinematics.Pose2D")
        if not isinstance(twist, Twist2D):
            raise InputError("twist", twist, "a terradyn.kinematics.Twist2D")
        b = runner.body
        speed = math.hypot(twist.vx, twist.vz) + abs(twist.omega) * b.reach
        if speed > self.max_speed * (1.0 + 1e-9):
            raise InputError(
                "twist",
                f"body-point speed {speed:.4g} m/s",
                f"at most max_speed = {self.max_speed:g} m/s",
                "create the terrain with a larger max_speed",
            )
        self._check_inside(b, pose, "pose")
        n = max(1, math.ceil(dt / self.dt - 1e-9))
        sub = dt / n
        with _HeldInterrupts():  # an interrupt waits until particles, step and time agree again
            runner.dt = sub
            b.pose[:] = pose.as_array()
            b.twist[:] = twist.as_array()
            b.free[:] = False
            try:
                forces = runner.advance_steps(n)
            finally:
                runner.dt = self.dt
            self._time += dt
        # Per-step torques are about the body origin of that step; move each to ``about``.
        k = np.arange(n) + 0.5
        ox = pose.x + k * sub * twist.vx
        oz = pose.z + k * sub * twist.vz
        ax, az = (pose.x, pose.z) if about is None else (float(about[0]), float(about[1]))
        fx, fz = forces[:, 0], forces[:, 1]
        ty = forces[:, 2] + (oz - az) * fx - (ox - ax) * fz
        w = b.width
        return Wrench2D(float(fx.mean() * w), float(fz.mean() * w), float(ty.mean() * w))

    def wrench(self, body: Body, pose: Pose2D, twist: Twist2D, *, about=None) -> Wrench2D:
        """Not available: MPM has state; use :meth:`init` and :meth:`step`."""
        raise InputError(
            "model",
            "mpm",
            "a stateless terrain model (rft, drft, wong-reece) for wrench()",
            "MPM is stateful: call init(body, pose) then step(pose, twist, dt)",
        )

    # -- checkpoints ------------------------------------------------------------------------------
    def save(self, path: str | Path) -> Path:
        """Write the bed, the body pose and the time to ``path`` (.npz, written atomically)."""
        runner = self._require()
        arrays = runner.particles.arrays()
        arrays.update(b_pose=runner.body.pose, time=np.array(self._time), step=np.array(runner.step))
        return save_checkpoint(path, arrays, self._inputs(self._body, self._eff))

    def restore(self, body: Body, path: str | Path) -> None:
        """Continue from a state written by :meth:`save` with the same terrain settings and ``body``.

        Raises :class:`~terradyn.errors.InputError` (field ``path``) if the file is missing, is not a
        readable terradyn checkpoint, or was written for other settings or another body (the message
        names the settings that differ).
        """
        runner, eff, _ = self._setup(body)
        names = [f"p_{k}" for k in ParticleState.NAMES]
        data = load_checkpoint(
            path, self._inputs(body, eff), required=(*names, "b_pose", "time", "step"), field="path"
        )
        try:
            particles = ParticleState.from_arrays(data)
            if len(particles) != len(runner.particles):
                raise ValueError("particle count")
            pose = np.asarray(data["b_pose"], dtype=float).reshape(3)
            step, t = int(data["step"]), float(data["time"])
        except (ValueError, TypeError) as exc:
            raise InputError(
                "path",
                str(path),
                "a readable terradyn checkpoint (.npz)",
                f"the file is not a readable terradyn checkpoint: its arrays do not fit this terrain "
                f"({type(exc).__name__}); remove it or give another path",
            ) from None
        runner.particles = particles
        runner.body.pose[:] = pose
        runner.step = step
        runner.has_body = True
        self._runner, self._body, self._eff, self._time = runner, body, eff, t

    def _inputs(self, body: Body | None, eff: Body | None) -> dict[str, object]:
        """The settings a saved state belongs to (see :func:`~terradyn.mpm.checkpoint.load_checkpoint`)."""
        return {
            "run": "terrain",
            "body": body,
            "model": self.model,
            "cell_size": self.grid.cell_size,
            "contact": self.contact.value,
            "bed_width": self.grid.width,
            "bed_depth": self.grid.depth,
            "air": self.grid.air,
            "x_left": self.grid.x_left,
            "walls": self.grid.walls,
            "packing": self.packing,
            "bed_density": self.bed_density,
            "particles_per_cell": self.particles_per_cell,
            "gravity": self.gravity,
            "cfl": self.cfl,
            "max_speed": self.max_speed,
            **({"volumetric": self.volumetric} if self.volumetric != "point" else {}),
            **({"flip": self.flip} if self.flip else {}),
            "derived": {"mpm_body": eff, "dt": self.dt},
        }

    def __repr__(self) -> str:
        g = self.grid
        state = f"t={self.time:.4g} s" if self.initialized else "not initialised"
        return (
            f"MPMTerrain(bed {g.width:g} x {g.depth:g} m, cell {g.cell_size:g} m, "
            f"dt {self.dt:.3g} s, {state})"
        )
