"""Errors raised by terradyn.

Every error a user can cause is an :class:`InputError`: it names the field, the value given, what is
allowed and, where useful, a hint. The CLI prints its message as one line and exits non-zero.
"""

from __future__ import annotations

import math
import os
from enum import IntEnum
from typing import Any

__all__ = [
    "ChecksFailed",
    "ExitCode",
    "InputError",
    "SolverError",
    "TerradynError",
    "check_finite",
    "check_length",
    "check_positive",
    "check_range",
]


class ExitCode(IntEnum):
    """Exit status of the ``terradyn`` command (documented in the README)."""

    OK = 0
    INPUT = 1  #: bad input: a flag, field or file the user gave
    USAGE = 2  #: the command line itself: unknown command or flag, missing argument
    SOLVER = 3  #: valid input without an answer (load the medium cannot carry, unstable run)
    CHECKS_FAILED = 4  #: ``terradyn validate`` ran and a check failed
    INTERNAL = 70  #: a bug in terradyn (EX_SOFTWARE)
    INTERRUPTED = 130  #: stopped by Ctrl-C (SIGINT)
    TERMINATED = 143  #: stopped by SIGTERM


class TerradynError(Exception):
    """Base class of every error terradyn raises on purpose."""

    exit_code: int = ExitCode.INPUT


def show_value(value: Any) -> str:
    """A value as a user would have typed it: no Python reprs (paths, NumPy scalars, tuples)."""
    if isinstance(value, os.PathLike):
        value = os.fspath(value)
    if hasattr(value, "item") and not isinstance(value, str | bytes):
        try:
            value = value.item()
        except (TypeError, ValueError):
            return str(value)
    if isinstance(value, bool) or value is None:
        return str(value).lower() if value is not None else "none"
    if isinstance(value, float):
        return f"{value:g}" if math.isfinite(value) else str(value)
    if isinstance(value, tuple | list):
        return ", ".join(show_value(v) for v in value)
    if hasattr(value, "value") and isinstance(getattr(value, "value", None), str):  # an Enum member
        return repr(value.value)
    text = repr(value) if isinstance(value, str) else str(value)
    return text if len(text) <= 90 else text[:60] + "..." + text[-20:]


class InputError(TerradynError, ValueError):
    """A bad input: names the field, the value, what is allowed and a hint."""

    exit_code = ExitCode.INPUT

    def __init__(self, field: str, value: Any, allowed: str, hint: str = "") -> None:
        self.field = field
        self.value = value
        self.allowed = allowed
        self.hint = hint
        super().__init__(self.render())

    def render(self, field: str | None = None, value: Any = None) -> str:
        """The one-line message, optionally naming the field as ``field`` (e.g. a CLI flag)."""
        shown = show_value(self.value if value is None else value)
        msg = f"{field or self.field} = {shown} is not allowed; expected {self.allowed}"
        if self.hint:
            msg += f" ({self.hint})"
        return " ".join(msg.split())


class SolverError(TerradynError, RuntimeError):
    """A solve that has no answer for valid inputs (e.g. a load the medium cannot carry)."""

    exit_code = ExitCode.SOLVER


class ChecksFailed(TerradynError):
    """Model checks ran and at least one failed (``terradyn validate``)."""

    exit_code = ExitCode.CHECKS_FAILED


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


#: largest body dimension terradyn accepts [m]: far beyond any wheel, leg or plate, and small enough
#: that discretising it can never overflow
MAX_LENGTH_M = 100.0


def check_length(field: str, value: float, *, allow_zero: bool = False) -> float:
    """Return ``value`` as float if it is a body dimension in (0, 100] m ([0, 100] with ``allow_zero``)."""
    v = check_positive(field, value, allow_zero=allow_zero)
    if v > MAX_LENGTH_M:
        low = "0 <=" if allow_zero else "0 <"
        raise InputError(field, value, f"a length with {low} value <= {MAX_LENGTH_M:g} [m]")
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
