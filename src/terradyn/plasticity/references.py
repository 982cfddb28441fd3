"""Reference ``N_gamma`` values for the strip-footing verification of the MPM solver, with sources.

The MPM model is non-associated (isochoric plastic flow, dilatancy ``psi = 0``), so its collapse load
is to be compared with a non-associated reference, not with the exact associated value. Each entry
of the table below says where its number comes from (``source``), which table or figure, what kind
of number it is (``kind``) and the caveats (``notes``):

* ``computed`` - terradyn's own method-of-characteristics solution (:func:`~.moc.moc_n_gamma`), exact
  for associated flow to the quoted mesh convergence;
* ``estimate`` - the Davis (1968) / Drescher & Detournay (1993) reduced-angle estimate for isochoric
  flow, ``tan phi* = sin phi``, evaluated with terradyn's characteristics solver;
* ``approximation`` - a design formula (Brinch Hansen 1970) used where no exact solution is available
  here (rough base), clearly not a reference of the same quality;
* ``published, not retrieved`` - a value known to exist in the literature that could not be read when
  this table was written (``value`` is ``None``; never guessed).

The numbers are data, like the material TOMLs; ``tests/unit/test_plasticity_references.py`` re-computes
the ``computed`` and ``estimate`` entries.
"""

from __future__ import annotations

import math
from typing import Any

from ..errors import InputError
from .bearing import davis1968_reduced_friction_angle, hansen1970_ngamma, prandtl1921_nc, reissner1924_nq

__all__ = ["reference_entries", "strip_footing_reference"]

_MOC = "terradyn.plasticity.moc_n_gamma (method of characteristics, smooth base; Martin 2005 construction)"
_DAVIS = (
    "Davis (1968) reduced friction angle tan(phi*) = sin(phi) cos(psi) / (1 - sin(phi) sin(psi)), psi = 0 "
    "(Drescher & Detournay 1993, Geotechnique 43(3) 443-456, doi:10.1680/geot.1993.43.3.443); "
    "N_gamma(phi*) from terradyn's method of characteristics"
)
_HANSEN = "Brinch Hansen (1970) N_gamma = 1.5 (N_q - 1) tan(phi), DGI Bulletin 28 (design approximation)"
_MARTIN = (
    "C. M. Martin, Exact bearing capacity calculations using the method of characteristics, "
    "Proc. 11th IACMAG, Turin, vol. 4, 441-450 (2005)"
)
_FB = (
    "S. Frydman, H. J. Burd, Numerical studies of bearing-capacity factor N_gamma, J. Geotech. Geoenviron. "
    "Eng. 123 (1997) (finite elements and FLAC, smooth and rough, phi 30-45 deg, 0 <= psi <= phi)"
)
_LS = (
    "D. Loukidis, R. Salgado, Bearing capacity of strip and circular footings in sand using finite elements, "
    "Comput. Geotech. 36, 871-879 (2009) (elastic-perfectly plastic Mohr-Coulomb, associated and "
    "non-associated flow)"
)
_NR = "published, not retrieved"
_NOT_RETRIEVED = (
    "only the abstract could be read when this table was written; the non-associated (psi = 0) N_gamma "
    "for this case is in the paper's tables/figures but was not retrieved, so no number is given"
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
    {"phi_deg": 30.0, "base": "rough", "flow": "associated", "value": None, "kind": _NR,
     "source": _MARTIN, "table": "table of exact rough-footing N_gamma",
     "notes": "terradyn's characteristics solver does not build the rough-base N_gamma field (non-centred "
              "wedge); the research digest quotes 14.75 from memory, UNVERIFIED, so it is not used."},
    {"phi_deg": 34.0, "base": "rough", "flow": "associated", "value": None, "kind": _NR,
     "source": _MARTIN, "table": "table of exact rough-footing N_gamma", "notes": "as for 30 deg."},
    # --- isochoric flow (psi = 0), published numerical values ------------------------------------
    *(
        {"phi_deg": phi, "base": base, "flow": "isochoric", "value": None, "kind": _NR,
         "source": src, "table": "non-associated N_gamma tables/figures", "notes": _NOT_RETRIEVED}
        for phi in (30.0, 34.0)
        for base in ("smooth", "rough")
        for src in (_FB, _LS)
    ),
    # --- isochoric flow (psi = 0), reduced-angle estimates ---------------------------------------
    {"phi_deg": 30.0, "base": "smooth", "flow": "isochoric", "value": 4.424, "kind": "estimate",
     "source": _DAVIS, "table": "phi* = atan(sin 30 deg) = 26.57 deg; moc_n_gamma(phi*)",
     "notes": "an estimate: the reduced-angle rule is exact only for translational mechanisms, not for "
              "the log-spiral footing mechanism; check it against the published FE values when available."},
    {"phi_deg": 34.0, "base": "smooth", "flow": "isochoric", "value": 6.726, "kind": "estimate",
     "source": _DAVIS, "table": "phi* = atan(sin 34 deg) = 29.21 deg; moc_n_gamma(phi*)",
     "notes": "an estimate, see the 30 deg entry."},
    {"phi_deg": 30.0, "base": "rough", "flow": "isochoric", "value": None, "kind": "approximation",
     "source": _DAVIS + "; N_gamma(phi*) from " + _HANSEN, "table": "phi* = 26.57 deg",
     "notes": "value filled at run time from hansen1970_ngamma(phi*): a design approximation (Hansen's "
              "formula is a fit to rough-base characteristics values), not an exact solution."},
    {"phi_deg": 34.0, "base": "rough", "flow": "isochoric", "value": None, "kind": "approximation",
     "source": _DAVIS + "; N_gamma(phi*) from " + _HANSEN, "table": "phi* = 29.21 deg",
     "notes": "as for 30 deg."},
)
# fmt: on


