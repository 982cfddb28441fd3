"""Each shipped medium's Bekker parameters against its cited source, with the unit conversion written out.

Source: Agarwal et al., J. Terramechanics 85, 1-14 (2019), arXiv:1901.10667, material table. Printed
(every column labelled kN/m^(n+1) for k_c and kN/m^(n+2) for k_phi):

    medium   k_c        k_phi     n     RFT constant [N/cm^3]
    MS       -2.05e+4   3.13e+6   1.0   2.02
    MMS       846       6708      1.4   3.05
    LPS      -2.06e+5   7.07e+6   1     0.35
    CPS      -3.24e+5   1.11e+7   1     0.55

The reading of each column (N or kN) is settled against the RFT constant of the same table: for
n = 1 the Bekker law p = (k_c/b + k_phi) z and the RFT plate law p = zeta z describe the same
plate-sinkage test (terradyn.report.bekker_audit).
"""

import math

import pytest

from terradyn import materials

KN = 1000.0  # N per kN
WHEEL_WIDTH = 0.16  # m, the Bekker b of the paper's wheel
Z = 0.02  # m, sinkage at which the pressures are compared

# medium: (printed k_c, printed k_phi, n, zeta [N/cm^3], N per printed unit)
SOURCE = {
    "MS": (-2.05e4, 3.13e6, 1.0, 2.02, 1.0),  # printed number read as N/m^2, N/m^3
    "MMS": (846.0, 6708.0, 1.4, 3.05, KN),  # printed kN/m^2.4, kN/m^3.4 -> x 1000 N per kN
    "LPS": (-2.06e5, 7.07e6, 1.0, 0.35, 1.0),  # N (the nearer reading; still inconsistent, below)
    "CPS": (-3.24e5, 1.11e7, 1.0, 0.55, 1.0),  # N (idem)
}


def _pressure_ratio(k_c: float, k_phi: float, n: float, zeta_n_per_cm3: float) -> float:
    zeta = zeta_n_per_cm3 * 1e6  # N/cm^3 -> N/m^3 (1 cm^3 = 1e-6 m^3)
    return (k_c / WHEEL_WIDTH + k_phi) * Z**n / (zeta * Z)


@pytest.mark.parametrize("medium", sorted(SOURCE))
def test_shipped_bekker_equals_source_in_the_settled_unit(medium):
    k_c, k_phi, n, zeta, factor = SOURCE[medium]
    mat = materials.get(medium)
    b = mat.require_bekker()
    assert b.k_c == pytest.approx(k_c * factor, rel=1e-12)  # N/m^(n+1)
    assert b.k_phi == pytest.approx(k_phi * factor, rel=1e-12)  # N/m^(n+2)
    assert b.n == n
    assert mat.zeta == pytest.approx(zeta * 1e6, rel=1e-12)
    # the stiffness at the wheel width, k_c / b + k_phi [N/m^(n+2)], pinned to the source
    assert b.k_c / WHEEL_WIDTH + b.k_phi == pytest.approx(factor * (k_c / WHEEL_WIDTH + k_phi), rel=1e-12)
    assert "bekker_audit" in mat.provenance.notes


def test_the_settled_reading_is_the_one_nearest_the_rft_plate_pressure():
    for medium, (k_c, k_phi, n, zeta, factor) in SOURCE.items():
        other = KN if factor == 1.0 else 1.0
        chosen = abs(math.log(_pressure_ratio(factor * k_c, factor * k_phi, n, zeta)))
        rejected = abs(math.log(_pressure_ratio(other * k_c, other * k_phi, n, zeta)))
        assert chosen < rejected, medium
    # MS and MMS are consistent with their RFT constant within a factor 2 ...
    assert _pressure_ratio(-2.05e4, 3.13e6, 1.0, 2.02) == pytest.approx(1.486, rel=1e-3)
    assert _pressure_ratio(846.0 * KN, 6708.0 * KN, 1.4, 3.05) == pytest.approx(0.822, rel=1e-3)
    # ... the poppy-seed columns are not, in either reading: 16.5 x (N) or 16500 x (kN) at b = 0.16 m
    for medium in ("LPS", "CPS"):
        k_c, k_phi, n, zeta, _ = SOURCE[medium]
        assert _pressure_ratio(k_c, k_phi, n, zeta) == pytest.approx(16.5, rel=2e-3)


def test_audit_module_agrees_with_this_file():
    from terradyn.report.bekker_audit import audit

    rows = {r["medium"]: r for r in audit()}
    for medium, (k_c, k_phi, _, _, factor) in SOURCE.items():
        r = rows[medium]
        assert r["reading"] == ("N" if factor == 1.0 else "kN")
        assert r["k_c_N_per_m_n1"] == pytest.approx(k_c * factor)
        assert r["k_phi_N_per_m_n2"] == pytest.approx(k_phi * factor)
        assert r["consistent"] is (medium in ("MS", "MMS"))
    assert rows["LPS"]["width_matching_rft_m"] == pytest.approx(0.0307, abs=2e-4)
