"""Patch-averaged velocity divergence (``Resolution(volumetric="patch")``, B-bar for material points)."""

from __future__ import annotations

import numpy as np
import pytest

from mpm_reference import KERNEL_H, KERNEL_ORIGIN, KERNEL_SHAPE, MODEL, kernel_particles
from terradyn.errors import InputError
from terradyn.mpm import _kernels as K
from terradyn.mpm.specs import Resolution

H = KERNEL_H
X0, Z0 = KERNEL_ORIGIN
SHAPE = KERNEL_SHAPE
particles = kernel_particles


def _no_body(n):
    node = np.zeros((*SHAPE, 3))
    node[..., 2] = 1e300
    return np.zeros((n, 3)), node


def _divergence(pos, vol, gv, geo=None, node=None):
    """Patch divergence with the far-side grain field equal to the near one (the split is then the
    only thing a body changes)."""
    g, nd = _no_body(len(pos))
    geo = g if geo is None else geo
    node = nd if node is None else node
    out = np.empty(len(pos))
    patch, keys = np.zeros((*SHAPE, 5, 2)), np.empty((len(pos), 3), np.int64)
    K.patch_divergence(pos, vol, geo, node, gv, gv.copy(), X0, Z0, H, patch, keys, out)
    return out


def _point_divergence(pos, gv):
    """tr L_p of every point, independently (quadratic B-splines)."""
    out = np.empty(len(pos))
    for p, (x, z) in enumerate(pos):
        wx, dwx, bi = _spline((x - X0) / H)
        wz, dwz, bj = _spline((z - Z0) / H)
        out[p] = sum(
            gv[bi + a, bj + b, 0] * dwx[a] * wz[b] + gv[bi + a, bj + b, 1] * wx[a] * dwz[b]
            for a in range(3)
            for b in range(3)
        )
    return out


def _spline(xi):
    base = int(xi - 0.5)
    f = xi - base
    w = np.array([0.5 * (1.5 - f) ** 2, 0.75 - (f - 1.0) ** 2, 0.5 * (f - 0.5) ** 2])
    dw = np.array([-(1.5 - f), -2.0 * (f - 1.0), f - 0.5]) / H
    return w, dw, base


def test_an_affine_field_has_the_same_divergence_everywhere():
    pos, *_, vol = particles(0)
    i, j = np.meshgrid(np.arange(SHAPE[0]), np.arange(SHAPE[1]), indexing="ij")
    x, z = X0 + i * H, Z0 + j * H
    a = np.array([[0.3, -0.2], [0.5, 0.7]])  # v = A x + c: divergence tr A = 1.0 / s
    gv = np.stack([a[0, 0] * x + a[0, 1] * z + 0.01, a[1, 0] * x + a[1, 1] * z - 0.02], axis=-1)
    np.testing.assert_allclose(_divergence(pos, vol, gv), 1.0, rtol=1e-10)


def test_patch_average_keeps_each_patch_total_and_removes_the_spread_within_it():
    pos, *_, vol = particles(1, n=600)
    gv = np.random.default_rng(3).normal(0, 0.05, (*SHAPE, 2))
    point = _point_divergence(pos, gv)
    bar = _divergence(pos, vol, gv)
    keys = np.floor((pos - [X0, Z0]) / H + 0.5).astype(int)  # nearest node
    patches = {tuple(k) for k in keys}
    assert len(patches) > 20
    for key in patches:
        inside = np.all(keys == key, axis=1)
        total = np.sum(vol[inside] * point[inside])
        assert np.sum(vol[inside] * bar[inside]) == pytest.approx(total, rel=1e-10, abs=1e-14)
        assert np.ptp(bar[inside]) <= 1e-12 * max(1.0, np.abs(bar[inside]).max())
    assert np.ptp(point) > 1.0  # the field is far from uniform, so the averaging did something


def test_the_two_sides_of_a_thin_body_are_not_averaged_together():
    # two points in the patch of node (5, 5), one above and one below a body surface (opposite normals)
    pos = np.array([[X0 + 5.0 * H, Z0 + 5.2 * H], [X0 + 5.0 * H, Z0 + 4.8 * H]])
    vol = np.ones(2) * 1e-5
    gv = np.random.default_rng(5).normal(0, 0.05, (*SHAPE, 2))
    geo = np.array([[0.0, 1.0, 0.001], [0.0, -1.0, 0.001]])
    _, band = _no_body(2)
    band[5, 5] = (0.0, 1.0, 0.0)  # node (5, 5) is in the body's band
    bar = _divergence(pos, vol, gv, geo=geo, node=band)
    np.testing.assert_allclose(bar, _point_divergence(pos, gv), rtol=1e-10)
    geo_same = np.array([[0.0, 1.0, 0.001], [0.0, 1.0, 0.001]])
    bar_same = _divergence(pos, vol, gv, geo=geo_same, node=band)
    assert bar_same[0] == pytest.approx(bar_same[1], rel=1e-12)
    # away from the band the body normals do not split a patch (the two fields are one there)
    _, no_band = _no_body(2)
    bar_far = _divergence(pos, vol, gv, geo=geo, node=no_band)
    assert bar_far[0] == pytest.approx(bar_far[1], rel=1e-12)
    assert bar_far[0] != pytest.approx(bar[0], rel=1e-6)


