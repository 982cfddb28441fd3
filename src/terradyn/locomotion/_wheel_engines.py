"""The time-stepped engines behind :func:`terradyn.locomotion.run_wheel`: dynamics of a force law, the
MPM and the DEM, each mapped onto the one :class:`~terradyn.locomotion.wheel_run.WheelRun`."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from typing import Any

import numpy as np

from ..errors import InputError
from ..kinematics import Pose2D
from .wheel_case import (
    HISTORY_KEYS,
    SUMMARY_KEYS,
    DEMSettings,
    Dynamics,
    Engine,
    MPMSettings,
    QuasiStatic,
    WheelCase,
    WheelRun,
    _force_law,
    _power,
    _summary,
)

#: default drive of the time-stepped engines [rad of rotation]: the MPM's measured settling rule
#: (:data:`terradyn.mpm.wheel_runs.DRIVE_RADIANS`, 4.5 rad, averaged over the last half)
DRIVE_RADIANS = 4.5
#: default drive of the force-law dynamics [revolutions]: the summary averages the last whole ones
DYNAMICS_REVOLUTIONS = 3.0


def _plane_body(case: WheelCase, engine: str) -> Any:
    from ..geometry import Body

    if not isinstance(case.wheel, Body):
        raise InputError("wheel", type(case.wheel).__name__, f"a plane Body for {engine}")
    if case.slip_angle != 0.0:
        raise InputError(
            "slip_angle", case.slip_angle, f"0 for {engine} (a plane engine)", "use model='rft3d'"
        )
    if case.sinkage is not None:
        raise InputError(
            "sinkage", case.sinkage, f"unset for {engine}: a time-stepped wheel sinks under a load"
        )
    return case.wheel


def _engine_summary(
    values: dict[str, Any], renames: dict[str, str] | None = None, **given: Any
) -> dict[str, Any]:
    """The contract's summary from an engine's: each key read under the engine's name for it
    (``renames``: contract key -> engine key), ``given`` values first, the power from torque and spin."""
    names = renames or {}
    out = {k: values.get(names.get(k, k)) for k in SUMMARY_KEYS}
    out.update(given)
    if "power_W" not in given:
        out["power_W"] = _power(out["drive_torque_Nm"], out["omega_rad_s"])
    return _summary(**out)


def _history(columns: dict[str, Any]) -> dict[str, np.ndarray]:
    return {k: np.asarray(columns[k], dtype=float) for k in HISTORY_KEYS if columns.get(k) is not None}


# ------------------------------------------------------------------------------------------ quasi-static
def run_quasi_static(case: WheelCase, model: Any, entry: Any, s: QuasiStatic) -> WheelRun:
    """The implicit steady solves: forced slip, free rolling or a prescribed sinkage; 3D for rft3d."""
    if case.drive_torque is not None:
        raise InputError(
            "drive_torque",
            case.drive_torque,
            "unset for a quasi-static solve",
            "a torque-driven wheel needs settings=Dynamics() or the MPM",
        )
    if entry is not None and entry.dimension == 3:
        return _run_3d(case, entry.name, s)
    if case.slip_angle != 0.0:
        raise InputError("slip_angle", case.slip_angle, "0 for a plane model", "use model='rft3d'")
    from ..geometry import Body

    if not isinstance(case.wheel, Body):
        raise InputError(
            "wheel", type(case.wheel).__name__, "a plane Body for a 2D model (a mesh needs rft3d)"
        )
    material = case.material
    terrain = _force_law(model, entry, material, s.element_size)
    slip, omega = case.drive()
    label = entry.name if entry is not None else str(getattr(terrain, "name", "user model"))
    if case.sinkage is not None:
        from .prescribed import wheel_at_sinkage

        if slip is None:
            raise InputError("slip", None, "a slip with a prescribed sinkage (a free wheel needs a load)")
        res = wheel_at_sinkage(
            case.wheel,
            terrain,
            case.sinkage,
            slip,
            omega=omega,
            phase_count=s.phase_count,
            slip_definition=case.slip_definition,
        )
        vertical = res.load_N
    elif slip is None:
        from .steady import wheel_self_propelled

        assert case.load is not None
        res = wheel_self_propelled(
            case.wheel,
            terrain,
            case.load,
            drawbar_load=case.drawbar_load,
            omega=omega,
            phase_count=s.phase_count,
        )
        vertical = case.load
    else:
        from .steady import wheel_steady

        assert case.load is not None
        res = wheel_steady(
            case.wheel,
            terrain,
            case.load,
            slip,
            omega=omega,
            phase_count=s.phase_count,
            slip_definition=case.slip_definition,
        )
        vertical = case.load
    summary = _summary(
        sinkage_m=res.sinkage_m,
        drawbar_pull_N=res.drawbar_pull_N,
        drive_torque_Nm=res.drive_torque_Nm,
        vertical_force_N=vertical,
        slip=res.slip,
        omega_rad_s=res.omega_rad_s,
        forward_velocity_m_s=res.forward_velocity_m_s,
        load_N=res.load_N,
        power_W=res.power_W,
    )
    meta = {"phase_count": res.phase_count, "axle_height_m": res.axle_height_m}
    return WheelRun(label, Engine.QUASI_STATIC, case, summary, {}, meta, res)


def _mesh(wheel: Any) -> Any:
    """A 3D wheel: a mesh as it is, a plane circular or grousered wheel extruded across its width."""
    from ..geometry import WheelCircular, WheelGrousered
    from ..geometry3d import TriangleMesh, wheel_cylinder, wheel_grousered

    if isinstance(wheel, TriangleMesh):
        return wheel
    if isinstance(wheel, WheelGrousered):
        return wheel_grousered(
            wheel.radius,
            wheel.width,
            grouser_count=wheel.grouser_count,
            grouser_height=wheel.grouser_height,
            grouser_thickness=wheel.grouser_thickness,
            circumferential_resolution=360,
            axial_resolution=2,
        )
    if isinstance(wheel, WheelCircular):
        return wheel_cylinder(wheel.radius, wheel.width, circumferential_resolution=360, axial_resolution=2)
    raise InputError(
        "wheel", type(wheel).__name__, "a TriangleMesh, WheelCircular or WheelGrousered for rft3d"
    )


def _run_3d(case: WheelCase, name: str, s: QuasiStatic) -> WheelRun:
    from .steady3d import steady3d_record, wheel_at_sinkage_3d, wheel_steady_3d
    from .wheel3d import rft3d_medium, wheel_contact_mesh

    slip, omega = case.drive()
    if slip is None:
        raise InputError("slip", None, "a slip for rft3d (it has no free-rolling solve)")
    mesh = _mesh(case.wheel)
    if s.cull:
        mesh = wheel_contact_mesh(mesh, slip_angle=case.slip_angle)
    medium, note = rft3d_medium(case.material)
    options: dict[str, Any] = {
        "slip_angle": case.slip_angle,
        "omega": omega,
        "slip_definition": case.slip_definition,
        "phase_count": s.phase_count,
    }
    if case.sinkage is not None:
        res = wheel_at_sinkage_3d(mesh, medium, case.sinkage, slip, **options)
    else:
        assert case.load is not None
        res = wheel_steady_3d(mesh, medium, case.load, slip, **options)
    rec = steady3d_record(res)
    summary = _summary(
        sinkage_m=rec["sinkage_m"],
        drawbar_pull_N=rec["drawbar_pull_N"],
        drive_torque_Nm=rec["drive_torque_Nm"],
        vertical_force_N=rec["vertical_force_N"],
        side_force_N=rec["side_force_N"],
        slip=rec["slip"],
        omega_rad_s=res.omega_rad_s,
        forward_velocity_m_s=res.longitudinal_velocity_m_s,
        load_N=res.load_N,
        power_W=rec["power_W"],
    )
    meta = {"facet_count": res.facet_count, "medium_note": note, "slip_angle_rad": case.slip_angle}
    return WheelRun(name, Engine.QUASI_STATIC, case, summary, {}, meta, res)


# ------------------------------------------------------------------------------------ force-law dynamics
def run_dynamics(
    case: WheelCase, model: Any, entry: Any, s: Dynamics, progress: Callable[[float, float], None] | None
) -> WheelRun:
    """A force law integrated in time: compiled for a free rft/drft wheel, else the coupled driver."""
    body = _plane_body(case, "dynamics")
    material = case.material
    assert case.load is not None
    mass = s.mass if s.mass is not None else case.load / s.gravity
    slip = case.classic_slip()
    if entry is not None and entry.name in ("rft", "drft") and slip is None:
        return _compiled(case, entry.name, body, material, mass, s)
    if case.drive_torque is not None:
        raise InputError("drive_torque", case.drive_torque, "a torque only through rft or drft in dynamics")
    terrain = _force_law(model, entry, material, s.element_size)
    return _coupled(case, terrain, body, material, mass, slip, s, progress)


def _compiled(case: WheelCase, name: str, body: Any, material: Any, mass: float, s: Dynamics) -> WheelRun:
    from .dynamics import simulate_wheel

    duration = case.duration or DYNAMICS_REVOLUTIONS * 2.0 * math.pi / case.omega
    omega, torque = (None, case.drive_torque) if case.drive_torque is not None else (case.omega, None)
    res = simulate_wheel(
        body,
        material,
        model=name,
        mass=mass,
        duration=duration,
        dt=s.dt,
        omega=omega,
        torque=torque,
        drawbar_load=case.drawbar_load,
        gravity=s.gravity,
        output_every=s.output_every,
        element_size=s.element_size,
    )
    st = res.steady_summary()
    summary = _engine_summary(st, load_N=case.load, power_W=st["power_W"])
    history = _history(
        {
            "time_s": res.t,
            "x_m": res.x,
            "sinkage_m": res.sinkage,
            "drawbar_pull_N": res.fx,
            "vertical_force_N": res.fz,
            "drive_torque_Nm": res.torque,
            "omega_rad_s": res.omega,
            "forward_velocity_m_s": res.vx,
        }
    )
    meta = {"averaging_window_s": st["averaging_window_s"], "revolutions": st["revolutions"], "dt_s": res.dt}
    return WheelRun(name, Engine.DYNAMICS, case, summary, history, meta, res)


def _coupled(
    case: WheelCase,
    terrain: Any,
    body: Any,
    material: Any,
    mass: float,
    slip: float | None,
    s: Dynamics,
    progress: Callable[[float, float], None] | None,
) -> WheelRun:
    from .coupled import simulate_coupled
    from .dynamics import stable_time_step

    if case.drawbar_load != 0.0:
        raise InputError("drawbar_load", case.drawbar_load, "0 here (the coupled driver has no towed load)")
    radius = case.radius
    omega = case.drive()[1]
    vx = None if slip is None else (1.0 - slip) * omega * radius
    dt = s.dt if s.dt is not None else 0.25 * stable_time_step(body, material, mass=mass, omega_max=omega)
    duration = case.duration or DRIVE_RADIANS / omega
    lowest = float(np.min(np.concatenate(body.outline())[:, 1]))
    assert case.load is not None  # _plane_body refused a prescribed sinkage
    res = simulate_coupled(
        body,
        terrain,
        load=case.load,
        pose=Pose2D(0.0, -lowest, 0.0),
        duration=duration,
        dt=dt,
        omega=omega,
        vx=vx,
        mass=mass,
        gravity=s.gravity,
        progress=progress,
    )
    renames = {
        "drawbar_pull_N": "force_x_N",
        "vertical_force_N": "force_z_N",
        "forward_velocity_m_s": "vx_m_s",
    }
    summary = _engine_summary(res.summary, renames, omega_rad_s=omega, load_N=case.load)
    series = dict(res.series, drive_torque_Nm=-res.series["torque_y_Nm"])
    history = _history({k: series.get(renames.get(k, k)) for k in HISTORY_KEYS})
    name = str(getattr(terrain, "name", "user model"))
    return WheelRun(name, Engine.DYNAMICS, case, summary, history, {"dt_s": dt, **res.metadata}, res)


# ------------------------------------------------------------------------------------------------- MPM
def run_mpm(case: WheelCase, s: MPMSettings, progress: Callable[[float, float], None] | None) -> WheelRun:
    """The plane-strain MPM wheel (:func:`terradyn.mpm.run_wheel`)."""
    from ..mpm import Bed, Drive, Outputs, Resolution
    from ..mpm import run_wheel as mpm_run_wheel

    body = _plane_body(case, "the MPM")
    drive = s.drive if s.drive is not None else Drive()
    if case.duration is not None:
        drive = replace(drive, duration=case.duration)
    outputs = s.outputs if s.outputs is not None else Outputs()
    if progress is not None:
        outputs = replace(outputs, progress=progress)
    spin, forward = _mpm_spin(case)
    assert case.load is not None
    res = mpm_run_wheel(
        body,
        case.material,
        load=case.load,
        drawbar_load=case.drawbar_load,
        bed=s.bed if s.bed is not None else Bed(),
        resolution=s.resolution if s.resolution is not None else Resolution(),
        outputs=outputs,
        drive=drive,
        **spin,
        **forward,
    )
    renames = {"vertical_force_N": "force_z_N", "forward_velocity_m_s": "vx_m_s"}
    summary = _engine_summary(res.summary, {"vertical_force_N": "force_z_N"})
    history = _history({k: res.series.get(renames.get(k, k)) for k in HISTORY_KEYS})
    return WheelRun("mpm", Engine.MPM, case, summary, history, dict(res.metadata), res)


def _mpm_spin(case: WheelCase) -> tuple[dict[str, Any], dict[str, Any]]:
    """(spin keywords, forward-motion keywords) of the MPM's run_wheel for the case's drive."""
    if case.drive_torque is not None:
        return {"drive_torque": case.drive_torque}, {}
    if case.rim_speed is not None and case.carriage_speed is not None:
        # speeds as given: a locked or slowly turning wheel towed at the carriage speed
        return {"omega": case.rim_speed / case.radius}, {"forward_speed": case.carriage_speed}
    return {"omega": case.omega}, {"slip": case.classic_slip()}


# ------------------------------------------------------------------------------------------------- DEM
def run_dem(case: WheelCase, s: DEMSettings, progress: Callable[[float, float], None] | None) -> WheelRun:
    """The LAMMPS DEM wheel (:func:`terradyn.dem.run_wheel`); forced slip only."""
    from ..dem.wheel import run_wheel as dem_run_wheel

    if case.sinkage is not None:
        raise InputError("sinkage", case.sinkage, "unset for the DEM: a DEM wheel sinks under a load")
    if case.drive_torque is not None:
        raise InputError("drive_torque", case.drive_torque, "unset for the DEM (it prescribes spin and slip)")
    slip = case.classic_slip()
    if slip is None:
        raise InputError("slip", None, "a slip for the DEM (it prescribes spin and forward speed)")
    if case.drawbar_load != 0.0:
        raise InputError("drawbar_load", case.drawbar_load, "0 for the DEM (its forward speed is prescribed)")
    if case.slip_angle != 0.0:
        raise InputError("slip_angle", case.slip_angle, "0 for the DEM wheel")
    omega = case.drive()[1]
    duration = case.duration or DRIVE_RADIANS / omega
    assert case.load is not None
    res = dem_run_wheel(
        case.wheel,
        case.material,
        load=case.load,
        omega=omega,
        slip=slip,
        duration=duration,
        bed=s.bed,
        kind=s.kind,
        packing=s.packing,
        grain_diameter=s.grain_diameter,
        seed=s.seed,
        record_interval=s.record_interval,
        checkpoint_path=s.checkpoint_path,
        resume=s.resume,
        progress=progress,
    )
    sm = res.summary
    summary = _engine_summary(sm)
    meta = {"grain_count": sm.get("grain_count"), "bed": dict(res.bed), "duration_s": duration}
    return WheelRun("dem", Engine.DEM, case, summary, _history(dict(res.history)), meta, res)
