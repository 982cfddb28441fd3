"""Start-up, JIT and thread figures: what a user waits for before and around the first result.

Every figure is wall time of whole fresh processes (``subprocess``), so imports, numba cache loads and
compiles all count. Each line says which cache it ran on and how many threads:

* ``warm cache``: the numba cache of this checkout, filled first by :func:`terradyn.warmup.warmup`;
  best of ``REPEATS`` runs.
* ``cold cache``: a fresh temporary ``NUMBA_CACHE_DIR``, so every kernel the command needs compiles in
  that process; one run each (a fresh directory per command).

Sections: start-up of ``terradyn --version``, ``terradyn --help``, ``python -c "import terradyn"`` and
a one-point ``terradyn wheel steady`` (warm and cold); the cold-cache compile cost per kernel family
(``warmup()`` on a fresh cache) and the warm load cost; one steady point in 2D (circular wheel, 360
elements) and 3D (50 000-facet cylinder, MS, 80 N, 5 deg slip angle) with 1 and 2 threads
(``TERRADYN_THREADS``); a 2D force-slip sweep with 1 and 2 threads; and the in-process-compile penalty
of the 3D kernels (a process that compiles them with numba's default optimisation, against one that
loads them from a cache written by ``warmup()``).

Run alone: ``python benchmarks/bench_startup.py [--quick]`` (``--quick`` skips the cold-cache parts).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPEATS = 5
BIN = Path(sys.executable).parent
TERRADYN = str(BIN / "terradyn") if (BIN / "terradyn").exists() else None

_POINT_2D = """
import json, sys, time
from terradyn import materials
from terradyn.geometry import WheelCircular
from terradyn.locomotion import wheel_steady
wheel, ms = WheelCircular(0.13, 0.16), materials.get("MS")
t0 = time.perf_counter(); wheel_steady(wheel, ms, 130.0, 0.3); first = time.perf_counter() - t0
best = 1e9
for _ in range(5):
    n, t0 = 0, time.perf_counter()
    while time.perf_counter() - t0 < 0.2:
        wheel_steady(wheel, ms, 130.0, 0.1 + 0.5 * (n % 7) / 7); n += 1
    best = min(best, (time.perf_counter() - t0) / n)
print(json.dumps({"first_s": first, "point_s": best, "elements": wheel.discretize().element_count}))
"""

_POINT_3D = """
import json, math, time
from terradyn import materials
from terradyn.geometry3d import wheel_cylinder
from terradyn.locomotion.steady3d import wheel_steady_3d
mesh = wheel_cylinder(0.13, 0.16, circumferential_resolution=1000, axial_resolution=10, radial_resolution=2)
ms, angle = materials.get("MS"), math.radians(5.0)
t0 = time.perf_counter()
wheel_steady_3d(mesh, ms, 80.0, 0.3, slip_angle=angle)
first = time.perf_counter() - t0
best = 1e9
for _ in range(5):
    t0 = time.perf_counter()
    for s in (0.1, 0.2, 0.3, 0.4, 0.5):
        wheel_steady_3d(mesh, ms, 80.0, s, slip_angle=angle)
    best = min(best, (time.perf_counter() - t0) / 5)
print(json.dumps({"first_s": first, "point_s": best, "facets": mesh.facet_count}))
"""

_SWEEP_2D = """
import json, time
import numpy as np
from terradyn import materials
from terradyn.geometry import WheelCircular
from terradyn.locomotion import force_slip_sweep
from terradyn.locomotion.models import ModelSpec
wheel = WheelCircular(0.13, 0.16)
media = [materials.get(m) for m in ("MS", "MMS", "LPS", "CPS")]
loads, slips = [80.0, 130.0, 150.0, 190.0], list(np.linspace(-0.7, 0.7, 15))
spec = {"rft": ModelSpec("rft")}
force_slip_sweep(wheel, media[:1], spec, loads[:1], slips[:2])
best = 1e9
for _ in range(3):
    t0 = time.perf_counter(); table = force_slip_sweep(wheel, media, spec, loads, slips)
    best = min(best, time.perf_counter() - t0)
