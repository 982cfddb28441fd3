"""Granular media: validated, citable parameter sets.

Each shipped medium is one TOML file in ``data/`` with a ``[meta]`` table naming its source. Load them
with :func:`get`, list them with :func:`available`, read a user's own file with :func:`load`, or build a
:class:`Material` directly in Python.
"""

from ._material import (
    BekkerParameters,
    ContinuumParameters,
    DEMParameters,
    LiCoefficients,
    Material,
    Provenance,
    RFTParameters,
)
from ._registry import available, from_dict, get, load
from ._writer import material_to_toml, write_material

__all__ = [
    "BekkerParameters",
    "ContinuumParameters",
    "DEMParameters",
    "LiCoefficients",
    "Material",
    "Provenance",
    "RFTParameters",
    "available",
    "from_dict",
    "get",
    "load",
    "material_to_toml",
    "write_material",
]
