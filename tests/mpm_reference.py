"""The granular model shared by the MPM tests: a generic dry sand with mu_s = 0.5 = sin(30 deg).

A soft bed (E = 1 MPa) keeps the explicit time step affordable; the values are test fixtures, not a
calibrated medium.
"""

import numpy as np

from terradyn.mpm import GranularModel

BULK_DENSITY = 1560.0

MODEL = GranularModel(
    youngs_modulus=1e6,
    poisson_ratio=0.33,
    friction_coefficient=0.5,
    friction_coefficient_2=0.5,
    inertial_number_0=0.278,
    grain_diameter=1e-3,
    grain_density=2600.0,
    critical_density=1500.0,
    bulk_density=BULK_DENSITY,
    surface_friction=0.4,
)

#: the small grid of the kernel tests: cell size [m], origin (x0, z0) [m] and node counts (nx, nz)
KERNEL_H = 0.01
KERNEL_ORIGIN = (-0.02, -0.03)
KERNEL_SHAPE = (14, 12)


def kernel_particles(seed: int, n: int = 300):
    """``n`` random material points well inside the kernel-test grid: positions, velocities, affine
    matrices, stresses (compressive normal stresses), masses and volumes."""
    h, (x0, z0) = KERNEL_H, KERNEL_ORIGIN
    rng = np.random.default_rng(seed)
    pos = np.column_stack(
        [rng.uniform(x0 + 2.5 * h, x0 + 10.5 * h, n), rng.uniform(z0 + 2.5 * h, z0 + 8.5 * h, n)]
    )
    vel = rng.normal(0, 0.1, (n, 2))
    aff = rng.normal(0, 1.0, (n, 2, 2))
    stress = -np.abs(rng.normal(800, 300, (n, 4)))
    stress[:, 2] = rng.normal(0, 200, n)
    mass = rng.uniform(0.03, 0.05, n)
    vol = mass / rng.uniform(1480, 1700, n)
    return pos, vel, aff, stress, mass, vol
