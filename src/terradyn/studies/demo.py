"""The built-in default study run by ``make demo`` / ``terradyn demo``."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from .. import materials
from ..errors import InputError
from ..geometry import Plate

__all__ = ["run_demo"]


def run_demo(out: Path) -> list[Path]:
    """Plate intrusion in every shipped medium with RFT: table, plot and summary. Returns files."""
    from ..cli._common import OutputFormat, format_output, save_figure
    from ..plotting import plot_force_depth
    from .intrusion import intrusion_forces

    out = Path(out)
    if out.exists() and not out.is_dir():
        raise InputError("--out", str(out), "a folder path")
    out.mkdir(parents=True, exist_ok=True)
    plate = Plate(0.05, 0.02)
    depths = np.linspace(0.0, 0.1, 21)
    frames, summary = [], []
    ax = None
    for name in materials.available():
        mat = materials.get(name)
        table = intrusion_forces(plate, mat, depths)
        df = table.to_dataframe()
        df.insert(0, "material", name)
        frames.append(df)
        ax = plot_force_depth(depths, {name: table.columns["force_z_N"]}, ax=ax)
        summary.append({"material": name, "force_z_at_0.1m_N": float(table.columns["force_z_N"][-1])})
    import pandas as pd

    from ..cli._common import atomic_write_text

    files = [atomic_write_text(out / "plate_intrusion.csv", pd.concat(frames).to_csv(index=False))]
    assert ax is not None
    ax.set_title("RFT: 50 mm x 20 mm plate pushed straight down")
    files.append(save_figure(ax.figure, out / "plate_intrusion.png"))
    sys.stdout.write(format_output(summary, OutputFormat.table, title="terradyn demo"))
    sys.stdout.write(f"wrote {', '.join(str(f) for f in files)}\n")
    return files
