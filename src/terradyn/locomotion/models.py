"""Picklable terrain-model specifications, so sweeps can ship them to other processes."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import InputError
from ..materials import Material
from ..terrain import TerrainModel

__all__ = ["MODEL_NAMES", "ModelSpec"]

MODEL_NAMES = ("rft", "wong-reece", "drft", "rft-ss")


@dataclass(frozen=True)
class ModelSpec:
    """A terrain model by name and options; call it with a Material to build the model.

    Attributes
    ----------
    name : "rft", "wong-reece", "drft" or "rft-ss" (slip-sinkage RFT with its default parameters,
    :mod:`terradyn.rft.slip_sinkage`)
    element_size : RFT/DRFT discretisation [m] (None: body default)
    c1, c2 : Wong-Reece theta_m coefficients [-]; exit_angle : Wong-Reece exit angle [rad]
    """

    name: str
    element_size: float | None = None
    c1: float = 0.43
    c2: float = 0.32
    exit_angle: float = 0.0

    def __post_init__(self) -> None:
        key = self.name.strip().lower()
        aliases = {"wongreece": "wong-reece", "wr": "wong-reece", "slip-sinkage": "rft-ss"}
        key = aliases.get(key, key)
        if key not in MODEL_NAMES:
            raise InputError("model", self.name, f"one of {list(MODEL_NAMES)}")
        object.__setattr__(self, "name", key)
        if not math.isfinite(self.exit_angle):
            raise InputError("exit_angle", self.exit_angle, "a finite angle [rad]")

    def __call__(self, material: Material) -> TerrainModel:
        if self.name == "rft":
            from ..rft import RFTModel

            return RFTModel(material, element_size=self.element_size)
        if self.name == "wong-reece":
            from ..terramechanics import WongReeceModel

            return WongReeceModel(material, c1=self.c1, c2=self.c2, exit_angle=self.exit_angle)
        if self.name == "rft-ss":
            from ..rft.slip_sinkage import SlipSinkageRFTModel

            return SlipSinkageRFTModel(material, element_size=self.element_size)
        from ..rft.drft import DRFTModel

        return DRFTModel(material, element_size=self.element_size)
