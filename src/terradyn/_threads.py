"""How many threads terradyn's compiled (numba ``parallel=True``) kernels use.

:func:`set_threads` is the library knob (the CLI's ``--threads``); the environment variable
``TERRADYN_THREADS`` sets the same at ``import terradyn``. Before numba is imported the count goes to
``NUMBA_NUM_THREADS`` (the size of numba's thread pool, inherited by worker processes); afterwards it
goes to :func:`numba.set_num_threads` (at most the pool size). numba itself is never imported here.

Idle worker threads sleep instead of spinning: ``import terradyn`` sets ``OMP_WAIT_POLICY=PASSIVE``
unless it is set already (it takes effect if no OpenMP runtime has started yet). With GNU OpenMP's
default (spin, then sleep) a parallel kernel on a machine whose other cores are busy waits for a
worker that has no core: the 3D steady scan took 16 ms on 2 threads against 3 ms on 1; with passive
waiting 2 threads are never slower than 1 (``benchmarks/bench_startup.py`` prints both).
"""

from __future__ import annotations

import os
import sys

from .errors import InputError

__all__ = ["ENVIRONMENT_VARIABLE", "apply_environment", "get_threads", "set_threads"]

#: Environment variable read at ``import terradyn``: a thread count >= 1.
ENVIRONMENT_VARIABLE = "TERRADYN_THREADS"


def _check(n: object, field: str) -> int:
    if isinstance(n, bool) or not isinstance(n, int):
        try:
            value = int(str(n).strip())
        except ValueError:
            raise InputError(field, n, "a whole number of threads >= 1") from None
    else:
        value = n
    if value < 1:
        raise InputError(field, n, "a whole number of threads >= 1")
    return value


def set_threads(n: int) -> int:
    """Use ``n`` threads (>= 1) in the parallel kernels; returns the count now in effect.

    Before numba is loaded this sizes its thread pool (``NUMBA_NUM_THREADS``), so any count works;
    after, ``n`` may not exceed the pool numba started with (its error names the limit).
    """
    count = _check(n, "threads")
    numba = sys.modules.get("numba")
    if numba is None:
        os.environ["NUMBA_NUM_THREADS"] = str(count)
        return count
    limit = int(numba.config.NUMBA_NUM_THREADS)
    if count > limit:
        raise InputError(
            "threads", n, f"at most {limit}", "numba's thread pool was started with that many threads"
        )
    numba.set_num_threads(count)
    return count


def get_threads() -> int:
    """Threads the parallel kernels use now (numba's count, or the pool size it will start with)."""
    numba = sys.modules.get("numba")
    if numba is not None:
        return int(numba.get_num_threads())
    value = os.environ.get("NUMBA_NUM_THREADS", "").strip()
    return int(value) if value.isdigit() and int(value) > 0 else max(1, os.cpu_count() or 1)


def apply_environment() -> int | None:
    """Apply ``TERRADYN_THREADS`` if it is set (called by ``import terradyn``); returns the count.

    A bad value is ignored with a :class:`RuntimeWarning` naming the variable.

    Also makes idle OpenMP workers sleep (``OMP_WAIT_POLICY=PASSIVE``) unless the variable is set.
    """
    os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")
    value = os.environ.get(ENVIRONMENT_VARIABLE, "").strip()
    if not value:
        return None
    try:
        return set_threads(_check(value, ENVIRONMENT_VARIABLE))
    except InputError as exc:  # never fail ``import terradyn`` (the CLI could not report it)
        import warnings

        warnings.warn(f"{exc}; using numba's default thread count", RuntimeWarning, stacklevel=2)
        return None
