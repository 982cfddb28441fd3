"""``terradyn reproduce``: bad input is one line (exit 1); a quick chapter builds; an interrupt exits 130."""

import re

import pytest


@pytest.mark.parametrize(
    ("args", "flag"),
    [
        (("--chapter", "5"), "--chapter"),
        (("--chapter", "x"), "--chapter"),
        (("--items", "nope"), "--items"),
        (("--workers", "0"), "--workers"),
        (("--scheduler", "fast"), "--scheduler"),
    ],
)
def test_bad_input_is_one_line(run_cli, tmp_path, args, flag):
    code, _, err = run_cli("reproduce", "--out", str(tmp_path / "r"), *args)
    assert code == 1
    assert err.count("\n") == 1 and flag in err and "Traceback" not in err
    assert not (tmp_path / "r" / "report.html").exists()


def test_quick_chapter_and_resume(run_cli, tmp_path):
    """The command builds one chapter and reuses its rows; chapter 3 (one row, seconds) since the
    quick report of every chapter is built by tests/unit/test_report.py."""
    out = tmp_path / "r"
    args = ("reproduce", "--chapter", "3", "--quick", "--scheduler", "serial", "--out", str(out))
    code, stdout, err = run_cli(*args)
    assert code == 0, err
    assert (out / "report.html").exists() and (out / "report.md").exists()
    html = (out / "report.html").read_text(encoding="utf-8")
    assert "ch3-pressure-sinkage" in html and "Chapter 9" not in html
    assert "0 reused" in stdout
    # stderr is not a terminal here: the expected time and where it comes from, then one line per
    # finished row naming it, the last with nothing left
    lines = [ln for ln in err.splitlines() if ln.startswith("reproduce (")]
    assert lines, err
    first = r"reproduce \(1 rows\): expected \d+:\d\d:\d\d \(row times: .*measured on .*\)"
    assert re.fullmatch(first, lines[0])
    last = (
        r"reproduce \((\d+) rows\): \1/\1 done \(ch3-pressure-sinkage/bekker\), "
        r"elapsed \d+:\d\d:\d\d, ETA 0:00:00"
    )
    assert re.fullmatch(last, lines[-1])
    assert len(lines) == 1 + int(lines[-1].split("(")[1].split()[0])
    code, stdout, err = run_cli(*args)
    assert code == 0 and "0 rows run" in stdout
    assert "done, elapsed" not in err  # nothing ran


def test_interrupt_exits_130_and_says_how_to_resume(run_cli, tmp_path, monkeypatch):
    import terradyn.report.build as build

    def interrupted(key, model):
        raise KeyboardInterrupt

    monkeypatch.setattr(build, "row_for", interrupted)
    code, _, err = run_cli(
        "reproduce", "--chapter", "9", "--quick", "--scheduler", "serial", "--out", str(tmp_path / "r")
    )
    assert code == 130
    assert "interrupted" in err and "rerun" in err
    assert not (tmp_path / "r" / "report.html").exists()
