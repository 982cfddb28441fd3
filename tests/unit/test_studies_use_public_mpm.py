"""The studies drive the MPM through its public API only (DESIGN.md section 1: a package's private
kernels are its own): no ``terradyn.studies`` module imports a private module or name of
``terradyn.mpm``, and every name it imports from it is exported in that module's ``__all__``. Checked
on the source with :mod:`ast`, lazy imports inside functions included, without importing anything."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import terradyn

SRC = Path(terradyn.__file__).parent
STUDIES = sorted((SRC / "studies").glob("*.py"))


def _module_file(dotted: str) -> Path | None:
    """The source file of the terradyn module ``dotted`` (package or module), None if none."""
    parts = dotted.split(".")[1:]
    base = SRC.joinpath(*parts)
    for path in (base / "__init__.py", base.with_suffix(".py")):
        if path.is_file():
            return path
    return None


def _exported(dotted: str) -> set[str]:
    """The names in the ``__all__`` of module ``dotted``, read from its source."""
    path = _module_file(dotted)
    if path is None:
        return set()
    for node in ast.parse(path.read_text()).body:
        targets = node.targets if isinstance(node, ast.Assign) else [getattr(node, "target", None)]
        names = [t.id for t in targets if isinstance(t, ast.Name)]
        if "__all__" in names and isinstance(node, ast.Assign | ast.AnnAssign) and node.value is not None:
            return set(ast.literal_eval(node.value))
    return set()


def _absolute(module: str | None, level: int, package: str) -> str:
    if not level:
        return module or ""
    base = package.split(".")[: len(package.split(".")) - (level - 1)]
    return ".".join(base + ([module] if module else []))


def _is_mpm(dotted: str) -> bool:
    return dotted == "terradyn.mpm" or dotted.startswith("terradyn.mpm.")


def private_mpm_uses(source: str, package: str) -> list[str]:
    """Each use of a private part of terradyn.mpm in ``source`` (a module of ``package``)."""
    bad = []
    aliases = set()  # local names bound to a terradyn.mpm module
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            for a in node.names:
                if _is_mpm(a.name):
                    if any(p.startswith("_") for p in a.name.split(".")):
                        bad.append(f"line {node.lineno}: import {a.name}")
                    aliases.add(a.asname or a.name.split(".")[0])
        elif isinstance(node, ast.ImportFrom):
            target = _absolute(node.module, node.level, package)
            if not _is_mpm(target):
                continue
            if any(p.startswith("_") for p in target.split(".")):
                bad.append(f"line {node.lineno}: from {target} import ...")
                continue
            exported = _exported(target)
            for a in node.names:
                submodule = _module_file(f"{target}.{a.name}") is not None
                if a.name.startswith("_") or not (a.name in exported or submodule):
                    bad.append(f"line {node.lineno}: from {target} import {a.name}")
                if submodule:
                    aliases.add(a.asname or a.name)
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
            if node.value.id in aliases and node.attr.startswith("_"):
                bad.append(f"line {node.lineno}: {node.value.id}.{node.attr}")
    return bad


def test_the_check_finds_private_uses():
    source = (
        "from ..mpm import _kernels as K\n"
        "from ..mpm.solver import _HeldInterrupts\n"
        "from ..mpm.solver import PARALLEL_MIN_PARTICLES\n"  # public by name, but not in __all__
        "from ..mpm import solver\n"
        "solver._check\n"
        "from ..mpm import run_intrusion, specs\n"
        "from ..mpm.specs import Bed\n"
    )
    found = private_mpm_uses(source, "terradyn.studies")
    assert [f.split(":")[0] for f in found] == ["line 1", "line 2", "line 3", "line 5"], found


@pytest.mark.parametrize("path", STUDIES, ids=lambda p: p.name)
def test_studies_import_no_private_name_of_mpm(path):
    assert private_mpm_uses(path.read_text(), "terradyn.studies") == []
