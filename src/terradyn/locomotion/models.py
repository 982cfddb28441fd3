"""Picklable terrain-model specifications, so sweeps can ship them to other processes.

The names come from the one model table, :mod:`terradyn.models`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import InputError
from ..materials import Material
from ..models import model_entry, model_names
from ..terrain import TerrainModel

__all__ = ["MODEL_NAMES", "ModelSpec"]

#: the plane force laws the quasi-static wheel solves and sweeps take by name
MODEL_NAMES = model_names(use="sweep", dimension=2)


@dataclass(frozen=True)
class ModelSpec:
    """A plane terrain model by name and options; call it with a Material to build the model.

    Attributes
    ----------
    name : one of :data:`MODEL_NAMES` ("rft", "drft", "rft-ss" (slip-sinkage RFT with its default
        parameters, :mod:`terradyn.rft.slip_sinkage`), "wong-reece"), or an alias of the table
    element_size : RFT/DRFT discretisation [m] (None: body default)
    c1, c2 : Wong-Reece theta_m coefficients [-]; exit_angle : Wong-Reece exit angle [rad]
    """

    name: str
    element_size: float | None = None
    c1: float = 0.43
    c2: float = 0.32
    exit_angle: float = 0.0

    def __post_init__(self) -> None:
        entry = model_entry(self.name, allowed=MODEL_NAMES)
        object.__setattr__(self, "name", entry.name)
        if not math.isfinite(self.exit_angle):
            raise InputError("exit_angle", self.exit_angle, "a finite angle [rad]")

    def __call__(self, material: Material) -> TerrainModel:
        entry = model_entry(self.name)
        if self.name == "wong-reece":
            model: TerrainModel = entry.build(material, c1=self.c1, c2=self.c2, exit_angle=self.exit_angle)
        else:
            model = entry.build(material, element_size=self.element_size)
        return model
