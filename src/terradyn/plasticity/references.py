"""Reference ``N_gamma`` values for the strip-footing verification of the MPM solver, with sources.

The MPM model is non-associated (isochoric plastic flow, dilatancy ``psi = 0``), so its collapse load
is to be compared with a non-associated reference, not with the exact associated value. Each entry
of the table below says where its number comes from (``source``), which table or figure, what kind
of number it is (``kind``) and the caveats (``notes``):

* ``computed`` - terradyn's own method-of-characteristics solution (:func:`~.moc.moc_n_gamma`), exact
  for associated flow to the quoted mesh convergence;
* ``computed, finite elements`` - terradyn's small-strain finite-element footing on the MPM's own cone
  with isochoric flow (:func:`~.fe_footing.fe_strip_footing`): a computed non-associated value, with a
  ``band`` [-] from its mesh and solution-procedure sensitivity (a non-associated limit load depends on
  the loading path; docs/plasticity.md);
* ``estimate`` - the Davis (1968) / Drescher & Detournay (1993) reduced-angle estimate for isochoric
  flow, ``tan phi* = sin phi``, evaluated with terradyn's characteristics solver;
* ``approximation`` - a design formula (Brinch Hansen 1970) used where no exact solution is available
  here (rough base), clearly not a reference of the same quality;
* ``published`` - a number read in the publication itself (none so far);
* ``published, secondary`` - a published number read in a third-party transcription that names the
  publication and its table, not in the publication itself;
* ``published, not retrieved`` - a value known to exist in the literature that could not be read when
  this table was written (``value`` is ``None``; never guessed).

Bounds. A non-associated material cannot carry more than the associated material with the same yield
surface (Radenkovic's first theorem; Drescher & Detournay 1993 show the non-associated limit load of
translational mechanisms is lower than, or at most equal to, the associated one). Two bounds follow:

* for the reference idealisation, Mohr-Coulomb ``phi`` with ``psi = 0``: the associated ``N_gamma(phi)``
  (``N_gamma_upper_bound``); no admissible isochoric reference value lies above it;
* for the MPM material itself, a Drucker-Prager cone ``sqrt(J2) = sin(phi) p`` with isochoric flow (it
  equals Mohr-Coulomb ``phi`` only where the plane-strain flow is isochoric, ``sigma_2`` the mean of the
  other two): the associated cone, whose plane-strain strength is the larger angle of
  :func:`cone_plane_strain_friction_angle` (``N_gamma_upper_bound_cone``, smooth base only).

:func:`compare_n_gamma` checks a measured value against both. The Davis estimate is not a proven bound.

The numbers are data, like the material TOMLs; ``tests/unit/test_plasticity_references.py`` re-computes
the ``computed`` and ``estimate`` entries and cross-checks the secondary one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from ..errors import InputError
from .bearing import davis1968_reduced_friction_angle, hansen1970_ngamma, prandtl1921_nc, reissner1924_nq

__all__ = [
    "compare_n_gamma",
    "cone_plane_strain_friction_angle",
    "literature_search_record",
    "reference_entries",
    "strip_footing_reference",
]

#: every ``kind`` a table row may have, best-sourced published kind first
KINDS = (
    "computed",
    "computed, finite elements",
    "estimate",
    "approximation",
    "published",
    "published, secondary",
    "published, not retrieved",
)

_MOC = "terradyn.plasticity.moc_n_gamma (method of characteristics, smooth base; Martin 2005 construction)"
_DAVIS = (
    "Davis (1968) reduced friction angle tan(phi*) = sin(phi) cos(psi) / (1 - sin(phi) sin(psi)), psi = 0 "
    "(Drescher & Detournay 1993, Geotechnique 43(3) 443-456, doi:10.1680/geot.1993.43.3.443); "
    "N_gamma(phi*) from terradyn's method of characteristics"
)
_HANSEN = "Brinch Hansen (1970) N_gamma = 1.5 (N_q - 1) tan(phi), DGI Bulletin 28 (design approximation)"
_DAVIS_HANSEN = _DAVIS.replace("terradyn's method of characteristics", _HANSEN)
_MARTIN = (
    "C. M. Martin, Exact bearing capacity calculations using the method of characteristics, "
    "Proc. 11th IACMAG, Turin, vol. 4, 441-450 (2005)"
)
_HAN = (
    "D. Han, X. Xie, L. Zheng, L. Huang, The bearing capacity factor N_gamma of strip footings on "
    "c-phi-gamma soil using the method of characteristics, SpringerPlus 5:1482 (2016), "
    "doi:10.1186/s40064-016-3084-6"
)
_FB = (
    "S. Frydman, H. J. Burd, Numerical studies of bearing-capacity factor N_gamma, J. Geotech. Geoenviron. "
    "Eng. 123(1) 20-29 (1997) (finite elements and FLAC, smooth and rough, phi 30-45 deg, 0 <= psi <= phi)"
)
_LS = (
    "D. Loukidis, R. Salgado, Bearing capacity of strip and circular footings in sand using finite elements, "
    "Comput. Geotech. 36, 871-879 (2009) (elastic-perfectly plastic Mohr-Coulomb, associated and "
    "non-associated flow)"
)
_BOUND = (
    "upper bound: a non-associated material carries no more than the associated one with the same yield "
    "surface (Radenkovic's first theorem; Drescher & Detournay 1993, Geotechnique 43(3) 443-456)"
)
_BOUND_CONE = (
    "upper bound for the MPM material itself: the associated Drucker-Prager cone sqrt(J2) = sin(phi) p, "
    "Mohr-Coulomb cone_plane_strain_angle_deg in plane strain, N_gamma from " + _MOC + " (smooth only)"
)
_NR = "published, not retrieved"
_FB_READ = (
    "only the abstract could be read: plane-strain finite elements and FLAC for smooth and rough bases, "
    "phi 30-45 deg, 0 <= psi <= phi, results given as curves of N_gamma against phi. The psi = 0 value "
    "for this case is on those curves; neither the figure nor a table of it was retrieved, so no number "
    "is given (a reading would have to be digitised from the figure)."
)
_LS_READ = (
    "only the first page could be read: finite elements with an elastic-perfectly plastic Mohr-Coulomb "
    "model, one associated and one non-associated series, and relationships for the bearing factors "
    "'valid for realistic pairs of friction angle and dilatancy angle' are proposed. Neither the tables "
    "nor the fitted relationships were on the readable page, so no number is given and the relationship "
    "is not implemented."
)

# One row per (phi [deg], base, flow). "value" is N_gamma [-] or None.
# fmt: off
_TABLE: tuple[dict[str, Any], ...] = (
    # --- associated flow (psi = phi) ---------------------------------------------------------------
    {"phi_deg": 30.0, "base": "smooth", "flow": "associated", "value": 7.650, "kind": "computed",
     "source": _MOC, "table": "moc_n_gamma(radians(30)), fan_count=30, ray_count=160",
     "notes": "mesh-converged to about 1e-3 (see docs/plasticity.md); Martin (2005) gives the exact value in "
              "his table of smooth-footing N_gamma, not retrieved here (the research digest's UNVERIFIED "
              "recollection, 7.65, agrees)."},
    {"phi_deg": 34.0, "base": "smooth", "flow": "associated", "value": 14.81, "kind": "computed",
     "source": _MOC, "table": "moc_n_gamma(radians(34)), fan_count=30, ray_count=160",
     "notes": "mesh-converged to about 1e-3; no published value for 34 deg was retrieved."},
    {"phi_deg": 30.0, "base": "smooth", "flow": "associated cone", "value": 9.737, "kind": "computed",
     "source": _MOC + " at the cone's plane-strain angle",
     "table": "moc_n_gamma(cone_plane_strain_friction_angle(radians(30)) = 31.48 deg), fan_count=30, "
              "ray_count=160",
     "notes": "the associated Drucker-Prager cone sqrt(J2) = sin(phi) p in plane strain is Mohr-Coulomb "
              "31.48 deg: the upper bound for the MPM material itself, not for the Mohr-Coulomb reference."},
    {"phi_deg": 34.0, "base": "smooth", "flow": "associated cone", "value": 21.71, "kind": "computed",
     "source": _MOC + " at the cone's plane-strain angle",
     "table": "moc_n_gamma(cone_plane_strain_friction_angle(radians(34)) = 36.22 deg), fan_count=30, "
              "ray_count=160",
     "notes": "as for 30 deg."},
    {"phi_deg": 30.0, "base": "rough", "flow": "associated", "value": 14.8, "kind": "published, secondary",
     "source": _MARTIN + "; as tabulated by " + _HAN,
     "table": "Han et al. (2016) Table 2: Martin's exact rough-base N_gamma, 14.8 / 34.5 / 85.6 / 234 at "
              "phi = 30 / 35 / 40 / 45 deg",
     "notes": "read in a third-party transcription in public source code that quotes Han et al. (2016) "
              "Table 2 (three significant figures); neither Han et al.'s table nor Martin's paper was read "
              "itself. Consistent with the abstract of Han et al. (read): smooth N_gamma is 'half or more' "
              "of rough (terradyn's smooth 7.650 / 14.8 = 0.52), and with the research digest's unverified "
              "recollection 14.75. terradyn's characteristics solver cannot check it (no non-centred "
              "wedge)."},
    {"phi_deg": 34.0, "base": "rough", "flow": "associated", "value": None, "kind": _NR,
     "source": _MARTIN, "table": "table of exact rough-footing N_gamma",
     "notes": "34 deg is not among the angles of the transcribed table (30 / 35 deg: 14.8 / 34.5, secondary, "
              "see the 30 deg row); N_gamma grows with phi, so the exact value lies between them, but an "
              "interpolated number is not a reference and none is given."},
    # --- isochoric flow (psi = 0), published numerical values ------------------------------------
    *(
        {"phi_deg": phi, "base": base, "flow": "isochoric", "value": None, "kind": _NR,
         "source": src, "table": "non-associated N_gamma curves / tables", "notes": read}
        for phi in (30.0, 34.0)
        for base in ("smooth", "rough")
        for src, read in ((_FB, _FB_READ), (_LS, _LS_READ))
    ),
    # --- isochoric flow (psi = 0), reduced-angle estimates ---------------------------------------
    {"phi_deg": 30.0, "base": "smooth", "flow": "isochoric", "value": 4.424, "kind": "estimate",
     "source": _DAVIS, "table": "phi* = atan(sin 30 deg) = 26.57 deg; moc_n_gamma(phi*)",
     "notes": "an estimate: the reduced-angle rule is exact only for translational mechanisms, not for "
              "the log-spiral footing mechanism, and it is not a proven bound; check it against the "
              "published FE values when available."},
    {"phi_deg": 34.0, "base": "smooth", "flow": "isochoric", "value": 6.726, "kind": "estimate",
     "source": _DAVIS, "table": "phi* = atan(sin 34 deg) = 29.21 deg; moc_n_gamma(phi*)",
     "notes": "an estimate, see the 30 deg entry."},
    {"phi_deg": 30.0, "base": "rough", "flow": "isochoric", "value": None, "kind": "approximation",
     "source": _DAVIS_HANSEN, "table": "phi* = 26.57 deg",
     "notes": "value filled at run time from hansen1970_ngamma(phi*): a design approximation (Hansen's "
              "formula is a fit to rough-base characteristics values), not an exact solution."},
    {"phi_deg": 34.0, "base": "rough", "flow": "isochoric", "value": None, "kind": "approximation",
     "source": _DAVIS_HANSEN, "table": "phi* = 29.21 deg",
     "notes": "as for 30 deg."},
)
# fmt: on

_FE = (
    "terradyn.plasticity.fe_strip_footing: small-strain B-bar Q4 finite elements of the cone sqrt(J2) = "
    "sin(phi) p with isochoric flow (the MPM's material), explicit relaxation; checked against the method "
    "of characteristics with associated flow (docs/plasticity.md)"
)
#: how a row's value and band were made from the readings its table text quotes
_FE_RULES = {
    "slow push": (
        "value: the reading at 40 elements per half-width with local damping 0.8, pushed over 1600 wave "
        "crossings (8 times slower than the default; there the dampings agree within 0-4 % and a held "
        "footing keeps its load, docs/plasticity.md); band: the Richardson error band of that reading "
        "from the slow readings at 10 / 20 / 40 elements, its estimated distance from the zero-mesh "
        "limit. A computed value with its error, not an exact solution."
    ),
}

# (phi [deg], base): (N_gamma, band, the readings the rule works on, rule)
_FE_ISOCHORIC: dict[tuple[float, str], tuple[float, float, str, str]] = {
    (30.0, "smooth"): (6.51, 0.41, "D = 0.8, 1600 crossings: 7.902 / 6.935 / 6.513 at 10 / 20 / 40 "
                       "elements (Richardson 6.19, order 1.20)", "slow push"),
    (34.0, "smooth"): (10.74, 1.21, "D = 0.8, 1600 crossings: 13.822 / 11.749 / 10.737 at 10 / 20 / 40 "
                       "elements (Richardson 9.77, order 1.03)", "slow push"),
    (30.0, "rough"): (11.66, 0.95, "D = 0.8, 1600 crossings: 14.453 / 12.542 / 11.659 at 10 / 20 / 40 "
                      "elements (Richardson 10.90, order 1.11)", "slow push"),
    (34.0, "rough"): (19.66, 1.77, "D = 0.8, 1600 crossings: 24.759 / 21.280 / 19.657 at 10 / 20 / 40 "
                      "elements (Richardson 18.24, order 1.10)", "slow push"),
}  # fmt: skip

_TABLE = _TABLE + tuple(
    {"phi_deg": phi, "base": base, "flow": "isochoric", "value": value, "band": band,
     "kind": "computed, finite elements", "source": _FE, "table": readings, "rule": rule,
     "notes": _FE_RULES[rule]}
    for (phi, base), (value, band, readings, rule) in _FE_ISOCHORIC.items()
)  # fmt: skip

# Sources searched for published psi = 0 strip-footing N_gamma and what of them could be read.
# fmt: off
_SEARCHED: tuple[dict[str, str], ...] = (
    {"source": _FB, "read": "abstract", "finding": _FB_READ},
    {"source": _LS, "read": "first page", "finding": _LS_READ},
    {"source": "Yin, Wang & Selvadurai (2001), influence of non-associativity on the bearing capacity of a "
               "strip footing (bibliographic details not verified)",
     "read": "nothing", "finding": "no copy found; no number."},
    {"source": "K. Krabbenhoft, M. R. Karim, A. V. Lyamin, S. W. Sloan, Associated computational plasticity "
               "schemes for nonassociated frictional materials, Int. J. Numer. Meth. Engng 90, 1089-1117 "
               "(2012), doi:10.1002/nme.3358",
     "read": "summary and first page",
     "finding": "strip-footing examples are in the body, which was not readable; no number."},
    {"source": "M. Hamlaoui, A. Oueslati, G. de Saxce, A bipotential approach for plastic limit loads of "
               "strip footings with nonassociated materials, Int. J. Non-Linear Mech. 90, 1-10 (2017)",
     "read": "abstract",
     "finding": "lower estimate from characteristics and an upper quasi-bound from the bipotential, "
                "'compared to the formulae and numerical results provided in literature'; the comparison "
                "tables were not readable; no number."},
    {"source": "Erickson & Drescher (2002), circular footings (cited for the effect of base roughness on "
               "N_gamma by J. Kumar, EJGE 2005, whose abstract and introduction were read)",
     "read": "nothing", "finding": "circular footings, not a strip reference; no copy found."},
    {"source": "A. Drescher, E. Detournay, translational failure mechanisms for the limit load of "
               "associative and non-associative materials, Geotechnique 43(3) 443-456 (1993)",
     "read": "abstract",
     "finding": "for non-associative materials with a coaxial flow rule the limit load of translational "
                "mechanisms is lower than the associative one (with a non-coaxial rule it may equal it): "
                "the basis of the upper bound used here; no footing N_gamma."},
    {"source": "A. Alencar, R. Galindo, C. Olalla, S. Melentijevic, Bearing capacity of footings on rock "
               "masses using flow laws, Appl. Sci. 11(24) 11829 (2021)",
     "read": "abstract and introduction",
     "finding": "finite differences, associative vs psi = 0 on Hoek-Brown rock masses; the introduction "
                "says Michalowski and Drescher & Detournay found the flow-rule effect 'very substantial for "
                "large friction angle values'; its correction coefficient is for weightless rock masses, "
                "not N_gamma of sand."},
)
# fmt: on


def reference_entries() -> list[dict[str, Any]]:
    """Every row of the reference table (copies), each with ``phi_deg``, ``base``, ``flow``, ``value``,
    ``kind``, ``source``, ``table`` and ``notes``."""
    return [dict(row) for row in _TABLE]


def literature_search_record() -> list[dict[str, str]]:
    """The sources searched for a published isochoric strip-footing ``N_gamma`` (copies): ``source``,
    ``read`` (what of it could be read) and ``finding``. None gave a number so far."""
    return [dict(row) for row in _SEARCHED]


def cone_plane_strain_friction_angle(friction_angle: float) -> float:
    """Plane-strain Mohr-Coulomb angle [rad] of the ASSOCIATED Drucker-Prager cone ``sqrt(J2) = mu p``
    with ``mu = sin(friction_angle)``, the cone the MPM uses for a Mohr-Coulomb ``friction_angle`` [rad].

    With isochoric flow that cone gives Mohr-Coulomb ``friction_angle`` in plane strain (``sigma_2`` the
    mean of ``sigma_1`` and ``sigma_3``); with associated flow the plane-strain condition
    ``d f / d sigma_2 = 0`` gives the classical match ``mu / 3 = tan(phi_a) / sqrt(9 + 12 tan^2 phi_a)``, i.e.
    ``tan^2(phi_a) = 3 sin^2(phi) / (3 - 4 sin^2(phi))`` (31.48 deg at 30 deg, 36.22 deg at 34 deg).
    Defined for ``sin^2(phi) < 3/4`` (``phi`` below 60 deg).
    """
    phi = float(friction_angle)
    s2 = math.sin(phi) ** 2
    if not (math.isfinite(phi) and 0.0 < phi and s2 < 0.75):
        raise InputError("friction_angle", friction_angle, "an angle in (0, 60) deg, in radians")
    return math.atan(math.sqrt(3.0 * s2 / (3.0 - 4.0 * s2)))


def _rows(phi_deg: float, base: str, flow: str) -> list[dict[str, Any]]:
    return [
        dict(row)
        for row in _TABLE
        if abs(row["phi_deg"] - phi_deg) < 1e-9 and row["base"] == base and row["flow"] == flow
    ]


def _lookup(phi_deg: float, base: str, flow: str, kind: str) -> dict[str, Any] | None:
    return next((row for row in _rows(phi_deg, base, flow) if row["kind"] == kind), None)


def _best_published(phi_deg: float, base: str, flow: str) -> dict[str, Any] | None:
    """The published row with a value, primary before secondary; ``None`` when there is none."""
    for kind in ("published", "published, secondary"):
        for row in _rows(phi_deg, base, flow):
            if row["kind"] == kind and row["value"] is not None:
                return row
    return None


def _check_angle(phi_deg: Any) -> float:
    try:
        phi_d = float(phi_deg)
    except (TypeError, ValueError):
        raise InputError("phi", phi_deg, "a friction angle between 10 and 45 [deg]") from None
    if not (math.isfinite(phi_d) and 10.0 <= phi_d <= 45.0):
        raise InputError("phi", phi_deg, "a friction angle between 10 and 45 [deg]")
    return phi_d


@dataclass(frozen=True)
class _Bounds:
    """The reduced-angle (Davis) estimate of the isochoric N_gamma and the associated value that bounds
    it from above, each with its kind and source, and the associated value of the MPM's cone (None
    where unknown)."""

    davis: float
    davis_kind: str
    davis_reference: str
    associated: float | None
    associated_reference: str
    associated_kind: str
    cone: float | None


def _smooth_bounds(phi_d: float, phi: float, phi_star: float, phi_cone: float) -> _Bounds:
    """Smooth base: characteristics at phi* (the estimate), at phi and at the cone's angle (tabulated
    values where the table has them)."""
    from .moc import moc_n_gamma

    row = _lookup(phi_d, "smooth", "isochoric", "estimate")
    davis = row["value"] if row else moc_n_gamma(phi_star).n_gamma
    assoc_row = _lookup(phi_d, "smooth", "associated", "computed")
    assoc = assoc_row["value"] if assoc_row else moc_n_gamma(phi).n_gamma
    cone_row = _lookup(phi_d, "smooth", "associated cone", "computed")
    if cone_row:
        cone = cone_row["value"]
    elif phi_cone <= math.radians(50.0):  # the characteristics solver's range
        cone = moc_n_gamma(phi_cone).n_gamma
    else:
        cone = None
    return _Bounds(davis, "estimate", _DAVIS, assoc, _MOC, "computed", cone)


def _rough_bounds(phi_d: float, phi_star: float) -> _Bounds:
    """Rough base: Hansen's formula at phi* (an approximation) and the best published associated value."""
    davis = float(hansen1970_ngamma(phi_star))
    assoc_row = _best_published(phi_d, "rough", "associated")
    if assoc_row:
        assoc, assoc_ref, assoc_kind = assoc_row["value"], assoc_row["source"], assoc_row["kind"]
    else:
        assoc = None
        assoc_ref = _MARTIN + " (exact value not retrieved; not computed by terradyn)"
        assoc_kind = _NR
    return _Bounds(davis, "approximation", _DAVIS_HANSEN, assoc, assoc_ref, assoc_kind, None)


