"""Named studies, their validated parameters (pydantic) and what they write.

A study is a plain function ``run(params) -> StudyOutput``. ``terradyn study run NAME`` runs it with
defaults; ``terradyn study run FILE.toml`` reads ``[study] kind = NAME`` and ``[parameters]``, validated
against the study's parameter model (unknown or bad fields are errors naming the field).
"""

from __future__ import annotations

import importlib
import math
import tomllib
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from pydantic import Field, ValidationError

from .. import materials
from ..errors import InputError
from ._base import StudyEntry, StudyOutput, _Params

__all__ = ["STUDIES", "StudyOutput", "load_studies", "load_study_file", "register_study", "run_study"]


class PlateDepthParams(_Params):
    media: list[str] = Field(default_factory=lambda: ["generic", "MS", "MMS", "LPS", "CPS"])
    length_m: float = Field(0.05, gt=0)
    width_m: float = Field(0.02, gt=0)
    max_depth_m: float = Field(0.1, gt=0)
    depth_count: int = Field(21, ge=2, le=10000)
    angle_deg: float = 0.0
    direction_deg: float = 90.0


class AlphaMapParams(_Params):
    step_deg: float = Field(5.0, ge=0.5, le=45)
    depth_m: float = Field(0.0762, gt=0)


class LiftDragParams(_Params):
    size_m: float = Field(0.0254, gt=0)
    width_m: float = Field(0.0254, gt=0)
    max_depth_m: float = Field(0.1, gt=0)
    depth_count: int = Field(21, ge=2, le=10000)


class WedgeParams(_Params):
    depth_m: float = Field(0.05, gt=0)
    base_m: float = Field(0.04, gt=0)
    width_m: float = Field(0.02, gt=0)
    heights_m: list[float] = Field(default_factory=lambda: [0.005, 0.01, 0.02, 0.04, 0.08])
    tip_offsets_m: list[float] = Field(default_factory=lambda: [0.0, 0.01, 0.02])


class SuperpositionParams(_Params):
    separations_m: list[float] = Field(default_factory=lambda: [0.02, 0.05, 0.1, 0.2])
    depth_m: float = Field(0.05, gt=0)
    direction_deg: float = 45.0


def _plate_depth(p: PlateDepthParams) -> StudyOutput:
    from ..geometry import Plate
    from ..plotting import plot_force_depth
    from .intrusion import intrusion_forces

    plate = Plate(p.length_m, p.width_m)
    depths = np.linspace(0.0, p.max_depth_m, 5 if p.quick else p.depth_count)
    out, ax = StudyOutput(), None
    for name in p.media:
        mat = materials.get(name)
        t = intrusion_forces(
            plate, mat, depths, angle=math.radians(p.angle_deg), direction=math.radians(p.direction_deg)
        )
        out.tables[f"plate_depth_{mat.name}"] = t
        ax = plot_force_depth(depths, {f"{mat.name} F_z": t.columns["force_z_N"]}, ax=ax)
        slope = np.polyfit(depths, t.columns["force_z_N"], 1)[0]
        out.summary.append(
            {"material": mat.name, "dFz_ddepth_N_per_m": float(slope), "zeta_N_per_m3": mat.zeta}
        )
    assert ax is not None
    ax.set_title(f"RFT plate {p.length_m * 1e3:g} x {p.width_m * 1e3:g} mm")
    out.figures["plate_depth"] = ax.figure
    return out


def _alpha_map(p: AlphaMapParams) -> StudyOutput:
    from ..plotting import plot_alpha_maps
    from .intrusion import alpha_map_plate

    mat = materials.get(p.material)
    step = 15.0 if p.quick else p.step_deg
    angles = np.radians(np.arange(-90.0, 90.0 + 1e-9, step))
    dirs = np.radians(np.arange(0.0, 180.0 + 1e-9, step))
    t = alpha_map_plate(mat, angles=angles, directions=dirs, depth=p.depth_m)
    shape = (angles.size, dirs.size)
    fig = plot_alpha_maps(
        t.columns["angle_rad"].reshape(shape),
        t.columns["direction_rad"].reshape(shape),
        t.columns["alpha_x_N_per_m3"].reshape(shape),
        t.columns["alpha_z_N_per_m3"].reshape(shape),
        title=f"Plate stress per depth (RFT), {mat.name}, depth {p.depth_m * 1e3:g} mm",
        xlabel="plate angle [deg]",
        ylabel="direction of motion [deg below +x]",
    )
    out = StudyOutput({"alpha_map": t}, {"alpha_map": fig})
    out.summary.append(
        {
            "material": mat.name,
            "points": len(t),
            "alpha_z_max_N_per_m3": float(t.columns["alpha_z_N_per_m3"].max()),
        }
    )
    return out


