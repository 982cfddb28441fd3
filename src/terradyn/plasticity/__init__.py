"""Plasticity-theory references for strip footings: closed forms, characteristics, slip-line fields.

No MPM and no RFT: this package is the theory the MPM strip-footing verification is checked against.

* :mod:`.bearing` - closed-form bearing factors (Prandtl ``N_c``, Reissner ``N_q``), the common
  ``N_gamma`` approximations (Vesic, Meyerhof, Hansen, EC7; approximations only), Hansen depth factors
  and the Davis reduced friction angle for non-associated flow;
* :mod:`.moc` - a method-of-characteristics solver (smooth and rough base, ``c``, ``q``, ``gamma``)
  returning the collapse pressure, ``N_gamma`` with its mesh convergence, and the slip-line net;
* :mod:`.slipline` - the Prandtl-Reissner mechanism as polylines for overlays on MPM field plots;
* :func:`strip_footing_reference` - the reference ``N_gamma`` (associated and isochoric) the MPM
  verification command compares with, with its sources.
"""

from __future__ import annotations

from .bearing import (
    davis1968_reduced_friction_angle,
    ec7_ngamma,
    hansen1970_depth_factor_q,
    hansen1970_ngamma,
    hansen1970_strip_pressure,
    meyerhof1963_ngamma,
    passive_earth_pressure_coefficient,
    prandtl1921_nc,
    reissner1924_nq,
    vesic1973_ngamma,
)
from .moc import (
    FootingBase,
    NGammaResult,
    StripFootingMoC,
    moc_bearing_factors,
    moc_n_gamma,
    moc_n_gamma_convergence,
    moc_strip_footing,
)
from .references import reference_entries, strip_footing_reference
from .slipline import SlipLine, prandtl_extent, prandtl_field

__all__ = [
    "FootingBase",
    "NGammaResult",
    "SlipLine",
    "StripFootingMoC",
    "davis1968_reduced_friction_angle",
    "ec7_ngamma",
    "hansen1970_depth_factor_q",
    "hansen1970_ngamma",
    "hansen1970_strip_pressure",
    "meyerhof1963_ngamma",
    "moc_bearing_factors",
    "moc_n_gamma",
    "moc_n_gamma_convergence",
    "moc_strip_footing",
    "passive_earth_pressure_coefficient",
    "prandtl1921_nc",
    "prandtl_extent",
    "prandtl_field",
    "reference_entries",
    "reissner1924_nq",
    "strip_footing_reference",
    "vesic1973_ngamma",
]
