"""Classical terramechanics: Bekker pressure-sinkage, Janosi-Hanamoto shear, the Wong-Reece wheel.

* :mod:`.bekker` - :func:`bekker_pressure`, :func:`reece_pressure`, :func:`janosi_hanamoto_shear`;
* :mod:`.wong_reece` - :func:`wong_reece_wheel` (sinkage and forces at a load and slip),
  :func:`wong_reece_wheel_forces` (forces at a given entry angle or sinkage) and
  :class:`WongReeceModel`, the terrain model for :class:`~terradyn.geometry.WheelCircular`;
* :mod:`.calibration` - fitting Bekker and Janosi-Hanamoto parameters to plate-sinkage and shear
  tests, reading their CSV files and writing a material TOML.
"""

from .bekker import bekker_pressure, janosi_hanamoto_shear, reece_pressure
from .calibration import (
    BekkerFit,
    PlateSinkageData,
    ShearData,
    ShearFit,
    combine_fits,
    fit_bekker,
    fit_shear,
    read_plate_sinkage_csv,
    read_shear_csv,
    write_material_toml,
)
from .wong_reece import (
    WongReeceModel,
    WongReeceProfiles,
    WongReeceResult,
    wong_reece_wheel,
    wong_reece_wheel_forces,
)

__all__ = [
    "BekkerFit",
    "PlateSinkageData",
    "ShearData",
    "ShearFit",
    "WongReeceModel",
    "WongReeceProfiles",
    "WongReeceResult",
    "bekker_pressure",
    "combine_fits",
    "fit_bekker",
    "fit_shear",
    "janosi_hanamoto_shear",
    "read_plate_sinkage_csv",
    "read_shear_csv",
    "reece_pressure",
    "wong_reece_wheel",
    "wong_reece_wheel_forces",
    "write_material_toml",
]
