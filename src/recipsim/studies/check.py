"""Stability checks: run a set of (hard) cases and compare each outcome with its expectation.

``recipsim check hard`` runs every case file of a directory (see
:mod:`recipsim.cli.check`), one row per case, and never stops at a failing case:

- outcome ``converged`` / ``not_converged``: the run went to its end (the periodic
  steady state was, or was not, reached within ``solver.max_revolutions``); the message
  is the run's status message (:mod:`recipsim.results.outcome`: the diagnosis of a
  ``not_converged`` run, what ``no_delivery`` or ``subharmonic`` leave out);
- ``refused``: the case was rejected before integrating (:class:`CaseError`, the
  refrigerant's envelope included);
- ``failed``: the integration stopped (:class:`SolverError`, crank angle and state in
  the message), or an internal error (its type is named).

Each case's expectation comes from ``expectations.toml`` beside the case files (a case
not listed there is expected to converge with closed balances): the expected outcome,
a regular expression its refusal or failure message must match, closure tolerances,
minimum values of cycle metrics (e.g. the number of suction-valve openings of a
fluttering reed) and extra ``--fast`` overrides.

Closures, normalised by the swept mass (not by the delivered mass)
------------------------------------------------------------------
Over the converged revolution, with ``m_sw = rho_suction V_swept`` (the mass an ideal
compressor would take in per revolution) and ``dh_s = h(p_d, s_suction) - h_suction``:

- ``mass_closure = |m_suction - m_discharge - m_leakage| / m_sw``;
- ``energy_closure = |W_indicated - (H_out - H_in - Q_in)| / (m_sw dh_s)``;
- ``drive_closure = |P_shaft - P_indicated - P_bearings| / |P_shaft|`` (the crank train's
  energy balance: drive work = gas work + bearing dissipation; 0 for the rigid crank).

The summary's own ``mass_balance_residual`` divides the same imbalance by the suction
mass, which tends to zero with the delivery: its error is the revolution's
non-periodicity (about the cycle tolerance times the trapped gas mass), so near zero
delivery it grows as 1/(volumetric efficiency) although nothing is wrong (5e-3 at a
volumetric efficiency of 1.6 %). Normalised by the swept mass the closures measure the
integration and periodicity error on the scale of what the cylinder handles, the same
for every operating point. Tolerances (defaults, ``expectations.toml`` may change them
per case): mass 1e-3 and energy 5e-3, the project's closure tolerances (README's
check table), about 10x and 20x above what a converged run at ``rtol = 1e-5`` gives;
drive 5e-3 as for energy.
"""

from __future__ import annotations

import math
import re
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from recipsim.errors import CaseError, RecipsimError

if TYPE_CHECKING:
    import pandas as pd

    from recipsim.results.run import CaseRun

OUTCOMES = ("converged", "not_converged", "refused", "failed")
EXPECTATIONS_FILE = "expectations.toml"

#: Default closure tolerances [-] (see the module docstring).
MASS_TOLERANCE = 1e-3
ENERGY_TOLERANCE = 5e-3
DRIVE_TOLERANCE = 5e-3

#: ``--fast`` settings applied before the case's own fast overrides and ``--set``.
FAST_OVERRIDES = ("solver.rtol=1e-5", "solver.samples_per_revolution=360")

#: Cycle metrics that an expectation may bound from below.
METRICS = ("suction_reed_openings", "discharge_reed_openings", "volumetric_efficiency")

#: The largest eccentricity ratio over the lubricated bearings of a run (``cycle_metrics``);
#: a converged run reaching 1 fails the check whatever its expectation says: a journal
#: never passes its sleeve (the film law and the asperity contact keep it inside).
ORBIT_METRIC = "largest_eccentricity_ratio"

# a reed is "closed" below this fraction of its stop height and "open" above the second
# (hysteresis, so that sampling noise near the seat is not counted as an opening)
_REED_CLOSED, _REED_OPEN = 0.02, 0.10

