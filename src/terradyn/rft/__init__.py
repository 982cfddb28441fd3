"""Granular resistive force theory: the Li et al. (2013) law and its sum over bodies."""

from .drft import DRFTModel, drft_structural_drop, drft_wrench
from .forces import (
    Backend,
    RFTElementForces,
    RFTModel,
    as_elements,
    rft_element_forces,
    rft_wrench,
    rft_wrench_many,
)
from .li2013 import li2013_alpha, li2013_alpha_from_directions, li2013_alpha_material, rft_angles

__all__ = [
    "Backend",
    "DRFTModel",
    "RFTElementForces",
    "RFTModel",
    "as_elements",
    "drft_structural_drop",
    "drft_wrench",
    "li2013_alpha",
    "li2013_alpha_from_directions",
    "li2013_alpha_material",
    "rft_angles",
    "rft_element_forces",
    "rft_wrench",
    "rft_wrench_many",
]
