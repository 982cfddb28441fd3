"""High-speed grousered wheel on poppy seeds: the onset of the sharp rise in slip (thesis ch. 8).

A grousered wheel of outer diameter l = 212 mm, driven at a prescribed spin omega, moves freely in x and z
on closely packed poppy seeds with a mass ratio m / (rho_c l^2 W) of about 6 (W = width). Each run is a
free-body time integration (:func:`terradyn.locomotion.dynamics.simulate_wheel`) to a steady state,
averaged over whole revolutions. Quasi-static RFT is rate independent, so its slip does not depend on
omega; dynamic RFT (its structural correction, a surface lowered by r (r omega^2 / g) behind the axle)
makes slip and sinkage rise past a spin rate of the order of sqrt(g / l).

Onset of the slip rise (our definition)
---------------------------------------
With s_0 the slip of the slowest run of the sweep (the low-speed value), the onset is the smallest spin
at which the slip reaches ``s_0 + slip_margin`` (linear interpolation between sweep points; default
margin 0.05). It is reported as omega_c [rad/s], omega_c sqrt(l / g) and two dimensionless criteria:
the Froude number r omega_c^2 / g and the ratio of the structural surface drop at onset to the
low-speed sinkage, ``delta_h_c / d_0 = r^2 omega_c^2 / (g d_0)``. The spin of the steepest slip rise
(largest d slip / d(omega sqrt(l/g)) between sweep points) is reported too.

Assumptions (the paper's wheel table was not available)
-------------------------------------------------------
15 grousers (the published 570-element discretisation is 15 x (14 + 3 x 8)), physical grouser height
18 mm, thickness 4 mm, width 50 mm (a plane model: results scale with W at a fixed mass ratio). With
``effective_grousers`` the lugs are one third of their physical height (shadowing) and the rim grows to
keep the outer radius at l / 2: sand trapped between the lugs moves with the wheel.

References
----------
S. Agarwal, A. Karsai, D. I. Goldman, K. Kamrin, "Surprising simplicity in the modeling of dynamic
granular intrusion", Sci. Adv. 7, eabe0631 (2021). doi:10.1126/sciadv.abe0631
S. Agarwal, "Development of a reduced-order modeling technique for granular locomotion", MS thesis,
MIT (2019), ch. 8.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..errors import InputError, check_finite, check_positive, check_range
from ..geometry import WheelGrousered
from ..locomotion.dynamics import simulate_wheel
from ..materials import Material, get
from ..results import TableResult

__all__ = [
    "HighSpeedResult",
    "HighSpeedWheel",
    "OnsetFit",
    "fit_onset_criterion",
    "high_speed_initial_conditions",
    "high_speed_onset_sensitivity",
    "high_speed_sweep",
    "plot_onset_criterion",
    "slip_onset",
]

_CITATION = "Agarwal, Karsai, Goldman, Kamrin, Sci. Adv. 7, eabe0631 (2021), doi:10.1126/sciadv.abe0631"


@dataclass(frozen=True)
class HighSpeedWheel:
    """The study wheel and its load (SI). Defaults: see the module's assumptions.

    Attributes
    ----------
    outer_diameter : l [m]; width : W [m]; grouser_count; grouser_height : physical [m];
    grouser_thickness [m]; effective_grousers : lugs at one third of their height, outer radius kept;
    mass_ratio : m / (rho_c l^2 W) [-]; rim_elements, face_elements : discretisation per lug pitch.
    """

    outer_diameter: float = 0.212
    width: float = 0.05
    grouser_count: int = 15
    grouser_height: float = 0.018
    grouser_thickness: float = 0.004
    effective_grousers: bool = True
    mass_ratio: float = 6.0
    rim_elements: int = 14
    face_elements: int = 8

    def __post_init__(self) -> None:
        check_positive("outer_diameter", self.outer_diameter)
        check_positive("width", self.width)
        check_range("grouser_height", self.grouser_height, 1e-6, 0.45 * self.outer_diameter, unit="m")
        check_positive("grouser_thickness", self.grouser_thickness)
        check_positive("mass_ratio", self.mass_ratio)
        if not isinstance(self.effective_grousers, bool):
            raise InputError("effective_grousers", self.effective_grousers, "True or False")
        for name in ("grouser_count", "rim_elements", "face_elements"):
            value = getattr(self, name)
            if not isinstance(value, int | np.integer) or isinstance(value, bool) or not 1 <= value <= 1000:
                raise InputError(name, value, "an integer in [1, 1000]")

    @property
    def lug_height(self) -> float:
        """Modelled grouser height [m] (a third of the physical one with ``effective_grousers``)."""
        return self.grouser_height / 3.0 if self.effective_grousers else self.grouser_height

    def body(self) -> WheelGrousered:
        """The wheel body; outer radius l / 2."""
        h = self.lug_height
        return WheelGrousered(
            0.5 * self.outer_diameter - h, self.width, int(self.grouser_count), h, self.grouser_thickness
        )

    def mass(self, critical_density: float) -> float:
        """m = mass_ratio rho_c l^2 W [kg]."""
        return self.mass_ratio * critical_density * self.outer_diameter**2 * self.width


@dataclass(frozen=True, eq=False)
class HighSpeedResult:
    """Steady states of an omega sweep and the slip onset per model.

    Attributes
    ----------
    table : TableResult  one row per (model, omega)
    onset : dict  onset of the dynamic model (``drft`` if swept, else the first model): keys
        ``omega_onset_rad_s``, ``omega_onset_normalised`` (omega sqrt(l/g)), ``froude_onset``
        (r omega^2 / g), ``drop_to_sinkage_onset`` (delta_h / d_0), ``omega_steepest_rad_s``,
        ``omega_steepest_normalised``, ``low_speed_slip``, ``low_speed_sinkage_m``; None where no onset
        was found within the sweep
    onsets : dict  model name -> the same dict
    """

    table: TableResult
    onset: dict[str, Any]
    onsets: dict[str, dict[str, Any]] = field(default_factory=dict)


def slip_onset(
    omega: Sequence[float] | np.ndarray,
    slip: Sequence[float] | np.ndarray,
    sinkage: Sequence[float] | np.ndarray,
    *,
    outer_diameter: float,
    gravity: float = 9.81,
    slip_margin: float = 0.05,
) -> dict[str, Any]:
    """Onset of the slip rise in a sweep (see the module notes for the definition).

    Parameters
    ----------
    omega : increasing spin rates [rad/s]; slip : steady slips [-]; sinkage : steady sinkages [m].
    outer_diameter : l [m]; gravity : g [m/s^2]; slip_margin : rise above the slowest run's slip [-].
    """
    w = np.asarray(omega, dtype=float)
    s = np.asarray(slip, dtype=float)
    d = np.asarray(sinkage, dtype=float)
    if w.ndim != 1 or w.size < 2 or s.shape != w.shape or d.shape != w.shape or np.any(np.diff(w) <= 0):
        raise InputError("omega", w.tolist(), "two or more increasing spin rates, one slip and sinkage each")
    margin = check_positive("slip_margin", slip_margin)
    g = check_positive("gravity", gravity)
    ell = check_positive("outer_diameter", outer_diameter)
    norm = math.sqrt(ell / g)
    out: dict[str, Any] = {
        "low_speed_slip": float(s[0]),
        "low_speed_sinkage_m": float(d[0]),
        "slip_margin": margin,
    }
    above = np.nonzero(s >= s[0] + margin)[0]
    if above.size:
        k = int(above[0])
        w_c = float(np.interp(s[0] + margin, [s[k - 1], s[k]], [w[k - 1], w[k]]))
        r = 0.5 * ell
        out.update(
            omega_onset_rad_s=w_c,
            omega_onset_normalised=w_c * norm,
            froude_onset=r * w_c**2 / g,
            drop_to_sinkage_onset=float(r * r * w_c**2 / (g * d[0])),
        )
    else:
        out.update(
            omega_onset_rad_s=None, omega_onset_normalised=None, froude_onset=None, drop_to_sinkage_onset=None
        )
    rate = np.diff(s) / np.diff(w * norm)
    j = int(np.argmax(rate))
    steep = float(0.5 * (w[j] + w[j + 1])) if rate[j] > margin else None
    out.update(
        omega_steepest_rad_s=steep,
        omega_steepest_normalised=None if steep is None else steep * norm,
        max_slope=float(rate[j]),
    )
    return out


def _material(material: str | Material, gravity: float, medium_follows_gravity: bool) -> Material:
    mat = get(material) if isinstance(material, str) else material
    if not isinstance(mat, Material):
        raise InputError("material", material, "a medium name (poppy-cp, CPS) or a Material")
    if mat.critical_density is None:
        raise InputError("material", mat.name, "a medium with a critical density (rho_c)")
    if medium_follows_gravity and gravity != 9.81:
        mat = mat.with_zeta(mat.zeta * gravity / 9.81)  # zeta ~ rho_c g
    return mat


def _omegas(omegas: Sequence[float] | np.ndarray | None, reduced: bool, ell: float, g: float) -> np.ndarray:
    if omegas is None:
        hat = (
            np.array([0.15, 0.5, 0.8, 1.1, 1.5, 2.2])
            if reduced
            else np.array([0.15, 0.3, 0.45, 0.6, 0.75, 0.9, 1.05, 1.2, 1.4, 1.7, 2.0, 2.4])
        )
        return hat * math.sqrt(g / ell)
    w = np.asarray(omegas, dtype=float)
    if w.ndim != 1 or w.size < 2 or not np.all(np.isfinite(w)) or np.any(w <= 0) or np.any(np.diff(w) <= 0):
        raise InputError("omegas", omegas, "two or more increasing spin rates > 0 [rad/s]")
    return w


def _steady_run(
    wheel: HighSpeedWheel,
    mat: Material,
    model: str,
    omega: float,
    *,
    gravity: float,
    initial_velocity: float,
    ramp: float | None,
    settle_revolutions: float,
    average_revolutions: float,
) -> dict[str, float]:
    body = wheel.body()
    elements = body.discretize_counts(int(wheel.rim_elements), int(wheel.face_elements))
    mass = wheel.mass(float(mat.critical_density))  # type: ignore[arg-type]
    ramp_time = 0.0 if ramp is None else omega / ramp
    duration = max(1.0, ramp_time + 2.0 * math.pi * (settle_revolutions + average_revolutions) / omega)
    run = simulate_wheel(
        body,
        mat,
        model=model,
        mass=mass,
        omega=omega,
        ramp=ramp,
        gravity=gravity,
        duration=duration,
        elements=elements,
        initial_velocity=initial_velocity,
        output_every=2,
    )
    return run.steady_summary(revolutions=average_revolutions)


@dataclass(frozen=True)
class _RunOptions:
    """What every run of a sweep shares: g [m/s^2], the initial forward speed [m/s], the spin-up rate
    [rad/s^2] (None: spin applied at t = 0) and the revolutions settled and then averaged."""

    gravity: float
    initial_velocity: float
    ramp: float | None
    settle_revolutions: float
    average_revolutions: float

    def steady(self, wheel: HighSpeedWheel, mat: Material, model: str, omega: float) -> dict[str, float]:
        """The steady summary of one run of ``model`` at spin ``omega`` [rad/s]."""
        return _steady_run(
            wheel,
            mat,
            model,
            omega,
            gravity=self.gravity,
            initial_velocity=self.initial_velocity,
            ramp=self.ramp,
            settle_revolutions=self.settle_revolutions,
            average_revolutions=self.average_revolutions,
        )


def _model_names(models: Sequence[str]) -> list[str]:
    """``models`` as lower-case names, each one of the terrain models the dynamics take."""
    from ..models import model_names

    allowed = model_names(use="dynamics")
    names = [str(m).strip().lower() for m in models]
    if not names or any(m not in allowed for m in names):
        raise InputError("models", models, f"one or more of {', '.join(allowed)}")
    return names


def _sweep_row(name: str, omega: float, s: dict[str, float], ell: float, g: float) -> dict[str, Any]:
    """One row of the sweep table: a run's steady figures, as they are and normalised by l and g."""
    v = s["forward_velocity_m_s"]
    return {
        "model": name,
        "omega_rad_s": omega,
        "omega_normalised": omega * math.sqrt(ell / g),
        "forward_velocity_m_s": v,
        "velocity_normalised": v / math.sqrt(g * ell),
        "slip": s["slip"],
        "sinkage_m": s["sinkage_m"],
        "sinkage_normalised": s["sinkage_m"] / ell,
        "drive_torque_Nm": s["drive_torque_Nm"],
        "froude": 0.5 * ell * omega**2 / g,
    }


