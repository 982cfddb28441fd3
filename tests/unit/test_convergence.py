"""Richardson extrapolation and the grid-convergence driver."""

from __future__ import annotations

import math

import pytest

from terradyn.errors import InputError
from terradyn.numerics import least_squares_limit, richardson
from terradyn.studies.convergence import converge


@pytest.mark.parametrize("order", [0.7, 1.0, 2.0])
@pytest.mark.parametrize(
    "sizes", [(0.01, 0.005, 0.0025), (0.012, 0.008, 0.005), (0.004, 0.01, 0.0065), (0.01, 0.0075, 0.005)]
)
def test_richardson_recovers_order_and_limit_of_a_power_law(order, sizes):
    f0, c = 25.0, -300.0
    est = richardson(sizes, [f0 + c * h**order for h in sizes])
    assert est.order == pytest.approx(order, rel=1e-6)
    assert est.extrapolated == pytest.approx(f0, rel=1e-9)
    assert est.monotone
    finest = min(sizes)
    # the band covers the true error of the finest result (safety factor 1.25 > 1)
    assert est.error_band >= abs(f0 + c * finest**order - f0)
    assert est.error_band == pytest.approx(1.25 * abs(c) * finest**order, rel=1e-6)


def test_richardson_uses_the_three_finest():
    sizes = [0.04, 0.02, 0.01, 0.005]
    values = [999.0] + [10 + 2 * h for h in sizes[1:]]  # the coarsest is off the asymptotic range
    assert richardson(sizes, values).extrapolated == pytest.approx(10.0)


def test_oscillating_results_get_no_extrapolation():
    est = richardson([0.01, 0.005, 0.0025], [10.0, 12.0, 11.0])
    assert est.extrapolated is None and est.order is None and not est.monotone
    assert est.error_band == pytest.approx(2.0)
    assert "oscillate" in est.note


def test_implausible_order_is_reported_not_extrapolated():
    sizes = (0.01, 0.005, 0.0025)
    est = richardson(sizes, [10.0 + 1e-6, 10.0, 10.0 - 1.0])  # changes grow as the grid is refined
    assert est.extrapolated is None and "order" in est.note
    assert est.error_band == pytest.approx(1.000001)


def test_converge_runs_coarse_to_fine_and_checks_inputs():
    seen = []

    def run(h):
        seen.append(h)
        return {"f": 3.0 + h, "g": 1.0 - h**2}

    res = converge(run, [0.005, 0.02, 0.01], ["f", "g"])
    assert seen == [0.02, 0.01, 0.005]
    assert res.estimates["f"].order == pytest.approx(1.0)
    assert res.estimates["g"].order == pytest.approx(2.0)
    assert res.estimates["g"].extrapolated == pytest.approx(1.0)
    assert [r["cell_size_m"] for r in res.runs()] == [0.02, 0.01, 0.005]
    assert {r["quantity"] for r in res.summary()} == {"f", "g"}
    with pytest.raises(InputError, match="three or more"):
        converge(run, [0.01, 0.005], ["f"])
    with pytest.raises(InputError, match="quantities"):
        converge(run, [0.02, 0.01, 0.005], ["nosuch"])
    assert math.isfinite(res.wall_s[0])


def test_changes_that_grow_on_refinement_get_no_extrapolation():
    # measured: 60 mm plate at 40 mm depth, MS, 10 / 7.5 / 5 / 3.75 mm cells. The last change (16.0 N
    # for a 1.33x refinement) exceeds the one before (6.3 N for 1.5x): no positive order fits. Taking
    # the absolute value of Celik's fixed point had turned this into an order of 6.1 and a 4 N band.
    sizes = [0.01, 0.0075, 0.005, 0.00375]
    est = richardson(sizes, [226.4003, 211.2405, 204.9065, 188.8667])
    assert est.order is None and est.extrapolated is None
    assert "asymptotic" in est.note
    assert est.error_band == pytest.approx(211.2405 - 188.8667)
    # the same sizes with a converging power law still extrapolate
    est = richardson(sizes, [100.0 + 50.0 * h**0.5 for h in sizes])
    assert est.order == pytest.approx(0.5, rel=1e-6)


def test_an_order_above_the_formal_order_is_capped_in_the_band():
    """A plate sequence of docs/mpm.md (patch divergence, "first split" column): observed order 6.8
    is not believed; the band uses order 2 and so is wider than the raw GCI."""
    sizes, values = (0.01, 0.0075, 0.005, 0.00375), (215.72, 200.79, 162.74, 160.52)
    est = richardson(sizes, values)
    assert est.order == pytest.approx(6.79, abs=0.05)
    r = 0.005 / 0.00375
    assert est.error_band == pytest.approx(1.25 * (162.74 - 160.52) / (r**2 - 1), rel=1e-9)
    assert est.extrapolated == pytest.approx((r**2 * 160.52 - 162.74) / (r**2 - 1), rel=1e-9)
    raw_band = 1.25 * (162.74 - 160.52) / (r**6.79 - 1)
    assert est.error_band > 3 * raw_band
    assert "formal order" in est.note
    # power laws up to the formal order are untouched (see the parametrised test above)
    assert richardson((0.01, 0.005, 0.0025), [25 - 300 * h**2 for h in (0.01, 0.005, 0.0025)]).note == ""