_CORE_FINITE = (
    "shaft_power [W]",
    "indicated_power [W]",
    "peak_cylinder_pressure [Pa]",
    "minimum_cylinder_pressure [Pa]",
    "mean_shaft_torque [N m]",
    "mean_crank_speed [rpm]",
    "cycle_residual [-]",
)
_GAS_FINITE = (
    "suction_mass_flow [kg/s]",
    "discharge_mass_flow [kg/s]",
    "leakage_mass_flow [kg/s]",
    "cooling_capacity [W]",
    "COP [-]",
    "volumetric_efficiency [-]",
    "isentropic_efficiency [-]",
    "discharge_temperature [K]",
    "mass_balance_residual [-]",
    "energy_balance_residual [-]",
)
_BEARING_PREFIXES = ("bearing_rms_", "bearing_max_", "orbit_radius_max_")


@dataclass(frozen=True)
class Expectation:
    """What a case is expected to do under ``recipsim check``.

    Attributes
    ----------
    expected : str
        One of :data:`OUTCOMES`.
    message : str
        Regular expression (case-insensitive search) that the message of a ``refused``
        or ``failed`` outcome must match; empty: any message.
    reason : str
        Why this is the expectation (documentation, copied to ``check.csv``).
    mass_tolerance, energy_tolerance, drive_tolerance : float
        Largest closures [-] accepted for a converged run.
    fast : tuple of str
        Extra ``KEY=VALUE`` overrides under ``--fast`` (after :data:`FAST_OVERRIDES`).
    minimum : mapping of str to float
        Lower bounds on cycle metrics (:data:`METRICS`) of a converged run.
    """

    expected: str = "converged"
    message: str = ""
    reason: str = ""
    mass_tolerance: float = MASS_TOLERANCE
    energy_tolerance: float = ENERGY_TOLERANCE
    drive_tolerance: float = DRIVE_TOLERANCE
    fast: tuple[str, ...] = FAST_OVERRIDES
    minimum: Mapping[str, float] = field(default_factory=dict)


@dataclass
class CheckRow:
    """One case's outcome under ``recipsim check`` (a row of ``check.csv``).

    Numbers are None where they do not apply (a refused case has no revolutions; a
    tabulated pressure has no mass closure).
    """

    case: str
    file: str
    expected: str
    outcome: str
    message: str = ""
    revolutions: int | None = None
    cycle_residual: float | None = None
    wall_time: float = 0.0  # load + simulate + tables [s]
    solve_time: float | None = None  # the periodic solution alone [s]
    steps: int | None = None
    mass_closure: float | None = None
    energy_closure: float | None = None
    drive_closure: float | None = None
    mass_balance_residual: float | None = None
    energy_balance_residual: float | None = None
    volumetric_efficiency: float | None = None
    non_finite: tuple[str, ...] = ()
    metrics: dict[str, float] = field(default_factory=dict)
    matches: bool = False
    note: str = ""
    reason: str = ""

    @property
    def finite(self) -> bool | None:
        """True when every checked result is finite (None: nothing ran)."""
        if self.outcome not in ("converged", "not_converged"):
            return None
        return not self.non_finite


# ------------------------------------------------------------------ case files


def find_cases(paths: Iterable[Path]) -> list[Path]:
    """Case files named by ``paths``: a directory gives its ``*.toml`` (sorted, without
    the expectations file), a file itself.

    Raises
    ------
    CaseError
        If a path does not exist or nothing is found.
    """
    files: list[Path] = []
    for path in map(Path, paths):
        if path.is_dir():
            files += sorted(p for p in path.glob("*.toml") if p.name != EXPECTATIONS_FILE)
        elif path.is_file():
            files.append(path)
        else:
            raise CaseError(str(path), "", "no such case file or directory")
    if not files:
        raise CaseError(", ".join(map(str, paths)), "", "no case files (*.toml) found")
    return files


_EXPECTATION_KEYS = {
    "expected",
    "message",
    "reason",
    "mass_tolerance",
    "energy_tolerance",
    "drive_tolerance",
    "fast",
    "minimum",
}