def _chosen_reference(
    published: dict[str, Any] | None, fe_row: dict[str, Any] | None, b: _Bounds
) -> dict[str, Any]:
    """``N_gamma_reference``, ``reference`` and ``reference_kind``: the published isochoric value, else
    the finite-element one, else the Davis estimate."""
    if published:
        return {
            "N_gamma_reference": published["value"],
            "reference": f"{published['source']} ({published['table']})",
            "reference_kind": published["kind"],
        }
    if fe_row:
        return {
            "N_gamma_reference": fe_row["value"],
            "reference": f"{fe_row['source']} ({fe_row['table']})",
            "reference_kind": fe_row["kind"],
        }
    return {"N_gamma_reference": b.davis, "reference": b.davis_reference, "reference_kind": b.davis_kind}


def _approximations(phi: float) -> dict[str, float]:
    """Hansen, Vesic, Meyerhof and EC7 N_gamma at ``phi`` [rad] (context only)."""
    from . import bearing

    return {
        "hansen1970": float(bearing.hansen1970_ngamma(phi)),
        "vesic1973": float(bearing.vesic1973_ngamma(phi)),
        "meyerhof1963": float(bearing.meyerhof1963_ngamma(phi)),
        "ec7": float(bearing.ec7_ngamma(phi)),
    }


