"""``terradyn warmup``: compile (or load from the cache) every numerical kernel once."""

from __future__ import annotations

from ._common import OutputFormat, emit, fraction_progress
from .options import FORMAT, OUT, out_file


def warmup(
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
) -> None:
    """Compile and cache every numba kernel so that later commands start fast; prints seconds per kernel."""
    from ..warmup import warmup as run_warmup

    out_path = out_file("--out", out)
    with fraction_progress("compiling kernels", "kernels") as update:
        rows = run_warmup(progress=lambda done, total, name: update(done, done / max(1, total)))
    emit(rows, fmt, out_path, title="terradyn warmup")
