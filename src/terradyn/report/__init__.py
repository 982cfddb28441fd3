"""``terradyn reproduce``: the thesis items (chapters 3-9) run with every model that applies, written as
one self-contained HTML report and as Markdown.

:mod:`.registry` lists the thesis items; :mod:`.rows` holds the rows (one model's computation for one
item) by thesis chapter and the one table naming them; rows of your own plug in with
:func:`register_row`. :func:`reproduce` runs the rows (cached per row, resumable, parallel) and writes
the report.
"""

from __future__ import annotations

from .build import reproduce
from .registry import CHAPTERS, ITEMS, Finding, ItemOutput, ThesisItem, register_row

__all__ = ["CHAPTERS", "ITEMS", "Finding", "ItemOutput", "ThesisItem", "register_row", "reproduce"]
