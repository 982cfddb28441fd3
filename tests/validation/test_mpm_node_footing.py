"""The MPM continuum against the finite-element reference, with the footing base as a grid condition
(no contact body): refining from B/20 to B/40 moves N_gamma toward the isochoric FE value of the same
cone (:mod:`terradyn.plasticity.references`) in each of the four tabulated cases. Slow: about six
minutes per case on one core (6 B x 3 B bed). Measured (docs/mpm.md, "Footing as a grid boundary
condition"): 18.62 / 14.42 (34 deg smooth, FE 10.74 slow push), 26.43 / 22.39 (34 deg rough, FE 19.66
slow push), 11.36 / 9.28 (30 deg smooth, FE 6.51 slow push), 17.27 / 14.46 (30 deg rough, FE 11.66 slow
push). At B/80 the 34 deg smooth and rough ones read 12.03 (4 B x 2 B) and 20.05, +12 % and +2 % (all
at 0.01 m/s with APIC, which is not rate converged: docs/mpm.md, "Loading rate" and "What the rate
error is")."""

from __future__ import annotations

import pytest

from terradyn.plasticity import strip_footing_reference
from terradyn.studies.mpm_footing_nodes import node_strip_footing


@pytest.mark.slow
@pytest.mark.parametrize(
    ("phi", "base"), [(34.0, "smooth"), (34.0, "rough"), (30.0, "smooth"), (30.0, "rough")]
)
def test_refinement_moves_the_node_footing_toward_the_fe_value(phi, base):
    reference = strip_footing_reference(phi, base)
    assert reference["reference_kind"] == "computed, finite elements"
    ref = reference["N_gamma_reference"]
    coarse = node_strip_footing(phi, base, cell_size=0.04 / 20).N_gamma
    fine = node_strip_footing(phi, base, cell_size=0.04 / 40).N_gamma
    assert abs(fine - ref) < abs(coarse - ref), (coarse, fine, ref)
