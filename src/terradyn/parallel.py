"""Running independent work items serially, on local processes or on a Dask cluster.

``map_items(fn, items, scheduler=...)``: ``"serial"`` runs in this process; ``"processes"`` uses a
standard-library pool of worker processes (no extra dependency); ``"local"`` starts a
Dask ``LocalCluster`` of single-threaded worker processes bound to the loopback interface;
anything else is taken as the address of an existing Dask scheduler (``tcp://host:8786``).
``fn`` must be a module-level function and the items picklable. Results come back in item order, so
a parallel run is identical to a serial one.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from typing import Any, TypeVar

from .errors import InputError

__all__ = ["map_items"]

T = TypeVar("T")
R = TypeVar("R")


def map_items(
    fn: Callable[[T], R],
    items: Sequence[T],
    *,
    scheduler: str = "serial",
    workers: int | None = None,
    on_done: Callable[[int], None] | None = None,
) -> list[R]:
    """Apply ``fn`` to every item; results in item order."""
    if scheduler == "serial":
        out = []
        for item in items:
            out.append(fn(item))
            if on_done is not None:
                on_done(1)
        return out
    if workers is not None and not (isinstance(workers, int) and workers >= 1):
        raise InputError("workers", workers, "an integer >= 1")
    if scheduler == "processes":
        return _process_pool(fn, items, workers, on_done)
    try:
        from dask.distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise InputError(
            "scheduler",
            scheduler,
            "'serial' or 'processes' unless dask is installed",
            "pip install 'terradyn[cluster]'",
        ) from None
    cluster: Any = None
    if scheduler == "local":
        n = _worker_count(items, workers)
        cluster = LocalCluster(
            n_workers=n,
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address=None,
            silence_logs=40,
        )
        client = Client(cluster)
    else:
        if "://" not in scheduler:
            raise InputError(
                "scheduler", scheduler, "'serial', 'processes', 'local' or an address like tcp://host:8786"
            )
        try:
            client = Client(scheduler, timeout="10s")
        except OSError as exc:
            raise InputError("scheduler", scheduler, "a reachable Dask scheduler", str(exc)) from None
    try:
        futures = client.map(fn, list(items), pure=False)
        index = {f.key: i for i, f in enumerate(futures)}
        results: list[Any] = [None] * len(futures)
        for fut in as_completed(futures):
            results[index[fut.key]] = fut.result()
            if on_done is not None:
                on_done(1)
        return results
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def _process_pool(
    fn: Callable[[T], R], items: Sequence[T], workers: int | None, on_done: Callable[[int], None] | None
) -> list[R]:
    """Standard-library process pool (spawned workers: safe with numba's threads)."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor, as_completed

    n = _worker_count(items, workers)
    results: list[Any] = [None] * len(items)
    ctx = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(max_workers=n, mp_context=ctx) as pool:
        futures = {pool.submit(fn, item): i for i, item in enumerate(items)}
        for fut in as_completed(futures):
            results[futures[fut]] = fut.result()
            if on_done is not None:
                on_done(1)
    return results


def _worker_count(items: Sequence[Any], workers: int | None) -> int:
    """``workers``, or one per item up to the number of CPUs."""
    return workers or max(1, min(len(items), os.cpu_count() or 1))