def _sweep_models(
    wheel: HighSpeedWheel,
    mat: Material,
    names: list[str],
    w: np.ndarray,
    options: _RunOptions,
    slip_margin: float,
    progress: Callable[[int, int], None] | None,
) -> tuple[dict[str, list[Any]], dict[str, dict[str, Any]]]:
    """Every model at every spin ``w`` [rad/s] (``progress(done, total)`` before each run): the table's
    columns and each model's slip onset (:func:`slip_onset`)."""
    ell, g = wheel.outer_diameter, options.gravity
    rows: dict[str, list[Any]] = {}
    onsets: dict[str, dict[str, Any]] = {}
    done, total = 0, len(names) * len(w)
    for name in names:
        slips, sinks = [], []
        for omega in w:
            if progress is not None:
                progress(done, total)
            done += 1
            s = options.steady(wheel, mat, name, float(omega))
            slips.append(s["slip"])
            sinks.append(s["sinkage_m"])
            for key, value in _sweep_row(name, omega, s, ell, g).items():
                rows.setdefault(key, []).append(value)
        onsets[name] = slip_onset(w, slips, sinks, outer_diameter=ell, gravity=g, slip_margin=slip_margin)
    return rows, onsets


def high_speed_sweep(
    *,
    material: str | Material = "poppy-cp",
    models: Sequence[str] = ("rft", "drft"),
    omegas: Sequence[float] | np.ndarray | None = None,
    wheel: HighSpeedWheel | None = None,
    gravity: float = 9.81,
    medium_follows_gravity: bool = True,
    initial_velocity: float = 0.0,
    ramp: float | None = None,
    settle_revolutions: float | None = None,
    average_revolutions: float = 2.0,
    slip_margin: float = 0.05,
    reduced: bool = False,
    progress: Callable[[int, int], None] | None = None,
) -> HighSpeedResult:
    """Steady speed, slip and sinkage of the study wheel over a sweep of spin rates, and the slip onset.

    Parameters
    ----------
    material : str or Material
        Medium with a critical density: "poppy-cp" (Li et al. CP fit) or "CPS".
    models : sequence of {"rft", "drft"}
        Terrain models to sweep.
    omegas : sequence of float, optional
        Increasing spin rates [rad/s]; default omega sqrt(l/g) from 0.15 to 2.4 (6 values when
        ``reduced``, 12 otherwise).
    wheel : HighSpeedWheel, optional
        Geometry and mass ratio (default: the module's assumptions).
    gravity : float
        g [m/s^2]. With ``medium_follows_gravity`` the RFT scale follows zeta ~ rho_c g (Earth: 9.81).
    initial_velocity : float
        Initial forward speed [m/s] of every run.
    ramp : float, optional
        Spin-up rate [rad/s^2] from rest (None: spin applied at t = 0).
    settle_revolutions : float, optional
        Revolutions run before averaging (default 6, or 3 when ``reduced``; 6 brings runs from different
        initial speeds and ramps within 0.002 in slip).
    average_revolutions : float
        Revolutions averaged over.
    slip_margin : float
        Slip rise above the low-speed value that defines the onset [-].
    reduced : bool
        Fewer spin rates (the fast form used by the default test suite).

    Returns
    -------
    HighSpeedResult
        Table columns: ``model``, ``omega_rad_s``, ``omega_normalised`` (omega sqrt(l/g)),
        ``forward_velocity_m_s``, ``velocity_normalised`` (V / sqrt(g l)), ``slip``, ``sinkage_m``,
        ``sinkage_normalised`` (sinkage / l), ``drive_torque_Nm``, ``froude`` (r omega^2 / g).
    """
    wheel = HighSpeedWheel() if wheel is None else wheel
    if not isinstance(wheel, HighSpeedWheel):
        raise InputError("wheel", type(wheel).__name__, "a HighSpeedWheel")
    g = check_positive("gravity", gravity)
    mat = _material(material, g, medium_follows_gravity)
    names = _model_names(models)
    ell = wheel.outer_diameter
    w = _omegas(omegas, reduced, ell, g)
    check_finite("initial_velocity", initial_velocity)
    if settle_revolutions is None:
        settle_revolutions = 3.0 if reduced else 6.0
    check_positive("settle_revolutions", settle_revolutions, allow_zero=True)
    check_positive("average_revolutions", average_revolutions)
    options = _RunOptions(g, initial_velocity, ramp, settle_revolutions, average_revolutions)
    rows, onsets = _sweep_models(wheel, mat, names, w, options, slip_margin, progress)
    meta = {
        "study": "high-speed slip onset",
        "material": mat.name,
        "gravity_m_s2": g,
        "wheel": {k: getattr(wheel, k) for k in wheel.__dataclass_fields__},
        "mass_kg": wheel.mass(float(mat.critical_density)),  # type: ignore[arg-type]
        "initial_velocity_m_s": initial_velocity,
        "ramp_rad_s2": ramp,
        "onsets": onsets,
        "citation": _CITATION,
    }
    table = TableResult({k: np.asarray(v) for k, v in rows.items()}, meta)
    main = "drft" if "drft" in onsets else names[0]
    return HighSpeedResult(table, onsets[main], onsets)


