"""import terradyn stays light; the thread-count knob; warmup's protocol (not its timings)."""

import json
import os
import subprocess
import sys

import pytest

import terradyn
from terradyn import warmup as warmup_module
from terradyn.errors import InputError

HEAVY = ("numba", "scipy", "matplotlib", "pandas")


def _python(code: str, **env: str) -> str:
    full = {**os.environ, **env}
    full.pop("TERRADYN_THREADS", None)
    full.update(env)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=full, check=True)
    return out.stdout.strip()


def test_import_terradyn_loads_no_heavy_dependency():
    code = f"import sys, json, terradyn; print(json.dumps([m for m in {HEAVY!r} if m in sys.modules]))"
    assert json.loads(_python(code)) == []


def test_subpackages_load_on_attribute_access():
    code = "import terradyn; print(terradyn.materials.get('MS').name, 'numba' in __import__('sys').modules)"
    name, numba_loaded = _python(code).split()
    assert name == "MS" and numba_loaded == "False"
    assert terradyn.rft is __import__("terradyn.rft").rft
    with pytest.raises(AttributeError):
        terradyn.not_a_module  # noqa: B018
    assert "locomotion" in dir(terradyn)


def test_environment_variable_sizes_the_pool_before_numba_loads():
    code = "import terradyn, numba; print(numba.get_num_threads(), terradyn.get_threads())"
    assert _python(code, TERRADYN_THREADS="1") == "1 1"


def test_bad_environment_value_warns_and_is_ignored():
    full = {**os.environ, "TERRADYN_THREADS": "two"}
    out = subprocess.run(
        [sys.executable, "-c", "import terradyn; print(terradyn.get_threads() >= 1)"],
        capture_output=True, text=True, env=full, check=True,
    )  # fmt: skip
    assert out.stdout.strip() == "True"
    assert "TERRADYN_THREADS" in out.stderr and "RuntimeWarning" in out.stderr


def test_set_threads_after_numba_loaded():
    import numba

    before = numba.get_num_threads()
    try:
        assert terradyn.set_threads(1) == 1
        assert numba.get_num_threads() == 1 == terradyn.get_threads()
    finally:
        numba.set_num_threads(before)
    for bad in (0, -2, 1.5, True, "x"):
        with pytest.raises(InputError):
            terradyn.set_threads(bad)
    with pytest.raises(InputError, match="at most"):
        terradyn.set_threads(int(numba.config.NUMBA_NUM_THREADS) + 1)


def test_warmup_reports_each_kernel_and_progress(monkeypatch):
    calls = []
    monkeypatch.setattr(warmup_module, "KERNELS", (("a", lambda: None), ("b", lambda: None)))
    rows = warmup_module.warmup(progress=lambda *a: calls.append(a), isolated=False)
    assert [r["kernel"] for r in rows] == ["a", "b"]
    assert all(r["seconds"] >= 0 and r["compiled"] == 0 for r in rows)
    assert calls == [(1, 2, "a"), (2, 2, "b")]


def test_warmup_covers_every_kernel_family():
    names = [name for name, _ in warmup_module.KERNELS]
    assert len(set(names)) == len(names)
    for family in ("rft-2d", "drft", "rft-3d", "rft-3d-steady", "wong-reece", "dynamics", "mpm"):
        assert family in names
