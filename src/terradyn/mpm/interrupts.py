"""Interrupts of MPM runs: the exception a stopped run raises, and the guard that holds SIGINT/SIGTERM
back while a chunk of steps brings the state to a consistent point."""

from __future__ import annotations

import signal
import threading
from collections.abc import Callable
from pathlib import Path
from types import FrameType, TracebackType
from typing import Any

__all__ = ["RunInterrupted"]


class RunInterrupted(KeyboardInterrupt):
    """A run stopped by an interrupt (SIGINT, or SIGTERM if the caller maps it to KeyboardInterrupt).

    Attributes
    ----------
    time_s : simulated time [s] of the last consistent state (the end of the last completed chunk)
    step, total_steps : its step and the steps of the whole run
    checkpoint_path : the checkpoint now holding that state, or None (no ``checkpoint_path`` was set,
        or writing it failed)
    failure : why the checkpoint could not be written ("" if it was, or none was asked for); an
        earlier checkpoint of the run, if any, is then still in place
    """

    def __init__(
        self,
        time_s: float,
        step: int,
        total_steps: int,
        checkpoint_path: Path | None,
        failure: str = "",
    ) -> None:
        self.time_s = float(time_s)
        self.step = int(step)
        self.total_steps = int(total_steps)
        self.checkpoint_path = checkpoint_path
        self.failure = failure
        where = f"interrupted at t = {self.time_s:.6g} s (step {self.step} of {self.total_steps})"
        if failure:
            tail = f"{failure}; an earlier checkpoint, if any, is kept"
        elif checkpoint_path is None:
            tail = "no checkpoint written (set checkpoint_path to keep the work of an interrupted run)"
        else:
            tail = f"checkpoint written to {checkpoint_path}; rerun with resume to continue"
        super().__init__(f"{where}; {tail}")

    def __reduce__(self) -> tuple[Any, ...]:
        return (type(self), (self.time_s, self.step, self.total_steps, self.checkpoint_path, self.failure))


#: Signals whose Python handlers :class:`_HeldInterrupts` holds back.
_HELD_SIGNALS = tuple(
    s for s in (getattr(signal, "SIGINT", None), getattr(signal, "SIGTERM", None)) if s is not None
)


class _HeldInterrupts:
    """Hold back SIGINT/SIGTERM handlers during a block that must not stop half-way.

    A KeyboardInterrupt raised between two Python statements of a chunk (say after the compiled
    steps updated the particles in place but before the step counter moved) would leave a state that
    cannot be saved. Inside the block the Python-level handlers only note the signal; on a normal exit
    the first noted signal is handed to its original handler (which raises KeyboardInterrupt, or
    whatever the caller installed), now at a consistent point. With ``deliver=False`` noted signals
    are dropped (used while writing the checkpoint of an interrupted run). Only the main thread
    receives signals; elsewhere this does nothing.
    """

    def __init__(self, *, deliver: bool = True) -> None:
        self.deliver = deliver
        self._old: dict[int, Callable[[int, FrameType | None], Any]] = {}
        self._noted: list[tuple[int, FrameType | None]] = []
        self._active = False

    def _note(self, signum: int, frame: FrameType | None) -> None:
        if self._active:
            self._noted.append((signum, frame))
        else:  # a signal after the block ended but before the handler was put back
            self._old[signum](signum, frame)

    def __enter__(self) -> _HeldInterrupts:
        if threading.current_thread() is threading.main_thread():
            for sig in _HELD_SIGNALS:
                old = signal.getsignal(sig)
                if callable(old):
                    self._old[sig] = old
                    signal.signal(sig, self._note)
            self._active = True
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self._active = False
        for sig, old in self._old.items():
            signal.signal(sig, old)
        if self._noted and exc_type is None and self.deliver:
            signum, frame = self._noted[0]
            self._old[signum](signum, frame)