def test_the_side_split_is_mirror_equivariant():
    """Mirroring x maps each side key to one key (a horizontal normal is not sent above or below by
    the sign of its x component), so a mirrored case groups its points as the original does."""
    normals = [(1.0, 0.0), (0.6, 0.8), (0.8, 0.6), (0.0, -1.0), (0.3, -0.95), (1.0, 1e-9)]
    keys = {n: K._side_key(*n) for n in normals}
    mirrored = {n: K._side_key(-n[0], n[1]) for n in normals}
    pairing = {}
    for n in normals:
        pairing.setdefault(keys[n], set()).add(mirrored[n])
    assert all(len(v) == 1 for v in pairing.values())
    assert K._side_key(0.0, 1.0) != K._side_key(0.0, -1.0)
    assert K._side_key(1.0, 0.0) != K._side_key(-1.0, 0.0)


def test_a_normal_at_45_degrees_to_rounding_is_vertical_on_both_sides():
    """A grain on the diagonal of a corner (the plate's end on a node column, the grains on the
    lattice) has |n_x| = |n_z| up to rounding, and a grain and its mirror image round differently;
    main sent one to a vertical key and the other to a horizontal one, which broke the mirror symmetry
    of a symmetric plate from the first step of settling (7.5 mm cells)."""
    a, b = 0.7071067811865476, 0.7071067811865475
    for npx, npz in ((a, -b), (b, -a), (-a, -b), (-b, -a)):
        assert K._side_key(npx, npz) == 2  # below
    for npx, npz in ((a, b), (-b, a)):
        assert K._side_key(npx, npz) == 1  # above


def test_g2p_with_the_patch_divergence_changes_only_the_isotropic_rate():
    pos, vel, aff, stress, mass, vol = particles(4)
    gv = np.random.default_rng(9).normal(0, 0.05, (*SHAPE, 2))
    bounds = np.array([X0 + 2 * H, X0 + 11 * H, Z0 + 2 * H, Z0 + 9 * H])
    mat = MODEL.as_kernel_array()
    geo, node = _no_body(len(pos))
    runs = []
    for averaged in (False, True):
        state = [a.copy() for a in (pos, vel, aff, stress, mass, vol)]
        gdot = np.zeros(len(pos))
        bar = _divergence(state[0], state[5], gv) if averaged else np.empty(0)
        grid = (gv, np.zeros_like(gv), geo, node, X0, Z0, H, 1e-4, bounds)
        K.g2p(*state[:6], gdot, *grid, *mat, 0.0, 0.0, bar)
        runs.append((state, bar))
    (plain, _), (patch, bar) = runs
    for k in (0, 1, 2):  # positions, velocities, affine matrices do not depend on it
        np.testing.assert_array_equal(plain[k], patch[k])
    np.testing.assert_allclose(patch[5], vol * np.exp(1e-4 * bar), rtol=1e-12)
    assert not np.allclose(plain[5], patch[5], rtol=1e-9)


def test_bad_volumetric_choice_names_the_field():
    with pytest.raises(InputError, match="volumetric"):
        Resolution(volumetric="cell")


def _plate_run(**kw):
    from terradyn.geometry import Plate
    from terradyn.mpm import Bed, Stroke, run_intrusion

    return run_intrusion(
        Plate(0.08, 0.1),
        MODEL,
        depth=0.02,
        speed=0.2,
        bed=Bed(width=0.2, depth=0.12, settle_time=0.02),
        stroke=Stroke(averaging_window=0.01),
        **kw,
    )


@pytest.mark.parametrize(
    ("field", "on", "off"),
    [("volumetric", "patch", "point"), ("flip", 0.99, 0.0)],
)
def test_a_run_with_the_option_resumes_bit_for_bit_and_a_resume_without_it_is_refused(
    tmp_path, field, on, off
):
    """``Resolution(volumetric="patch")`` and ``Resolution(flip=...)`` (the FLIP blend of the grains'
    velocity update, docs/mpm.md "What the rate error is") each reach the kernels (the force changes),
    are part of the run's fingerprint and resume exactly."""
    from terradyn.mpm import Outputs
    from terradyn.mpm.solver import RunInterrupted

    with_it = Resolution(cell_size=0.01, **{field: on})
    whole = _plate_run(resolution=with_it)
    without = _plate_run(resolution=with_it.replace(**{field: off}))
    f_on, f_off = whole.summary["force_z_N"], without.summary["force_z_N"]
    assert np.isfinite(f_on) and f_on > 0
    assert f_on != pytest.approx(f_off, rel=1e-6)  # the option reaches the kernels
    ckpt = tmp_path / "run.npz"
    calls = []

    def stop(t, frac):
        calls.append(t)
        if len(calls) == 10:
            raise KeyboardInterrupt

    with pytest.raises(RunInterrupted):
        _plate_run(resolution=with_it, outputs=Outputs(checkpoint_path=ckpt, progress=stop))
    with pytest.raises(InputError, match=field):
        _plate_run(
            resolution=with_it.replace(**{field: off}), outputs=Outputs(checkpoint_path=ckpt, resume=True)
        )
    resumed = _plate_run(resolution=with_it, outputs=Outputs(checkpoint_path=ckpt, resume=True))
    np.testing.assert_array_equal(resumed.to_dataframe().to_numpy(), whole.to_dataframe().to_numpy())