def _expectation(raw: Any, base: Expectation, file: str, key: str) -> Expectation:
    """Validate one table of the expectations file on top of ``base``."""
    from recipsim.case.schema import check_keys

    if not isinstance(raw, dict):
        raise CaseError(file, key, "expected a table")
    check_keys(raw, _EXPECTATION_KEYS, file, key)
    values: dict[str, Any] = {}
    for name, value in raw.items():
        where = f"{key}.{name}"
        if name == "expected":
            if value not in OUTCOMES:
                raise CaseError(file, where, f"{value!r} is not allowed; choose one of {OUTCOMES}")
        elif name in ("message", "reason"):
            if not isinstance(value, str):
                raise CaseError(file, where, "expected a string")
            if name == "message":
                try:
                    re.compile(value)
                except re.error as exc:
                    raise CaseError(file, where, f"not a regular expression: {exc}") from None
        elif name.endswith("_tolerance"):
            if isinstance(value, bool) or not isinstance(value, int | float) or value <= 0:
                raise CaseError(file, where, "expected a positive number, e.g. 1e-3")
            value = float(value)
        elif name == "fast":
            if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
                raise CaseError(file, where, 'expected a list of "KEY=VALUE" strings')
            value = base.fast + tuple(value)
        elif name == "minimum":
            if not isinstance(value, dict):
                raise CaseError(file, where, f"expected a table of metrics {METRICS}")
            check_keys(value, set(METRICS), file, where)
            value = {m: float(v) for m, v in value.items()}
        values[name] = value
    return replace(base, **values)


def load_expectations(path: Path) -> tuple[Expectation, dict[str, Expectation]]:
    """Read an expectations file: ``[defaults]`` and ``[cases.<case file stem>]`` tables.

    Returns
    -------
    default : Expectation
        For cases the file does not list.
    cases : dict
        Case file stem -> expectation.

    Raises
    ------
    CaseError
        Naming the file and key of anything invalid, including a ``[cases.<name>]``
        with no ``<name>.toml`` beside the file.
    """
    from recipsim.case.load import read_toml
    from recipsim.case.schema import check_keys

    raw, _ = read_toml(path, "expectations")
    file = str(path)
    check_keys(raw, {"defaults", "cases"}, file, "")
    default = _expectation(raw.get("defaults", {}), Expectation(), file, "defaults")
    cases: dict[str, Expectation] = {}
    table = raw.get("cases", {})
    if not isinstance(table, dict):
        raise CaseError(file, "cases", "expected a table of [cases.<case name>] tables")
    for name, value in table.items():
        if not (path.parent / f"{name}.toml").is_file():
            raise CaseError(file, f"cases.{name}", f"no case file {name}.toml beside this file")
        cases[name] = _expectation(value, default, file, f"cases.{name}")
    return default, cases


def expectations_for(
    files: Sequence[Path], expectations_file: Path | None = None
) -> list[Expectation]:
    """The expectation of each case file: from ``expectations_file`` if given, otherwise
    from the ``expectations.toml`` beside each case (default: converge, closed balances).
    """
    loaded: dict[Path, tuple[Expectation, dict[str, Expectation]]] = {}
    out = []
    for file in files:
        source = expectations_file or file.parent / EXPECTATIONS_FILE
        if source not in loaded:
            missing = expectations_file is None and not source.is_file()
            loaded[source] = (Expectation(), {}) if missing else load_expectations(source)
        default, cases = loaded[source]
        out.append(cases.get(file.stem, default))
    return out


# ------------------------------------------------------------------ measuring a run


def reed_openings(lift: np.ndarray, stop_height: float) -> int:
    """Number of separate openings of a reed over one periodic revolution.

    The reed counts as closed below 2 % of its stop height and as open again above
    10 % (hysteresis): a reed that flutters back onto (or to within 2 % of) its seat in
    mid-stroke and lifts off again opens twice.
    """
    lift = np.asarray(lift, dtype=float)
    if lift.size == 0 or not np.all(np.isfinite(lift)):
        return 0
    closed, opened = _REED_CLOSED * stop_height, _REED_OPEN * stop_height
    start = int(np.argmin(lift))  # start where the reed is most closed
    is_open = False
    count = 0
    for x in np.roll(lift, -start):
        if not is_open and x > opened:
            is_open = True
            count += 1
        elif is_open and x < closed:
            is_open = False
    return count


