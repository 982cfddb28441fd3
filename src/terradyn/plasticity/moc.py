"""Method of characteristics (slip-line method) for a rigid strip footing on a Mohr-Coulomb half-space.

Plane strain, rigid-perfectly plastic Mohr-Coulomb soil (friction angle ``phi``, cohesion ``c``, unit
weight ``gamma``), horizontal free surface loaded by a surcharge ``q``, vertical central load on a
footing of width ``B`` with a smooth or a fully rough base. Associated flow: the stress field built
here is the exact collapse solution in the sense of Martin (2005).

Frame of the solver: ``x`` horizontal from the footing centre line, ``y`` depth (down); the right
footing edge is at ``x = B/2``. Public results convert to terradyn's frame (``z`` up) on request.

Stress variables (compression positive): ``s = p + c cot phi`` (``p`` the in-plane mean stress) and
``theta``, the angle from +x to the major principal stress, so that

    sigma_x = s (1 + sin phi cos 2 theta) - c cot phi
    sigma_y = s (1 - sin phi cos 2 theta) - c cot phi
    tau_xy  = s sin phi sin 2 theta.

With ``mu = pi/4 - phi/2`` the two families of characteristics and their compatibility relations are
(Sokolovskii 1965)

    alpha lines, dy/dx = tan(theta + mu):  ds + 2 s tan phi dtheta = gamma (dy + tan phi dx)
    beta lines,  dy/dx = tan(theta - mu):  ds - 2 s tan phi dtheta = gamma (dy - tan phi dx)

solved on the net of their intersections by the standard second-order (trapezoidal, iterated)
finite-difference scheme.

Construction (right half; the left half is the mirror image):

1. Passive Rankine zone under the free surface beyond the edge: ``theta = 0`` and
   ``s = (q + c cot phi + gamma y) / (1 - sin phi)`` on the alpha line from the edge at angle ``mu``
   below the surface (points spaced geometrically from the edge).
2. Radial shear fan centred on the footing edge: alpha lines leave the edge with ``theta`` from 0 to
   the fan angle, ``s = s_0 exp(2 theta tan phi)`` at the apex.
3. Smooth base: the footing base is a boundary with ``theta = pi/2`` (no shear); each beta line that
   reaches it fixes ``s`` there and starts a new alpha line (mixed boundary-value problem), until the
   base is covered to the centre line. ``q_u`` is the mean of ``sigma_y`` over the base.
4. Rough base: a rigid wedge sits under the footing, bounded by the last fan alpha line from each edge;
   the fan angle is found (bisection) so that this line meets the centre line with ``theta = pi/2``
   (symmetric stresses at the wedge tip). ``q_u`` follows from the vertical equilibrium of the wedge.
   For weightless soil this is Prandtl's wedge and reproduces ``N_q``, ``N_c`` exactly.

``N_gamma`` (``c = q = 0``) is singular at the footing edge (``s = 0`` there). It is obtained, as in
Han et al. (2016), from the surcharge ratio ``lambda = q / (gamma B)``: ``N_gamma(lambda) =
(q_u - q N_q) / (gamma B / 2)`` computed at ``lambda = 1e-3, 1e-4, 1e-5`` and extrapolated to
``lambda -> 0`` (Aitken's delta-squared), see :func:`moc_n_gamma`.

Limitation: for a rough base the wedge construction of step 4 has no solution once the self-weight
dominates (``lambda`` below about 0.05 at phi = 30 deg): the exact rough ``N_gamma`` needs the
non-centred "false head" construction of Martin (2005), which this module does not implement;
:func:`moc_n_gamma` raises :class:`~terradyn.errors.SolverError` for ``base="rough"``.

References
----------
V. V. Sokolovskii, Statics of Granular Media (Pergamon, Oxford, 1965).
C. M. Martin, Exact bearing capacity calculations using the method of characteristics, Proc. 11th
Int. Conf. IACMAG, Turin, vol. 4, 441-450 (2005).
D. Han, X. Xie, L. Zheng, L. Huang, The bearing capacity factor N_gamma of strip footings on c-phi-gamma
soil using the method of characteristics, SpringerPlus 5, 1482 (2016). doi:10.1186/s40064-016-3084-6
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from enum import Enum

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError, SolverError, check_finite, check_length, check_positive
from .slipline import SlipLine

__all__ = [
    "FootingBase",
    "NGammaResult",
    "StripFootingMoC",
    "moc_bearing_factors",
    "moc_n_gamma",
    "moc_n_gamma_convergence",
    "moc_strip_footing",
]

FloatArray = NDArray[np.float64]
Node = tuple[float, float, float, float]  # x [m], y [m], s [Pa], theta [rad]


class FootingBase(str, Enum):
    """Footing-soil interface: ``smooth`` (no shear) or ``rough`` (no slip)."""

    SMOOTH = "smooth"
    ROUGH = "rough"


def _base(value: FootingBase | str) -> FootingBase:
    try:
        return FootingBase(value)
    except ValueError:
        raise InputError("base", value, "'smooth' or 'rough'") from None


# --------------------------------------------------------------------------------------------------
# Kernels: plain floats, no checks.
# --------------------------------------------------------------------------------------------------


def _interior(a: Node, b: Node, mu: float, tphi: float, gam: float) -> Node:
    """Node on the alpha line through ``a`` and the beta line through ``b`` (iterated trapezoid rule)."""
    xa, ya, sa, ta = a
    xb, yb, sb, tb = b
    tp, sp = 0.5 * (ta + tb), 0.5 * (sa + sb)
    xp, yp = 0.5 * (xa + xb), 0.5 * (ya + yb)
    for _ in range(40):
        ang_a = 0.5 * (ta + tp) + mu
        ang_b = 0.5 * (tb + tp) - mu
        ca, sna = math.cos(ang_a), math.sin(ang_a)
        cb, snb = math.cos(ang_b), math.sin(ang_b)
        det = cb * sna - ca * snb
        if abs(det) < 1e-300:
            raise SolverError("characteristics became parallel: the slip-line net degenerated")
        rx, ry = xb - xa, yb - ya
        la = (ry * cb - rx * snb) / det
        xp, yp = xa + la * ca, ya + la * sna
        ma, mb = 0.5 * (sa + sp), 0.5 * (sb + sp)
        r1 = sa + 2.0 * ma * tphi * ta + gam * ((yp - ya) + tphi * (xp - xa))
        r2 = sb - 2.0 * mb * tphi * tb + gam * ((yp - yb) - tphi * (xp - xb))
        den = 2.0 * tphi * (ma + mb)
        tn = (r1 - r2) / den if den > 0.0 else tp
        sn = r1 - 2.0 * ma * tphi * tn
        done = abs(tn - tp) < 1e-14 and abs(sn - sp) <= 1e-13 * (1.0 + abs(sn))
        tp, sp = tn, sn
        if done:
            break
    return (xp, yp, sp, tp)


def _on_base(b: Node, theta_base: float, mu: float, tphi: float, gam: float) -> Node:
    """Node where the beta line through ``b`` meets the base ``y = 0`` with ``theta = theta_base``."""
    xb, yb, sb, tb = b
    ang = 0.5 * (tb + theta_base) - mu
    xp = xb - yb * math.cos(ang) / math.sin(ang)
    sp = sb
    for _ in range(60):
        mb = 0.5 * (sb + sp)
        sn = sb + 2.0 * mb * tphi * (theta_base - tb) + gam * ((0.0 - yb) - tphi * (xp - xb))
        if abs(sn - sp) <= 1e-14 * (1.0 + abs(sn)):
            sp = sn
            break
        sp = sn
    return (xp, 0.0, sp, theta_base)


def _ray_radii(half_width: float, extent: float, count: int, first: float) -> list[float]:
    """Distances from the edge along the passive boundary: 0, then geometric from ``first`` to ``extent``."""
    if first >= extent:
        return [extent * j / count for j in range(count + 1)]
    ratio = (extent / first) ** (1.0 / (count - 1))
    return [0.0] + [first * ratio**j for j in range(count)]


def _fan(
    half_width: float,
    phi: float,
    gam: float,
    s0: float,
    fan_angle: float,
    radii: list[float],
    n: int,
) -> list[list[Node]]:
    """Passive boundary (row 0) and the fan alpha lines 1..n; row i holds nodes j = 0..m."""
    sin_phi, tphi, mu = math.sin(phi), math.tan(phi), math.pi / 4 - phi / 2
    row: list[Node] = [
        (half_width + r * math.cos(mu), r * math.sin(mu), s0 + gam * r * math.sin(mu) / (1.0 - sin_phi), 0.0)
        for r in radii
    ]
    rows = [row]
    for i in range(1, n + 1):
        th = fan_angle * i / n
        new: list[Node] = [(half_width, 0.0, s0 * math.exp(2.0 * tphi * th), th)]
        for j in range(1, len(radii)):
            new.append(_interior(new[j - 1], row[j], mu, tphi, gam))
        rows.append(new)
        row = new
    return rows


@dataclass(frozen=True)
class _Net:
    """The nodes of a solve: ``rows[i]`` is alpha line i as a list of (j, node)."""

    rows: list[list[tuple[int, Node]]]
    pressure: float
    fan_angle: float


def _solve_smooth(
    half_width: float, phi: float, gam: float, s0: float, cot_c: float, radii: list[float], n: int
) -> _Net:
    sin_phi, tphi, mu = math.sin(phi), math.tan(phi), math.pi / 4 - phi / 2
    fan_angle = math.pi / 2
    fan = _fan(half_width, phi, gam, s0, fan_angle, radii, n)
    rows: list[list[tuple[int, Node]]] = [list(enumerate(r)) for r in fan]
    m = len(radii) - 1
    prev: list[Node | None] = list(fan[-1])
    base: list[Node] = [fan[-1][0]]
    for k in range(1, m + 1):
        cur: list[Node | None] = [None] * (m + 1)
        pk = prev[k]
        assert pk is not None
        cur[k] = _on_base(pk, fan_angle, mu, tphi, gam)
        for j in range(k + 1, m + 1):
            a, b = cur[j - 1], prev[j]
            assert a is not None and b is not None
            cur[j] = _interior(a, b, mu, tphi, gam)
        rows.append([(j, nd) for j, nd in enumerate(cur) if nd is not None])
        node = cur[k]
        assert node is not None
        base.append(node)
        prev = cur
        if node[0] <= 0.0:
            break
    else:
        raise SolverError(
            "the slip-line net did not cover the footing base",
        )
    # sigma_y on the base (theta = pi/2): s (1 + sin phi) - c cot phi; trapezoid from the edge to x = 0
    force = 0.0
    for a, b in itertools.pairwise(base):
        pa = a[2] * (1.0 + sin_phi) - cot_c
        pb = b[2] * (1.0 + sin_phi) - cot_c
        xa, xb = a[0], b[0]
        if xb < 0.0:
            pb = pa + (pb - pa) * xa / (xa - xb)
            xb = 0.0
        force += 0.5 * (pa + pb) * (xa - xb)
    return _Net(rows, force / half_width, fan_angle)


def _wedge_line(line: list[Node]) -> list[Node] | None:
    """The fan line from the edge up to its crossing of the centre line, or None if it never crosses."""
    out = [line[0]]
    for a, b in itertools.pairwise(line):
        if b[0] <= 0.0:
            t = a[0] / (a[0] - b[0])
            out.append((0.0, a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2]), a[3] + t * (b[3] - a[3])))
            return out
        out.append(b)
    return None


def _wedge_pressure(line: list[Node], half_width: float, phi: float, gam: float, cot_c: float) -> float:
    """Mean footing pressure from the vertical equilibrium of the rigid half-wedge above ``line``."""
    sin_phi = math.sin(phi)
    force = 0.0
    for a, b in itertools.pairwise(line):
        s = 0.5 * (a[2] + b[2])
        th = 0.5 * (a[3] + b[3])
        sy = s * (1.0 - sin_phi * math.cos(2.0 * th)) - cot_c
        txy = s * sin_phi * math.sin(2.0 * th)
        dx, dy = b[0] - a[0], b[1] - a[1]
        force += txy * dy - sy * dx  # (sigma . n ds)_y with n the wedge's outward normal
    poly = [(half_width, 0.0)] + [(p[0], p[1]) for p in line[1:]] + [(0.0, 0.0)]
    area = 0.5 * abs(
        sum(x1 * y2 - x2 * y1 for (x1, y1), (x2, y2) in zip(poly, poly[1:] + poly[:1], strict=True))
    )
    return (force - gam * area) / half_width


def _solve_rough(
    half_width: float, phi: float, gam: float, s0: float, cot_c: float, radii: list[float], n: int
) -> _Net:
    mu = math.pi / 4 - phi / 2

    def attempt(fan_angle: float) -> tuple[float, list[list[Node]], list[Node] | None]:
        fan = _fan(half_width, phi, gam, s0, fan_angle, radii, n)
        line = _wedge_line(fan[-1])
        return (-1.0 if line is None else line[-1][3] - math.pi / 2), fan, line

    lo, hi = math.pi / 2, math.pi - mu - 1e-9
    f_lo, fan, line = attempt(lo)
    if f_lo >= -1e-12 and line is not None:
        best = (lo, fan, line)
    else:
        f_hi, fan_hi, line_hi = attempt(hi)
        if f_hi < 0.0 or line_hi is None:
            raise SolverError(
                "rough base: no rigid-wedge stress field reaches the centre line "
                "(self-weight dominates; raise the surcharge ratio (q + c cot phi) / (gamma B) above ~0.1)"
            )
        best = (hi, fan_hi, line_hi)
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            f_mid, fan_mid, line_mid = attempt(mid)
            if f_mid < 0.0 or line_mid is None:
                lo = mid
            else:
                hi = mid
                best = (mid, fan_mid, line_mid)
            if hi - lo < 1e-10:
                break
    fan_angle, fan, wedge = best
    assert wedge is not None
    rows: list[list[tuple[int, Node]]] = [list(enumerate(r)) for r in fan[:-1]]
    rows.append(list(enumerate(wedge)))
    return _Net(rows, _wedge_pressure(wedge, half_width, phi, gam, cot_c), fan_angle)


# --------------------------------------------------------------------------------------------------
# Public layer
# --------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class StripFootingMoC:
    """A method-of-characteristics collapse solution for a strip footing (see module docstring).

    Attributes
    ----------
    friction_angle : ``phi`` [rad]
    width : footing width ``B`` [m]
    unit_weight : ``gamma`` [N/m^3]
    surcharge : ``q`` on the surface beside the footing [Pa]
    cohesion : ``c`` [Pa]
    base : smooth or rough
    fan_count, ray_count : mesh parameters (alpha lines in the edge fan, nodes on the passive boundary)
    bearing_pressure : collapse pressure ``q_u`` (mean over the base) [Pa]
    fan_angle : opening of the edge fan [rad] (``pi/2`` smooth; found by iteration when rough)
    alpha_lines, beta_lines : the net in the solver frame, each line an ``(k, 4)`` array of
        ``x`` [m, from the centre line], ``y`` [m, depth], ``s`` [Pa], ``theta`` [rad]
    """

    friction_angle: float
    width: float
    unit_weight: float
    surcharge: float
    cohesion: float
    base: FootingBase
    fan_count: int
    ray_count: int
    bearing_pressure: float
    fan_angle: float
    alpha_lines: tuple[FloatArray, ...]
    beta_lines: tuple[FloatArray, ...]

    def slip_lines(
        self, *, center_x: float = 0.0, surface_z: float = 0.0, mirror: bool = True
    ) -> list[SlipLine]:
        """The net as polylines in terradyn's frame (``x`` [m], ``z`` up [m]), clipped to the right half
        and mirrored to the left one (``mirror=True``)."""
        cx = check_finite("center_x", center_x)
        sz = check_finite("surface_z", surface_z)
        out: list[SlipLine] = []
        for family, lines in (("alpha", self.alpha_lines), ("beta", self.beta_lines)):
            for arr in lines:
                keep = arr[:, 0] >= -1e-12
                if np.count_nonzero(keep) < 2:
                    continue
                x, y = arr[keep, 0], arr[keep, 1]
                out.append(SlipLine(cx + x, sz - y, family, "moc"))
                if mirror:
                    out.append(SlipLine(cx - x, sz - y, "beta" if family == "alpha" else "alpha", "moc"))
        return out


def _lines(net: _Net, phi: float) -> tuple[tuple[FloatArray, ...], tuple[FloatArray, ...]]:
    """Alpha lines (rows) and beta lines (columns) of the net; each beta line starts on the free surface:
    in the passive Rankine zone (``theta = 0``) it is straight, rising at ``mu`` from the passive boundary."""
    alpha = tuple(np.array([nd for _, nd in row], dtype=np.float64) for row in net.rows if len(row) > 1)
    columns: dict[int, list[Node]] = {}
    for row in net.rows:
        for j, nd in row:
            columns.setdefault(j, []).append(nd)
    tan_mu = math.tan(math.pi / 4 - phi / 2)
    s_surface = net.rows[0][0][1][2]  # passive boundary at the edge: s = (q + c cot phi) / (1 - sin phi)
    beta = []
    for j in sorted(columns):
        col = columns[j]
        if j == 0 or len(col) < 2:
            continue
        x0, y0 = col[0][0], col[0][1]
        surface: Node = (x0 + y0 / tan_mu, 0.0, s_surface, 0.0)
        beta.append(np.array([surface, *col], dtype=np.float64))
    return alpha, tuple(beta)


def _check_phi(friction_angle: float) -> float:
    phi = check_finite("friction_angle", friction_angle)
    if not (math.radians(1.0) <= phi <= math.radians(50.0)):
        raise InputError(
            "friction_angle", friction_angle, "an angle between 1 and 50 deg, in radians", "use math.radians"
        )
    return phi


def moc_strip_footing(
    friction_angle: float,
    *,
    width: float = 1.0,
    unit_weight: float = 0.0,
    surcharge: float = 0.0,
    cohesion: float = 0.0,
    base: FootingBase | str = FootingBase.SMOOTH,
    fan_count: int = 30,
    ray_count: int = 120,
) -> StripFootingMoC:
    """Collapse pressure and slip-line net of a strip footing by the method of characteristics.

    Parameters
    ----------
    friction_angle : ``phi`` [rad], 1 to 50 deg
    width : footing width ``B`` [m]
    unit_weight : soil unit weight ``gamma = rho g`` [N/m^3], >= 0
    surcharge : surface surcharge ``q`` beside the footing [Pa], >= 0
    cohesion : ``c`` [Pa], >= 0; ``q + c`` must be > 0 (the ``q = c = 0`` case is :func:`moc_n_gamma`)
    base : ``"smooth"`` or ``"rough"``
    fan_count : alpha lines in the fan at the footing edge (>= 4)
    ray_count : nodes on the passive boundary (>= 8), spaced geometrically away from the edge

    Returns
    -------
    :class:`StripFootingMoC`; ``bearing_pressure`` is ``q_u`` [Pa].

    Raises
    ------
    SolverError
        rough base with a surcharge too small for the wedge construction (see module docstring).
    """
    phi = _check_phi(friction_angle)
    b_width = check_length("width", width)
    gam = check_positive("unit_weight", unit_weight, allow_zero=True)
    q = check_positive("surcharge", surcharge, allow_zero=True)
    c = check_positive("cohesion", cohesion, allow_zero=True)
    kind = _base(base)
    if q + c <= 0.0:
        raise InputError(
            "surcharge", surcharge, "surcharge + cohesion > 0 [Pa]", "for N_gamma (q = c = 0) use moc_n_gamma"
        )
    if not isinstance(fan_count, int) or fan_count < 4:
        raise InputError("fan_count", fan_count, "an integer >= 4")
    if not isinstance(ray_count, int) or ray_count < 8:
        raise InputError("ray_count", ray_count, "an integer >= 8")
    half = 0.5 * b_width
    cot_c = c / math.tan(phi)
    s0 = (q + cot_c) / (1.0 - math.sin(phi))
    # first passive node where weight and surcharge stresses compare (a hundredth of that length)
    length_q = (q + cot_c) / gam if gam > 0 else half
    first = min(0.05 * half, 0.01 * length_q)
    reach = math.exp(0.5 * math.pi * math.tan(phi)) / (2.0 * math.sin(math.pi / 4 - phi / 2))
    extent = 1.6 * half * reach
    net: _Net | None = None
    for _ in range(4):
        radii = _ray_radii(half, extent, ray_count, first)
        try:
            if kind is FootingBase.SMOOTH:
                net = _solve_smooth(half, phi, gam, s0, cot_c, radii, fan_count)
            else:
                net = _solve_rough(half, phi, gam, s0, cot_c, radii, fan_count)
            break
        except SolverError as exc:
            if "did not cover" not in str(exc) and "no rigid-wedge" not in str(exc):
                raise
            if kind is FootingBase.ROUGH and "no rigid-wedge" in str(exc) and extent > 4.0 * half * reach:
                raise
            extent *= 2.0
    if net is None:
        raise SolverError("the slip-line net did not cover the footing base; raise ray_count")
    if not math.isfinite(net.pressure):
        raise SolverError("the characteristics solution produced a non-finite pressure")
    alpha, beta = _lines(net, phi)
    return StripFootingMoC(
        friction_angle=phi,
        width=b_width,
        unit_weight=gam,
        surcharge=q,
        cohesion=c,
        base=kind,
        fan_count=fan_count,
        ray_count=ray_count,
        bearing_pressure=net.pressure,
        fan_angle=net.fan_angle,
        alpha_lines=alpha,
        beta_lines=beta,
    )


def moc_bearing_factors(
    friction_angle: float,
    *,
    base: FootingBase | str = FootingBase.SMOOTH,
    fan_count: int = 30,
    ray_count: int = 60,
) -> dict[str, float]:
    """``N_q`` and ``N_c`` [-] from weightless characteristics solutions (``q = 1`` Pa, then ``c = 1`` Pa).

    Reproduces Reissner's ``N_q`` and Prandtl's ``N_c`` (the tests hold it to 0.5 %).
    """
    nq = moc_strip_footing(friction_angle, surcharge=1.0, base=base, fan_count=fan_count, ray_count=ray_count)
    nc = moc_strip_footing(friction_angle, cohesion=1.0, base=base, fan_count=fan_count, ray_count=ray_count)
    return {"N_q": nq.bearing_pressure, "N_c": nc.bearing_pressure}


@dataclass(frozen=True)
class NGammaResult:
    """``N_gamma`` of a smooth strip footing on cohesionless weighted soil, extrapolated to ``q -> 0``.

    Attributes
    ----------
    friction_angle : ``phi`` [rad]
    base : smooth (rough raises, see module docstring)
    n_gamma : extrapolated ``N_gamma`` [-]
    surcharge_ratios : ``lambda = q / (gamma B)`` of the solves [-]
    n_gamma_at_ratio : ``(q_u - q N_q) / (gamma B / 2)`` at each ratio [-]
    fan_count, ray_count : mesh parameters of the solves
    """

    friction_angle: float
    base: FootingBase
    n_gamma: float
    surcharge_ratios: tuple[float, ...]
    n_gamma_at_ratio: tuple[float, ...]
    fan_count: int
    ray_count: int


def moc_n_gamma(
    friction_angle: float,
    *,
    base: FootingBase | str = FootingBase.SMOOTH,
    fan_count: int = 30,
    ray_count: int = 160,
    surcharge_ratios: tuple[float, float, float] = (1e-3, 1e-4, 1e-5),
) -> NGammaResult:
    """Self-weight bearing factor ``N_gamma`` [-] (exact for associated flow) by characteristics.

    Solves the footing (width 1 m, ``gamma`` = 1 N/m^3) at three small surcharge ratios
    ``lambda = q / (gamma B)`` and extrapolates ``N_gamma(lambda) = (q_u - q N_q) / (gamma B / 2)`` to
    ``lambda -> 0`` with Aitken's delta-squared formula (the last ratio's value when the sequence is
    not monotone).

    Raises
    ------
    SolverError
        for ``base="rough"``: the rough ``N_gamma`` needs Martin's (2005) non-centred wedge
        construction, not implemented (see the module docstring).
    """
    from .bearing import reissner1924_nq

    phi = _check_phi(friction_angle)
    kind = _base(base)
    if kind is FootingBase.ROUGH:
        raise SolverError(
            "N_gamma for a rough base is not available from terradyn's characteristics solver "
            "(needs the non-centred wedge of Martin 2005); see terradyn.plasticity.strip_footing_reference"
        )
    ratios = tuple(float(r) for r in surcharge_ratios)
    if len(ratios) != 3 or not all(0 < r < 0.1 for r in ratios):
        raise InputError("surcharge_ratios", surcharge_ratios, "three ratios between 0 and 0.1")
    nq = float(reissner1924_nq(phi))
    values = []
    for lam in ratios:
        sol = moc_strip_footing(
            phi,
            width=1.0,
            unit_weight=1.0,
            surcharge=lam,
            base=kind,
            fan_count=fan_count,
            ray_count=ray_count,
        )
        values.append((sol.bearing_pressure - lam * nq) / 0.5)
    d1, d2 = values[1] - values[0], values[2] - values[1]
    if d1 != 0.0 and d2 / d1 > 0.0 and abs(d2) < abs(d1):
        n_gamma = values[2] - d2 * d2 / (d2 - d1)
    else:
        n_gamma = values[2]
    return NGammaResult(phi, kind, n_gamma, ratios, tuple(values), fan_count, ray_count)


def moc_n_gamma_convergence(
    friction_angle: float, *, levels: int = 3, fan_count: int = 10, ray_count: int = 50
) -> dict[str, object]:
    """``N_gamma`` (smooth) on ``levels`` meshes, each twice as fine in both mesh parameters.

    Returns ``{"fan_count": [...], "ray_count": [...], "n_gamma": [...], "observed_order": p}`` where
    ``p = log2((N_1 - N_2) / (N_2 - N_3))`` from the last three levels (NaN-free: ``None`` when the
    differences do not shrink monotonically).
    """
    if not isinstance(levels, int) or levels < 3:
        raise InputError("levels", levels, "an integer >= 3")
    fans, rays, values = [], [], []
    for k in range(levels):
        f, r = fan_count * 2**k, ray_count * 2**k
        fans.append(f)
        rays.append(r)
        values.append(moc_n_gamma(friction_angle, fan_count=f, ray_count=r).n_gamma)
    e1, e2 = values[-3] - values[-2], values[-2] - values[-1]
    order = math.log2(e1 / e2) if e2 != 0.0 and e1 / e2 > 1.0 else None
    return {"fan_count": fans, "ray_count": rays, "n_gamma": values, "observed_order": order}