_DEFAULT_VARIATIONS: dict[str, tuple[float, ...]] = {
    "grouser_count": (10, 20),
    "grouser_height": (0.009, 0.027),
    "outer_diameter": (0.15, 0.30),
    "mass_ratio": (3.0, 12.0),
    "gravity": (3.71, 24.79),
}


def high_speed_onset_sensitivity(
    *,
    variations: dict[str, Sequence[float]] | None = None,
    material: str | Material = "poppy-cp",
    wheel: HighSpeedWheel | None = None,
    gravity: float = 9.81,
    omega_normalised: Sequence[float] | None = None,
    slip_margin: float = 0.05,
    reduced: bool = False,
) -> TableResult:
    """How the DRFT slip onset moves when one parameter of the study changes at a time.

    Parameters
    ----------
    variations : dict, optional
        Parameter -> values; parameters: ``grouser_count``, ``grouser_height`` [m] (physical),
        ``outer_diameter`` [m], ``mass_ratio`` [-] (the load), ``gravity`` [m/s^2] (same mass; the
        medium's zeta ~ rho_c g follows). Default: two values each around the reference wheel.
    omega_normalised : sequence of float, optional
        Sweep in omega sqrt(l/g) (default that of :func:`high_speed_sweep`).
    material, wheel, gravity, slip_margin, reduced : as in :func:`high_speed_sweep`.

    Returns
    -------
    TableResult
        One row per case (the reference first): ``parameter``, ``value``, ``omega_onset_rad_s``,
        ``omega_onset_normalised``, ``froude_onset``, ``drop_to_sinkage_onset``, ``low_speed_slip``,
        ``low_speed_sinkage_m``, ``low_speed_sinkage_normalised``. Cases without an onset in the sweep
        hold -1 in the onset columns, listed in ``metadata["no_onset"]``.
    """
    base = HighSpeedWheel() if wheel is None else wheel
    g0 = check_positive("gravity", gravity)
    cases: list[tuple[str, float]] = [("reference", math.nan)]
    chosen: dict[str, Sequence[float]] = dict(_DEFAULT_VARIATIONS if variations is None else variations)
    if reduced and variations is None:
        chosen = {"gravity": (3.71,), "grouser_height": (0.027,)}
    for key, values in chosen.items():
        if key not in _DEFAULT_VARIATIONS:
            raise InputError("variations", key, f"one of {sorted(_DEFAULT_VARIATIONS)}")
        cases.extend((key, float(v)) for v in values)
    rows: dict[str, list[Any]] = {
        k: []
        for k in (
            "parameter",
            "value",
            "omega_onset_rad_s",
            "omega_onset_normalised",
            "froude_onset",
            "drop_to_sinkage_onset",
            "low_speed_slip",
            "low_speed_sinkage_m",
            "low_speed_sinkage_normalised",
        )
    }
    no_onset = []
    for key, value in cases:
        wheel_k, g = base, g0
        if key == "gravity":
            g = check_positive("gravity", value)
        elif key == "grouser_count":
            wheel_k = replace(base, grouser_count=int(value))
        elif key == "grouser_height":
            wheel_k = replace(base, grouser_height=value)
        elif key == "outer_diameter":
            wheel_k = replace(base, outer_diameter=value)
        elif key == "mass_ratio":
            wheel_k = replace(base, mass_ratio=value)
        ell = wheel_k.outer_diameter
        hat = np.asarray(
            omega_normalised if omega_normalised is not None else _omegas(None, reduced, 1.0, 1.0),
            dtype=float,
        )
        res = high_speed_sweep(
            material=material,
            models=("drft",),
            omegas=hat * math.sqrt(g / ell),
            wheel=wheel_k,
            gravity=g,
            slip_margin=slip_margin,
            reduced=reduced,
        )
        on = res.onset
        if on["omega_onset_rad_s"] is None:
            no_onset.append(f"{key}={value}")
        for col in ("omega_onset_rad_s", "omega_onset_normalised", "froude_onset", "drop_to_sinkage_onset"):
            rows[col].append(math.nan if on[col] is None else on[col])
        rows["parameter"].append(key)
        rows["value"].append(value if key != "reference" else 0.0)
        rows["low_speed_slip"].append(on["low_speed_slip"])
        rows["low_speed_sinkage_m"].append(on["low_speed_sinkage_m"])
        rows["low_speed_sinkage_normalised"].append(on["low_speed_sinkage_m"] / ell)
    meta = {
        "study": "high-speed onset sensitivity",
        "no_onset": no_onset,
        "slip_margin": slip_margin,
        "citation": _CITATION,
    }
    columns = {k: np.asarray(v) for k, v in rows.items()}
    return _table_allowing_nan(columns, meta)


