"""terradyn replay: the shipped example table end to end, and one-line errors for bad input."""

from __future__ import annotations

import json
from importlib import resources
from pathlib import Path

import pytest

EXAMPLE = str(resources.files("terradyn.replay").joinpath("data/example_runs.csv"))


def test_replay_example_with_calibration_writes_tables_and_plots(run_cli, tmp_path):
    out = tmp_path / "replay"
    code, stdout, err = run_cli(
        "replay", EXAMPLE, "--model", "rft", "--out", str(out), "--calibrate-on", "0.5",
        "--group-by", "wheel_type", "--plot", "--format", "json",
    )  # fmt: skip
    assert code == 0, err
    summary = json.loads(stdout)
    assert summary["calibration"]["parameters"]["scale"] == pytest.approx(1.2, rel=0.03)
    assert summary["replayed_runs"] == summary["run_count"] == 28
    sets = {(m["set"], m["wheel_type"]) for m in summary["metrics"]}
    assert ("held-out", "smooth") in sets and ("calibration", "grousered") in sets
    names = sorted(p.name for p in out.iterdir())
    assert names == ["metrics.csv", "parity.png", "predictions.csv", "replay.json", "residuals_vs_slip.png"]
    header = (out / "predictions.csv").read_text().splitlines()[0].split(",")
    assert {"predicted_drawbar_pull_N", "residual_sinkage_m", "std_sinkage_m", "set"} <= set(header)


def test_replay_table_output_prints_metrics(run_cli):
    code, stdout, err = run_cli("replay", EXAMPLE, "--model", "rft", "--format", "csv")
    assert code == 0, err
    lines = stdout.strip().splitlines()
    assert lines[0].startswith("set,quantity,n,mae,rmse,nrmse,bias,pearson_r") and len(lines) == 4


def _bad(tmp_path: Path, text: str) -> str:
    p = tmp_path / "runs.csv"
    p.write_text(text)
    return str(p)


@pytest.mark.parametrize(
    ("args", "starts"),
    [
        (["--model", "bekker"], "terradyn: error: --model = 'bekker' is not allowed"),
        (["--calibrate-on", "1.5"], "terradyn: error: --calibrate-on = '1.5' is not allowed"),
        (["--calibrate-on", "no_such_column"], "terradyn: error: --calibrate-on = 'no_such_column'"),
        (["--plot"], "terradyn: error: --plot"),
        (["--group-by", "colour"], "terradyn: error: --group-by = 'colour'"),
        (["--model", "wong-reece", "--calibrate-on", "0.5"], "terradyn: error: --model = 'wong-reece'"),
    ],
)
def test_bad_options_give_one_line(run_cli, args, starts):
    code, _, err = run_cli("replay", EXAMPLE, *args)
    assert code == 1, err
    assert err.startswith(starts) and len(err.strip().splitlines()) == 1, err


def test_bad_table_gives_one_line_naming_row_and_column(run_cli, tmp_path):
    path = _bad(
        tmp_path,
        "run_id,medium,radius_m,width_m,load_N,slip,drawbar_pull_N\na,MS,0.06,0.06,20,0.1,1\nb,MS,0.06,0.06,-3,0.1,1\n",
    )
    code, stdout, err = run_cli("replay", path, "--out", str(tmp_path / "out"))
    assert code == 1 and stdout == ""
    assert (
        err.strip()
        == "terradyn: error: runs.csv row 2 column load_N = '-3' is not allowed; expected a number > 0 [N]"
    )
    assert not (tmp_path / "out").exists()
    code, _, err = run_cli("replay", str(tmp_path / "missing.csv"))
    assert code == 1 and len(err.strip().splitlines()) == 1 and "RUNS" in err


def test_out_folder_holding_the_table_is_refused_if_an_output_would_overwrite_it(run_cli, tmp_path):
    table = tmp_path / "predictions.csv"
    table.write_text(Path(EXAMPLE).read_text())
    code, _, err = run_cli("replay", str(table), "--out", str(tmp_path))
    assert code == 1 and "--out" in err and "overwrites the runs table" in err
    assert table.read_text() == Path(EXAMPLE).read_text()


def test_a_table_no_run_of_which_the_model_can_replay_is_one_solver_line(run_cli, tmp_path):
    path = _bad(
        tmp_path, "run_id,medium,radius_m,width_m,load_N,slip,drawbar_pull_N\na,MS,0.01,0.01,5000,0.1,1\n"
    )
    code, stdout, err = run_cli("replay", path)
    assert code == 3 and stdout == "" and len(err.strip().splitlines()) == 1 and "no run of" in err
