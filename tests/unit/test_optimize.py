import pytest

from terradyn.errors import InputError, SolverError
from terradyn.optimize import Bound, optimize


def test_finds_known_optimum_of_synthetic_objective():
    # Maximum 3 at (x, y, n) = (0.3, -1.2, 4); a second, lower peak at x = -1.5.
    def f(p):
        main = 3 - (p["x"] - 0.3) ** 2 - 2 * (p["y"] + 1.2) ** 2 - 0.1 * (p["n"] - 4) ** 2
        decoy = 2.5 - 10 * (p["x"] + 1.5) ** 2
        return max(main, decoy)

    res = optimize(
        f,
        [Bound("x", -2, 2), Bound("y", -2, 2), Bound("n", 1, 9, integer=True)],
        seed=1,
        max_iterations=200,
        population=20,
        tolerance=1e-10,
        polish=False,
    )
    assert res.best["n"] == 4
    assert res.best["x"] == pytest.approx(0.3, abs=2e-2)
    assert res.best["y"] == pytest.approx(-1.2, abs=2e-2)
    assert res.best_value == pytest.approx(3.0, abs=1e-3)
    assert len(res.trace) > 5
    assert res.trace == sorted(res.trace)  # best-so-far never gets worse
    assert res.trace[-1] == pytest.approx(res.best_value)
    assert len(res.evaluations) > 100


def test_minimise_and_infeasible_points():
    def g(p):
        if p["x"] < 0:
            raise SolverError("infeasible")
        return (p["x"] - 0.5) ** 2

    res = optimize(g, [Bound("x", -1, 1)], maximize=False, seed=0, max_iterations=100)
    assert res.best["x"] == pytest.approx(0.5, abs=1e-2)
    assert not res.evaluations.columns["feasible"].all()


def test_bad_bounds():
    with pytest.raises(InputError, match=r"bounds\.x"):
        Bound("x", 1, 0)
    with pytest.raises(InputError, match="distinct"):
        optimize(lambda p: 0.0, [Bound("x", 0, 1), Bound("x", 0, 1)])
