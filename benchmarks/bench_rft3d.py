"""3D-RFT speed: facet evaluations per second, numba (one core and all threads) and NumPy.

A random cloud of F = 1e3 .. 1e6 facets (random unit normals, every facet below the surface, the body
translating and spinning) is summed to a force and moment by
:func:`terradyn.rft.kernels.rft3d_wrench_kernel` (one thread),
:func:`~terradyn.rft.kernels.rft3d_wrench_parallel_kernel` (numba threads set to 1, then to all) and
the NumPy reference :func:`terradyn.rft.rft3d.rft3d_facet_forces`. The leading-edge rule is on, so
about half the facets carry load; every facet is counted as one evaluation. One-thread figures are
timed in process CPU time (robust on a shared machine), the all-threads figure in wall time.
Goal: >= 20 million facet evaluations per second on one core.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numba
import numpy as np

from terradyn.geometry3d import Pose3D, TriangleMesh, Twist3D
from terradyn.rft.kernels import rft3d_wrench_kernel, rft3d_wrench_parallel_kernel
from terradyn.rft.rft3d import UPWARD_TOLERANCE, agarwal2023_coefficients, rft3d_facet_forces

SIZES = (1_000, 10_000, 100_000, 1_000_000)
XI = 2.4e6  # media scale of a medium sand [N/m^3]


def _cloud(count: int, seed: int = 0) -> TriangleMesh:
    """``count`` small disjoint triangles at random places and orientations, 0.01-0.2 m deep."""
    rng = np.random.default_rng(seed)
    centres = rng.uniform([-0.2, -0.2, -0.2], [0.2, 0.2, -0.01], size=(count, 3))
    normals = rng.normal(size=(count, 3))
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    a = np.cross(normals, rng.normal(size=(count, 3)))
    a /= np.linalg.norm(a, axis=1)[:, None]
    b = np.cross(normals, a)
    h = 1e-3
    vertices = np.stack(
        (centres + h * a, centres - 0.5 * h * a + h * b, centres - 0.5 * h * a - h * b), axis=1
    )
    faces = np.arange(3 * count).reshape(count, 3)
    return TriangleMesh(vertices.reshape(-1, 3), faces)


def _rate(
    run: Callable[[], object],
    count: int,
    clock: Callable[[], float] = time.process_time,
    min_time: float = 0.3,
) -> float:
    """Facets per second of ``run`` timed by ``clock`` (CPU time for one-core figures, wall otherwise)."""
    run()  # compile / warm up
    repeats, elapsed = 0, 0.0
    t0 = clock()
    while elapsed < min_time:
        run()
        repeats += 1
        elapsed = clock() - t0
    return count * repeats / elapsed


def main() -> None:
    pose = Pose3D.from_rpy(0.0, 0.0, 0.0, pitch=0.2)
    twist = Twist3D.from_components(0.1, 0.02, -0.03, wy=1.5)
    coeffs = agarwal2023_coefficients()
    rot, pos = np.ascontiguousarray(pose.rotation), np.array(pose.position)
    lin, ang, about = np.array(twist.linear), np.array(twist.angular), np.zeros(3)
    threads = numba.config.NUMBA_NUM_THREADS
    print("3D RFT facet evaluations per second [million/s] (goal >= 20 on one core)")
    columns = ("numba 1 core", "parallel x1", f"parallel x{threads}", "numpy")
    print(f"{'facets':>9} " + " ".join(f"{c:>13}" for c in columns))
    for count in SIZES:
        mesh = _cloud(count)
        args = (*mesh.kernel_arrays, rot, pos, lin, ang, coeffs, XI, 0.0, True, -1.0,
                UPWARD_TOLERANCE, about)  # fmt: skip
        numba.set_num_threads(1)
        serial = _rate(lambda args=args: rft3d_wrench_kernel(*args), count)
        par_one = _rate(lambda args=args: rft3d_wrench_parallel_kernel(*args), count)
        numba.set_num_threads(threads)
        par_all = _rate(lambda args=args: rft3d_wrench_parallel_kernel(*args), count, time.perf_counter)
        ref = _rate(lambda mesh=mesh: rft3d_facet_forces(mesh, XI, pose, twist), count)
        rates = (serial, par_one, par_all, ref)
        print(f"{count:>9} " + " ".join(f"{r / 1e6:>13.2f}" for r in rates))


if __name__ == "__main__":
    main()
