"""Errors raised by terradyn.

Every error a user can cause is an :class:`InputError`: it names the field, the value given, what is
allowed and, where useful, a hint. The CLI prints its message as one line and exits non-zero.
"""

from __future__ import annotations

import math
from typing import Any

__all__ = [
    "InputError",
    "SolverError",
    "TerradynError",
    "check_finite",
    "check_positive",
    "check_range",
]


class TerradynError(Exception):
    """Base class of every error terradyn raises on purpose."""

    exit_code = 1


class InputError(TerradynError, ValueError):
    """A bad input: names the field, the value, what is allowed and a hint."""

    exit_code = 2

    def __init__(self, field: str, value: Any, allowed: str, hint: str = "") -> None:
        self.field = field
        self.value = value
        self.allowed = allowed
        self.hint = hint
        msg = f"{field} = {value!r} is not allowed; expected {allowed}"
        if hint:
            msg += f" ({hint})"
        super().__init__(msg)


class SolverError(TerradynError, RuntimeError):
    """A solve that has no answer for valid inputs (e.g. a load the medium cannot carry)."""

    exit_code = 3


def check_finite(field: str, value: float) -> float:
    """Return ``value`` as float, or raise :class:`InputError` if it is not a finite number."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(field, value, "a finite number") from None
    if not math.isfinite(v):
        raise InputError(field, value, "a finite number")
    return v


def check_positive(field: str, value: float, *, allow_zero: bool = False) -> float:
    """Return ``value`` as float if it is finite and > 0 (>= 0 with ``allow_zero``)."""
    v = check_finite(field, value)
    if v < 0 or (v == 0 and not allow_zero):
        raise InputError(field, value, "a number >= 0" if allow_zero else "a number > 0")
    return v


def check_range(
    field: str,
    value: float,
    low: float,
    high: float,
    *,
    unit: str = "",
    hint: str = "",
) -> float:
    """Return ``value`` as float if it is finite and in the closed range [low, high]."""
    v = check_finite(field, value)
    if not (low <= v <= high):
        u = f" {unit}" if unit else ""
        raise InputError(field, value, f"a number in [{low:g}, {high:g}]{u}", hint)
    return v
