"""3D RFT wheels against the plane (2D) RFT wheel: consistency and edge effects.

The plane model (Li, Zhang & Goldman 2013, generic Fourier shape scaled by the medium's zeta) and 3D
RFT (Agarwal, Goldman & Kamrin 2023, cubic fits scaled by xi from the critical density and the
friction angle) are *different fits*. Their one shared limit is a horizontal plate pushed straight
down: the plane law gives zeta [N/m^3], 3D RFT gives ``xi * alpha_z3`` with ``alpha_z3`` = 0.87574.
This module first normalises in that limit (the 2D medium is rescaled so that its zeta equals
``xi * alpha_z3``; :func:`matched_plane_medium`), then compares a cylinder wheel meshed in 3D with the
plane wheel times its width at the same axle heights and kinematics. What is left is the difference
between the two fits' alpha maps away from the plate limit; it is measured, not tuned.

Edge effects: 3D RFT is a local law, so a cylinder rolling straight (slip angle 0) has its side walls
moving in their own plane (n . v = 0): under the leading-edge rule they carry nothing and the 3D wheel
is exactly ``width x`` the per-width force, at every width-to-radius ratio. Width matters only when
the side walls are loaded: at a slip angle (one wall bulldozes) or without the leading-edge rule.
:func:`wheel3d_width_effect` measures both.

References
----------
C. Li, T. Zhang, D. I. Goldman, Science 339, 1408 (2013). doi:10.1126/science.1229163
S. Agarwal, D. I. Goldman, K. Kamrin, PNAS 120, e2214017120 (2023). doi:10.1073/pnas.2214017120
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from pydantic import Field

from .. import materials
from ..errors import InputError
from ..materials import Material
from ..results import TableResult
from ._base import StudyEntry, StudyOutput, _Params

__all__ = [
    "Wheel3DVs2DParams",
    "Wheel3DWidthParams",
    "matched_plane_medium",
    "plot_width_effect",
    "rft3d_plate_alpha_z",
    "wheel3d_vs_2d",
    "wheel3d_vs_2d_steady",
    "wheel3d_width_effect",
]


def rft3d_plate_alpha_z() -> float:
    """alpha_z [-] of 3D RFT for a horizontal plate pushed straight down (0.87574, default fit)."""
    from ..rft.rft3d import agarwal2023_alpha

    return float(agarwal2023_alpha([[0.0, 0.0, -1.0]], [[0.0, 0.0, -1.0]])[0, 2])


def matched_plane_medium(material: Material) -> tuple[Material, float]:
    """The medium for the plane law rescaled to 3D RFT's plate value, and xi [N/m^3].

    Returns ``(material.with_zeta(xi * alpha_z3), xi)`` with xi from :func:`agarwal2023_xi_material`.
    """
    from ..rft.rft3d import agarwal2023_xi_material

    xi = agarwal2023_xi_material(material)
    return material.with_zeta(xi * rft3d_plate_alpha_z()), xi


def _pair_wrenches(
    material: Material,
    radius: float,
    width: float,
    heights: np.ndarray,
    slips: np.ndarray,
    slip_angle: float,
    *,
    circumferential_resolution: int,
    axial_resolution: int,
    leading_edge: bool = True,
) -> tuple[np.ndarray, np.ndarray, float, float]:
    """Plane (M, 3) = (F_x, F_z, T_y) and 3D (M, 6) wrenches at axle heights x slips (M = H x S)."""
    from ..geometry import WheelCircular
    from ..geometry3d import wheel_cylinder
    from ..rft import rft_wrench_many
    from ..rft.rft3d import rft3d_wrench_many

    plane, xi = matched_plane_medium(material)
    z, s = (a.ravel() for a in np.meshgrid(heights, slips, indexing="ij"))
    count = z.size
    vx = (1.0 - s) * radius  # omega = 1 rad/s
    w2 = rft_wrench_many(
        WheelCircular(radius, width),
        plane,
        np.column_stack((np.zeros(count), z, np.zeros(count))),
        np.column_stack((vx, np.zeros(count), np.ones(count))),
    )
    mesh = wheel_cylinder(
        radius,
        width,
        circumferential_resolution=circumferential_resolution,
        axial_resolution=axial_resolution,
    )
    w3 = rft3d_wrench_many(
        mesh, xi, np.column_stack((np.zeros(count), np.zeros(count), z)),
        np.broadcast_to(np.eye(3), (count, 3, 3)),
        np.column_stack((vx, vx * math.tan(slip_angle), np.zeros(count))),
        np.broadcast_to([0.0, 1.0, 0.0], (count, 3)), leading_edge=leading_edge,
    )  # fmt: skip
    return w2, w3, xi, plane.zeta


def _ratio(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.divide(a, b, out=np.zeros_like(a), where=np.abs(b) > 0.0)


def wheel3d_vs_2d(
    material: Material | str = "MS",
    *,
    radius: float = 0.13,
    width: float = 0.16,
    sinkages: Sequence[float] = (0.005, 0.01, 0.02, 0.04),
    slips: Sequence[float] = (-0.5, -0.3, 0.0, 0.3, 0.5, 0.7),
    circumferential_resolution: int = 360,
    axial_resolution: int = 2,
) -> TableResult:
    """A cylinder wheel in 3D RFT against the plane RFT wheel times its width, at fixed sinkages.

    Parameters
    ----------
    material : Material or str
        Medium with RFT, critical density and friction angle (MS, MMS, LPS, CPS).
    radius, width : float
        Wheel radius and width [m].
    sinkages : sequence of float
        Depths of the wheel bottom below the surface [m] (axle height = radius - sinkage).
    slips : sequence of float
        Slips [-] (V_x = (1 - s) omega r, omega = 1 rad/s; quasi-static, so omega does not matter).
    circumferential_resolution, axial_resolution : int
        Mesh of the 3D wheel (quads around and across).

    Returns
    -------
    TableResult
        Per sinkage x slip: vertical force, drawbar pull and drive torque of both models [N, N m],
        ``ratio_*`` = 3D / 2D, and the differences normalised by the plane vertical force
        (``dp_difference_per_fz`` [-]) and by vertical force x radius (``torque_difference_per_fz_r``
        [-]), which stay meaningful where the plane drawbar pull or torque crosses zero. Metadata
        holds xi, the medium's own zeta and the matched zeta (the normalisation).
    """
    mat = materials.get(material) if isinstance(material, str) else material
    depth = np.asarray(sinkages, dtype=np.float64)
    s = np.asarray(slips, dtype=np.float64)
    if depth.ndim != 1 or depth.size == 0 or np.any(depth <= 0) or np.any(depth > radius):
        raise InputError("sinkages", sinkages, f"depths in (0, radius = {radius:g}] m")
    w2, w3, xi, zeta = _pair_wrenches(
        mat, radius, width, radius - depth, s, 0.0,
        circumferential_resolution=circumferential_resolution, axial_resolution=axial_resolution,
    )  # fmt: skip
    sink, slip = (a.ravel() for a in np.meshgrid(depth, s, indexing="ij"))
    fz2, fz3 = w2[:, 1], w3[:, 2]
    dp2, dp3 = w2[:, 0], w3[:, 0]
    t2, t3 = -w2[:, 2], -w3[:, 4]
    cols = {
        "sinkage_m": sink,
        "slip": slip,
        "vertical_force_2d_N": fz2,
        "vertical_force_3d_N": fz3,
        "drawbar_pull_2d_N": dp2,
        "drawbar_pull_3d_N": dp3,
        "drive_torque_2d_Nm": t2,
        "drive_torque_3d_Nm": t3,
        "ratio_vertical_force": _ratio(fz3, fz2),
        "ratio_drawbar_pull": _ratio(dp3, dp2),
        "ratio_drive_torque": _ratio(t3, t2),
        "dp_difference_per_fz": _ratio(dp3 - dp2, fz2),
        "torque_difference_per_fz_r": _ratio(t3 - t2, fz2 * radius),
    }
    return TableResult(
        cols,
        {
            "material": mat.name,
            "radius_m": radius,
            "width_m": width,
            "xi_N_per_m3": xi,
            "zeta_material_N_per_m3": mat.zeta,
            "zeta_matched_N_per_m3": zeta,
            "alpha_z_plate_3d": rft3d_plate_alpha_z(),
            "normalisation": "plane medium rescaled so that zeta = xi * alpha_z(plate pushed down) of 3D RFT",
            "circumferential_resolution": circumferential_resolution,
            "axial_resolution": axial_resolution,
        },
    )


def wheel3d_vs_2d_steady(
    material: Material | str = "MS",
    *,
    radius: float = 0.13,
    width: float = 0.16,
    loads: Sequence[float] = (80.0, 150.0),
    slips: Sequence[float] = (-0.3, 0.0, 0.3, 0.6),
    circumferential_resolution: int = 360,
) -> TableResult:
    """Steady solves at equal loads [N] and slips [-]: 3D-RFT cylinder against the plane RFT wheel.

    The plane medium is matched in the plate limit (:func:`matched_plane_medium`). Columns: sinkage,
    drawbar pull and drive torque of both models [m, N, N m] and the 3D / 2D ratios of each.
    """
    from ..geometry import WheelCircular
    from ..geometry3d import wheel_cylinder
    from ..locomotion import wheel_steady
    from ..locomotion.steady3d import wheel_steady_3d

    mat = materials.get(material) if isinstance(material, str) else material
    plane, _ = matched_plane_medium(mat)
    body = WheelCircular(radius, width)
    mesh = wheel_cylinder(
        radius, width, circumferential_resolution=circumferential_resolution, axial_resolution=1,
        radial_resolution=1,
    )  # fmt: skip
    rows = []
    for load in loads:
        for slip in slips:
            a = wheel_steady(body, plane, float(load), float(slip))
            b = wheel_steady_3d(mesh, mat, float(load), float(slip))
            rows.append(
                (
                    float(load), float(slip), a.sinkage_m, b.sinkage_m, a.drawbar_pull_N, b.drawbar_pull_N,
                    a.drive_torque_Nm, b.drive_torque_Nm, b.sinkage_m / a.sinkage_m,
                    b.drawbar_pull_N / a.drawbar_pull_N if a.drawbar_pull_N != 0 else 0.0,
                    b.drive_torque_Nm / a.drive_torque_Nm if a.drive_torque_Nm != 0 else 0.0,
                )
            )  # fmt: skip
    names = (
        "load_N", "slip", "sinkage_2d_m", "sinkage_3d_m", "drawbar_pull_2d_N", "drawbar_pull_3d_N",
        "drive_torque_2d_Nm", "drive_torque_3d_Nm", "ratio_sinkage", "ratio_drawbar_pull",
        "ratio_drive_torque",
    )  # fmt: skip
    cols = {k: np.array([r[i] for r in rows]) for i, k in enumerate(names)}
    return TableResult(cols, {"material": mat.name, "radius_m": radius, "width_m": width})


def wheel3d_width_effect(
    material: Material | str = "MS",
    *,
    radius: float = 0.13,
    width_ratios: Sequence[float] = (0.1, 0.25, 0.5, 1.0, 2.0, 4.0),
    sinkage: float = 0.02,
    slip: float = 0.3,
    slip_angles: Sequence[float] = (0.0, math.radians(10.0)),
    leading_edge: Sequence[bool] = (True, False),
    circumferential_resolution: int = 360,
    axial_resolution: int = 4,
) -> TableResult:
    """3D / (2D x width) of a cylinder wheel versus its width-to-radius ratio (edge effects).

    At one sinkage [m] and slip [-], for each width ratio (width / radius [-]), slip angle [rad] and
    leading-edge setting: the ratios of 3D vertical force, drawbar pull and drive torque to the plane
    wheel times the width (plane medium matched in the plate limit, :func:`matched_plane_medium`), and
    the side force per width [N/m]. The plane wheel is always evaluated straight (its law has no
    lateral motion); the 3D wheel moves with V_y = V_x tan(slip angle).
    """
    mat = materials.get(material) if isinstance(material, str) else material
    ratios = np.asarray(width_ratios, dtype=np.float64)
    if ratios.ndim != 1 or ratios.size == 0 or np.any(ratios <= 0):
        raise InputError("width_ratios", width_ratios, "positive width / radius values")
    if not 0.0 < sinkage <= radius:
        raise InputError("sinkage", sinkage, f"a depth in (0, {radius:g}] m")
    rows: list[tuple[float, ...]] = []
    for ratio in ratios:
        width = float(ratio) * radius
        for angle in slip_angles:
            for rule in leading_edge:
                w2, w3, _, _ = _pair_wrenches(
                    mat, radius, width, np.array([radius - sinkage]), np.array([slip]), float(angle),
                    circumferential_resolution=circumferential_resolution,
                    axial_resolution=axial_resolution, leading_edge=bool(rule),
                )  # fmt: skip
                rows.append(
                    (
                        float(ratio), width, float(angle), float(rule),
                        w3[0, 2] / w2[0, 1], w3[0, 0] / w2[0, 0], w3[0, 4] / w2[0, 2], w3[0, 1] / width,
                    )
                )  # fmt: skip
    names = (
        "width_over_radius", "width_m", "slip_angle_rad", "leading_edge", "ratio_vertical_force",
        "ratio_drawbar_pull", "ratio_drive_torque", "side_force_per_width_N_per_m",
    )  # fmt: skip
    cols: dict[str, Any] = {k: np.array([r[i] for r in rows]) for i, k in enumerate(names)}
    cols["leading_edge"] = cols["leading_edge"].astype(bool)
    return TableResult(
        cols,
        {
            "material": mat.name,
            "radius_m": radius,
            "sinkage_m": sinkage,
            "slip": slip,
            "circumferential_resolution": circumferential_resolution,
            "axial_resolution": axial_resolution,
        },
    )


def plot_width_effect(table: TableResult, *, ax: Any = None) -> Any:
    """3D / 2D vertical-force and torque ratios versus width / radius, one line per case. Returns ax."""
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    from matplotlib.ticker import FixedLocator, NullLocator

    if ax is None:
        _, ax = plt.subplots(figsize=(6.5, 4.2), layout="constrained")
    c = table.columns
    for angle in dict.fromkeys(c["slip_angle_rad"].tolist()):
        for rule in (True, False):
            m = (c["slip_angle_rad"] == angle) & (c["leading_edge"] == rule)
            if not np.any(m):
                continue
            label = f"slip angle {math.degrees(angle):g} deg, leading edge {'on' if rule else 'off'}"
            line = ax.plot(c["width_over_radius"][m], c["ratio_vertical_force"][m], marker="o", label=label)
            ax.plot(
                c["width_over_radius"][m], c["ratio_drive_torque"][m], marker="s", ls="--",
                color=line[0].get_color(),
            )  # fmt: skip
    ax.set_xscale("log")
    ratios = sorted(set(np.asarray(c["width_over_radius"], dtype=float).tolist()))
    ax.xaxis.set_major_locator(FixedLocator(ratios))
    ax.xaxis.set_minor_locator(NullLocator())
    ax.set_xticklabels([f"{r:g}" for r in ratios])
    ax.set_xlabel("width / radius [-]")
    ax.set_ylabel("3D / (2D x width) [-]")
    ax.axhline(1.0, color="0.7", lw=0.8)
    ax.grid(True, alpha=0.35)
    handles = ax.get_legend_handles_labels()[0]
    handles += [
        Line2D([], [], color="k", marker="o", label="vertical force $F_z$"),
        Line2D([], [], color="k", marker="s", ls="--", label="drive torque"),
    ]
    ax.legend(handles=handles, fontsize=7)
    return ax


class Wheel3DVs2DParams(_Params):
    radius_m: float = Field(0.13, gt=0)
    width_m: float = Field(0.16, gt=0)
    sinkages_m: list[float] = Field(default_factory=lambda: [0.005, 0.01, 0.02, 0.04])
    slips: list[float] = Field(default_factory=lambda: [-0.5, -0.3, 0.0, 0.3, 0.5, 0.7])
    circumferential_resolution: int = Field(360, ge=16, le=20000)


class Wheel3DWidthParams(_Params):
    radius_m: float = Field(0.13, gt=0)
    width_ratios: list[float] = Field(default_factory=lambda: [0.1, 0.25, 0.5, 1.0, 2.0, 4.0])
    sinkage_m: float = Field(0.02, gt=0)
    slip: float = Field(0.3, ge=-1, le=1)
    slip_angles_deg: list[float] = Field(default_factory=lambda: [0.0, 10.0])
    circumferential_resolution: int = Field(360, ge=16, le=20000)


def _summary(t: TableResult, keys: Sequence[str]) -> list[dict[str, Any]]:
    out = []
    for k in keys:
        v = t.columns[k]
        out.append(
            {"quantity": k, "min": float(v.min()), "median": float(np.median(v)), "max": float(v.max())}
        )
    return out


def _resolution(p: Wheel3DVs2DParams | Wheel3DWidthParams) -> int:
    return min(p.circumferential_resolution, 180) if p.quick else p.circumferential_resolution


def _run_vs_2d(p: Wheel3DVs2DParams) -> StudyOutput:
    import matplotlib.pyplot as plt

    t = wheel3d_vs_2d(
        p.material, radius=p.radius_m, width=p.width_m,
        sinkages=p.sinkages_m[:2] if p.quick else p.sinkages_m,
        slips=[s for s in p.slips if abs(s) <= 0.3] if p.quick else p.slips,
        circumferential_resolution=_resolution(p),
    )  # fmt: skip
    fig, axes = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
    c = t.columns
    for d in dict.fromkeys(c["sinkage_m"].tolist()):
        m = c["sinkage_m"] == d
        for ax, key in zip(axes, ("ratio_vertical_force", "torque_difference_per_fz_r"), strict=True):
            ax.plot(c["slip"][m], c[key][m], marker="o", label=f"sinkage {d * 1e3:g} mm")
    axes[0].set_ylabel(r"$F_{z,3D} / (F_{z,2D} \times$ width) [-]")
    axes[1].set_ylabel(r"$(T_{3D} - T_{2D}) / (F_{z,2D}\, r)$ [-]")
    for ax in axes:
        ax.set_xlabel("slip [-]")
        ax.grid(True, alpha=0.35)
        ax.legend(fontsize=8)
    fig.suptitle(f"3D RFT cylinder vs plane RFT x width, {t.metadata['material']} (matched plate value)")
    keys = (
        "ratio_vertical_force",
        "ratio_drive_torque",
        "dp_difference_per_fz",
        "torque_difference_per_fz_r",
    )
    steady = wheel3d_vs_2d_steady(
        p.material, radius=p.radius_m, width=p.width_m, loads=[80.0] if p.quick else [80.0, 150.0],
        slips=[0.0, 0.3] if p.quick else [-0.3, 0.0, 0.3, 0.6],
        circumferential_resolution=180 if p.quick else p.circumferential_resolution,
    )  # fmt: skip
    return StudyOutput(
        {"wheel3d_vs_2d": t, "wheel3d_vs_2d_steady": steady},
        {"wheel3d_vs_2d": fig},
        _summary(t, keys) + _summary(steady, ("ratio_sinkage",)),
    )


def _run_width(p: Wheel3DWidthParams) -> StudyOutput:
    t = wheel3d_width_effect(
        p.material, radius=p.radius_m,
        width_ratios=[0.25, 1.0, 4.0] if p.quick else p.width_ratios, sinkage=p.sinkage_m, slip=p.slip,
        slip_angles=[math.radians(a) for a in p.slip_angles_deg],
        circumferential_resolution=_resolution(p),
    )  # fmt: skip
    ax = plot_width_effect(t)
    ax.set_title(f"Edge effects of 3D RFT, {t.metadata['material']}, sinkage {p.sinkage_m * 1e3:g} mm")
    summary = [{k: (v.item() if hasattr(v, "item") else v) for k, v in r.items()} for r in t.records()]
    return StudyOutput({"wheel3d_width": t}, {"wheel3d_width": ax.figure}, summary)


def study_entries() -> tuple[StudyEntry, ...]:
    """The studies this module provides (:mod:`terradyn.studies.registry` lists them)."""
    return (
        (
            "wheel3d-vs-2d",
            Wheel3DVs2DParams,
            _run_vs_2d,
            "3D-RFT cylinder wheel vs plane RFT wheel x width (plate-matched media), force and torque ratios",
        ),
        (
            "wheel3d-width",
            Wheel3DWidthParams,
            _run_width,
            "edge effects: 3D/2D force ratios of a cylinder wheel versus width / radius and slip angle",
        ),
    )