def closures(run: CaseRun) -> dict[str, float | None]:
    """Mass, energy and drive closures of a run (module docstring); None: not applicable."""
    from recipsim.physics.thermo import cylinder as cyl

    out: dict[str, float | None] = {"mass": None, "energy": None, "drive": None}
    sol = run.solution
    if sol is None:
        return out
    row = run.row
    p_shaft = float(row["shaft_power [W]"])
    p_ind = float(row["indicated_power [W]"])
    p_bearings = float(row.get("bearing_dissipation_power [W]", 0.0))
    out["drive"] = abs(p_shaft - p_ind - p_bearings) / abs(p_shaft) if p_shaft else math.nan
    model = sol.model
    if not model.has_gas:
        return out
    y = sol.final.y_end
    m_suc = y[cyl.Q_MSUC_IN] - y[cyl.Q_MSUC_OUT]
    m_dis = y[cyl.Q_MDIS_OUT] - y[cyl.Q_MDIS_IN]
    m_leak = y[cyl.Q_MLEAK_OUT] - y[cyl.Q_MLEAK_IN]
    h_out = (y[cyl.Q_HDIS_OUT] - y[cyl.Q_HDIS_IN]) + (y[cyl.Q_HLEAK_OUT] - y[cyl.Q_HLEAK_IN])
    h_in = y[cyl.Q_HSUC_IN] - y[cyl.Q_HSUC_OUT]
    suction = model.suction
    m_swept = suction.density * run.case.geometry.swept_volume
    h_2s = model.fluid.state_ps(run.case.operating_point.discharge_pressure, suction.entropy)["h"]
    out["mass"] = float(abs(m_suc - m_dis - m_leak) / m_swept)
    out["energy"] = float(
        abs(y[cyl.Q_WORK] - (h_out - h_in - y[cyl.Q_HEAT])) / (m_swept * (h_2s - suction.enthalpy))
    )
    return out


def non_finite_results(run: CaseRun) -> tuple[str, ...]:
    """Names of results that should be finite and are not (cycle columns and summary)."""
    row = run.row
    has_gas = run.solution is not None and run.solution.model.has_gas
    names = list(_CORE_FINITE) + [k for k in row if k.startswith(_BEARING_PREFIXES)]
    if has_gas:
        names += _GAS_FINITE
    bad = [k for k in names if k in row and not np.isfinite(float(row[k]))]
    numbers = run.cycle.select_dtypes("number")
    bad += [f"cycle:{c}" for c in numbers.columns if not np.all(np.isfinite(numbers[c]))]
    return tuple(bad)


def cycle_metrics(run: CaseRun) -> dict[str, float]:
    """Metrics of the converged revolution that expectations may bound (:data:`METRICS`)."""
    case = run.case
    out: dict[str, float] = {}
    ratios = [float(v) for k, v in run.row.items() if k.startswith("max_eccentricity_ratio_")]
    if ratios:
        out[ORBIT_METRIC] = max(ratios)
    if run.solution is None or not run.solution.model.has_gas:
        return out
    out["volumetric_efficiency"] = float(run.row["volumetric_efficiency [-]"])
    if case.options.valves == "reed":
        for side in ("suction", "discharge"):
            lift = run.cycle[f"{side}_valve_lift [m]"].to_numpy()
            stop = getattr(case.valves, side).stop_height
            out[f"{side}_reed_openings"] = float(reed_openings(lift, stop))
    return out


# ------------------------------------------------------------------ judging


def judge(row: CheckRow, expectation: Expectation) -> tuple[bool, str]:
    """Whether ``row``'s outcome meets ``expectation``, and why not.

    A converged or not-converged run must have finite results; a converged run
    expected to converge must also have its closures within tolerance (a closure that
    is NaN fails, None means not applicable) and its metrics at or above the minima;
    a refused or failed case must have a message matching the expected pattern.
    """
    notes = []
    if row.outcome != expectation.expected:
        notes.append(f"expected {expectation.expected.replace('_', ' ')}")
    elif row.outcome in ("refused", "failed") and expectation.message:
        if not re.search(expectation.message, row.message, re.IGNORECASE):
            notes.append(f"message does not match /{expectation.message}/")
    if row.non_finite:
        notes.append("non-finite results: " + ", ".join(row.non_finite[:4]))
    if row.outcome == "converged" and expectation.expected == "converged":
        for name, value, tol in (
            ("mass", row.mass_closure, expectation.mass_tolerance),
            ("energy", row.energy_closure, expectation.energy_tolerance),
            ("drive", row.drive_closure, expectation.drive_tolerance),
        ):
            if value is not None and not value <= tol:
                notes.append(f"{name} closure {value:.2g} > {tol:.2g}")
        for metric, minimum in expectation.minimum.items():
            value = row.metrics.get(metric)
            if value is None or not value >= minimum:
                notes.append(f"{metric} {value} < {minimum:g}")
    if row.outcome in ("converged", "not_converged"):
        ratio = row.metrics.get(ORBIT_METRIC)
        if ratio is not None and not ratio < 1.0:
            notes.append(f"a journal left its clearance (eccentricity ratio {ratio:.3g})")
    return not notes, "; ".join(notes)


