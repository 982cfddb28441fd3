"""Atomic outputs: single files, sets of files committed together, output path checks."""

from __future__ import annotations

import os

import pytest

from terradyn.errors import InputError
from terradyn.io import (
    OutputFormat,
    atomic_write_text,
    check_output_file,
    check_output_folder,
    format_output,
    output_set,
)


def _visible(folder):
    return sorted(p.name for p in folder.iterdir())


def test_atomic_write_replaces_whole_file_and_leaves_no_temporary(tmp_path):
    target = tmp_path / "a.txt"
    target.write_text("old")
    atomic_write_text(target, "new")
    assert target.read_text() == "new"
    assert _visible(tmp_path) == ["a.txt"]


def test_a_set_appears_only_at_the_end(tmp_path, capsys):
    a, b = tmp_path / "a.csv", tmp_path / "new" / "deeper" / "b.csv"
    with output_set() as outs:
        outs.folder(tmp_path / "new" / "deeper")
        atomic_write_text(a, "1")
        atomic_write_text(b, "2")
        outs.print("summary\n")
        assert not a.exists() and not (tmp_path / "new").exists()
        assert capsys.readouterr().out == ""
    assert a.read_text() == "1" and b.read_text() == "2"
    assert capsys.readouterr().out == "summary\n"
    assert sorted(p.name for p in tmp_path.rglob("*")) == ["a.csv", "b.csv", "deeper", "new"]


def test_a_failed_set_leaves_nothing_and_overwrites_nothing(tmp_path, capsys):
    old = tmp_path / "a.csv"
    old.write_text("keep")
    with pytest.raises(KeyboardInterrupt), output_set() as outs:
        outs.folder(tmp_path / "new")
        atomic_write_text(old, "replaced")
        atomic_write_text(tmp_path / "new" / "b.csv", "2")
        outs.print("never printed\n")
        raise KeyboardInterrupt
    assert old.read_text() == "keep"
    assert _visible(tmp_path) == ["a.csv"]
    assert capsys.readouterr().out == ""


def test_nested_sets_join_the_outer_one(tmp_path):
    with output_set() as outer:
        with output_set() as inner:
            assert inner is outer
            atomic_write_text(tmp_path / "x", "1")
        assert not (tmp_path / "x").exists()
    assert (tmp_path / "x").exists()


@pytest.mark.parametrize(
    ("value", "needle"),
    [
        ("", "empty"),
        (".", "not a folder"),
        ("DIR", "not a folder"),
        ("FILE/x.csv", "is a file"),
        ("missing/x.csv", "does not exist"),
        ("x.txt", "ending in"),
        ("a" * 300 + ".csv", "at most"),
    ],
)
def test_output_file_checks(tmp_path, value, needle):
    (tmp_path / "DIR").mkdir()
    (tmp_path / "FILE").write_text("x")
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        with pytest.raises(InputError, match=needle) as info:
            check_output_file("--out", value, suffixes=(".json", ".csv"))
    finally:
        os.chdir(cwd)
    message = str(info.value)
    assert message.startswith("--out = ") and "\n" not in message and "PosixPath" not in message


def test_output_folder_checks(tmp_path):
    (tmp_path / "FILE").write_text("x")
    assert check_output_folder("--out", tmp_path / "new") == tmp_path / "new"
    with pytest.raises(InputError, match="existing file"):
        check_output_folder("--out", tmp_path / "FILE")
    with pytest.raises(InputError, match="is a file"):
        check_output_folder("--out", tmp_path / "FILE" / "sub")


def test_tables_never_cut_a_header():
    rows = [{"a_rather_long_quantity_name_N": 1.5, "name": "x" * 40}, {"a_rather_long_quantity_name_N": 2.0,
                                                                        "name": "y"}]  # fmt: skip
    text = format_output(rows, OutputFormat.table)
    assert "a_rather_long_quantity_name_N" in text and "x" * 40 in text
    with pytest.raises(InputError, match="non-finite"):
        format_output({"f": float("nan")}, OutputFormat.json)
