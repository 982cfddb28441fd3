"""Result containers shared by studies: frozen tables with units and provenance."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .errors import InputError

__all__ = ["TableResult"]


@dataclass(frozen=True, eq=False)
class TableResult:
    """Columns of equal length with unit-suffixed names (``depth_m``, ``force_z_N``) and metadata.

    Attributes
    ----------
    columns : dict of str -> ndarray
    metadata : dict  free-form JSON-able provenance (material, body, model, citation)
    """

    columns: dict[str, np.ndarray]
    metadata: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        lengths = {len(v) for v in self.columns.values()}
        if len(lengths) > 1:
            raise InputError("columns", sorted(lengths), "columns of equal length")
        for name, col in self.columns.items():
            arr = np.asarray(col)
            if arr.dtype.kind == "f" and not np.all(np.isfinite(arr)):
                raise InputError(name, "non-finite values", "finite results")

    def __len__(self) -> int:
        return len(next(iter(self.columns.values()))) if self.columns else 0

    def records(self) -> list[dict[str, Any]]:
        keys = list(self.columns)
        return [{k: self.columns[k][i].item() for k in keys} for i in range(len(self))]

    def to_dataframe(self) -> Any:
        import pandas as pd

        df = pd.DataFrame({k: np.asarray(v) for k, v in self.columns.items()})
        df.attrs.update(self.metadata)
        return df

    def save(self, path: str | Path) -> Path:
        """Write CSV (``.csv``), JSON (``.json``) or Parquet (``.parquet``) atomically."""
        from .io import atomic_write_text

        p = Path(path)
        if p.suffix == ".csv":
            return atomic_write_text(p, self.to_dataframe().to_csv(index=False))
        if p.suffix == ".json":
            payload = {"metadata": self.metadata, "rows": self.records()}
            return atomic_write_text(p, json.dumps(payload, indent=2))
        raise InputError("path", str(path), "a file ending in .csv or .json")
