"""Writing a material TOML and reading it back gives the same material."""

from __future__ import annotations

import dataclasses

import pytest

from terradyn import materials


@pytest.mark.parametrize("name", materials.available())
def test_every_shipped_medium_round_trips(name, tmp_path):
    original = materials.get(name)
    path = materials.write_material(tmp_path / f"{name}.toml", original)
    again = materials.load(path)
    assert again == original


def test_changed_continuum_round_trips(tmp_path):
    ms = materials.get("MS")
    changed = ms.with_changes(
        name="MS-fit",
        continuum=dataclasses.replace(ms.continuum, friction_coefficient=0.61, friction_coefficient_2=0.9),
    )
    again = materials.load(materials.write_material(tmp_path / "fit.toml", changed))
    assert again.continuum.friction_coefficient == 0.61 and again.name == "MS-fit"
    assert again.rft == ms.rft


def test_write_refuses_other_extensions(tmp_path):
    from terradyn.errors import InputError

    with pytest.raises(InputError, match="toml"):
        materials.write_material(tmp_path / "x.txt", materials.get("MS"))
