import math

import pytest

from terradyn import materials
from terradyn.errors import InputError
from terradyn.materials import LiCoefficients, Material, RFTParameters


def test_shipped_media_present_and_cited():
    names = materials.available()
    for required in ("generic", "poppy-lp", "poppy-cp", "MS", "MMS", "LPS", "CPS"):
        assert required in names
    for name in names:
        mat = materials.get(name)
        assert mat.provenance.citation, name
        assert mat.provenance.doi, name


@pytest.mark.parametrize(
    ("name", "zeta"),
    [
        ("generic", 1.0e6),
        ("MS", 2.02e6),
        ("MMS", 3.05e6),
        ("LPS", 0.35e6),
        ("CPS", 0.55e6),
        ("poppy-lp", 0.254e6),
        ("poppy-cp", 0.464e6),
    ],
)
def test_zeta_values(name, zeta):
    assert materials.get(name).zeta == pytest.approx(zeta, rel=1e-12)


def test_generic_coefficients_normalised():
    assert LiCoefficients.generic().alpha_z_plate_down() == pytest.approx(1.0, abs=1e-15)


def test_wheel_media_have_bekker_and_unit_reading():
    # MS/LPS/CPS read in N, MMS in kN (see the files' notes): the equivalent plate modulus for a
    # 0.16 m wide wheel must be positive and of the order of MPa/m for all four.
    for name in ("MS", "MMS", "LPS", "CPS"):
        b = materials.get(name).require_bekker()
        k = b.k_c / 0.16 + b.k_phi
        assert 1e6 < k < 1e8, name
        assert "Unit caveat" in materials.get(name).provenance.notes


def test_get_is_case_insensitive_and_rejects_unknown():
    assert materials.get("ms").name == "MS"
    with pytest.raises(InputError, match="material"):
        materials.get("moon-dust")


def test_load_user_file_and_errors(tmp_path):
    p = tmp_path / "mine.toml"
    p.write_text('[meta]\nname = "mine"\n[rft]\nzeta_N_per_cm3 = 1.5\n')
    mat = materials.load(p)
    assert mat.zeta == pytest.approx(1.5e6)
    assert materials.get(str(p)).name == "mine"
    bad = tmp_path / "bad.toml"
    bad.write_text('[meta]\nname = "x"\n[rft]\nzeta_N_per_cm3 = 1.5\nzetta = 2\n')
    with pytest.raises(InputError, match=r"\[rft\]\.zetta"):
        materials.load(bad)
    neg = tmp_path / "neg.toml"
    neg.write_text('[meta]\nname = "x"\n[rft]\nzeta_N_per_cm3 = -1\n')
    with pytest.raises(InputError, match="zeta_N_per_cm3"):
        materials.load(neg)
    broken = tmp_path / "broken.toml"
    broken.write_text("[meta\n")
    with pytest.raises(InputError, match="valid TOML"):
        materials.load(broken)
    with pytest.raises(InputError, match="existing"):
        materials.load(tmp_path / "missing.toml")


def test_custom_material_in_python_and_validation():
    mat = Material("custom", rft=RFTParameters(LiCoefficients.generic(), 2.5e6))
    assert mat.zeta == pytest.approx(2.5e6)
    assert mat.with_zeta(1e6).zeta == pytest.approx(1e6)
    with pytest.raises(InputError, match=r"rft\.scale"):
        RFTParameters(LiCoefficients.generic(), -1.0)
    with pytest.raises(InputError, match="A00"):
        LiCoefficients(math.nan, 0, 0, 0, 0, 0, 0, 0, 0)
    with pytest.raises(InputError, match="critical_density"):
        Material("x", grain_density=1000.0, critical_density=2000.0)
    with pytest.raises(InputError, match="bekker"):
        Material("x").require_bekker()
