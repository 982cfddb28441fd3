"""The report's rows: one literal table names a row for every model of every thesis item, every named
function exists, nothing is imported before its row runs, and the physics packages stay below the report."""

import ast
import importlib
import os
import subprocess
import sys
from pathlib import Path

import terradyn
from terradyn.report.registry import ITEMS
from terradyn.report.rows import ROWS

#: the packages above the simulation layers: terradyn.mpm and terradyn.dem import none of them
UPPER = ("report", "studies", "locomotion", "plotting", "optimize")


def test_the_table_names_a_row_for_every_model_of_every_item():
    listed = {(it.key, model) for it in ITEMS for model in it.models}
    # no model is pending today: every (item, model) has a row, and the table names no other
    assert set(ROWS) == listed
    for (key, model), spec in ROWS.items():
        if spec.startswith("="):  # one computation for two models: the other model's row of the item
            assert ROWS[(key, spec[1:])].startswith("terradyn.report.rows."), (key, model)
            continue
        module, name = spec.split(":")
        assert module.startswith("terradyn.report.rows.ch"), spec
        assert callable(getattr(importlib.import_module(module), name)), spec


def _run(code: str) -> str:
    src = str(Path(terradyn.__file__).resolve().parents[1])
    out = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        check=True,
        env={**os.environ, "PYTHONPATH": src, "MPLBACKEND": "Agg"},
    )
    return out.stdout.strip()


def test_listing_the_rows_imports_no_row_module():
    code = (
        "import sys\n"
        "from terradyn.report.registry import ITEMS, rows_of\n"
        "for it in ITEMS:\n"
        "    rows_of(it)\n"
        "print(sorted(m for m in sys.modules if m.startswith('terradyn.report.rows.')))\n"
    )
    assert _run(code) == "[]"


def test_mpm_and_dem_import_nothing_above_them():
    code = (
        "import sys\n"
        "import terradyn.mpm, terradyn.dem\n"
        f"print(sorted(m for m in sys.modules if m.split('.')[:2] in [['terradyn', p] for p in {UPPER!r}]))\n"
    )
    assert _run(code) == "[]"


def test_mpm_and_dem_sources_never_import_the_upper_packages():
    """Not at module level and not lazily inside a function either (the import test above sees only the
    first)."""
    root = Path(terradyn.__file__).resolve().parent
    bad = []
    for package in ("mpm", "dem"):
        for path in sorted((root / package).rglob("*.py")):
            for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
                if isinstance(node, ast.ImportFrom):
                    if node.level == 0:
                        names = [node.module or ""]
                    elif node.level == 1:  # from . import x / from .x import y: inside the package
                        continue
                    elif node.module:  # from ..x import y
                        names = [f"terradyn.{node.module}"]
                    else:  # from .. import x, y
                        names = [f"terradyn.{a.name}" for a in node.names]
                elif isinstance(node, ast.Import):
                    names = [a.name for a in node.names]
                else:
                    continue
                for name in names:
                    parts = name.split(".")
                    if parts[0] == "terradyn" and len(parts) > 1 and parts[1] in UPPER:
                        bad.append(f"{path.relative_to(root)}:{node.lineno} {name}")
    assert bad == []