def _lift_drag(p: LiftDragParams) -> StudyOutput:
    import matplotlib.pyplot as plt

    from .intrusion import lift_drag

    mat = materials.get(p.material)
    depths = np.linspace(0.0, p.max_depth_m, 5 if p.quick else p.depth_count)
    t = lift_drag(mat, depths, size=p.size_m, width=p.width_m)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
    out = StudyOutput({"lift_drag": t}, {"lift_drag": fig})
    for name in dict.fromkeys(t.columns["body"].tolist()):
        m = t.columns["body"] == name
        axes[0].plot(t.columns["depth_m"][m] * 1e3, t.columns["drag_N"][m], marker="o", ms=3, label=name)
        axes[1].plot(t.columns["depth_m"][m] * 1e3, t.columns["lift_N"][m], marker="o", ms=3, label=name)
        out.summary.append(
            {
                "body": name,
                "drag_at_max_depth_N": float(t.columns["drag_N"][m][-1]),
                "lift_at_max_depth_N": float(t.columns["lift_N"][m][-1]),
            }
        )
    for ax, lab in zip(axes, ("drag [N]", "lift [N]"), strict=True):
        ax.set_xlabel("depth of body centre [mm]")
        ax.set_ylabel(lab)
        ax.axhline(0, color="0.7", lw=0.8)
        ax.grid(True, alpha=0.35)
    axes[0].legend(fontsize=8)
    fig.suptitle(f"RFT drag and lift, {mat.name}")
    return out


def _wedges(p: WedgeParams) -> StudyOutput:
    import matplotlib.pyplot as plt

    from .intrusion import wedges_versus_plate

    mat = materials.get(p.material)
    heights = p.heights_m[:3] if p.quick else p.heights_m
    t = wedges_versus_plate(
        mat, depth=p.depth_m, base=p.base_m, width=p.width_m, heights=heights, tip_offsets=p.tip_offsets_m
    )
    fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
    for e in p.tip_offsets_m:
        m = np.isclose(t.columns["tip_offset_m"], e)
        ax.plot(
            np.degrees(t.columns["tip_half_angle_rad"][m]),
            t.columns["ratio"][m],
            marker="o",
            label=f"tip offset {e * 1e3:g} mm",
        )
    ax.set_xlabel("tip half-angle [deg]")
    ax.set_ylabel("wedge / plate vertical force [-]")
    ax.axhline(1.0, color="0.6", lw=0.8, ls=":")
    ax.set_title(f"RFT, {mat.name}: wedge base and plate at {p.depth_m * 1e3:g} mm (equal projected depth)")
    ax.grid(True, alpha=0.35)
    ax.legend()
    out = StudyOutput({"wedges": t}, {"wedges": fig})
    out.summary = [{k: v for k, v in r.items() if k != "plate_force_z_N"} for r in t.records()]
    return out


def _superposition(p: SuperpositionParams) -> StudyOutput:
    from ..geometry import Plate, WheelCircular
    from .intrusion import superposition

    mat = materials.get(p.material)
    out = StudyOutput()
    for sep in p.separations_m:
        t = superposition(
            mat,
            Plate(0.02, 0.02),
            WheelCircular(0.01, 0.02),
            separation=sep,
            depth=p.depth_m,
            direction=math.radians(p.direction_deg),
        )
        out.tables[f"superposition_{sep:g}m"] = t
        diff = float(np.max(np.abs(t.columns["force_z_N"][3] - t.columns["force_z_N"][2])))
        out.summary.append(
            {
                "separation_m": sep,
                "composite_force_z_N": float(t.columns["force_z_N"][3]),
                "sum_force_z_N": float(t.columns["force_z_N"][2]),
                "difference_N": diff,
            }
        )
    return out