def strip_footing_reference(phi_deg: float, base: str) -> dict[str, Any]:
    """Reference ``N_gamma`` for an MPM strip footing (isochoric flow) at ``phi_deg`` [deg] and ``base``.

    Returns a JSON-ready dict:

    * ``N_gamma_reference`` - the isochoric (``psi = 0``) reference [-]: a published value when the table
      has one for the case, otherwise the reduced-angle estimate (``N_gamma_davis_estimate``);
    * ``reference`` - where it comes from, ``reference_kind`` - ``published``, ``published, secondary``,
      ``estimate`` (smooth: characteristics at ``phi*``) or ``approximation`` (rough: Hansen at ``phi*``);
    * ``N_gamma_published_non_associated`` [-] - the published isochoric value or ``None``;
    * ``N_gamma_davis_estimate`` [-] with ``davis_estimate_kind`` and ``davis_estimate_reference``;
    * ``N_gamma_associated`` [-] (``None`` when not available) with ``associated_reference`` and
      ``associated_kind``; ``N_gamma_upper_bound`` [-] - the same number as a bound on the isochoric
      value (``upper_bound_reference``), ``None`` when unknown; ``N_gamma_upper_bound_cone`` [-] - the
      bound for the MPM's own Drucker-Prager cone (smooth base; ``None`` for rough and when the cone
      angle exceeds the solver's 50 deg) at ``cone_plane_strain_angle_deg``; ``N_gamma_lower_bound`` [-]
      - Radenkovic's lower bound, the associated value at ``phi*`` (smooth base; ``None`` for rough,
      where only Hansen's formula is available) with ``lower_bound_reference``;
    * ``reduced_friction_angle_deg`` - ``phi*``; ``N_q``, ``N_c`` at ``phi``;
    * ``approximations`` - Hansen, Vesic, Meyerhof, EC7 ``N_gamma`` at ``phi`` (context only);
    * ``published_non_associated`` - the literature entries for the case with their status.

    Tabulated for 30 and 34 deg; other angles in [10, 45] deg are computed on the fly (about a second
    per characteristics solve).
    """
    phi_d = _check_angle(phi_deg)
    if base not in ("smooth", "rough"):
        raise InputError("base", base, "'smooth' or 'rough'")
    phi = math.radians(phi_d)
    phi_star = float(davis1968_reduced_friction_angle(phi, 0.0))
    phi_cone = cone_plane_strain_friction_angle(phi)
    out: dict[str, Any] = {
        "phi_deg": phi_d,
        "base": base,
        "reduced_friction_angle_deg": math.degrees(phi_star),
        "cone_plane_strain_angle_deg": math.degrees(phi_cone),
    }
    # the reduced-angle (Davis) estimate, and the associated value
    b = _smooth_bounds(phi_d, phi, phi_star, phi_cone) if base == "smooth" else _rough_bounds(phi_d, phi_star)
    published = _best_published(phi_d, base, "isochoric")
    fe_row = _lookup(phi_d, base, "isochoric", "computed, finite elements")
    out.update(_chosen_reference(published, fe_row, b))
    out.update(
        N_gamma_fe_isochoric=fe_row["value"] if fe_row else None,
        N_gamma_fe_band=fe_row["band"] if fe_row else None,
    )
    out.update(
        N_gamma_published_non_associated=published["value"] if published else None,
        N_gamma_davis_estimate=b.davis,
        davis_estimate_kind=b.davis_kind,
        davis_estimate_reference=b.davis_reference,
        N_gamma_associated=b.associated,
        associated_reference=b.associated_reference,
        associated_kind=b.associated_kind,
        N_gamma_upper_bound=b.associated,
        upper_bound_reference=_BOUND,
        N_gamma_upper_bound_cone=b.cone,
        upper_bound_cone_reference=_BOUND_CONE,
        # Radenkovic's second theorem: the associated material of the reduced strength tan(phi*) =
        # sin(phi) carries no more than the non-associated one, so the Davis value at psi = 0 is a
        # lower bound where it is an exact associated solution (the smooth-base characteristics
        # value; the rough base has only Hansen's design formula, which bounds nothing)
        N_gamma_lower_bound=b.davis if b.davis_kind == "estimate" else None,
        lower_bound_reference=_LOWER_BOUND,
    )
    out["N_q"] = float(reissner1924_nq(phi))
    out["N_c"] = float(prandtl1921_nc(phi))
    out["approximations"] = _approximations(phi)
    out["published_non_associated"] = [
        {"source": r["source"], "value": r["value"], "kind": r["kind"], "notes": r["notes"]}
        for r in _rows(phi_d, base, "isochoric")
        if r["kind"].startswith("published")
    ]
    return out


