"""``terradyn intrude BODY``: RFT force on a body moving through the medium at given depths."""

from __future__ import annotations

import math
from typing import Any

import typer

from .. import materials
from ..errors import check_finite
from ..kinematics import Pose2D, Twist2D
from ..studies.intrusion import intrusion_forces
from ._bodies import BODY_SIZE_FLAGS, BodyKind, BodyOptions, build_body
from ._common import OutputFormat, emit, parse_float_list, save_figure
from .options import (
    ANGLE,
    DIRECTION,
    ELEMENT_SIZE,
    FORMAT,
    MATERIAL,
    OUT,
    PLOT,
    out_file,
    plot_file,
    with_flags,
)


@with_flags("sizes", BODY_SIZE_FLAGS)
def intrude(
    body: BodyKind = typer.Argument(..., help="Body shape."),
    depth: str = typer.Option(..., "--depth", help="Depth of the body origin [m]: 0.03, list or a:b:n."),
    angle: float = ANGLE,
    direction: float = DIRECTION,
    material: str = MATERIAL,
    element_size: float | None = ELEMENT_SIZE,
    width: float = BodyOptions.width,
    sizes: dict[str, Any] = {},  # the body size flags (BODY_SIZE_FLAGS)  # noqa: B006
    fmt: OutputFormat = FORMAT,
    out: str | None = OUT,
    plot: str | None = PLOT,
) -> None:
    """RFT force [N] and torque [N m] on BODY moving through the medium (quasi-static).

    With one depth --plot draws the per-element tractions; with several, force against depth."""
    out_path, plot_path = out_file("--out", out), plot_file("--plot", plot)
    depths = parse_float_list("--depth", depth)
    shape = build_body(body, width, **sizes)
    mat = materials.get(material)
    theta = math.radians(check_finite("--angle", angle))
    direc = math.radians(check_finite("--direction", direction))
    table = intrusion_forces(shape, mat, depths, angle=theta, direction=direc, element_size=element_size)
    if plot_path is not None:
        _plot(shape, mat, table, depths, theta, direc, element_size, plot_path)
    rows = table.records()
    if len(rows) == 1:
        rec = rows[0]
        emit({k: rec[k] for k in ("force_x_N", "force_z_N", "torque_y_Nm")}, fmt, out_path)
    else:
        emit(rows, fmt, out_path, title=f"{body.value} in {mat.name}")


def _plot(shape, mat, table, depths, theta, direc, element_size, path):
    import numpy as np

    from ..kinematics import to_world
    from ..plotting import plot_body_tractions, plot_force_depth
    from ..rft import rft_element_forces

    if len(depths) > 1:
        ax = plot_force_depth(
            table.columns["depth_m"],
            {"F_x": table.columns["force_x_N"], "F_z": table.columns["force_z_N"]},
            title=f"RFT, {mat.name}",
        )
    else:
        pose = Pose2D(0.0, -depths[0], theta)
        el = rft_element_forces(
            shape,
            mat,
            pose,
            Twist2D(math.cos(direc), -math.sin(direc), 0.0),
            element_size=element_size,
        )
        outline = [to_world(np.asarray(p), pose) for p in shape.outline()]
        ax = plot_body_tractions(outline, el.positions, el.forces, title=f"RFT, {mat.name}")
    save_figure(ax.figure, path)