def _table_allowing_nan(columns: dict[str, np.ndarray], meta: dict[str, Any]) -> TableResult:
    """A TableResult with missing onsets (NaN) stored as -1, listed in the metadata (never silent)."""
    clean = {k: (np.where(np.isnan(v), -1.0, v) if v.dtype.kind == "f" else v) for k, v in columns.items()}
    return TableResult(clean, meta)


def high_speed_initial_conditions(
    *,
    omegas_normalised: Sequence[float] = (0.5, 1.5),
    initial_velocities_normalised: Sequence[float] = (0.0, 0.3),
    ramps_normalised: Sequence[float | None] = (None, 0.5),
    material: str | Material = "poppy-cp",
    wheel: HighSpeedWheel | None = None,
    model: str = "drft",
    gravity: float = 9.81,
    settle_revolutions: float = 6.0,
) -> TableResult:
    """Effect of the initial forward speed and of the spin-up ramp rate on the steady state.

    Parameters
    ----------
    omegas_normalised : spin rates omega sqrt(l/g) [-] (below and above the onset).
    initial_velocities_normalised : initial speeds V_0 / sqrt(g l) [-].
    ramps_normalised : spin-up rates (d omega / dt) / (g / l) [-]; None = spin applied at t = 0.
    material, wheel, model, gravity, settle_revolutions : as in :func:`high_speed_sweep`.

    Returns
    -------
    TableResult
        ``omega_normalised``, ``initial_velocity_normalised``, ``ramp_normalised`` (0 = step),
        ``velocity_normalised``, ``slip``, ``sinkage_normalised``.
    """
    wheel = HighSpeedWheel() if wheel is None else wheel
    g = check_positive("gravity", gravity)
    mat = _material(material, g, True)
    ell = wheel.outer_diameter
    rows: dict[str, list[float]] = {
        k: []
        for k in (
            "omega_normalised",
            "initial_velocity_normalised",
            "ramp_normalised",
            "velocity_normalised",
            "slip",
            "sinkage_normalised",
        )
    }
    for hat in omegas_normalised:
        omega = check_positive("omegas_normalised", hat) * math.sqrt(g / ell)
        for v0 in initial_velocities_normalised:
            for ramp in ramps_normalised:
                rate = None if ramp is None else check_positive("ramps_normalised", ramp) * g / ell
                s = _steady_run(
                    wheel,
                    mat,
                    model,
                    omega,
                    gravity=g,
                    initial_velocity=check_finite("initial_velocities_normalised", v0) * math.sqrt(g * ell),
                    ramp=rate,
                    settle_revolutions=settle_revolutions,
                    average_revolutions=2.0,
                )
                for key, value in (
                    ("omega_normalised", hat),
                    ("initial_velocity_normalised", v0),
                    ("ramp_normalised", 0.0 if ramp is None else ramp),
                    ("velocity_normalised", s["forward_velocity_m_s"] / math.sqrt(g * ell)),
                    ("slip", s["slip"]),
                    ("sinkage_normalised", s["sinkage_m"] / ell),
                ):
                    rows[key].append(float(value))
    meta = {
        "study": "high-speed initial conditions",
        "model": model,
        "material": mat.name,
        "citation": _CITATION,
    }
    return TableResult({k: np.asarray(v) for k, v in rows.items()}, meta)


