"""Matplotlib plots: each takes a result and ``ax=None``, returns the axes, never shows."""

from .core import plot_alpha_map, plot_body_tractions, plot_force_depth

__all__ = ["plot_alpha_map", "plot_body_tractions", "plot_force_depth"]
