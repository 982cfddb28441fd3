"""terradyn: locomotion and intrusion in dry granular media.

Granular resistive force theory (RFT) on arbitrary plane bodies, classical terramechanics, a
plane-strain MPM continuum solver and the studies built on them. SI units throughout.
"""

from __future__ import annotations

__version__ = "0.1.0"

__all__ = ["__version__"]
