"""RFT's public kernel API: the compiled kernels other packages build on (the wheel solves and the time
integrator of :mod:`terradyn.locomotion`, benchmarks).

Kernels are plain numba functions of NumPy arrays and floats in SI (DESIGN.md section 5); each one's
docstring gives units and shapes. They live in RFT's private modules (``_kernels``, ``_kernels3d``,
``_kernels_drft``) beside the friendly functions that launch them; this module is the only door other
packages use, so RFT may reorganise its private modules without breaking them.
"""

from __future__ import annotations

from ._kernels import li2013_alpha_unit, rft_contact_angles_kernel, rft_wrench_kernel
from ._kernels3d import (
    rft3d_alpha_kernel,
    rft3d_wrench_kernel,
    rft3d_wrench_parallel_kernel,
    rft3d_wrench_range_kernel,
)
from ._kernels_drft import body_angles_kernel, drft_wrench_kernel, drft_wrench_smooth_kernel

__all__ = [
    "body_angles_kernel",
    "drft_wrench_kernel",
    "drft_wrench_smooth_kernel",
    "li2013_alpha_unit",
    "rft3d_alpha_kernel",
    "rft3d_wrench_kernel",
    "rft3d_wrench_parallel_kernel",
    "rft3d_wrench_range_kernel",
    "rft_contact_angles_kernel",
    "rft_wrench_kernel",
]
