import numpy as np
import pytest

from terradyn import materials
from terradyn.geometry import WheelCircular
from terradyn.locomotion import force_slip_sweep
from terradyn.locomotion.models import ModelSpec


def test_local_dask_cluster_equals_serial():
    pytest.importorskip("dask.distributed")
    wheel = WheelCircular(0.13, 0.16)
    media = [materials.get("MS"), materials.get("LPS")]
    models = {"rft": ModelSpec("rft")}
    kwargs = dict(loads=[80.0, 190.0], slips=[-0.3, 0.0, 0.4])
    serial = force_slip_sweep(wheel, media, models, **kwargs)
    local = force_slip_sweep(wheel, media, models, scheduler="local", workers=2, **kwargs)
    for key, col in serial.columns.items():
        np.testing.assert_array_equal(local.columns[key], col)
