"""General numerics shared by the solvers and the studies: grid convergence (Richardson extrapolation
with Roache's grid convergence index, and a least-squares limit over four or more resolutions).

The procedure is the one of Roache's grid convergence index as written up by Celik et al. (2008) for
unequal refinement ratios: with the three finest resolutions h1 < h2 < h3 and results f1, f2, f3,
the observed order p solves

    p = | ln|e32 / e21| + q(p) | / ln r21,   q(p) = ln((r21^p - s) / (r32^p - s)),

with e21 = f2 - f1, e32 = f3 - f2, r21 = h2/h1, r32 = h3/h2 and s = sign(e32/e21). The extrapolated
value is f_ext = (r21^p f1 - f2) / (r21^p - 1) and the error band of the finest result is
GCI = 1.25 |f1 - f2| / (r21^p - 1) (absolute, in the quantity's unit). Oscillating results (s < 0)
or an order outside [0.2, 8] get no extrapolation: the band is then the spread of the three results.
An observed order above the scheme's formal order (2: quadratic B-splines; Roache's advice) is not
believed: the extrapolation and the band then use the formal order, which widens the band.

Results that ring with resolution (a force that oscillates by a few per cent as body faces and node
rows change their alignment) defeat a three-point estimate: one ringing reading flips the sign of a
change. With four or more resolutions :func:`least_squares_limit` also fits ``f = f_0 + C h^p`` at the
formal order p by least squares over all of them and reports f_0 with its standard error (the
residual scatter, the ringing, enters the error instead of the order).

References
----------
P. J. Roache, *Verification and Validation in Computational Science and Engineering* (1998).
I. B. Celik et al., "Procedure for estimation and reporting of uncertainty due to discretization in CFD
applications", J. Fluids Eng. 130, 078001 (2008), doi:10.1115/1.2960953.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .errors import InputError, check_positive

__all__ = [
    "FORMAL_ORDER",
    "LeastSquaresLimit",
    "RichardsonEstimate",
    "least_squares_limit",
    "richardson",
]

SAFETY_FACTOR = 1.25
ORDER_RANGE = (0.2, 8.0)
#: the highest order the MPM discretisation can show (quadratic B-spline shape functions)
FORMAL_ORDER = 2.0


@dataclass(frozen=True)
class RichardsonEstimate:
    """Richardson extrapolation of one quantity from its three finest resolutions.

    ``order`` [-] observed order (None when the results oscillate); ``extrapolated`` the estimate at
    zero cell size (None when no extrapolation is trustworthy); ``error_band`` the absolute
    uncertainty of the finest result (GCI, or the spread when not extrapolated); ``finest`` the
    finest result; ``monotone`` whether the three results change in one direction; ``note`` why an
    estimate is missing."""

    order: float | None
    extrapolated: float | None
    error_band: float
    finest: float
    monotone: bool
    note: str = ""

    def record(self, quantity: str) -> dict[str, Any]:
        """JSON-ready fields of the estimate of ``quantity`` (a key prefix such as ``"N_gamma"``):
        ``{quantity}_finest``, ``observed_order``, ``{quantity}_extrapolated``,
        ``error_band_of_finest``, ``monotone`` and ``note``."""
        return {
            f"{quantity}_finest": self.finest,
            "observed_order": self.order,
            f"{quantity}_extrapolated": self.extrapolated,
            "error_band_of_finest": self.error_band,
            "monotone": self.monotone,
            "note": self.note,
        }

    @property
    def relative_error(self) -> float | None:
        """|finest - extrapolated| / |extrapolated| [-] (None without an extrapolation)."""
        if self.extrapolated is None or self.extrapolated == 0:
            return None
        return abs(self.finest - self.extrapolated) / abs(self.extrapolated)


@dataclass(frozen=True)
class LeastSquaresLimit:
    """Least-squares fit ``f = extrapolated + C h^order`` over every resolution.

    ``coefficient`` C [quantity / m^order]; ``standard_error`` of the extrapolated value and
    ``residual_sd`` (the scatter about the fit, in the quantity's unit) from the residuals with
    ``points - 2`` degrees of freedom; ``finest`` the finest result."""

    extrapolated: float
    standard_error: float
    residual_sd: float
    order: float
    points: int
    finest: float
    coefficient: float

    @property
    def relative_error(self) -> float | None:
        """|finest - extrapolated| / |extrapolated| [-]."""
        return abs(self.finest - self.extrapolated) / abs(self.extrapolated) if self.extrapolated else None


def least_squares_limit(
    cell_sizes: Sequence[float], values: Sequence[float], order: float = FORMAL_ORDER
) -> LeastSquaresLimit:
    """Fit ``f = f_0 + C h^order`` to four or more (cell size [m], value) pairs; f_0 with its error."""

    if len(cell_sizes) != len(values) or len(cell_sizes) < 4:
        raise InputError("cell_sizes", list(cell_sizes), "four or more cell sizes, one value each")
    h = np.array([check_positive("cell_sizes", float(x)) for x in cell_sizes])
    f = np.array([float(v) for v in values])
    if len(set(h.tolist())) != h.size or not np.all(np.isfinite(f)):
        raise InputError("values", list(values), "finite values at distinct cell sizes")
    order = check_positive("order", order)
    a = np.column_stack([np.ones_like(h), h**order])
    coef, *_ = np.linalg.lstsq(a, f, rcond=None)
    resid = f - a @ coef
    s2 = float(resid @ resid) / (h.size - 2)
    cov = s2 * np.linalg.inv(a.T @ a)
    return LeastSquaresLimit(float(coef[0]), float(math.sqrt(cov[0, 0])), math.sqrt(s2), order, int(h.size),
                             float(f[np.argmin(h)]), float(coef[1]))  # fmt: skip


def _observed_order(ratio: float, r21: float, r32: float) -> float:
    """The order p > 0 with ``r21^p (r32^p - 1) / (r21^p - 1) = ratio`` (Celik et al. 2008, monotone
    case; the left side grows with p), by bisection on log p; inf when beyond p = 64."""

    def excess(p: float) -> float:
        return (
            p * math.log(r21)
            + math.log(math.expm1(p * math.log(r32)) / math.expm1(p * math.log(r21)))
            - math.log(ratio)
        )

    lo, hi = 1e-6, 64.0
    if excess(hi) < 0:
        return math.inf
    for _ in range(200):
        mid = math.sqrt(lo * hi)
        if excess(mid) < 0:
            lo = mid
        else:
            hi = mid
        if hi / lo < 1.0 + 1e-13:
            break
    return math.sqrt(lo * hi)


def richardson(cell_sizes: Sequence[float], values: Sequence[float]) -> RichardsonEstimate:
    """Observed order, extrapolated value and error band from results at three or more cell sizes.

    ``cell_sizes`` [m] (any order, distinct) and ``values`` (same length, finite). The three finest
    resolutions are used."""
    if len(cell_sizes) != len(values) or len(cell_sizes) < 3:
        raise InputError("cell_sizes", list(cell_sizes), "three or more cell sizes, one value each")
    pairs = sorted(zip((float(h) for h in cell_sizes), (float(v) for v in values), strict=True))
    if any(not (math.isfinite(h) and h > 0 and math.isfinite(v)) for h, v in pairs):
        raise InputError("values", list(values), "finite values at positive cell sizes")
    (h1, f1), (h2, f2), (h3, f3) = pairs[:3]
    if not (h1 < h2 < h3):
        raise InputError("cell_sizes", list(cell_sizes), "distinct cell sizes")
    e21, e32 = f2 - f1, f3 - f2
    spread = max(f1, f2, f3) - min(f1, f2, f3)
    scale = max(abs(f1), abs(f2), abs(f3), 1e-300)
    if abs(e21) <= 1e-12 * scale and abs(e32) <= 1e-12 * scale:
        return RichardsonEstimate(None, f1, 0.0, f1, True, "the results do not change with resolution")
    if abs(e21) <= 1e-12 * scale or e32 * e21 < 0:
        return RichardsonEstimate(None, None, spread, f1, False, "the results oscillate with resolution")
    r21, r32 = h2 / h1, h3 / h2
    ratio = e32 / e21  # > 0 here (same sign)
    lowest = math.log(r32) / math.log(r21)  # the ratio an order p -> 0+ gives
    if ratio <= lowest * (1.0 + 1e-12):
        # e32 / e21 = r21^p (r32^p - 1) / (r21^p - 1) grows with p from this value: no positive order
        # fits, the changes do not shrink as the grid is refined (not in the asymptotic range)
        note = (
            f"no positive observed order fits: the change on the finest refinement ({e21:.4g}) is not "
            f"smaller than the one before ({e32:.4g}) by the cell-size ratios; not in the asymptotic "
            "range, no extrapolation"
        )
        return RichardsonEstimate(None, None, spread, f1, True, note)
    p = _observed_order(ratio, r21, r32)
    if not (math.isfinite(p) and ORDER_RANGE[0] <= p <= ORDER_RANGE[1]):
        note = f"observed order {p:.3g} outside [{ORDER_RANGE[0]:g}, {ORDER_RANGE[1]:g}]: no extrapolation"
        return RichardsonEstimate(p, None, spread, f1, True, note)
    note = ""
    if p > FORMAL_ORDER:
        note = (
            f"observed order {p:.3g} is above the formal order {FORMAL_ORDER:g} of the scheme: the "
            f"extrapolation and the band use {FORMAL_ORDER:g}"
        )
    rp = r21 ** min(p, FORMAL_ORDER)
    extrapolated = (rp * f1 - f2) / (rp - 1.0)
    band = SAFETY_FACTOR * abs(f1 - f2) / (rp - 1.0)
    return RichardsonEstimate(p, extrapolated, band, f1, True, note)