# ------------------------------------------------------------------ running


def check_case(
    file: Path, expectation: Expectation, overrides: Sequence[str] = (), fast: bool = False
) -> CheckRow:
    """Run one case and judge it; never raises for a failing case (a failure is a row).

    Overrides are applied in this order: the case file, then (with ``fast``) the
    expectation's fast overrides, then ``overrides`` (``--set``).
    """
    from recipsim.case.load import load_case
    from recipsim.results.run import simulate_case

    file = Path(file)
    row = CheckRow(case=file.stem, file=str(file), expected=expectation.expected, outcome="failed")
    row.reason = expectation.reason
    applied = [*(expectation.fast if fast else ()), *overrides]
    start = time.perf_counter()
    try:
        case = load_case(file, applied)
        row.case = case.name
        _fill_run(row, simulate_case(case))
    except CaseError as exc:
        row.outcome, row.message = "refused", str(exc)
    except RecipsimError as exc:
        row.outcome, row.message = "failed", str(exc)
    except Exception as exc:  # a bug: reported as a row, the check goes on
        row.outcome, row.message = "failed", f"internal error {type(exc).__name__}: {exc}"
    row.wall_time = time.perf_counter() - start
    row.matches, row.note = judge(row, expectation)
    return row


def _fill_run(row: CheckRow, run: CaseRun) -> None:
    r = run.row
    row.outcome = "converged" if r["converged [-]"] else "not_converged"
    if r.get("status_message"):  # the diagnosis, or what no_delivery / subharmonic mean
        row.message = f"{r['status']}: {r['status_message']}"
    row.revolutions = int(r["revolutions [-]"])
    row.cycle_residual = float(r["cycle_residual [-]"])
    row.solve_time = float(r["wall_time [s]"])
    row.steps = int(r["steps [-]"])
    c = closures(run)
    row.mass_closure, row.energy_closure, row.drive_closure = c["mass"], c["energy"], c["drive"]
    for name in ("mass_balance_residual", "energy_balance_residual", "volumetric_efficiency"):
        value = r.get(f"{name} [-]")
        setattr(row, name, None if value is None else float(value))
    row.non_finite = non_finite_results(run)
    row.metrics = cycle_metrics(run)


def _check_job(args: tuple[Path, Expectation, tuple[str, ...], bool]) -> CheckRow:
    return check_case(*args)


def run_check(
    paths: Iterable[Path],
    overrides: Sequence[str] = (),
    fast: bool = False,
    jobs: int = 1,
    expectations_file: Path | None = None,
    progress: Callable[[CheckRow], None] | None = None,
) -> list[CheckRow]:
    """Check every case named by ``paths`` (files or directories), in file order.

    Parameters
    ----------
    paths : iterable of Path
        Case files or directories of case files.
    overrides : sequence of str
        ``KEY=VALUE`` applied to every case (after the fast settings).
    fast : bool
        Apply the fast settings (:data:`FAST_OVERRIDES` and the expectations' ``fast``).
    jobs : int
        Worker processes; 1 runs every case in this process, one after the other.
    expectations_file : Path, optional
        Instead of the ``expectations.toml`` beside the cases.
    progress : callable, optional
        Called with each row as it is finished.

    Raises
    ------
    CaseError
        For missing paths or an invalid expectations file (cases themselves never raise).
    """
    files = find_cases(paths)
    expectations = expectations_for(files, expectations_file)
    tasks = [(f, e, tuple(overrides), fast) for f, e in zip(files, expectations, strict=True)]
    rows: list[CheckRow] = []
    if jobs <= 1 or len(tasks) == 1:
        for task in tasks:
            rows.append(_check_job(task))
            if progress is not None:
                progress(rows[-1])
        return rows
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(max_workers=min(jobs, len(tasks))) as pool:
        for row in pool.map(_check_job, tasks):
            rows.append(row)
            if progress is not None:
                progress(row)
    return rows


