"""terradyn: locomotion and intrusion in dry granular media.

Granular resistive force theory (RFT) on arbitrary plane bodies, classical terramechanics, a
plane-strain MPM continuum solver and the studies built on them. SI units throughout.

``import terradyn`` is cheap: the subpackages (and numba, scipy, matplotlib, pandas behind them) load
on first attribute access, so ``terradyn.materials.get("MS")`` and ``from terradyn import rft`` work
as if they had been imported up front. :func:`set_threads` (or the environment variable
``TERRADYN_THREADS``) sets how many threads the compiled kernels use; :func:`terradyn.warmup.warmup`
compiles every kernel into the numba cache.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from ._threads import apply_environment, get_threads, set_threads
from ._version import __version__

# Subpackages and modules loaded on first access (``terradyn.<name>``).
_SUBMODULES = frozenset(
    {
        "errors",
        "geometry",
        "geometry3d",
        "io",
        "kinematics",
        "locomotion",
        "materials",
        "mpm",
        "optimize",
        "parallel",
        "plasticity",
        "plotting",
        "results",
        "rft",
        "scaling",
        "studies",
        "terrain",
        "terramechanics",
        "units",
        "warmup",
    }
)

__all__ = ["__version__", "get_threads", "set_threads", *sorted(_SUBMODULES)]

if TYPE_CHECKING:  # pragma: no cover - for type checkers and IDEs only
    from . import errors as errors
    from . import geometry as geometry
    from . import geometry3d as geometry3d
    from . import kinematics as kinematics
    from . import locomotion as locomotion
    from . import materials as materials
    from . import mpm as mpm
    from . import optimize as optimize
    from . import parallel as parallel
    from . import plotting as plotting
    from . import results as results
    from . import rft as rft
    from . import scaling as scaling
    from . import studies as studies
    from . import terrain as terrain
    from . import terramechanics as terramechanics
    from . import units as units
    from . import warmup as warmup


def __getattr__(name: str) -> Any:
    """Import ``terradyn.<name>`` on first use (PEP 562)."""
    if name in _SUBMODULES:
        module = importlib.import_module(f"{__name__}.{name}")
        globals()[name] = module
        return module
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *_SUBMODULES})


apply_environment()