@dataclass(frozen=True, eq=False)
class OnsetFit:
    """The slip-onset criterion fitted over sensitivity sweeps.

    Attributes
    ----------
    formula : the fitted criterion as text, e.g. ``omega_c sqrt(l/g) = 0.61 (h/l)^0.11 M^-0.05 N^0.02``
    coefficients : prefactor ``C`` and the exponent of each group that varied (``h_over_l``,
        ``mass_ratio``, ``grouser_count``)
    r_squared : of log(omega_c sqrt(l/g)) [-]; max_relative_error : of omega_c sqrt(l/g) [-]
    alternative : the one-constant form ``delta_h_c / d_0 = K`` (structural surface drop at onset over
        low-speed sinkage, i.e. omega_c sqrt(l/g) = sqrt(4 K d_0 / l)) with its own fit quality
    table : one row per case: the groups, ``omega_onset_normalised`` observed and ``predicted``
    """

    formula: str
    coefficients: dict[str, float]
    r_squared: float
    max_relative_error: float
    alternative: dict[str, Any]
    table: TableResult


_REDUCED_FIT_VARIATIONS: dict[str, Sequence[float]] = {
    "grouser_height": (0.009, 0.027),
    "mass_ratio": (3.0, 12.0),
}


def fit_onset_criterion(
    *,
    variations: dict[str, Sequence[float]] | None = None,
    material: str | Material = "poppy-cp",
    slip_margin: float = 0.05,
    reduced: bool = False,
) -> OnsetFit:
    """Fit the DRFT slip onset over :func:`high_speed_onset_sensitivity` sweeps as a formula.

    The onset spin is made dimensionless as omega_c sqrt(l/g) (l outer diameter) and fitted by least
    squares in logs as a power law of the dimensionless groups that vary among the cases: grouser
    height over diameter h/l, mass ratio M = m / (rho_c l^2 W) and grouser count N. Gravity enters
    only through sqrt(l/g) (the cases at other g check that scaling: their normalised onset equals the
    reference's). Also fitted: the one-constant criterion delta_h_c / d_0 = K, the structural surface
    drop r (r omega_c^2 / g) at onset over the low-speed sinkage d_0, i.e.
    omega_c sqrt(l/g) = sqrt(4 K d_0 / l). Both are printed with R^2 (of the log onset) and the
    largest relative error. Cases without an onset are left out (listed in the table metadata).

    Parameters
    ----------
    variations : parameter -> values as for :func:`high_speed_onset_sensitivity` (default: all five
        parameters at two values each; ``reduced``: grouser height and mass ratio, two values each)
    material, slip_margin : as :func:`high_speed_sweep`; reduced : the fast sweeps (6 spin rates)
    """
    chosen = variations if variations is not None else (_REDUCED_FIT_VARIATIONS if reduced else None)
    sens = high_speed_onset_sensitivity(
        variations=chosen, material=material, slip_margin=slip_margin, reduced=reduced
    )
    c = sens.columns
    base = HighSpeedWheel()
    keep = c["omega_onset_normalised"] > 0
    if int(keep.sum()) < 3:
        raise InputError("variations", chosen, "sweeps with a slip onset in at least three cases")
    groups: dict[str, list[float]] = {"h_over_l": [], "mass_ratio": [], "grouser_count": []}
    for par, val in zip(c["parameter"].tolist(), c["value"].tolist(), strict=True):
        ell = val if par == "outer_diameter" else base.outer_diameter
        h = val if par == "grouser_height" else base.grouser_height
        groups["h_over_l"].append(h / ell)
        groups["mass_ratio"].append(val if par == "mass_ratio" else base.mass_ratio)
        groups["grouser_count"].append(val if par == "grouser_count" else float(base.grouser_count))
    y = np.log(c["omega_onset_normalised"][keep])
    logs = {k: np.log(np.asarray(v)[keep]) for k, v in groups.items()}
    varying = [k for k, v in logs.items() if np.ptp(v) > 1e-9]
    design = np.column_stack([np.ones_like(y)] + [logs[k] for k in varying])
    coef, *_ = np.linalg.lstsq(design, y, rcond=None)

    def quality(pred_log: np.ndarray) -> tuple[float, float]:
        ss_res = float(np.sum((y - pred_log) ** 2))
        ss_tot = float(np.sum((y - y.mean()) ** 2))
        r2 = 1.0 - ss_res / ss_tot if ss_tot > 0 else 1.0
        return r2, float(np.max(np.abs(np.exp(pred_log - y) - 1.0)))

    pred = design @ coef
    r2, err = quality(pred)
    symbols = {"h_over_l": "(h/l)", "mass_ratio": "M", "grouser_count": "N"}
    formula = f"omega_c sqrt(l/g) = {math.exp(coef[0]):.3g}" + "".join(
        f" {symbols[k]}^{a:+.3f}" for k, a in zip(varying, coef[1:], strict=True)
    )
    d0 = c["low_speed_sinkage_normalised"][keep]  # d_0 / l
    k_const = float(np.exp(np.mean(2.0 * y - np.log(4.0 * d0))))  # least squares in logs
    alt_pred = 0.5 * np.log(4.0 * k_const * d0)
    alt_r2, alt_err = quality(alt_pred)
    alternative = {
        "formula": f"delta_h_c / d_0 = {k_const:.3g}, i.e. omega_c sqrt(l/g) = sqrt(4 x "
        f"{k_const:.3g} d_0 / l)",
        "K": k_const,
        "r_squared": alt_r2,
        "max_relative_error": alt_err,
    }
    table = TableResult(
        {
            "parameter": c["parameter"][keep],
            "value": c["value"][keep],
            **{k: np.asarray(v)[keep] for k, v in groups.items()},
            "low_speed_sinkage_normalised": d0,
            "omega_onset_normalised": c["omega_onset_normalised"][keep],
            "predicted": np.exp(pred),
            "predicted_alternative": np.exp(alt_pred),
        },
        {
            "study": "high-speed onset criterion",
            "no_onset": sens.metadata.get("no_onset", []),
            "formula": formula,
            "citation": _CITATION,
        },
    )
    coefficients = {"C": math.exp(coef[0]), **{k: float(a) for k, a in zip(varying, coef[1:], strict=True)}}
    return OnsetFit(formula, coefficients, r2, err, alternative, table)


