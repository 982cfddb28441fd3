"""Exit codes, interrupts, outputs written as a set, help text: the command line's contract.

The codes are those of :class:`terradyn.errors.ExitCode`, documented in the README.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from terradyn.errors import ExitCode, SolverError

SWEEP = ["wheel", "sweep", "--model", "rft", "--load", "50:200:200", "--slip", "-0.7:0.7:2000"]


def test_exit_code_values_are_the_documented_ones():
    readme = (Path(__file__).parents[2] / "README.md").read_text()
    for code in ExitCode:
        assert f"| {int(code)} |" in readme, code
    assert (ExitCode.OK, ExitCode.INPUT, ExitCode.USAGE, ExitCode.SOLVER) == (0, 1, 2, 3)
    assert (ExitCode.INTERRUPTED, ExitCode.TERMINATED) == (130, 143)


def test_bad_input_usage_and_solver_failure(run_cli):
    code, _, err = run_cli("wheel", "steady", "--load", "-1", "--slip", "0.2")
    assert code == 1 and err.startswith("terradyn: error: --load = -1 ")
    code, _, err = run_cli("wheel", "steady", "--load", "1", "--slip", "0.2", "--nosuch", "1")
    assert code == 2 and "--nosuch" in err and len(err.strip().splitlines()) == 1
    code, _, err = run_cli("wheel", "steady", "--load", "1e6", "--slip", "0.2")
    assert code == 3 and "carries at most" in err and len(err.strip().splitlines()) == 1


def test_failing_validation_exits_4_and_keeps_its_report(run_cli, tmp_path, monkeypatch):
    from terradyn.studies import validation
    from terradyn.studies.validation import Check

    failing = Check("always fails", measured=1.0, expected=0.0, tolerance=0.1, about="test")
    monkeypatch.setattr(validation, "run_checks", lambda: [failing])
    report = tmp_path / "report.json"
    code, out, err = run_cli("validate", "--format", "json", "--out", str(report))
    assert code == 4, err
    assert "always fails" in err and len(err.strip().splitlines()) == 1
    assert json.loads(report.read_text())[0]["passed"] is False
    assert json.loads(out)[0]["check"] == "always fails"


def test_interrupt_in_process_exits_130_without_outputs(run_cli, tmp_path, monkeypatch):
    import terradyn.locomotion as loco

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(loco, "force_slip_sweep", interrupted)
    out = tmp_path / "sweep.csv"
    code, stdout, err = run_cli(*SWEEP, "--out", str(out), "--plot", str(tmp_path / "p.png"))
    assert code == 130
    assert err.strip() == "terradyn: interrupted" and stdout == ""
    assert list(tmp_path.iterdir()) == []


def test_a_late_failure_leaves_no_output_behind(run_cli, tmp_path, monkeypatch):
    """--out is computed before the plot fails: neither file may appear (outputs are one set)."""
    from terradyn.cli import wheel_cmd

    def failing_plot(*args, **kwargs):
        raise SolverError("the plot could not be drawn")

    monkeypatch.setattr(wheel_cmd, "plot_sweep", failing_plot)
    existing = tmp_path / "old.csv"
    existing.write_text("keep me\n")
    code, stdout, err = run_cli(
        "wheel", "sweep", "--model", "rft", "--load", "100", "--slip", "0,0.3",
        "--out", str(existing), "--plot", str(tmp_path / "p.png"),
    )  # fmt: skip
    assert code == 3 and "could not be drawn" in err
    assert stdout == ""
    assert existing.read_text() == "keep me\n"  # not overwritten
    assert sorted(p.name for p in tmp_path.iterdir()) == ["old.csv"]


def test_outputs_are_checked_before_work(run_cli, tmp_path, monkeypatch):
    import terradyn.locomotion as loco

    def must_not_run(*args, **kwargs):
        raise AssertionError("the computation started before the outputs were checked")

    monkeypatch.setattr(loco, "force_slip_sweep", must_not_run)
    (tmp_path / "folder").mkdir()
    (tmp_path / "file.txt").write_text("x")
    cases = [
        ("--out", ""),
        ("--out", "."),
        ("--out", str(tmp_path / "folder")),
        ("--out", str(tmp_path / "file.txt" / "x.csv")),
        ("--out", str(tmp_path / ("a" * 300 + ".csv"))),
        ("--out", str(tmp_path / "x.txt")),
        ("--plot", str(tmp_path / "x.gif")),
        ("--plot", str(tmp_path / "missing" / "x.png")),
    ]
    for flag, value in cases:
        code, _, err = run_cli(*SWEEP, flag, value)
        assert code == 1, (flag, value, err)
        assert err.startswith(f"terradyn: error: {flag} = ") and len(err.strip().splitlines()) == 1, err
        assert "PosixPath" not in err


def _spawn(args: list[str], folder: Path) -> subprocess.Popen[str]:
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    return subprocess.Popen(
        [sys.executable, "-m", "terradyn", *args],
        cwd=folder,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


@pytest.mark.parametrize(("sig", "expected", "delay"), [
    (signal.SIGINT, 130, 2.5), (signal.SIGTERM, 143, 2.5), (signal.SIGINT, 130, 0.4),
])  # fmt: skip
def test_signals_stop_a_run_cleanly(tmp_path, sig, expected, delay):
    """Ctrl-C or SIGTERM, during the work or during start-up: one line, the code, no files."""
    proc = _spawn([*SWEEP, "--out", "sweep.csv"], tmp_path)
    time.sleep(delay)
    proc.send_signal(sig)
    _, stderr = proc.communicate(timeout=60)
    assert proc.returncode == expected, stderr
    assert "Traceback" not in stderr
    lines = stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("terradyn: "), stderr
    assert list(tmp_path.iterdir()) == [], "no partial or temporary output"


def _leaves():
    from terradyn.cli.app import COMMANDS, load_command

    for name in COMMANDS:
        command = load_command(name)
        subs = getattr(command, "commands", None) or {None: command}
        for sub_name, sub in subs.items():
            yield [name] + ([sub_name] if sub_name else []), sub


def test_help_shows_every_unit_and_no_markup(run_cli):
    import re

    for path, command in _leaves():
        code, out, err = run_cli(*path, "--help")
        assert code == 0, (path, err)
        flat = " ".join(out.split())
        for p in command.params:
            text = getattr(p, "help", None) or ""
            for unit in re.findall(r"\[[^\]]+\]", text):
                assert unit in flat, (path, p.name, unit)
        assert "<bool>" not in out, path
        assert "--install-completion" not in out, path


def test_help_lists_every_model_of_wheel_steady(run_cli):
    _, out, _ = run_cli("wheel", "steady", "--help")
    for model in ("rft", "drft", "wong-reece", "rft3d"):
        assert model in out


def test_version_and_help_start_fast():
    """Not a timing test: --version and --help must not import the numerical stack at all."""
    code = (
        "import sys; from terradyn.cli.app import main\n"
        "try:\n    main(sys.argv[1:])\nexcept SystemExit:\n    pass\n"
        "names = ('numpy', 'numba', 'scipy', 'matplotlib', 'pandas', 'typer')\n"
        "heavy = [m for m in names if m in sys.modules]\n"
        "print('HEAVY', heavy)\n"
    )
    for flag in ("--version", "--help"):
        res = subprocess.run([sys.executable, "-c", code, flag], capture_output=True, text=True, check=True)
        assert "HEAVY []" in res.stdout, (flag, res.stdout, res.stderr)


RETIRED = (
    "--reduced",
    "--models",
    "--plate-length",
    "--plate-width",
    "--record-spacing",
    "--snapshot-spacing",
)


def test_one_option_vocabulary():
    """Shared flags: one default medium and wheel, the same help and defaults, no retired spellings."""
    seen: dict[str, dict[str, object]] = {}
    for path, command in _leaves():
        for p in command.params:
            opts = [o for o in getattr(p, "opts", []) if o.startswith("--")]
            if not opts:
                continue
            flag = opts[0]
            assert flag not in RETIRED, (path, flag)
            # the high-speed study is the poppy-seed experiment of Agarwal et al. 2021 (its help says so)
            if flag == "--material" and p.default is not None and path != ["study", "high-speed"]:
                assert p.default == "MS", (path, p.default)
            if flag == "--format":
                seen.setdefault(flag, {})[" ".join(path)] = (p.default, p.help)
    wheel_commands = [(path, c) for path, c in _leaves() if path[:1] == ["wheel"] or path == ["mpm", "wheel"]]
    for path, command in wheel_commands:
        params = {p.name: p for p in command.params}
        assert params["radius"].default == 0.13 and params["width"].default == 0.16, path
    assert len(set(seen["--format"].values())) == 1


def test_checkpoint_flags_are_checked_before_the_run(run_cli, tmp_path):
    base = ["mpm", "intrude", "plate", "--length", "0.06", "--depth", "0.03"]
    existing = tmp_path / "run.npz"
    existing.write_bytes(b"not a checkpoint")
    code, _, err = run_cli(*base, "--checkpoint", str(existing))
    assert code == 1 and "--resume" in err and existing.read_bytes() == b"not a checkpoint"
    code, _, err = run_cli(*base, "--checkpoint", str(tmp_path / "missing.npz"), "--resume")
    assert code == 1 and "--checkpoint" in err and "no such file" in err
    code, _, err = run_cli(*base, "--checkpoint", str(tmp_path / "run.txt"))
    assert code == 1 and ".npz" in err


@pytest.mark.parametrize("with_checkpoint", [False, True])
def test_snapshots_of_a_stopped_run_go_unless_it_can_resume(run_cli, tmp_path, monkeypatch, with_checkpoint):
    import terradyn.mpm as mpm

    def stopped_run(*args, outputs, **kw):
        snapshot_dir, checkpoint_path = outputs.snapshot_dir, outputs.checkpoint_path
        snapshot_dir.mkdir(exist_ok=True)
        (snapshot_dir / "particles_000000010.nc").write_bytes(b"x")
        if checkpoint_path is not None:
            checkpoint_path.write_bytes(b"ckpt")
        raise KeyboardInterrupt

    monkeypatch.setattr(mpm, "run_intrusion", stopped_run)
    snaps = tmp_path / "snaps"
    extra = ["--checkpoint", str(tmp_path / "run.npz")] if with_checkpoint else []
    code, _, err = run_cli("mpm", "intrude", "plate", "--length", "0.06", "--depth", "0.03",
                           "--snapshots", str(snaps), *extra)  # fmt: skip
    assert code == 130 and len(err.strip().splitlines()) == 1
    if with_checkpoint:
        assert (snaps / "particles_000000010.nc").exists() and "--resume" in err
    else:
        assert not snaps.exists() and "nothing saved" in err


def _main_with_run(monkeypatch, app, run) -> int:
    """Exit code of ``app.main`` with its command replaced by ``run(args) -> code``."""
    monkeypatch.setattr(app, "_run", run)
    with pytest.raises(SystemExit) as done:
        app.main(["materials", "list"])
    return done.value.code


def test_an_interrupt_swallowed_on_the_way_still_ends_the_run_as_interrupted(tmp_path, monkeypatch, capsys):
    """A Ctrl-C raised inside a callback from C code is printed as "Exception ignored" and dropped
    (measured: numba's cache callback while a kernel compiles, 0.4 s after start); the handler's
    record of it still stops outputs from being committed and makes the exit code 130."""
    from terradyn import io as tio
    from terradyn._interrupts import note_interrupt, reset_interrupts
    from terradyn.cli import app

    target = tmp_path / "out.txt"
    reset_interrupts()
    with pytest.raises(KeyboardInterrupt):
        with tio.output_set():
            tio.atomic_write(target, lambda tmp: Path(tmp).write_text("x"))
            note_interrupt()  # the exception itself was swallowed
    assert not target.exists() and list(tmp_path.iterdir()) == []

    def run_and_swallow(args):
        note_interrupt()
        return 0

    assert _main_with_run(monkeypatch, app, run_and_swallow) == 130
    assert capsys.readouterr().err == "terradyn: interrupted\n"
    reset_interrupts()


def test_a_failure_after_a_swallowed_interrupt_is_reported_as_the_interrupt(monkeypatch, capsys):
    """The CI failure of stop 34: a budget's SIGINT swallowed inside matplotlib left a figure half laid
    out and saving it raised ``ValueError``; the run printed "internal error" and then "interrupted".
    A failure after an interrupt is its consequence: one line, exit code 130. Without an interrupt
    the same failure is still an internal error (70)."""
    from terradyn._interrupts import note_interrupt, reset_interrupts
    from terradyn.cli import app

    def run_and_fail(args, interrupted=True):
        if interrupted:
            note_interrupt()
        raise ValueError("Invalid bounding box")

    reset_interrupts()
    assert _main_with_run(monkeypatch, app, run_and_fail) == 130
    assert capsys.readouterr().err == "terradyn: interrupted\n"
    assert _main_with_run(monkeypatch, app, lambda args: run_and_fail(args, interrupted=False)) == 70
    err = capsys.readouterr().err
    assert err.startswith("terradyn: internal error: ValueError: Invalid bounding box")
    assert err.count("\n") == 1
    reset_interrupts()


def test_an_interrupt_inside_a_destructor_prints_only_the_one_line(monkeypatch, capsys):
    """The CI failure of stop 32: SIGINT 0.4 s after start landed in llvmlite's ``__del__``; the
    interpreter printed "Exception ignored in ... Traceback" before "terradyn: interrupted". A
    destructor that receives the handler's exception, and one that fails afterwards (an interrupt
    can leave a library object half closed), must leave just the one line; without an interrupt, a
    failing destructor still reaches the usual hook."""
    import gc

    from terradyn._interrupts import reset_interrupts
    from terradyn.cli import app

    class Finalised:
        def __del__(self):
            app._on_sigint(signal.SIGINT, None)  # what the handler does when the signal lands here

    class Broken:
        def __del__(self):
            raise ValueError("a real fault in a destructor")

    def run_and_collect(args):
        Finalised()
        Broken()
        gc.collect()
        return 0

    assert _main_with_run(monkeypatch, app, run_and_collect) == 130
    assert capsys.readouterr().err == "terradyn: interrupted\n"
    reset_interrupts()

    seen = []
    monkeypatch.setattr(sys, "unraisablehook", seen.append)

    def run_with_fault(args):
        Broken()
        return 0

    assert _main_with_run(monkeypatch, app, run_with_fault) == 0 and capsys.readouterr().err == ""
    assert [type(u.exc_value) for u in seen] == [ValueError]
    assert sys.unraisablehook == seen.append  # the command line's hook is gone after the run