print(json.dumps({"sweep_s": best, "points": len(table)}))
"""


def _env(cache: str | None = None, threads: int | None = None, **extra: str) -> dict[str, str]:
    env = dict(os.environ)
    env.pop("TERRADYN_THREADS", None)
    if cache is not None:
        env["NUMBA_CACHE_DIR"] = cache
    if threads is not None:
        env["TERRADYN_THREADS"] = str(threads)
    env.update(extra)
    return env


def _wall(argv: list[str], env: dict[str, str], repeats: int) -> float:
    best = float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        subprocess.run(argv, env=env, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        best = min(best, time.perf_counter() - t0)
    return best


def _json(code: str, env: dict[str, str]) -> dict[str, float]:
    out = subprocess.run([sys.executable, "-c", code], env=env, check=True, capture_output=True, text=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def _commands() -> list[tuple[str, list[str]]]:
    cli = [TERRADYN] if TERRADYN else [sys.executable, "-m", "terradyn"]
    return [
        ("terradyn --version", [*cli, "--version"]),
        ("terradyn --help", [*cli, "--help"]),
        ('python -c "import terradyn"', [sys.executable, "-c", "import terradyn"]),
        ("terradyn wheel steady (1 point)", [*cli, "wheel", "steady", "--load", "130", "--slip", "0.2"]),
    ]


def _startup(quick: bool) -> None:
    print(f"-- start-up, whole process, wall time (bare interpreter for scale); warm: best of {REPEATS}")
    bare = _wall([sys.executable, "-c", "pass"], _env(), REPEATS)
    print(f"{'bare python':34s} warm {bare:7.3f} s")
    for label, argv in _commands():
        warm = _wall(argv, _env(), REPEATS)
        line = f"{label:34s} warm {warm:7.3f} s"
        if not quick:
            with tempfile.TemporaryDirectory(prefix="terradyn-bench-") as cache:
                line += f"   cold {_wall(argv, _env(cache), 1):7.3f} s"
        print(line, flush=True)


def _compile_costs() -> None:
    from terradyn.warmup import warmup

    print("-- warmup(): per kernel family, cold cache (fresh NUMBA_CACHE_DIR) then the warm load")
    with tempfile.TemporaryDirectory(prefix="terradyn-bench-") as cache:
        old = os.environ.get("NUMBA_CACHE_DIR")
        os.environ["NUMBA_CACHE_DIR"] = cache
        try:
            t0 = time.perf_counter()
            cold = warmup()
            cold_total = time.perf_counter() - t0
            t0 = time.perf_counter()
            warm = warmup()
            warm_total = time.perf_counter() - t0
        finally:
            if old is None:
                os.environ.pop("NUMBA_CACHE_DIR", None)
            else:
                os.environ["NUMBA_CACHE_DIR"] = old
    print(f"{'kernel':16s} {'cold s':>8s} {'compiles':>8s} {'warm s':>8s}")
    for c, w in zip(cold, warm, strict=True):
        print(f"{c['kernel']:16s} {c['seconds']:8.2f} {c['compiled']:8d} {w['seconds']:8.3f}")
    print(f"{'total (process)':16s} {cold_total:8.2f} {'':8s} {warm_total:8.3f}", flush=True)


def _points_and_threads() -> None:
    print("-- steady points and a 2D sweep, warm cache, fresh process per line (TERRADYN_THREADS)")
    for threads in (1, 2):
        p2 = _json(_POINT_2D, _env(threads=threads))
        p3 = _json(_POINT_3D, _env(threads=threads))
        sw = _json(_SWEEP_2D, _env(threads=threads))
        print(
            f"threads {threads}: 2D point ({p2['elements']:.0f} elements) {p2['point_s'] * 1e3:.3f} ms; "
            f"3D point ({p3['facets']:.0f} facets) {p3['point_s'] * 1e3:.2f} ms; "
            f"2D sweep {sw['points']:.0f} points {sw['sweep_s']:.3f} s",
            flush=True,
        )


def _compile_penalty() -> None:
    print("-- 3D point after compiling in-process vs loading from the cache (1 thread)")
    rows = []
    with tempfile.TemporaryDirectory(prefix="terradyn-bench-") as cache:
        env = _env(cache, threads=1)
        env.pop("NUMBA_OPT", None)
        rows.append(("compiles in-process (numba default opt)", _json(_POINT_3D, env)))
        rows.append(("loads that cache", _json(_POINT_3D, env)))
    with tempfile.TemporaryDirectory(prefix="terradyn-bench-") as cache:
        env = _env(cache, threads=1)
        env.pop("NUMBA_OPT", None)
        subprocess.run(
            [sys.executable, "-m", "terradyn.warmup"], env=env, check=True, stdout=subprocess.DEVNULL
        )
        rows.append(("loads a cache written by warmup()", _json(_POINT_3D, env)))
    for label, r in rows:
        print(f"{label:42s} first call {r['first_s']:6.2f} s, then {r['point_s'] * 1e3:6.2f} ms per point")


def main() -> None:
    quick = "--quick" in sys.argv
    from terradyn.warmup import warmup

    warmup()  # the warm cache of this checkout
    _startup(quick)
    if not quick:
        _compile_costs()
    _points_and_threads()
    if not quick:
        _compile_penalty()


if __name__ == "__main__":
    main()
