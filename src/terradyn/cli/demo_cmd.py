"""``terradyn demo``: compile the kernels, then run the built-in default study into a folder."""

from __future__ import annotations

import typer

from .options import OUT_FOLDER_HELP, out_folder


def demo(
    out: str = typer.Option("terradyn-demo", "--out", help=OUT_FOLDER_HELP),
) -> None:
    """Run the headline study (rigid wheel force-slip, RFT vs Wong-Reece) and write tables and plots."""
    from ..studies.demo import run_demo
    from ._common import progress

    folder = out_folder("--out", out)
    assert folder is not None
    with progress(1, "terradyn demo") as advance:
        run_demo(folder)
        advance(1)
