"""Shared fixtures: headless plotting and the shipped media."""

from __future__ import annotations

import os
import sys

import matplotlib
import pytest
from hypothesis import settings

# Deterministic property tests by default (reproducible CI); explore with HYPOTHESIS_PROFILE=explore.
settings.register_profile("ci", derandomize=True)
settings.register_profile("explore", max_examples=500)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

matplotlib.use("Agg")
os.environ.setdefault("CI", "1")


@pytest.fixture(autouse=True)
def _numba_pool_size_in_the_environment():
    """Keep ``NUMBA_NUM_THREADS`` equal to the size of numba's thread pool between tests.

    ``terradyn.set_threads`` (the CLI's ``--threads``, run in-process by ``run_cli``) writes the
    variable while numba is not imported yet; numba re-reads it at every compilation and refuses a
    value other than the pool it launched with. Which test first imports numba depends on the order
    tests run in (one process, or several with ``-n``), so after each test the variable is set back
    to the pool's size (or to its value before the test while numba is not loaded)."""
    before = os.environ.get("NUMBA_NUM_THREADS")
    yield
    numba = sys.modules.get("numba")
    value = str(numba.config.NUMBA_NUM_THREADS) if numba is not None else before
    if value is None:
        os.environ.pop("NUMBA_NUM_THREADS", None)
    else:
        os.environ["NUMBA_NUM_THREADS"] = value


@pytest.fixture
def run_cli(capsys):
    """Run the CLI in-process; returns (exit_code, stdout, stderr)."""
    from terradyn.cli.app import main

    def _run(*args: str) -> tuple[int, str, str]:
        try:
            main(list(args))
            code = 0
        except SystemExit as exc:
            code = int(exc.code or 0)
        captured = capsys.readouterr()
        return code, captured.out, captured.err

    return _run
