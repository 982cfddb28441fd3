"""Prandtl-Reissner slip-line geometry (terradyn.plasticity.slipline) and its plot."""

from __future__ import annotations

import math

import numpy as np
import pytest

from terradyn.errors import InputError
from terradyn.plasticity import moc_strip_footing, prandtl_extent, prandtl_field

PHI30 = math.radians(30.0)


@pytest.fixture(autouse=True)
def _close_figures():
    import matplotlib.pyplot as plt

    yield
    plt.close("all")


@pytest.mark.parametrize("base", ["rough", "smooth"])
def test_field_is_symmetric_about_the_footing_centre(base):
    lines = prandtl_field(0.1, PHI30, base=base, center_x=0.25, surface_z=0.02)
    pts = {(round(x, 9), round(z, 9)) for s in lines for x, z in zip(s.x, s.z, strict=True)}
    mirrored = {(round(0.5 - x, 9), z) for x, z in pts}
    assert pts == mirrored
    assert all(np.all(s.z <= 0.02 + 1e-12) for s in lines)


def test_fan_spiral_radius_grows_as_exp_theta_tan_phi():
    b = 0.05
    lines = prandtl_field(2 * b, PHI30, points=81)
    spiral = next(s for s in lines if s.zone == "boundary" and len(s.x) == 81 and s.x[-1] > b)
    dx, dz = spiral.x - b, spiral.z  # from the right footing edge
    r = np.hypot(dx, dz)
    turned = np.unwrap(np.arctan2(-dz, dx))
    turned = turned[0] - turned  # angle swept from the active side [rad]
    r0 = b / math.cos(math.pi / 4 + PHI30 / 2)
    assert r[0] == pytest.approx(r0)
    assert np.allclose(r / r0, np.exp(turned * math.tan(PHI30)), rtol=1e-9)
    assert turned[-1] == pytest.approx(math.pi / 2)
    assert r[-1] / r[0] == pytest.approx(math.exp(0.5 * math.pi * math.tan(PHI30)))


def test_extents_match_the_closed_form_mechanism():
    width = 0.1
    ext = prandtl_extent(width, PHI30)
    b = width / 2
    r1 = b / math.cos(math.pi / 4 + PHI30 / 2) * math.exp(0.5 * math.pi * math.tan(PHI30))
    assert ext["heave_extent"] == pytest.approx(2 * r1 * math.cos(math.pi / 4 - PHI30 / 2))
    assert ext["heave_extent"] / b == pytest.approx(8.58, abs=5e-3)  # research digest, section 7.1 table
    assert ext["wedge_depth"] == pytest.approx(b * math.sqrt(3.0))
    lines = prandtl_field(width, PHI30, center_x=1.0)
    xs = np.concatenate([s.x for s in lines])
    zs = np.concatenate([s.z for s in lines])
    assert xs.max() == pytest.approx(1.0 + ext["half_extent"])
    assert xs.min() == pytest.approx(1.0 - ext["half_extent"])
    assert -zs.min() == pytest.approx(ext["max_depth"], rel=1e-3)


def test_spiral_is_tangent_to_the_passive_wedge_side_it_continues_into():
    lines = [s for s in prandtl_field(0.1, PHI30, points=2001) if s.zone == "boundary" and s.x[-1] > 0.05]
    spiral = next(s for s in lines if len(s.x) == 2001)
    side = next(s for s in lines if len(s.x) == 2 and np.isclose(s.x[0], spiral.x[-1]))
    t_spiral = np.arctan2(spiral.z[-1] - spiral.z[-2], spiral.x[-1] - spiral.x[-2])
    t_side = np.arctan2(side.z[1] - side.z[0], side.x[1] - side.x[0])
    assert t_spiral == pytest.approx(t_side, abs=2e-3)
    assert t_side == pytest.approx(math.pi / 4 - PHI30 / 2)  # rises at pi/4 - phi/2 to the surface


def test_rough_base_has_a_rigid_wedge_and_smooth_an_active_zone():
    rough = prandtl_field(0.1, PHI30, base="rough")
    smooth = prandtl_field(0.1, PHI30, base="smooth")
    assert not any(s.zone == "active" for s in rough)
    assert any(s.zone == "active" for s in smooth)


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [({"base": "glued"}, "base"), ({"line_count": 0}, "line_count"), ({"points": 2}, "points")],
)
def test_bad_field_options_are_refused(kwargs, field):
    with pytest.raises(InputError, match=field):
        prandtl_field(0.1, PHI30, **kwargs)


def test_plot_slip_lines_labels_axes_and_accepts_a_moc_solution():
    from terradyn.plotting.slipline import plot_slip_lines

    ax = plot_slip_lines(prandtl_field(0.1, PHI30))
    assert ax.get_xlabel() == "x [m]" and ax.get_ylabel() == "z [m]"
    assert ax.get_aspect() == 1.0
    assert len(ax.lines) == len(prandtl_field(0.1, PHI30))
    sol = moc_strip_footing(PHI30, width=0.1, surcharge=1.0, fan_count=6, ray_count=10)
    ax2 = plot_slip_lines(sol, ax)
    assert ax2 is ax and len(ax.lines) > len(prandtl_field(0.1, PHI30))
    with pytest.raises(InputError, match="field"):
        plot_slip_lines([])
    with pytest.raises(InputError, match="opacity"):
        plot_slip_lines(prandtl_field(0.1, PHI30), opacity=2.0)


def test_physics_modules_do_not_import_matplotlib():
    import subprocess
    import sys

    code = (
        "import sys, terradyn.plasticity as p; p.prandtl_field(0.1, 0.5); print('matplotlib' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
