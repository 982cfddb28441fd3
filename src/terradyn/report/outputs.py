"""What a report row returns: its findings and its output (figures, settings, metrics, tables).

The rows (:mod:`terradyn.report.rows`) and the registry both import this; it imports neither.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from ..errors import InputError

__all__ = ["Finding", "ItemOutput"]


@dataclass(frozen=True)
class Finding:
    """One line of "what agrees / what does not", its numbers computed by the run.

    ``verdict`` is ``agrees``, ``disagrees`` or ``info`` (a measured fact with no reference)."""

    text: str
    verdict: str = "info"

    def __post_init__(self) -> None:
        if self.verdict not in ("agrees", "disagrees", "info"):
            raise InputError("finding.verdict", self.verdict, "agrees, disagrees or info")


@dataclass
class ItemOutput:
    """What a row returns: figures (name -> matplotlib figure), settings, metrics, findings and
    optional small tables (name -> list of row dicts)."""

    figures: dict[str, Any] = field(default_factory=dict)
    settings: dict[str, Any] = field(default_factory=dict)
    metrics: dict[str, Any] = field(default_factory=dict)
    findings: list[Finding] = field(default_factory=list)
    tables: dict[str, list[dict[str, Any]]] = field(default_factory=dict)
