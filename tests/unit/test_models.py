"""The one model table: names, aliases, builders, what each driver lists, and users' own models."""

from __future__ import annotations

import math
import re

import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.geometry import WheelCircular, WheelGrousered
from terradyn.kinematics import Pose2D, Twist2D
from terradyn.models import (
    MODELS,
    CallableModel,
    ModelKind,
    build_model,
    model_entry,
    model_names,
    model_title,
)
from terradyn.rft import RFTModel, rft_wrench


def test_names_aliases_and_refusals():
    names = [e.name for e in MODELS]
    aliases = [a for e in MODELS for a in e.aliases]
    assert len(set(names + aliases)) == len(names) + len(aliases)
    assert model_entry(" WR ").name == "wong-reece"
    assert model_entry("Slip-Sinkage").name == "rft-ss"
    with pytest.raises(InputError, match=r"--model.*'rft4d'.*rft, drft"):
        model_entry("rft4d", field="--model")
    # a model a driver does not take is refused with that driver's list
    with pytest.raises(InputError, match="rft, drft"):
        model_entry("wong-reece", use="dynamics")
    assert model_title("wr") == "Wong-Reece" and model_title("my-law") == "my-law"


def test_every_builder_builds_its_model_on_a_medium_with_its_parameters():
    ms = materials.get("MS")
    for entry in MODELS:
        if entry.kind is not ModelKind.FORCE_LAW or entry.builder is None:
            continue
        model = entry.build(ms)
        assert model.name == entry.name
    assert isinstance(build_model("rft", ms, element_size=0.002), RFTModel)
    with pytest.raises(InputError, match="report reference"):
        model_entry("bekker").build(ms)


def test_cli_help_replay_sweeps_and_report_read_the_same_table(run_cli):
    from terradyn.locomotion.models import MODEL_NAMES
    from terradyn.replay.predict import REPLAY_MODELS
    from terradyn.report.registry import ITEMS

    assert model_names(use="replay") == REPLAY_MODELS
    assert model_names(use="sweep", dimension=2) == MODEL_NAMES
    for argv, use in (
        (["wheel", "steady", "--help"], "steady"),
        (["wheel", "self-propelled", "--help"], "self-propelled"),
        (["wheel", "sweep", "--help"], "sweep"),
        (["wheel", "simulate", "--help"], "dynamics"),
        (["replay", "--help"], "replay"),
    ):
        code, out, _ = run_cli(*argv)
        assert code == 0
        text = " ".join(re.sub(r"-\n\s+", "-", out).split())  # help wraps lines at hyphens
        listed = set(re.findall(r"[a-z0-9-]+", text.split("--model", 1)[1].split("--", 1)[0]))
        assert set(model_names(use=use)) <= listed, (argv, listed)
        others = set(model_names()) - set(model_names(use=use))
        assert not (others & listed - {"rft", "drft"}), (argv, others & listed)
    report_models = {m for it in ITEMS for m in it.models}
    assert report_models == set(model_names(use="report"))


def test_callable_model_moves_the_torque_like_rft_does():
    ms = materials.get("MS")
    wheel = WheelCircular(radius=0.1, width=0.1)
    pose, twist = Pose2D(0.01, 0.07, 0.3), Twist2D(0.05, 0.0, 1.0)
    user = CallableModel(lambda b, p, t: rft_wrench(b, ms, p, t))
    assert user.name == "<lambda>"
    for about in (None, (0.02, -0.01), (-0.3, 0.4)):
        a = RFTModel(ms).wrench(wheel, pose, twist, about=about)
        b = user.wrench(wheel, pose, twist, about=about)
        assert math.isclose(a.torque_y, b.torque_y, rel_tol=1e-12, abs_tol=1e-12)
    with pytest.raises(InputError, match="Wrench2D"):
        CallableModel(lambda b, p, t: 1.0).wrench(wheel, pose, twist)


def test_wheel_steady_takes_a_user_model_and_a_plain_function():
    """A user's object wrapping RFT goes the generic path (one wrench call per phase and height); it
    must give the compiled RFT path's answer (two independent solves of one law)."""
    from terradyn.locomotion import wheel_steady

    ms = materials.get("MS")
    wheel = WheelGrousered(0.1, 0.06, 8, 0.01, 0.004)

    class Mine:
        name = "mine"

        def wrench(self, body, pose, twist, *, about=None):
            return rft_wrench(body, ms, pose, twist, about=about)

    ref = wheel_steady(wheel, RFTModel(ms), 20.0, 0.3, phase_count=8)
    for model in (Mine(), lambda b, p, t: rft_wrench(b, ms, p, t)):
        got = wheel_steady(wheel, model, 20.0, 0.3, phase_count=8)
        assert math.isclose(got.sinkage_m, ref.sinkage_m, rel_tol=1e-4)
        assert math.isclose(got.drawbar_pull_N, ref.drawbar_pull_N, rel_tol=1e-3, abs_tol=1e-3)
        assert math.isclose(got.drive_torque_Nm, ref.drive_torque_Nm, rel_tol=1e-3)
    with pytest.raises(InputError, match="a terrain model"):
        wheel_steady(wheel, 3.0, 20.0, 0.3)


def test_replay_takes_a_user_model_and_refuses_to_calibrate_it():
    from importlib import resources
    from pathlib import Path

    from terradyn.replay import ReplayModel, read_runs, replay

    path = Path(str(resources.files("terradyn.replay").joinpath("data/example_runs.csv")))
    table = read_runs(path)
    rows = type(table)(table.rows[:4], table.extra_columns, table.source)
    named = replay(rows, ReplayModel("rft"))
    user = replay(rows, ReplayModel("my-rft", terrain=lambda m: RFTModel(m)))
    assert user.metadata["model"] == "my-rft"
    for a, b in zip(named.runs, user.runs, strict=True):
        assert a["predicted_drawbar_pull_N"] == pytest.approx(b["predicted_drawbar_pull_N"], rel=1e-9)
    with pytest.raises(InputError, match="scale"):
        ReplayModel("mine", terrain=RFTModel(materials.get("MS")), scale=2.0)
    with pytest.raises(InputError, match="calibration"):
        replay(rows, ReplayModel("mine", terrain=lambda m: RFTModel(m)), calibrate_on=0.5)


def test_the_models_page_lists_every_model():
    from pathlib import Path

    page = (Path(__file__).parents[2] / "docs" / "models.md").read_text(encoding="utf-8")
    section = page.split("## The model table", 1)[1].split("##", 1)[0]
    table = [line for line in section.splitlines() if line.startswith("| `")]
    assert [line.split("`")[1] for line in table] == [e.name for e in MODELS]
    for line, entry in zip(table, MODELS, strict=True):
        cells = [c.strip() for c in line.split("|")]
        assert cells[2] == entry.title and cells[3] == entry.kind.value.replace("-", " ")
        assert set(cells[6].split(", ")) == {u.replace("run-wheel", "run_wheel") for u in entry.uses}