_LOWER_BOUND = (
    "lower bound: a non-associated Mohr-Coulomb material carries no less than the associated one with "
    "the reduced strength tan(phi*) = sin(phi), c* = c cos(phi) (Radenkovic's second theorem, J. Radenkovic, "
    "C. R. Acad. Sci. Paris 252 (1961) 4103-4104; the psi = 0 case of Davis 1968); N_gamma(phi*) from "
    "terradyn's method of characteristics (smooth base only)"
)


def compare_n_gamma(n_gamma: float, reference: dict[str, Any]) -> dict[str, Any]:
    """Ratios of a measured (MPM) ``n_gamma`` [-] to the numbers of a :func:`strip_footing_reference`
    result: ``ratio_to_reference``, ``ratio_to_published`` (``None`` without a published value),
    ``ratio_to_davis_estimate``, ``ratio_to_upper_bound`` and ``exceeds_upper_bound`` (``None`` when the
    bound is unknown), ``ratio_to_upper_bound_cone`` and ``exceeds_upper_bound_cone``. A value above
    ``N_gamma_upper_bound`` cannot match any Mohr-Coulomb ``psi = 0`` reference; a value above the cone
    bound cannot be a collapse load of the MPM material at all."""
    try:
        value = float(n_gamma)
    except (TypeError, ValueError):
        raise InputError("N_gamma", n_gamma, "a positive bearing factor [-]") from None
    if not (math.isfinite(value) and value > 0.0):
        raise InputError("N_gamma", n_gamma, "a positive bearing factor [-]")

    def ratio(key: str) -> float | None:
        ref = reference.get(key)
        return value / float(ref) if ref else None

    bound = reference.get("N_gamma_upper_bound")
    cone = reference.get("N_gamma_upper_bound_cone")
    lower = reference.get("N_gamma_lower_bound")
    return {
        "N_gamma": value,
        "ratio_to_reference": ratio("N_gamma_reference"),
        "ratio_to_published": ratio("N_gamma_published_non_associated"),
        "ratio_to_davis_estimate": ratio("N_gamma_davis_estimate"),
        "ratio_to_upper_bound": ratio("N_gamma_upper_bound"),
        "exceeds_upper_bound": None if not bound else value > float(bound),
        "ratio_to_upper_bound_cone": ratio("N_gamma_upper_bound_cone"),
        "exceeds_upper_bound_cone": None if not cone else value > float(cone),
        "ratio_to_lower_bound": ratio("N_gamma_lower_bound"),
        "below_lower_bound": None if not lower else value < float(lower),
    }
