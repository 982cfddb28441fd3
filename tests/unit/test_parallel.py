"""map_items: the parallel schedulers return what the serial one does, in item order."""

from __future__ import annotations

import math

import pytest

from terradyn.errors import InputError
from terradyn.parallel import map_items


def test_process_pool_matches_serial_in_order():
    items = [float(k) for k in range(7)]
    done = []
    serial = map_items(math.sqrt, items)
    pooled = map_items(math.sqrt, items, scheduler="processes", workers=2, on_done=done.append)
    assert pooled == serial
    assert sum(done) == len(items)


@pytest.mark.parametrize("workers", [0, -1, 1.5])
def test_bad_worker_count_is_rejected(workers):
    with pytest.raises(InputError, match="workers"):
        map_items(abs, [1], scheduler="processes", workers=workers)


def test_unknown_scheduler_is_named():
    pytest.importorskip("dask.distributed")
    with pytest.raises(InputError, match="scheduler"):
        map_items(abs, [1], scheduler="nowhere")
