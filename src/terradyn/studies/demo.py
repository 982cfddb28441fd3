"""The built-in default study run by ``make demo`` / ``terradyn demo``.

The headline result of the thesis as one command: the 0.26 m x 0.16 m rigid wheel of Agarwal et al.
(2019) on MS, MMS, LPS and CPS at 80, 130, 150 and 190 N, slip -0.7 to 0.7, with RFT and Wong-Reece.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

__all__ = ["run_demo"]


def run_demo(out: Path) -> list[Path]:
    """Run the wheel force-slip study; write CSV and PNG files to ``out``; print a summary."""
    from ..io import OutputFormat, check_output_folder, format_output, output_set
    from .registry import run_study

    out = check_output_folder("out", out)
    t0 = time.perf_counter()
    _, result = run_study("wheel-force-slip")
    elapsed = time.perf_counter() - t0
    with output_set() as outs:
        outs.folder(out)
        files = _write(result, out)
        outs.print(
            format_output(
                result.summary,
                OutputFormat.table,
                title="terradyn demo: rigid wheel, RFT vs Wong-Reece (slip 0.3)",
            )
        )
        outs.print(f"computed in {elapsed:.2f} s; wrote {', '.join(str(f) for f in files)}\n")
    return files


def _write(result: Any, out: Path) -> list[Path]:
    from ..io import atomic_write_text, save_figure

    files = []
    for name, table in result.tables.items():
        files.append(atomic_write_text(out / f"{name}.csv", table.to_dataframe().to_csv(index=False)))
        failures = table.metadata.get("failures", [])
        if failures:
            files.append(atomic_write_text(out / f"{name}_unsolved.txt", "\n".join(failures) + "\n"))
    files.append(atomic_write_text(out / "summary.csv", _summary_csv(result.summary)))
    for name, fig in result.figures.items():
        files.append(save_figure(fig, out / f"{name}.png"))
    return files


def _summary_csv(rows: list[dict[str, object]]) -> str:
    from ..io import OutputFormat, format_output

    keys: list[str] = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    return format_output([{k: r.get(k, "") for k in keys} for r in rows], OutputFormat.csv)
