"""``terradyn wheel steady/sweep --model rft3d``: CAD meshes, slip angle to 90 deg, slip definitions,
prescribed sinkage, the 3D-RFT scale from --xi or a calibration TOML."""

from __future__ import annotations

import json

import numpy as np
import pytest

from terradyn.geometry3d import TriangleMesh, wheel_cylinder

ROT_Z = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])
PRIMITIVE = ["--radius", "0.0625", "--width", "0.06"]


@pytest.fixture(scope="module")
def cad_stl(tmp_path_factory):
    pytest.importorskip("trimesh")
    from terradyn.geometry3d import save_mesh

    w = wheel_cylinder(0.0625, 0.06, circumferential_resolution=360, axial_resolution=2)
    v = (w.vertices @ ROT_Z) * 1000.0
    path = tmp_path_factory.mktemp("mesh") / "wheel_mm_z.stl"
    return save_mesh(TriangleMesh(v - v.min(axis=0) + 10.0, w.faces), path)


def _json(run_cli, *args):
    code, out, err = run_cli("wheel", "steady", "--model", "rft3d", *args, "--format", "json")
    assert code == 0, err
    return json.loads(out), err


def test_cad_mesh_in_mm_recovers_the_primitive(run_cli, cad_stl):
    base = ("--load", "20", "--slip", "0.3", "--slip-angle", "10")
    ref, _ = _json(run_cli, *PRIMITIVE, *base)
    got, err = _json(
        run_cli, "--mesh", str(cad_stl), "--mesh-units", "mm", "--axle", "z", "--phases", "1", *base
    )
    assert "radius 62.5 mm" in err and "width 60 mm" in err
    for key in ("sinkage_m", "drawbar_pull_N", "side_force_N", "drive_torque_Nm"):
        assert got[key] == pytest.approx(ref[key], rel=1e-5), key


@pytest.mark.parametrize(
    ("extra", "flag"),
    [
        ((), "--mesh-units"),
        (("--mesh-units", "mm"), "--axle"),
        (("--mesh-units", "mm", "--axle", "z", "--center", "0,0,0"), "--center"),
        (("--mesh-units", "inch"), "--mesh-units"),
    ],
)
def test_implausible_mesh_is_refused_in_one_line(run_cli, cad_stl, extra, flag):
    code, out, err = run_cli(
        "wheel", "steady", "--model", "rft3d", "--mesh", str(cad_stl), *extra, "--load", "20", "--slip", "0.3"
    )
    assert code == 1 and out == ""
    lines = [ln for ln in err.strip().splitlines() if "error" in ln]
    assert len(lines) == 1 and flag in lines[0] and "Traceback" not in err


def test_ninety_degrees_locked_wheel_and_messages_in_degrees(run_cli):
    speeds = ("--rim-speed", "0.05", "--carriage-speed", "0.01", "--slip-definition", "bounded")
    plus, _ = _json(run_cli, *PRIMITIVE, "--load", "20", "--slip-angle", "90", *speeds)
    minus, _ = _json(run_cli, *PRIMITIVE, "--load", "20", "--slip-angle", "-90", *speeds)
    assert plus["slip_angle_deg"] == 90.0 and plus["side_force_N"] < 0.0
    assert minus["side_force_N"] == pytest.approx(-plus["side_force_N"], rel=1e-9)
    locked, _ = _json(run_cli, *PRIMITIVE, "--load", "20", "--slip", "-1", "--slip-definition", "bounded")
    assert locked["omega_rad_s"] == 0.0 and locked["drawbar_pull_N"] < 0.0
    code, _, err = run_cli(
        "wheel", "steady", "--model", "rft3d", "--load", "20", "--slip", "0.2", "--slip-angle", "95"
    )
    assert code == 1 and "--slip-angle = 95" in err and "[-90, 90] [deg]" in err


