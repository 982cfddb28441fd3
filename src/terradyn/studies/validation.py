"""Built-in checks of terradyn's models against invariants and reference values (``terradyn validate``).

Each check computes a measured value and compares it with an expected one; nothing here is tuned.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .. import materials

__all__ = ["CHECKS", "Check", "run_checks"]


@dataclass(frozen=True)
class Check:
    name: str
    measured: float
    expected: float
    tolerance: float
    about: str

    @property
    def passed(self) -> bool:
        return bool(abs(self.measured - self.expected) <= self.tolerance)

    def record(self) -> dict[str, object]:
        return {
            "check": self.name,
            "measured": self.measured,
            "expected": self.expected,
            "tolerance": self.tolerance,
            "passed": self.passed,
            "about": self.about,
        }


def _zeta() -> list[Check]:
    from ..rft import li2013_alpha_material

    out = []
    for name in materials.available():
        mat = materials.get(name)
        _, az = li2013_alpha_material(0.0, math.pi / 2, mat)
        out.append(
            Check(
                f"alpha_z(0, 90 deg) / zeta [{name}]",
                float(az) / mat.zeta,
                1.0,
                1e-12,
                "RFT scale definition",
            )
        )
    return out


def _symmetry() -> list[Check]:
    from ..rft import li2013_alpha_material

    mat = materials.get("generic")
    rng = np.random.default_rng(0)
    b, g = rng.uniform(-np.pi, np.pi, 10000), rng.uniform(-np.pi, np.pi, 10000)
    ax, az = li2013_alpha_material(b, g, mat)
    px, pz = li2013_alpha_material(b + np.pi, g, mat)
    mx, mz = li2013_alpha_material(-b, np.pi - g, mat)
    period = float(max(np.abs(px - ax).max(), np.abs(pz - az).max()) / mat.zeta)
    mirror = float(max(np.abs(mx + ax).max(), np.abs(mz - az).max()) / mat.zeta)
    return [
        Check("beta period pi, max |d alpha| / zeta", period, 0.0, 1e-12, "Li 2013 Fourier form"),
        Check("mirror x -> -x, max |d alpha| / zeta", mirror, 0.0, 1e-12, "cosine C_-11 term"),
    ]


def _plate_and_map() -> list[Check]:
    from ..geometry import Plate
    from ..rft import li2013_alpha_material
    from .intrusion import alpha_map_plate, intrusion_forces

    ms = materials.get("MS")
    t = intrusion_forces(Plate(0.05, 0.02), ms, [0.02, 0.05, 0.08])
    fz = t.columns["force_z_N"] / (ms.zeta * 0.05 * 0.02 * t.columns["depth_m"])
    a = np.radians(np.arange(-90, 91, 30))
    m = alpha_map_plate(ms, angles=a, directions=np.radians(np.arange(0, 181, 30)))
    ax, az = li2013_alpha_material(m.columns["beta_rad"], m.columns["direction_rad"], ms)
    dev = float(
        max(
            np.abs(m.columns["alpha_z_N_per_m3"] - az).max(), np.abs(m.columns["alpha_x_N_per_m3"] - ax).max()
        )
        / ms.zeta
    )
    return [
        Check(
            "plate F_z / (zeta A d), horizontal plate",
            float(fz.mean()),
            1.0,
            1e-12,
            "linear in depth and area",
        ),
        Check(
            "alpha map from plate intrusion vs law, max dev / zeta",
            dev,
            0.0,
            1e-8,
            "body sum reproduces the pointwise law (edge-on cells use a 1e-9 rad limit)",
        ),
    ]


def _wheel() -> list[Check]:
    from ..geometry import WheelCircular
    from ..kinematics import Pose2D, Twist2D
    from ..locomotion import wheel_steady
    from ..rft import rft_wrench

    ms, wheel = materials.get("MS"), WheelCircular(0.13, 0.16)
    r = wheel_steady(wheel, ms, 130.0, 0.3)
    w = rft_wrench(wheel, ms, Pose2D(0, r.axle_height_m, 0), Twist2D(r.forward_velocity_m_s, 0, 1.0))
    r2 = wheel_steady(wheel, ms, 130.0, 0.3, omega=25.0)
    pose, tw = Pose2D(0, 0.11, 0.2), Twist2D(0.05, -0.01, 1.3)
    nb = rft_wrench(wheel, ms, pose, tw).as_array()
    npy = rft_wrench(wheel, ms, pose, tw, backend="numpy").as_array()
    return [
        Check("steady wheel: F_z / W", w.fz / 130.0, 1.0, 1e-6, "load balance"),
        Check(
            "steady wheel: DP(omega=25) / DP(omega=1)",
            r2.drawbar_pull_N / r.drawbar_pull_N,
            1.0,
            1e-9,
            "quasi-static RFT is rate independent",
        ),
        Check(
            "numba vs NumPy wrench, max rel dev",
            float(np.max(np.abs(nb - npy)) / np.max(np.abs(npy))),
            0.0,
            1e-10,
            "kernel equals its reference",
        ),
    ]


def _wong_reece() -> list[Check]:
    from ..geometry import WheelCircular
    from ..locomotion import wheel_steady
    from ..terramechanics import WongReeceModel, wong_reece_wheel, wong_reece_wheel_forces

    lps = materials.get("LPS")
    direct = wong_reece_wheel(0.13, 0.16, lps, 0.3, 130.0)
    again = wong_reece_wheel_forces(0.13, 0.16, lps, 0.3, entry_angle=direct.entry_angle)
    via = wheel_steady(WheelCircular(0.13, 0.16), WongReeceModel(lps), 130.0, 0.3)
    return [
        Check(
            "Wong-Reece: W from its own integrals / load",
            again.load / 130.0,
            1.0,
            1e-9,
            "entry-angle solve closes the vertical balance",
        ),
        Check(
            "Wong-Reece: DP via steady solver / direct",
            via.drawbar_pull_N / direct.drawbar_pull,
            1.0,
            1e-6,
            "terrain-model interface agrees with the direct solve",
        ),
    ]


def _dynamics() -> list[Check]:
    from ..geometry import WheelCircular
    from ..kinematics import Pose2D, Twist2D
    from ..locomotion import simulate_wheel, wheel_self_propelled
    from ..rft import DRFTModel, rft_wrench

    ms, wheel = materials.get("MS"), WheelCircular(0.13, 0.16)
    pose, tw = Pose2D(0, 0.11, 0.3), Twist2D(0.05, -0.01, 1e-9)
    rft = rft_wrench(wheel, ms, pose, tw).as_array()
    drft = DRFTModel(ms, inertial_coefficient=0.0, structural_correction=True).wrench(wheel, pose, tw)
    dev = float(np.max(np.abs(drft.as_array() - rft)) / np.max(np.abs(rft)))
    steady = wheel_self_propelled(wheel, ms, 130.0, omega=5.0)
    run = simulate_wheel(wheel, ms, mass=130.0 / 9.81, omega=5.0, duration=8.0)
    dyn = run.steady_summary()
    return [
        Check("DRFT (lambda = 0, omega -> 0) vs RFT, max rel dev", dev, 0.0, 1e-9, "DRFT reduces to RFT"),
        Check(
            "free wheel: dynamic slip - steady slip",
            dyn["slip"] - steady.slip,
            0.0,
            2e-3,
            "time integration reaches the quasi-static steady state",
        ),
    ]


CHECKS: list[Callable[[], list[Check]]] = [
    _zeta,
    _symmetry,
    _plate_and_map,
    _wheel,
    _wong_reece,
    _dynamics,
]


def run_checks() -> list[Check]:
    """Run every registered check."""
    out: list[Check] = []
    for fn in CHECKS:
        out.extend(fn())
    return out
