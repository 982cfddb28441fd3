"""The granular model shared by the MPM tests: a generic dry sand with mu_s = 0.5 = sin(30 deg).

A soft bed (E = 1 MPa) keeps the explicit time step affordable; the values are test fixtures, not a
calibrated medium.
"""

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