def test_xi_and_a_calibration_toml(run_cli, tmp_path):
    from terradyn import materials
    from terradyn.locomotion.steady3d import xi_from_zeta

    csv = tmp_path / "plate.csv"
    csv.write_text("depth_m,force_z_N\n0.02,12.12\n0.04,24.24\n0.06,36.36\n")
    toml = tmp_path / "cal.toml"
    code, _, err = run_cli("calibrate", "rft", str(csv), "--length", "0.05", "--width", "0.06",
                           "--material-out", str(toml))  # fmt: skip
    assert code == 0, err
    zeta = materials.load(toml).zeta
    base = (*PRIMITIVE, "--load", "20", "--slip", "0.3")
    from_file, err = _json(run_cli, "--material", str(toml), *base)
    assert "xi =" in err
    direct, _ = _json(run_cli, "--xi", repr(xi_from_zeta(zeta)), *base)
    assert from_file["sinkage_m"] == pytest.approx(direct["sinkage_m"], rel=1e-12)
    code, _, err = run_cli("wheel", "steady", "--model", "rft3d", "--xi", "-1", *base)
    assert code == 1 and "--xi" in err


def test_prescribed_sinkage_2d_and_3d(run_cli):
    for model in ("rft", "rft3d"):
        head = ("wheel", "steady", "--model", model, *PRIMITIVE)
        code, out, err = run_cli(*head, "--load", "20", "--slip", "0.3", "--format", "json")
        assert code == 0, err
        loaded = json.loads(out)
        code, out, err = run_cli("wheel", "steady", "--model", model, *PRIMITIVE, "--sinkage",
                                 repr(loaded["sinkage_m"]), "--slip", "0.3", "--format", "json")  # fmt: skip
        assert code == 0, err
        held = json.loads(out)
        assert held["load_N"] == pytest.approx(20.0, rel=1e-5)
        assert held["drawbar_pull_N"] == pytest.approx(loaded["drawbar_pull_N"], rel=1e-4)
    code, _, err = run_cli("wheel", "steady", *PRIMITIVE, "--slip", "0.3")
    assert code == 1 and "--load" in err


def test_sweep_rft3d_matches_steady_points(run_cli):
    code, out, err = run_cli(
        "wheel", "sweep", "--model", "rft,rft3d", *PRIMITIVE, "--load", "20", "--slip", "-0.5,0.5",
        "--slip-angle", "0,30", "--slip-definition", "bounded", "--format", "json",
    )  # fmt: skip
    assert code == 0, err
    rows = json.loads(out)
    spatial = [r for r in rows if r["model"] == "rft3d"]
    assert len(spatial) == 4 and len(rows) == 6 and all(r["solved"] for r in rows)
    point = next(r for r in spatial if r["slip"] == -0.5 and r["slip_angle_deg"] == 30.0)
    ref, _ = _json(run_cli, *PRIMITIVE, "--load", "20", "--slip", "-0.5", "--slip-angle", "30",
                   "--slip-definition", "bounded")  # fmt: skip
    for key in ("sinkage_m", "drawbar_pull_N", "side_force_N"):
        assert point[key] == pytest.approx(ref[key], rel=1e-12), key
    code, _, err = run_cli("wheel", "sweep", "--model", "rft", "--slip-angle", "10")
    assert code == 1 and "--slip-angle" in err


def test_mesh_with_a_hidden_hub_is_culled_by_default(run_cli, tmp_path):
    pytest.importorskip("trimesh")
    from terradyn.geometry3d import save_mesh

    outer = wheel_cylinder(0.0625, 0.06, circumferential_resolution=120, axial_resolution=2)
    hub = wheel_cylinder(0.056, 0.04, circumferential_resolution=60, axial_resolution=2)
    plain = save_mesh(outer, tmp_path / "outer.stl")
    hubbed = save_mesh(outer.merged(hub), tmp_path / "hubbed.stl")
    base = ("--load", "60", "--slip", "0.3", "--slip-angle", "15", "--phases", "1")
    ref, _ = _json(run_cli, "--mesh", str(plain), *base)
    culled, _ = _json(run_cli, "--mesh", str(hubbed), *base)
    kept, _ = _json(run_cli, "--mesh", str(hubbed), "--no-cull", *base)
    assert culled["culled_facet_count"] >= hub.facet_count
    assert culled["sinkage_m"] == pytest.approx(ref["sinkage_m"], rel=1e-9)
    assert kept["sinkage_m"] < 0.97 * ref["sinkage_m"]  # without culling the hidden hub carries load
