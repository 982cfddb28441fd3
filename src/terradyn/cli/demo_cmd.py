"""``terradyn demo``: compile the kernels, then run the built-in default study into a folder."""

from __future__ import annotations

import typer

from .options import OUT_FOLDER_HELP, out_folder


def demo(
    out: str = typer.Option("terradyn-demo", "--out", help=OUT_FOLDER_HELP),
) -> None:
    """Run the headline study (rigid wheel force-slip, RFT vs Wong-Reece) and write tables and plots."""
    from ..parallel import reporting
    from ..studies.demo import run_demo
    from ._common import fraction_progress

    folder = out_folder("--out", out)
    assert folder is not None
    with fraction_progress("terradyn demo", "points") as update:
        with reporting(lambda done, total: update(done, done / max(1, total))):
            run_demo(folder)
