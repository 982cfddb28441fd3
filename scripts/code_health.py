"""Size and shape counts of terradyn's source, for the architecture notes and tests/unit/test_layers.py.

Counts functions (and methods) by length and parameter count, leaving out numba kernels (decorated
with ``njit``/``jit``: their argument lists are the arrays they work on), and the private names one
package imports from another. Run: python scripts/code_health.py [SRC_DIR]
"""

from __future__ import annotations

import ast
import sys
from pathlib import Path


def _is_kernel(node: ast.FunctionDef | ast.AsyncFunctionDef) -> bool:
    for dec in node.decorator_list:
        target = dec.func if isinstance(dec, ast.Call) else dec
        name = target.attr if isinstance(target, ast.Attribute) else getattr(target, "id", "")
        if name in ("njit", "jit", "vectorize", "guvectorize", "stencil"):
            return True
    return False


def functions(src: Path) -> list[dict[str, object]]:
    """One record per function or method: module, name, lines, parameters, kernel or not."""
    out = []
    for path in sorted(src.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                a = node.args
                params = [*a.posonlyargs, *a.args, *a.kwonlyargs]
                names = [p.arg for p in params if p.arg not in ("self", "cls")]
                start = min([node.lineno, *(d.lineno for d in node.decorator_list)])
                out.append(
                    {
                        "where": f"{path.relative_to(src)}:{node.lineno}",
                        "name": node.name,
                        "lines": (node.end_lineno or node.lineno) - start + 1,
                        "parameters": len(names),
                        "kernel": _is_kernel(node),
                    }
                )
    return out


def private_imports_across_packages(src: Path) -> list[str]:
    """``module -> name`` for every private name (or private module) imported from another package."""
    root = src / "terradyn"
    found = []
    for path in sorted(root.rglob("*.py")):
        rel = path.relative_to(root).parts
        package = rel[0] if len(rel) > 1 else ""
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if not isinstance(node, ast.ImportFrom):
                continue
            if node.level == 0 and not (node.module or "").startswith("terradyn"):
                continue
            if node.level:
                base = list(path.relative_to(root).with_suffix("").parts)
                base = base[: len(base) - node.level]
                target = [*base, *((node.module or "").split(".") if node.module else [])]
            else:
                target = (node.module or "").split(".")[1:]
            target_package = target[0] if target else ""
            if target_package == package or not target_package or target_package.startswith("_"):
                continue  # inside one package, or the root package's own private modules
            private_module = any(part.startswith("_") and not part.startswith("__") for part in target)
            for alias in node.names:
                if private_module or (alias.name.startswith("_") and not alias.name.startswith("__")):
                    found.append(f"{path.relative_to(src)}:{node.lineno} {'.'.join(target)}:{alias.name}")
    return found


def main(src: Path) -> None:
    funcs = functions(src / "terradyn")
    plain = [f for f in funcs if not f["kernel"]]
    print(f"functions: {len(funcs)} ({len(funcs) - len(plain)} numba kernels)")
    for limit in (100, 120):
        over = [f for f in plain if int(f["lines"]) > limit]  # type: ignore[call-overload]
        print(f"  over {limit} lines (not kernels): {len(over)}")
        for f in sorted(over, key=lambda f: -int(f["lines"])):  # type: ignore[call-overload]
            print(f"    {f['lines']:4d}  {f['where']} {f['name']}")
    many = [f for f in funcs if int(f["parameters"]) > 10]  # type: ignore[call-overload]
    print(f"  more than 10 parameters: {len(many)} ({sum(not f['kernel'] for f in many)} not kernels)")
    private = private_imports_across_packages(src)
    print(f"private names or modules imported across packages: {len(private)}")
    for p in private:
        print(f"    {p}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).parents[1] / "src")
