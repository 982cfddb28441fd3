"""Drivers: steady (quasi-static) wheel solves and sweeps over any terrain model."""

from .steady import (
    WheelSteadyResult,
    wheel_nominal_radius,
    wheel_self_propelled,
    wheel_steady,
)
from .sweeps import force_slip_sweep

__all__ = [
    "WheelSteadyResult",
    "force_slip_sweep",
    "wheel_nominal_radius",
    "wheel_self_propelled",
    "wheel_steady",
]
