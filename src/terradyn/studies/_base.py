"""What every study shares: its output and the base of its validated parameters (the study modules and
:mod:`terradyn.studies.registry` import this; it imports none of them)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from ..results import TableResult

__all__ = ["StudyEntry", "StudyOutput"]


@dataclass
class StudyOutput:
    """Tables (name -> TableResult), figures (name -> matplotlib figure) and a summary table."""

    tables: dict[str, TableResult] = field(default_factory=dict)
    figures: dict[str, Any] = field(default_factory=dict)
    summary: list[dict[str, Any]] = field(default_factory=list)


class _Params(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)
    material: str = "MS"
    quick: bool = Field(False, description="Reduced resolution (used by the default test suite).")


#: one study: (name, parameter model, run(params) -> StudyOutput, one-line description)
StudyEntry = tuple[str, type[_Params], Callable[[Any], StudyOutput], str]
