"""``terradyn validate``: run the built-in model checks; exit code 4 if any fails."""

from __future__ import annotations

from ..errors import ChecksFailed
from ._common import OutputFormat, emit, spinner
from .options import FORMAT, OUT, out_file


def validate(
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
) -> None:
    """Check the models against their invariants and reference values (exit code 4 if one fails)."""
    from ..io import current_output_set
    from ..studies.validation import run_checks

    out_path = out_file("--out", out)
    with spinner("terradyn validate"):
        checks = run_checks()
    rows = [c.record() for c in checks]
    if fmt is OutputFormat.table:
        rows = [{k: v for k, v in r.items() if k != "about"} for r in rows]
    emit(rows, fmt, out_path, title="terradyn validate")
    failed = [c.name for c in checks if not c.passed]
    if failed:
        outs = current_output_set()
        if outs is not None:  # the report itself is the output: keep it, then fail
            outs.commit()
        raise ChecksFailed(f"{len(failed)} check(s) failed: {', '.join(failed)}")
