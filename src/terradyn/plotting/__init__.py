"""Matplotlib plots: each takes a result (and ``ax=None`` where it draws one panel), returns the axes or
the Figure, never shows and never saves (the CLI saves)."""

from .core import plot_alpha_map, plot_alpha_maps, plot_body_tractions, plot_force_depth
from .wheels import new_force_slip_figure, plot_force_slip

__all__ = [
    "new_force_slip_figure",
    "plot_alpha_map",
    "plot_alpha_maps",
    "plot_body_tractions",
    "plot_force_depth",
    "plot_force_slip",
]
