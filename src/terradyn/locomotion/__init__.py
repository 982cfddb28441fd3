"""Drivers: one wheel-run contract over every engine (:func:`run_wheel`), steady (quasi-static) wheel
solves, time integration and sweeps over any terrain model."""

from typing import Any

from .steady import (
    WheelSteadyResult,
    wheel_nominal_radius,
    wheel_self_propelled,
    wheel_steady,
)
from .sweeps import force_slip_sweep
from .wheel_case import DEMSettings, Dynamics, Engine, MPMSettings, QuasiStatic, WheelCase, WheelRun
from .wheel_run import compare_models, run_wheel


def __getattr__(name: str) -> Any:
    """Lazy access to the time integrator (its numba kernels load on first use)."""
    if name in ("simulate_wheel", "stable_time_step", "WheelDynamicsResult"):
        from . import dynamics

        return getattr(dynamics, name)
    if name in ("simulate_coupled", "CoupledResult"):
        from . import coupled

        return getattr(coupled, name)
    if name in ("wheel_steady_3d", "sweep_3d", "WheelSteady3DResult"):
        from . import steady3d

        return getattr(steady3d, name)
    raise AttributeError(name)


__all__ = [
    "CoupledResult",
    "DEMSettings",
    "Dynamics",
    "Engine",
    "MPMSettings",
    "QuasiStatic",
    "WheelCase",
    "WheelDynamicsResult",
    "WheelRun",
    "WheelSteady3DResult",
    "WheelSteadyResult",
    "compare_models",
    "force_slip_sweep",
    "run_wheel",
    "simulate_coupled",
    "simulate_wheel",
    "stable_time_step",
    "sweep_3d",
    "wheel_nominal_radius",
    "wheel_self_propelled",
    "wheel_steady",
    "wheel_steady_3d",
]
