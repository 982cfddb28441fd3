"""The architecture as tests: the import-linter contracts of pyproject.toml (layers, no cycle between
siblings, private modules kept private) and the size limits of STYLE.md."""

from __future__ import annotations

import importlib.util
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[2]


def _code_health():
    spec = importlib.util.spec_from_file_location("code_health", ROOT / "scripts" / "code_health.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules["code_health"] = module
    spec.loader.exec_module(module)
    return module


def test_import_contracts_hold():
    exe = shutil.which("lint-imports", path=str(Path(sys.executable).parent)) or shutil.which("lint-imports")
    if exe is None:
        pytest.fail("lint-imports (import-linter, the dev extra) is not installed: run make test")
    run = subprocess.run([exe, "--no-cache"], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout[-4000:] + run.stderr[-2000:]
    assert "3 kept, 0 broken" in run.stdout


def test_no_function_over_120_lines_outside_numba_kernels():
    health = _code_health()
    long = [f for f in health.functions(ROOT / "src" / "terradyn") if not f["kernel"] and f["lines"] > 120]
    assert not long, [f"{f['where']} {f['name']} ({f['lines']} lines)" for f in long]


def test_no_private_name_imported_across_packages():
    assert _code_health().private_imports_across_packages(ROOT / "src") == []


def test_the_engines_load_without_the_report_or_the_studies():
    code = (
        "import sys, terradyn.mpm, terradyn.rft, terradyn.terramechanics, terradyn.locomotion;"
        "bad = [m for m in sys.modules if m.startswith(('terradyn.report', 'terradyn.studies', "
        "'terradyn.cli', 'terradyn.plotting'))]; print(bad); sys.exit(1 if bad else 0)"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stdout + run.stderr
