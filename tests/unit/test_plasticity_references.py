"""The shipped strip-footing reference table and strip_footing_reference (terradyn.plasticity.references)."""

from __future__ import annotations

import json
import math

import pytest

from terradyn.errors import InputError
from terradyn.plasticity import davis1968_reduced_friction_angle, moc_n_gamma, reference_entries
from terradyn.plasticity import strip_footing_reference as ref

KINDS = {"computed", "estimate", "approximation", "published, not retrieved"}


def test_every_entry_names_its_source_kind_and_caveats():
    rows = reference_entries()
    assert len(rows) >= 8
    for row in rows:
        assert row["kind"] in KINDS
        assert row["source"] and row["table"] and row["notes"]
        assert row["base"] in ("smooth", "rough") and row["flow"] in ("associated", "isochoric")
        # a number only where terradyn computed it; nothing guessed for unread papers
        if row["kind"] == "published, not retrieved":
            assert row["value"] is None
        if row["kind"] in ("computed", "estimate"):
            assert isinstance(row["value"], float) and row["value"] > 0
    covered = {(r["phi_deg"], r["base"]) for r in rows}
    assert covered == {(30.0, "smooth"), (30.0, "rough"), (34.0, "smooth"), (34.0, "rough")}


@pytest.mark.parametrize("row", [r for r in reference_entries() if r["kind"] in ("computed", "estimate")])
def test_computed_entries_reproduce_on_a_coarser_mesh(row):
    phi = math.radians(row["phi_deg"])
    if row["flow"] == "isochoric":
        phi = davis1968_reduced_friction_angle(phi, 0.0)
    fresh = moc_n_gamma(phi, fan_count=16, ray_count=80).n_gamma
    assert fresh == pytest.approx(row["value"], rel=3e-3)


@pytest.mark.parametrize("phi_deg", [30, 34])
def test_smooth_reference_is_the_isochoric_estimate_below_the_associated_value(phi_deg):
    out = ref(phi_deg, "smooth")
    json.dumps(out)  # JSON-ready, as the MPM verify command prints it
    assert out["reference_kind"] == "estimate"
    assert 0.0 < out["N_gamma_reference"] < out["N_gamma_associated"]
    assert "Davis" in out["reference"]
    assert out["reduced_friction_angle_deg"] == pytest.approx(
        math.degrees(math.atan(math.sin(math.radians(phi_deg))))
    )
    assert {e["kind"] for e in out["published_non_associated"]} == {"published, not retrieved"}
    assert len(out["published_non_associated"]) == 2


def test_rough_reference_is_labelled_an_approximation_without_an_exact_value():
    out = ref(30, "rough")
    assert out["reference_kind"] == "approximation"
    assert out["N_gamma_associated"] is None
    assert "Hansen" in out["reference"]
    assert out["N_gamma_reference"] > ref(30, "smooth")["N_gamma_reference"]


def test_untabulated_angle_is_computed():
    out = ref(32.0, "smooth")
    assert (
        ref(30, "smooth")["N_gamma_reference"]
        < out["N_gamma_reference"]
        < ref(34, "smooth")["N_gamma_reference"]
    )


@pytest.mark.parametrize(
    ("phi", "base", "field"), [(5.0, "smooth", "phi"), (30.0, "glued", "base"), ("x", "rough", "phi")]
)
def test_bad_arguments_are_refused(phi, base, field):
    with pytest.raises(InputError, match=field):
        ref(phi, base)