def plot_onset_criterion(fit: OnsetFit) -> Any:
    """Predicted against observed omega_c sqrt(l/g) for both fitted criteria (parity plot); the Figure."""
    import matplotlib.pyplot as plt

    c = fit.table.columns
    fig, ax = plt.subplots(figsize=(5.6, 4.6), layout="constrained")
    obs = c["omega_onset_normalised"]
    ax.plot(obs, c["predicted"], "o", label=f"power law, R$^2$ = {fit.r_squared:.3f}")
    ax.plot(
        obs,
        c["predicted_alternative"],
        "s",
        mfc="none",
        label=f"delta_h/d_0 = K, R$^2$ = {fit.alternative['r_squared']:.3f}",
    )
    for x, y, name in zip(obs, c["predicted"], c["parameter"].tolist(), strict=True):
        ax.annotate(name, (x, y), fontsize=6, xytext=(3, 3), textcoords="offset points")
    lo, hi = (
        float(min(obs.min(), c["predicted"].min())) * 0.95,
        float(max(obs.max(), c["predicted"].max())) * 1.05,
    )
    ax.plot([lo, hi], [lo, hi], "k:", lw=0.8, label="equality")
    ax.set_xlabel(r"DRFT onset $\omega_c \sqrt{\ell/g}$ (sweep) [-]")
    ax.set_ylabel(r"criterion $\omega_c \sqrt{\ell/g}$ (fit) [-]")
    ax.set_title(fit.formula, fontsize=8)
    ax.grid(True, alpha=0.35)
    ax.legend(fontsize=7)
    return fig


def study_entries() -> tuple[Any, ...]:
    """The studies this module provides (:mod:`terradyn.studies.registry` lists them)."""
    from pydantic import Field

    from ._base import StudyOutput, _Params

    class OnsetCriterionParams(_Params):
        material: str = "poppy-cp"
        slip_margin: float = Field(0.05, gt=0, lt=1)

    def run(p: OnsetCriterionParams) -> StudyOutput:
        fit = fit_onset_criterion(material=p.material, slip_margin=p.slip_margin, reduced=p.quick)
        summary = [
            {
                "criterion": fit.formula,
                "r_squared": fit.r_squared,
                "max_relative_error": fit.max_relative_error,
                "cases": len(fit.table),
            },
            {
                "criterion": fit.alternative["formula"],
                "r_squared": fit.alternative["r_squared"],
                "max_relative_error": fit.alternative["max_relative_error"],
                "cases": len(fit.table),
            },
        ]
        return StudyOutput(
            {"onset_criterion": fit.table}, {"onset_criterion": plot_onset_criterion(fit)}, summary
        )

    return (
        (
            "high-speed-criterion",
            OnsetCriterionParams,
            run,
            "slip-onset criterion of the high-speed wheel as a formula in the dimensionless groups (ch. 8)",
        ),
    )