STUDIES: dict[str, tuple[type[_Params], Callable[[Any], StudyOutput], str]] = {
    "plate-depth": (PlateDepthParams, _plate_depth, "RFT force on a plate versus depth, several media"),
    "alpha-map": (AlphaMapParams, _alpha_map, "alpha_x, alpha_z of a plate over angle and direction"),
    "lift-drag": (LiftDragParams, _lift_drag, "drag and lift of cylinder, square, half-cylinders"),
    "wedges": (WedgeParams, _wedges, "wedges versus a plate of the same projected width and depth"),
    "superposition": (SuperpositionParams, _superposition, "two bodies apart = sum of each (RFT)"),
}


def register_study(name: str, params: type[_Params], run: Callable[[Any], StudyOutput], about: str) -> None:
    """Add a study of the user's to the registry (``terradyn study`` and :func:`run_study` then run it)."""
    STUDIES[name] = (params, run, about)


def _validate(kind: str, values: dict[str, Any], where: str) -> _Params:
    load_studies()
    if kind not in STUDIES:
        raise InputError(f"{where}kind", kind, f"one of {sorted(STUDIES)}")
    model = STUDIES[kind][0]
    try:
        return model(**values)
    except ValidationError as exc:
        err = exc.errors()[0]
        loc = ".".join(str(x) for x in err["loc"])
        raise InputError(f"{where}parameters.{loc}", err.get("input"), err["msg"]) from None


def load_study_file(path: str | Path) -> tuple[str, _Params]:
    """Read a study TOML: ``[study] kind = NAME`` and optional ``[parameters]``."""
    p = Path(path)
    if not p.is_file():
        raise InputError("study file", str(path), "an existing TOML file")
    try:
        data = tomllib.loads(p.read_text(encoding="utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise InputError("study file", str(path), "valid TOML", str(exc)) from None
    for key in data:
        if key not in ("study", "parameters"):
            raise InputError(f"{p.name}: [{key}]", "...", "only [study] and [parameters] tables")
    study = data.get("study", {})
    if "kind" not in study:
        raise InputError(f"{p.name}: study.kind", None, f"one of {sorted(STUDIES)}")
    for key in study:
        if key != "kind":
            raise InputError(
                f"{p.name}: study.{key}", study[key], "only 'kind' (put settings in [parameters])"
            )
    kind = str(study["kind"])
    return kind, _validate(kind, data.get("parameters", {}), f"{p.name}: ")


#: the modules whose ``study_entries()`` list the studies they provide (loaded on first use)
_STUDY_MODULES = (
    "dem_calibrated",
    "dem_compare",
    "dem_scaling",
    "flapped",
    "high_speed",
    "mpm_compare",
    "optimisation",
    "wheel3d",
    "wheels",
)
_LOADED = [False]


def load_studies() -> None:
    """Add the studies of :data:`_STUDY_MODULES` to :data:`STUDIES` (once); a study a user registered
    under the same name stays."""
    if _LOADED[0]:
        return
    _LOADED[0] = True
    for name in _STUDY_MODULES:
        entries: tuple[StudyEntry, ...] = importlib.import_module(f"{__package__}.{name}").study_entries()
        for study, params, run, about in entries:
            STUDIES.setdefault(study, (params, run, about))


def run_study(
    name_or_file: str, *, quick: bool = False, overrides: dict[str, Any] | None = None
) -> tuple[str, StudyOutput]:
    """Run a named study with defaults, or a study TOML file. Returns (kind, output)."""
    load_studies()
    if name_or_file.endswith(".toml"):
        kind, params = load_study_file(name_or_file)
        values = params.model_dump()
    else:
        kind, values = name_or_file, {}
    values.update(overrides or {})
    if quick:
        values["quick"] = True
    params = _validate(kind, values, "")
    return kind, STUDIES[kind][1](params)
