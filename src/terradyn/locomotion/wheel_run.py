"""One call for one wheel case through any model or engine: :func:`run_wheel` and :func:`compare_models`.

The case, the settings and the result are in :mod:`terradyn.locomotion.wheel_case` (exported by
:mod:`terradyn.locomotion`);
the engines' adapters in :mod:`terradyn.locomotion._wheel_engines`.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ..errors import InputError
from ..models import ModelKind, model_entry
from . import _wheel_engines as engines
from .wheel_case import (
    DEMSettings,
    Dynamics,
    MPMSettings,
    QuasiStatic,
    Settings,
    WheelCase,
    WheelRun,
)

__all__ = ["compare_models", "run_wheel"]


def run_wheel(
    case: WheelCase,
    model: Any = "rft",
    *,
    settings: Settings | None = None,
    progress: Callable[[float, float], None] | None = None,
) -> WheelRun:
    """Run ``case`` through ``model`` (a model-table name or a user's terrain model) with ``settings``
    (:class:`QuasiStatic` by default for force laws; :class:`MPMSettings` / :class:`DEMSettings` for
    the engines). ``progress(simulated_time, fraction)`` reports time-stepped runs. A model that
    cannot run the case (a 2D law with a slip angle, a torque in a steady solve, a free wheel in the
    DEM...) raises :class:`~terradyn.errors.InputError` naming the field."""
    if not isinstance(case, WheelCase):
        raise InputError("case", type(case).__name__, "a terradyn.locomotion.WheelCase")
    name = model.strip().lower() if isinstance(model, str) else None
    entry = model_entry(model, use="run-wheel") if name is not None else None
    if entry is not None and entry.kind is ModelKind.ENGINE:
        if entry.name == "mpm":
            return engines.run_mpm(case, _settings(settings, MPMSettings, "mpm"), progress)
        return engines.run_dem(case, _settings(settings, DEMSettings, "dem"), progress)
    if isinstance(settings, Dynamics):
        return engines.run_dynamics(case, model, entry, settings, progress)
    return engines.run_quasi_static(case, model, entry, _settings(settings, QuasiStatic, "a force law"))


def _settings(settings: Any, kind: type, what: str) -> Any:
    if settings is None:
        return kind()
    if not isinstance(settings, kind):
        raise InputError("settings", type(settings).__name__, f"a {kind.__name__} (or None) for {what}")
    return settings


def compare_models(
    case: WheelCase,
    models: Any,
    *,
    settings: dict[str, Settings] | None = None,
    progress: Callable[[str, int, int], None] | None = None,
) -> list[WheelRun]:
    """:func:`run_wheel` of one case through each of ``models`` (names or model objects), with the
    settings ``settings[name]`` where given; ``progress(name, done, total)`` after each."""
    models = list(models)
    settings = dict(settings or {})
    out = []
    for k, m in enumerate(models):
        key = m if isinstance(m, str) else str(getattr(m, "name", k))
        out.append(run_wheel(case, m, settings=settings.get(key)))
        if progress is not None:
            progress(key, k + 1, len(models))
    return out
