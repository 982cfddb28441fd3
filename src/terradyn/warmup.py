"""Compile (or load from numba's on-disk cache) every numba kernel of terradyn once.

:func:`warmup` calls each kernel family through its public function on a tiny input, so the compiled
type signatures are exactly the ones later calls use, and reports the seconds each took: on a cold
cache that is the compile cost, on a warm one the cost of loading. ``terradyn warmup`` and
``make demo`` call it.

By default the work runs in a child process (``isolated=True``). Code that numba compiles in the
running process can be slower than the same code loaded from the cache: a kernel that calls another
compiled function (the 3D-RFT facet loop ``rft3d_wrench_range_kernel``) links its own, better
optimised copy of it, but in the compiling process the call resolves to the callee's stand-alone
compilation, which is not vectorised (about 3x slower; a process that loads both from the cache gets
the vectorised copy).
Compiling in a child fills the cache and leaves the calling process to load the fast code on first
use. Run as ``python -m terradyn.warmup`` it prints one JSON line per kernel.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import time
from collections.abc import Callable
from typing import Any

__all__ = ["KERNELS", "ProgressCallback", "warmup"]

ProgressCallback = Callable[[int, int, str], None]


def _rft_2d() -> None:
    from .geometry import WheelCircular
    from .kinematics import Pose2D, Twist2D
    from .materials import get
    from .rft import rft_wrench, rft_wrench_many

    ms = get("MS")
    wheel = WheelCircular(0.05, 0.02)
    rft_wrench(wheel, ms, Pose2D(0.0, 0.04, 0.0), Twist2D(0.05, 0.0, 1.0))
    rft_wrench_many(wheel, ms, [[0.0, 0.04, 0.0]] * 2, [[0.05, 0.0, 1.0]] * 2)


def _steady_2d() -> None:
    from .geometry import WheelCircular, WheelGrousered
    from .locomotion.steady import wheel_steady
    from .materials import get

    ms = get("MS")
    wheel_steady(WheelCircular(0.05, 0.02), ms, 2.0, 0.2)
    wheel_steady(WheelGrousered(0.045, 0.02, 6, 0.005, 0.003), ms, 2.0, 0.2, phase_count=2)


def _drft() -> None:
    from .geometry import WheelCircular
    from .kinematics import Pose2D, Twist2D
    from .materials import get
    from .rft import DRFTModel, drft_wrench

    drft_wrench(
        WheelCircular(0.05, 0.02), DRFTModel(get("MS")), Pose2D(0.0, 0.04, 0.0), Twist2D(0.2, 0.0, 5.0)
    )


def _rft_3d() -> None:
    import numpy as np

    from .geometry3d import Pose3D, Twist3D, wheel_cylinder
    from .materials import get
    from .rft.rft3d import rft3d_facet_tractions, rft3d_wrench, rft3d_wrench_many

    ms = get("MS")
    mesh = _small_mesh(wheel_cylinder)
    pose = Pose3D(np.array([0.0, 0.0, 0.04]), np.eye(3))
    twist = Twist3D.from_components(vx=0.05, wy=1.0)
    for parallel in (False, True):
        rft3d_wrench(mesh, ms, pose, twist, parallel=parallel)
    rot = np.tile(np.eye(3), (2, 1, 1))
    pos = np.zeros((2, 3))
    pos[:, 2] = 0.04
    lin = np.tile([0.05, 0.0, 0.0], (2, 1))
    ang = np.tile([0.0, 1.0, 0.0], (2, 1))
    rft3d_wrench_many(mesh, ms, pos, rot, lin, ang)
    c = mesh.centroids.copy()
    c[:, 2] -= 0.01
    rft3d_facet_tractions(c, mesh.normals, np.tile([0.05, 0.0, -0.01], (mesh.facet_count, 1)), xi=1e6)


def _small_mesh(wheel_cylinder: Callable[..., Any]) -> Any:
    return wheel_cylinder(0.05, 0.02, circumferential_resolution=24, axial_resolution=2, radial_resolution=1)


def _steady_3d() -> None:
    from .geometry3d import wheel_cylinder
    from .locomotion.steady3d import wheel_steady_3d
    from .materials import get

    mesh = _small_mesh(wheel_cylinder)
    wheel_steady_3d(mesh, get("MS"), 2.0, 0.2, slip_angle=math.radians(5.0))
    wheel_steady_3d(mesh, get("MS"), 2.0, 0.2, phase_count=2)


def _wong_reece() -> None:
    from .geometry import WheelCircular
    from .locomotion.steady import wheel_steady
    from .materials import get
    from .terramechanics import WongReeceModel

    wheel_steady(WheelCircular(0.13, 0.16), WongReeceModel(get("MS")), 130.0, 0.2)


def _dynamics() -> None:
    from .geometry import WheelCircular
    from .locomotion.dynamics import simulate_wheel
    from .materials import get

    for model in ("rft", "drft"):
        simulate_wheel(
            WheelCircular(0.13, 0.16), get("MS"), model=model, mass=13.0, omega=5.0, duration=0.004
        )


def _mpm() -> None:
    from .geometry import Plate
    from .materials import get
    from .mpm import run_intrusion

    run_intrusion(Plate(0.03, 0.02), get("MS"), depth=0.001, cell_size=0.005, settle_time=0.0005, speed=1.0)


#: (name, function) of every kernel family, in the order :func:`warmup` runs them.
KERNELS: tuple[tuple[str, Callable[[], None]], ...] = (
    ("rft-2d", _rft_2d),
    ("rft-2d-steady", _steady_2d),
    ("drft", _drft),
    ("rft-3d", _rft_3d),
    ("rft-3d-steady", _steady_3d),
    ("wong-reece", _wong_reece),
    ("dynamics", _dynamics),
    ("mpm", _mpm),
)


def _numba_counts() -> tuple[int, int]:
    """(cache hits, cache misses = compiles) over every numba dispatcher of terradyn loaded so far."""
    numba = sys.modules.get("numba")
    if numba is None:
        return 0, 0
    from numba.core.registry import CPUDispatcher

    hits = misses = 0
    for name, module in list(sys.modules.items()):
        if not name.startswith("terradyn.") or module is None:
            continue
        for obj in list(vars(module).values()):
            if isinstance(obj, CPUDispatcher) and getattr(obj, "__module__", "") == name:
                stats = obj.stats
                hits += sum(stats.cache_hits.values())
                misses += sum(stats.cache_misses.values())
    return hits, misses


def _run_in_process(
    progress: ProgressCallback | None, on_row: Callable[[dict[str, Any], int, int], None] | None = None
) -> list[dict[str, Any]]:
    rows: list[dict[str, Any]] = []
    total = len(KERNELS)
    for done, (name, fn) in enumerate(KERNELS, start=1):
        before = _numba_counts()
        t0 = time.perf_counter()
        fn()
        seconds = time.perf_counter() - t0
        after = _numba_counts()
        row = {
            "kernel": name,
            "seconds": seconds,
            "compiled": after[1] - before[1],
            "loaded": after[0] - before[0],
        }
        rows.append(row)
        if on_row is not None:
            on_row(row, done, total)
        if progress is not None:
            progress(done, total, name)
    return rows


def _run_isolated(progress: ProgressCallback | None) -> list[dict[str, Any]]:
    env = dict(os.environ)
    # Full optimisation in the child: every copy of a called kernel gets vectorised, so the cached code
    # is fast whichever copy a loading process links (module notes). Compile time is about the same.
    env.setdefault("NUMBA_OPT", "max")
    # The child must import this very package, wherever it was imported from.
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    env["PYTHONPATH"] = os.pathsep.join(p for p in (here, env.get("PYTHONPATH", "")) if p)
    with subprocess.Popen(
        [sys.executable, "-m", "terradyn.warmup", "--in-process"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    ) as child:
        assert child.stdout is not None and child.stderr is not None
        rows: list[dict[str, Any]] = []
        try:
            for line in child.stdout:
                if not line.startswith("{"):
                    continue
                row = json.loads(line)
                done, total = row.pop("done"), row.pop("total")
                rows.append(row)
                if progress is not None:
                    progress(done, total, row["kernel"])
            err = child.stderr.read()
            code = child.wait()
        except BaseException:  # an interrupt: stop the child too, never leave it running
            child.kill()
            child.wait()
            raise
    if code != 0:
        from .errors import SolverError

        tail = err.strip().splitlines()[-1] if err.strip() else f"exit code {code}"
        raise SolverError(f"warmup: compiling the kernels in a child process failed: {tail}")
    return rows


def warmup(*, progress: ProgressCallback | None = None, isolated: bool = True) -> list[dict[str, Any]]:
    """Compile (or load from the numba cache) every numba kernel of terradyn once.

    Parameters
    ----------
    progress : callable, optional
        Called as ``progress(done, total, name)`` after each kernel family.
    isolated : bool
        Compile in a child process (default), so that this process later loads the cached code,
        which runs faster than code compiled in-process (module notes). ``False``: compile here.

    Returns
    -------
    list of dict
        One per kernel family, in order: ``kernel`` (name), ``seconds`` (wall time of the call),
        ``compiled`` and ``loaded`` (numba compilations and cache loads it caused).
    """
    if isolated:
        try:
            return _run_isolated(progress)
        except OSError:  # no interpreter to start (a frozen application): compile here
            pass
    return _run_in_process(progress)


def _main(argv: list[str]) -> int:
    """``python -m terradyn.warmup [--in-process]``: one JSON line per kernel family."""

    def emit(row: dict[str, Any], done: int, total: int) -> None:
        print(json.dumps({**row, "done": done, "total": total}), flush=True)

    if "--in-process" in argv:
        _run_in_process(None, emit)
    else:
        for row in warmup():
            print(json.dumps(row), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(_main(sys.argv[1:]))