# ------------------------------------------------------------------ tables

TABLE_COLUMNS = (
    ("case", "case"),
    ("expected", "expected"),
    ("outcome", "outcome"),
    ("ok", "match"),
    ("revs", "revolutions"),
    ("wall [s]", "wall_time"),
    ("solve [s]", "solve_time"),
    ("mass", "mass_closure"),
    ("energy", "energy_closure"),
    ("drive", "drive_closure"),
    ("message / note", "text"),
)


def _cell(row: CheckRow, attr: str, width: int = 70) -> str:
    if attr == "match":
        return "yes" if row.matches else "NO"
    if attr in ("expected", "outcome"):
        return str(getattr(row, attr)).replace("_", " ")
    if attr == "text":
        message = row.message.removeprefix(f"{row.file}: ")  # the case column names it
        text = f"{row.note} ({message})" if not row.matches and message else row.note or message
        return text if len(text) <= width else text[: width - 3] + "..."
    value = getattr(row, attr)
    if value is None:
        return "-"
    if attr == "revolutions":
        return str(value)
    if attr in ("wall_time", "solve_time"):
        return f"{value:.2f}"
    if isinstance(value, float):
        return "nan" if math.isnan(value) else f"{value:.1e}"
    return str(value)


def format_table(rows: Sequence[CheckRow], width: int = 70) -> str:
    """A fixed-width text table of ``rows`` (closures [-], wall time [s]) and a count."""
    header = [h for h, _ in TABLE_COLUMNS]
    cells = [[_cell(r, a, width) for _, a in TABLE_COLUMNS] for r in rows]
    widths = [max([len(h)] + [len(c[i]) for c in cells]) for i, h in enumerate(header)]

    def line(values: Sequence[str]) -> str:
        return "  ".join(v.ljust(w) for v, w in zip(values, widths, strict=True)).rstrip()

    lines = [line(header), line(["-" * w for w in widths])]
    lines += [line(c) for c in cells]
    n_ok = sum(r.matches for r in rows)
    lines.append(f"{n_ok} of {len(rows)} cases as expected")
    return "\n".join(lines)


def rows_frame(rows: Sequence[CheckRow]) -> pd.DataFrame:
    """``check.csv``'s table: one row per case, units in the column names."""
    import pandas as pd

    units = {
        "revolutions": "revolutions [-]",
        "cycle_residual": "cycle_residual [-]",
        "wall_time": "wall_time [s]",
        "solve_time": "solve_time [s]",
        "steps": "steps [-]",
        "mass_closure": "mass_closure [-]",
        "energy_closure": "energy_closure [-]",
        "drive_closure": "drive_closure [-]",
        "mass_balance_residual": "mass_balance_residual [-]",
        "energy_balance_residual": "energy_balance_residual [-]",
        "volumetric_efficiency": "volumetric_efficiency [-]",
    }
    records = []
    for row in rows:
        data = asdict(row)
        metrics = data.pop("metrics")
        data["non_finite"] = " ".join(data["non_finite"])
        data["finite"] = row.finite
        record = {units.get(k, k): v for k, v in data.items()}
        for metric in (*METRICS, ORBIT_METRIC):
            if metric not in units:  # volumetric efficiency has its column already
                record[f"{metric} [-]"] = metrics.get(metric)
        records.append(record)
    return pd.DataFrame.from_records(records)


def write_check_csv(rows: Sequence[CheckRow], out: Path) -> Path:
    """Write ``out/check.csv`` atomically; returns its path."""
    from recipsim.atomic import atomic_write

    path = Path(out) / "check.csv"
    frame = rows_frame(rows)
    atomic_write(path, lambda tmp: frame.to_csv(tmp, index=False))
    return path
