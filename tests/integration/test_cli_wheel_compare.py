"""``terradyn wheel compare``: one case through several models, the same columns, clear refusals."""

from __future__ import annotations

import json

from terradyn.locomotion.wheel_case import SUMMARY_KEYS

SMALL = ("--load", "5", "--radius", "0.05", "--width", "0.03")


def test_compare_prints_one_row_per_model_with_the_same_keys(run_cli):
    code, out, err = run_cli("wheel", "compare", "--model", "rft,wr,rft3d", "--slip", "0.3", *SMALL,
                             "--dynamics", "--format", "json")  # fmt: skip
    assert code == 0, err
    rows = json.loads(out)
    assert [(r["model"], r["engine"]) for r in rows] == [
        ("rft", "quasi-static"), ("wong-reece", "quasi-static"), ("rft3d", "quasi-static"),
        ("rft", "dynamics"), ("wong-reece", "dynamics"),
    ]  # fmt: skip
    for r in rows:
        assert set(r) == {"model", "engine", *SUMMARY_KEYS}
        assert abs(r["vertical_force_N"] - 5.0) < 0.05


def test_compare_refuses_an_unknown_model_in_one_line(run_cli):
    code, _, err = run_cli("wheel", "compare", "--model", "rft,rft9", "--slip", "0.3", *SMALL)
    assert code == 1  # bad input (README: exit codes)
    assert "--model" in err and "rft9" in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1
