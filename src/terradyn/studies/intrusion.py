"""Intrusion experiments with RFT: force versus depth, alpha maps, lift and drag, superposition."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ..errors import InputError, check_finite, check_positive
from ..geometry import Body
from ..materials import Material
from ..results import TableResult
from ..rft import rft_wrench_many

__all__ = ["alpha_map_plate", "intrusion_forces"]


def _direction_twist(direction: float, count: int, speed: float = 1.0) -> np.ndarray:
    v = np.array([speed * math.cos(direction), -speed * math.sin(direction), 0.0])
    return np.tile(v, (count, 1))


def intrusion_forces(
    body: Body,
    material: Material,
    depths: Sequence[float] | np.ndarray,
    *,
    angle: float = 0.0,
    direction: float = 0.5 * math.pi,
    surface_level: float = 0.0,
    element_size: float | None = None,
) -> TableResult:
    """RFT force and torque on a body translated through the medium at several depths.

    Parameters
    ----------
    body : Body
        The intruder; its origin is the reference point whose depth is given.
    material : Material
    depths : sequence of float
        Depths of the body origin below the free surface [m] (negative: above it).
    angle : float
        Body orientation [rad] about +y (clockwise in view).
    direction : float
        Direction of motion [rad] below the +x axis (0: moving forward, pi/2: straight down).
    surface_level : float
        Free-surface height [m].

    Returns
    -------
    TableResult
        Columns ``depth_m, force_x_N, force_z_N, torque_y_Nm`` (torque about the body origin).
        Quasi-static RFT does not depend on the speed, only on the direction.
    """
    d = np.atleast_1d(np.asarray(depths, dtype=np.float64))
    if d.ndim != 1 or d.size == 0 or not np.all(np.isfinite(d)):
        raise InputError("depth", depths, "one or more finite depths [m]")
    angle = check_finite("angle", angle)
    direction = check_finite("direction", direction)
    surface = check_finite("surface_level", surface_level)
    poses = np.column_stack((np.zeros_like(d), surface - d, np.full_like(d, angle)))
    w = rft_wrench_many(
        body, material, poses, _direction_twist(direction, d.size),
        surface_level=surface, element_size=element_size,
    )
    return TableResult(
        {"depth_m": d, "force_x_N": w[:, 0], "force_z_N": w[:, 1], "torque_y_Nm": w[:, 2]},
        {
            "model": "rft",
            "material": material.name,
            "body": repr(body),
            "angle_rad": angle,
            "direction_rad": direction,
        },
    )


def alpha_map_plate(
    material: Material,
    *,
    angles: Sequence[float] | np.ndarray,
    directions: Sequence[float] | np.ndarray,
    length: float = 0.0381,
    width: float = 0.0254,
    depth: float = 0.0762,
    element_size: float | None = None,
) -> TableResult:
    """Stress per depth of a plate over a grid of plate angles and motion directions.

    The plate (``length`` x ``width`` [m], default the 3.81 cm x 2.54 cm plate of Li et al. 2013) is
    held with its centre at ``depth`` [m]; alpha = force / (plate area x depth) [N/m^3]. With RFT this
    recovers the alpha map of the force law, the check of thesis Fig. 4-1 against MPM.

    Returns columns ``angle_rad, beta_rad, direction_rad, alpha_x_N_per_m3, alpha_z_N_per_m3``:
    a plate turned by ``angle`` about +y (clockwise in view) has RFT orientation beta = -angle (wrapped
    to [-pi/2, pi/2)); ``alpha_x`` follows the law's sign (positive resists motion along +x).
    """
    from ..geometry import Plate

    check_positive("depth", depth)
    plate = Plate(length, width)
    b = np.asarray(angles, dtype=np.float64).ravel()
    g = np.asarray(directions, dtype=np.float64).ravel()
    if b.size == 0 or g.size == 0 or not (np.all(np.isfinite(b)) and np.all(np.isfinite(g))):
        raise InputError("angles/directions", (b.size, g.size), "non-empty finite grids [rad]")
    bb, gg = np.meshgrid(b, g, indexing="ij")
    bb, gg = bb.ravel(), gg.ravel()
    poses = np.column_stack((np.zeros_like(bb), np.full_like(bb, -depth), bb))
    twists = np.column_stack((np.cos(gg), -np.sin(gg), np.zeros_like(gg)))
    w = rft_wrench_many(plate, material, poses, twists, element_size=element_size)
    norm = length * width * depth
    return TableResult(
        {
            "angle_rad": bb,
            "beta_rad": np.mod(-bb + 0.5 * np.pi, np.pi) - 0.5 * np.pi,
            "direction_rad": gg,
            "alpha_x_N_per_m3": -w[:, 0] / norm,
            "alpha_z_N_per_m3": w[:, 1] / norm,
        },
        {"model": "rft", "material": material.name, "plate_length_m": length, "depth_m": depth},
    )
