"""Running independent work items serially, on local processes or on a Dask cluster.

``map_items(fn, items, scheduler=...)``: ``"serial"`` runs in this process; ``"processes"`` uses a
standard-library pool of worker processes (no extra dependency); ``"local"`` starts a
Dask ``LocalCluster`` of single-threaded worker processes bound to the loopback interface;
anything else is taken as the address of an existing Dask scheduler (``tcp://host:8786``).
``fn`` must be a module-level function and the items picklable. Results come back in item order, so
a parallel run is identical to a serial one.
"""

from __future__ import annotations

import contextvars
import os
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from typing import Any, TypeVar

from .errors import InputError

__all__ = ["map_items", "reporting"]

_REPORT: contextvars.ContextVar[Callable[[int, int], None] | None] = contextvars.ContextVar(
    "terradyn_progress", default=None
)


@contextmanager
def reporting(callback: Callable[[int, int], None]) -> Iterator[None]:
    """Inside the block every :func:`map_items` call reports ``callback(done, total)`` (items of that
    call) as items finish: how a command shows progress of a study it does not know the inside of."""
    token = _REPORT.set(callback)
    try:
        yield
    finally:
        _REPORT.reset(token)


def _with_report(total: int, on_done: Callable[[int], None] | None) -> Callable[[int], None] | None:
    report = _REPORT.get()
    if report is None:
        return on_done
    done = [0]
    report(0, total)

    def both(n: int) -> None:
        done[0] += n
        report(done[0], total)
        if on_done is not None:
            on_done(n)

    return both


def _with_item(
    on_done: Callable[[int], None] | None, on_item: Callable[[int], None] | None
) -> Callable[[int], None] | None:
    """One callback taking the finished item's index: counts one item for ``on_done`` and passes
    the index to ``on_item``."""
    if on_done is None and on_item is None:
        return None

    def finished(index: int) -> None:
        if on_done is not None:
            on_done(1)
        if on_item is not None:
            on_item(index)

    return finished


T = TypeVar("T")
R = TypeVar("R")


def map_items(
    fn: Callable[[T], R],
    items: Sequence[T],
    *,
    scheduler: str = "serial",
    workers: int | None = None,
    on_done: Callable[[int], None] | None = None,
    on_item: Callable[[int], None] | None = None,
) -> list[R]:
    """Apply ``fn`` to every item; results in item order.

    ``on_done(n)`` is called with the number of items just finished, ``on_item(i)`` with the index
    of each item as it finishes (in completion order, which differs from item order in parallel)."""
    on_done = _with_report(len(items), on_done)
    finished = _with_item(on_done, on_item)
    if scheduler == "serial":
        out = []
        for i, item in enumerate(items):
            out.append(fn(item))
            if finished is not None:
                finished(i)
        return out
    if workers is not None and not (isinstance(workers, int) and workers >= 1):
        raise InputError("workers", workers, "an integer >= 1")
    if scheduler == "processes":
        return _process_pool(fn, items, workers, finished)
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
            if finished is not None:
                finished(index[fut.key])
        return results
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def _process_pool(
    fn: Callable[[T], R], items: Sequence[T], workers: int | None, finished: Callable[[int], None] | None
) -> list[R]:
    """Standard-library process pool (spawned workers: safe with numba's threads)."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor, as_completed

    n = _worker_count(items, workers)
    results: list[Any] = [None] * len(items)
    ctx = multiprocessing.get_context("spawn")
    pool = ProcessPoolExecutor(max_workers=n, mp_context=ctx)
    try:
        futures = {pool.submit(fn, item): i for i, item in enumerate(items)}
        for fut in as_completed(futures):
            results[futures[fut]] = fut.result()
            if finished is not None:
                finished(futures[fut])
    except BaseException:  # an interrupt or a failed item: stop the workers now, do not wait for them
        workers_left = list(getattr(pool, "_processes", {}).values())
        pool.shutdown(wait=False, cancel_futures=True)
        for proc in workers_left:
            proc.terminate()
        for proc in workers_left:
            proc.join(timeout=5)
        raise
    pool.shutdown(wait=True)
    return results


def _worker_count(items: Sequence[Any], workers: int | None) -> int:
    """``workers``, or one per item up to the number of CPUs."""
    return workers or max(1, min(len(items), os.cpu_count() or 1))