def test_least_squares_limit_recovers_a_power_law_and_measures_ringing():
    sizes = [0.005, 0.00375, 0.003, 0.0025]
    exact = least_squares_limit(sizes, [160.0 + 1.5e6 * h**2 for h in sizes])
    assert exact.extrapolated == pytest.approx(160.0, rel=1e-9)
    assert exact.coefficient == pytest.approx(1.5e6, rel=1e-6)
    assert exact.standard_error == pytest.approx(0.0, abs=1e-6)
    assert exact.finest == pytest.approx(160.0 + 1.5e6 * 0.0025**2)
    # +-3 N of alternating ringing on the same law: the limit stays near 160 and the error grows
    rung = least_squares_limit(sizes, [160.0 + 1.5e6 * h**2 + 3.0 * (-1) ** k for k, h in enumerate(sizes)])
    assert abs(rung.extrapolated - 160.0) < 3 * rung.standard_error
    assert rung.residual_sd > 1.0 and rung.standard_error > 1.0
    with pytest.raises(InputError, match="four or more"):
        least_squares_limit(sizes[:3], [1.0, 2.0, 3.0])
    with pytest.raises(InputError, match="distinct"):
        least_squares_limit([0.01, 0.01, 0.005, 0.002], [1.0, 2.0, 3.0, 4.0])


def test_the_measured_plate_sequence_rings_and_gets_a_least_squares_limit():
    """docs/mpm.md, classical update, 60 mm plate at 40 mm: 5 / 3.75 / 3 / 2.5 mm. The three finest
    oscillate (no Richardson value); the least-squares limit at order 2 is 164.7 +- 6.5 N."""
    sizes, values = [0.005, 0.00375, 0.003, 0.0025], [203.7, 189.3, 171.9, 178.8]
    assert richardson(sizes, values).extrapolated is None
    fit = least_squares_limit(sizes, values)
    assert fit.extrapolated == pytest.approx(164.7, abs=0.1)
    assert fit.standard_error == pytest.approx(6.46, abs=0.01)
    res = converge(lambda h: {"f": dict(zip(sizes, values, strict=True))[h]}, sizes, ["f"])
    (row,) = res.summary()
    assert row["ls_extrapolated"] == pytest.approx(164.7, abs=0.1)
    assert row["relative_error_finest_ls"] == pytest.approx(178.8 / fit.extrapolated - 1)
    assert converge(lambda h: {"f": 1.0 + h}, sizes[:3], ["f"]).fits == {}


def test_grid_phases_average_a_ringing_that_depends_on_where_the_grid_lies():
    """A force F0 + C h^2 + A cos(2 pi (D / h + offset)): one phase per cell size rings with h; the mean
    of two phases half a cell apart cancels the ringing, so the limit comes out at F0."""
    f0, c, a, depth = 100.0, 2.0e5, 6.0, 0.04

    def run(h, offset=0.0):
        return {"f": f0 + c * h * h + a * math.cos(2 * math.pi * (depth / h + offset))}

    sizes = [0.01, 0.0075, 0.006, 0.005, 0.004]
    one = converge(run, sizes, ["f"])
    two = converge(run, sizes, ["f"], grid_phases=2)
    assert two.metadata["grid_phases"] == 2 and "grid_phases" not in one.metadata
    assert two.fits["f"].extrapolated == pytest.approx(f0, abs=1e-6)
    assert abs(one.fits["f"].extrapolated - f0) > 1.0  # the single phase is thrown off by the ringing
    (row, *_) = two.runs()
    assert row["f_phase_spread"] == pytest.approx(2 * a * abs(math.cos(2 * math.pi * depth / 0.01)), rel=1e-9)
    calls = []
    converge(
        lambda h, offset: calls.append((h, offset)) or {"f": 1.0}, [0.03, 0.02, 0.01], ["f"], grid_phases=2
    )
    assert calls == [(0.03, 0.0), (0.03, 0.5), (0.02, 0.0), (0.02, 0.5), (0.01, 0.0), (0.01, 0.5)]
    with pytest.raises(InputError, match="grid_phases"):
        converge(run, sizes, ["f"], grid_phases=0)


def test_converge_intrusion_moves_the_bed_grid_per_phase(monkeypatch):
    import terradyn.mpm as mpm
    from terradyn.mpm.specs import Bed, Resolution
    from terradyn.studies.convergence import converge_intrusion

    seen = []

    def fake(body, material, *, resolution, bed=None, **kw):
        seen.append((resolution.cell_size, bed.surface_offset, bed.packing.value))
        return type("R", (), {"summary": {"force_z_N": 1.0}})()

    monkeypatch.setattr(mpm, "run_intrusion", fake)
    converge_intrusion(None, None, cell_sizes=[0.03, 0.02, 0.01], quantities=["force_z_N"], grid_phases=2,
                       depth=0.01, bed=Bed(packing="unconsolidated"))  # fmt: skip
    assert seen[:2] == [(0.03, 0.0, "unconsolidated"), (0.03, 0.5, "unconsolidated")] and len(seen) == 6
    with pytest.raises(InputError, match="grid_phases"):  # 3 phases need 3 points per cell
        converge_intrusion(None, None, cell_sizes=[0.03, 0.02, 0.01], grid_phases=3, depth=0.01)
    with pytest.raises(InputError, match="grid_phases"):
        converge_intrusion(None, None, cell_sizes=[0.03, 0.02, 0.01], grid_phases=2, depth=0.01,
                           resolution=Resolution(particles_per_cell=3))  # fmt: skip