def reference_entries() -> list[dict[str, Any]]:
    """Every row of the reference table (copies), each with ``phi_deg``, ``base``, ``flow``, ``value``,
    ``kind``, ``source``, ``table`` and ``notes``."""
    return [dict(row) for row in _TABLE]


def _lookup(phi_deg: float, base: str, flow: str, kind: str) -> dict[str, Any] | None:
    for row in _TABLE:
        if (
            abs(row["phi_deg"] - phi_deg) < 1e-9
            and row["base"] == base
            and row["flow"] == flow
            and row["kind"] == kind
        ):
            return dict(row)
    return None


def strip_footing_reference(phi_deg: float, base: str) -> dict[str, Any]:
    """Reference ``N_gamma`` for an MPM strip footing (isochoric flow) at ``phi_deg`` [deg] and ``base``.

    Returns a JSON-ready dict:

    * ``N_gamma_reference`` - the isochoric (``psi = 0``) reference [-]: the reduced-angle estimate
      from the characteristics solver (smooth) or Hansen's approximation at ``phi*`` (rough);
    * ``reference`` - where it comes from, ``reference_kind`` - ``estimate`` or ``approximation``;
    * ``N_gamma_associated`` [-] (``None`` when not available: rough base) with
      ``associated_reference``;
    * ``reduced_friction_angle_deg`` - ``phi*``; ``N_q``, ``N_c`` at ``phi``;
    * ``approximations`` - Hansen, Vesic, Meyerhof, EC7 ``N_gamma`` at ``phi`` (context only);
    * ``published_non_associated`` - the literature entries (Frydman & Burd 1997, Loukidis &
      Salgado 2009) with their status.

    Tabulated for 30 and 34 deg; other angles in [10, 45] deg are computed on the fly (about a second
    per characteristics solve).
    """
    from . import bearing
    from .moc import moc_n_gamma

    try:
        phi_d = float(phi_deg)
    except (TypeError, ValueError):
        raise InputError("phi", phi_deg, "a friction angle between 10 and 45 [deg]") from None
    if not (math.isfinite(phi_d) and 10.0 <= phi_d <= 45.0):
        raise InputError("phi", phi_deg, "a friction angle between 10 and 45 [deg]")
    if base not in ("smooth", "rough"):
        raise InputError("base", base, "'smooth' or 'rough'")
    phi = math.radians(phi_d)
    phi_star = float(davis1968_reduced_friction_angle(phi, 0.0))
    out: dict[str, Any] = {
        "phi_deg": phi_d,
        "base": base,
        "reduced_friction_angle_deg": math.degrees(phi_star),
    }
    if base == "smooth":
        row = _lookup(phi_d, base, "isochoric", "estimate")
        value = row["value"] if row else moc_n_gamma(phi_star).n_gamma
        out.update(N_gamma_reference=value, reference=_DAVIS, reference_kind="estimate")
        assoc = _lookup(phi_d, base, "associated", "computed")
        out.update(
            N_gamma_associated=assoc["value"] if assoc else moc_n_gamma(phi).n_gamma,
            associated_reference=_MOC,
        )
    else:
        out.update(
            N_gamma_reference=float(hansen1970_ngamma(phi_star)),
            reference=_DAVIS.replace("N_gamma(phi*) from terradyn's method of characteristics", "")
            + "N_gamma(phi*) from "
            + _HANSEN,
            reference_kind="approximation",
            N_gamma_associated=None,
            associated_reference=_MARTIN + " (exact value not retrieved; not computed by terradyn)",
        )
    out["N_q"] = float(reissner1924_nq(phi))
    out["N_c"] = float(prandtl1921_nc(phi))
    out["approximations"] = {
        "hansen1970": float(bearing.hansen1970_ngamma(phi)),
        "vesic1973": float(bearing.vesic1973_ngamma(phi)),
        "meyerhof1963": float(bearing.meyerhof1963_ngamma(phi)),
        "ec7": float(bearing.ec7_ngamma(phi)),
    }
    out["published_non_associated"] = [
        {"source": r["source"], "value": r["value"], "kind": r["kind"], "notes": r["notes"]}
        for r in _TABLE
        if abs(r["phi_deg"] - phi_d) < 1e-9
        and r["base"] == base
        and r["flow"] == "isochoric"
        and r["kind"].startswith("published")
    ]
    return out
