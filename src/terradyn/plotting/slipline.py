"""Slip-line fields (Prandtl mechanism, method-of-characteristics nets) drawn on their own or over an
MPM field plot."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from ..errors import InputError

__all__ = ["plot_slip_lines"]


def plot_slip_lines(
    field: Any,
    ax: Any = None,
    *,
    alpha_color: str = "tab:blue",
    beta_color: str = "tab:red",
    boundary_color: str = "black",
    linewidth: float = 0.9,
    opacity: float = 0.9,
    zorder: float = 3.0,
    label: bool = True,
) -> Any:
    """Draw slip lines (``x``, ``z`` [m]) and return the axes.

    Parameters
    ----------
    field : list of :class:`terradyn.plasticity.SlipLine` (e.g. from
        :func:`~terradyn.plasticity.prandtl_field`) or a :class:`~terradyn.plasticity.StripFootingMoC`
        (its net, mirrored)
    ax : axes to draw on (e.g. an MPM field plot), new axes when None; labelled ``x [m]``, ``z [m]``
    alpha_color, beta_color : colours of the two families
    boundary_color : colour of the mechanism boundary (zone ``"boundary"``), drawn thicker
    linewidth : line width [pt]; opacity : line alpha in [0, 1]; zorder : drawing order
    label : add a legend entry per family

    The axes get an equal aspect ratio; limits are left to matplotlib (so an underlying field plot
    keeps its own).
    """
    from .core import new_axes

    lines = field.slip_lines() if hasattr(field, "slip_lines") else field
    if not isinstance(lines, Iterable):
        raise InputError("field", type(field).__name__, "a list of SlipLine or a StripFootingMoC")
    lines = list(lines)
    if not lines or not all(hasattr(s, "x") and hasattr(s, "family") for s in lines):
        raise InputError("field", f"{len(lines)} items", "a non-empty list of SlipLine")
    if not 0.0 <= opacity <= 1.0:
        raise InputError("opacity", opacity, "a number in [0, 1]")
    ax = new_axes(ax, figsize=(7.0, 3.8))
    seen: set[str] = set()
    for s in lines:
        boundary = s.zone == "boundary"
        color = boundary_color if boundary else (alpha_color if s.family == "alpha" else beta_color)
        key = "boundary" if boundary else s.family
        name = {"boundary": "mechanism boundary", "alpha": "alpha lines", "beta": "beta lines"}[key]
        ax.plot(
            s.x,
            s.z,
            color=color,
            lw=linewidth * (1.8 if boundary else 1.0),
            alpha=opacity,
            zorder=zorder + (0.5 if boundary else 0.0),
            label=name if label and key not in seen else None,
        )
        seen.add(key)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    if label:
        ax.legend(loc="lower right", fontsize="small")
    return ax
