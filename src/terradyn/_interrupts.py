"""A record of Ctrl-C and SIGTERM that survives code which swallows the exception.

The command line's signal handlers raise ``KeyboardInterrupt``; raised inside a callback that C code
makes into Python (measured: numba's object-cache callback in llvmlite while a kernel is compiled and
cached, about 0.4 s after start on a fresh cache) the exception is printed as "Exception ignored" and
dropped, and the run went on to exit 0. The handlers also note the interrupt here, so the command line
can still end the run as interrupted, and :func:`terradyn.io.output_set` refuses to commit outputs.
Standard library only: imported at start-up.
"""

from __future__ import annotations

__all__ = ["interrupt_seen", "note_interrupt", "raise_if_interrupted", "reset_interrupts"]

_seen = False


def note_interrupt() -> None:
    """Record that an interrupt (SIGINT or SIGTERM) was delivered to this process."""
    global _seen
    _seen = True


def interrupt_seen() -> bool:
    """Whether an interrupt was delivered since the last :func:`reset_interrupts`."""
    return _seen


def reset_interrupts() -> None:
    """Forget earlier interrupts (the start of a command)."""
    global _seen
    _seen = False


def raise_if_interrupted() -> None:
    """Raise ``KeyboardInterrupt`` if an interrupt was delivered, even one that was swallowed."""
    if _seen:
        raise KeyboardInterrupt
