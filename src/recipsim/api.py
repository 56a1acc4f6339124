"""The public API: load a case, change it, simulate it, look at and write the result.

>>> import recipsim
>>> case = recipsim.load_case("reference_r134a_lbp", {"operating_point.standard": "EN12900"})
>>> result = recipsim.simulate(case.with_(solver__rtol=1e-7))
>>> result.summary["COP [-]"]                                   # doctest: +SKIP
>>> ax = result.plot_pv()                                       # doctest: +SKIP
>>> result.write("reports/my_run")                              # doctest: +SKIP

Everything the ``recipsim run`` command does goes through these functions. Plot methods
draw into the Axes they are given (or a new figure's) and return the Axes; no backend
is ever chosen.

Size (over the project's 400 lines): the whole public API in one module, a function per
study (simulate, compare, sweep, calibrate, rate), each a thin layer over its study.
"""

from __future__ import annotations

import tempfile
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pandas as pd

from recipsim.case.case import Case
from recipsim.case.load import load_case as _load_case
from recipsim.case.shipped import KIND_FOLDERS, shipped_cases_table
from recipsim.errors import CaseError
from recipsim.pipeline import simulate_case
from recipsim.progress import notes_shown
from recipsim.report.case_report import report_dir, write_case_report
from recipsim.report.loss_plot import plot_loss_breakdown
from recipsim.report.mechanics_plots import film_bearings, plot_bearing_loads, plot_orbits
from recipsim.report.plotting import plot_pressure, plot_pv, plot_torque, plot_valves
from recipsim.report.startup_plot import plot_startup
from recipsim.report.summary_text import summary_markdown, summary_text
from recipsim.results.case_run import CaseRun
from recipsim.results.startup import startup_table
from recipsim.solve.periodic import PeriodicSolution
from recipsim.studies.calibrate.family import Member
from recipsim.studies.calibrate.report import write_calibration
from recipsim.studies.calibrate.run import calibrate_case
from recipsim.studies.compare import case_labels, comparison_table
from recipsim.studies.rate.coefficients import read_coefficients
from recipsim.studies.rate.grid import standard_of
from recipsim.studies.rate.report import write_rating
from recipsim.studies.rate.run import Rating, rate_case
from recipsim.studies.sweep.engine import run_sweep
from recipsim.studies.sweep.spec import DEFAULT_MAX_POINTS, case_sweep_spec, checked_axes

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = ["Case", "Member", "Rating", "Result", "calibrate", "cases", "compare", "load_case"]
__all__ += ["rate", "read_coefficients", "simulate", "sweep"]


@dataclass(frozen=True)
class Result:
    """A simulated case.

    Attributes
    ----------
    case : Case
        The case as simulated.
    summary : pandas.Series
        One value per quantity, the unit in the name (``"COP [-]"``,
        ``"cooling_capacity [W]"``); the row of the report's ``summary.csv``.
    cycle : pandas.DataFrame
        The converged revolution, one row per crank-angle sample (``cycle.csv``).
    provenance : dict
        Versions, options, solver settings and statistics.
    converged : bool
        Whether the periodic steady state was reached within the case's tolerance.
    solution : PeriodicSolution or None
        The solver's result (None for the pinned crank under a tabulated pressure,
        which is inverse dynamics only).
    """

    case: Case
    summary: pd.Series
    cycle: pd.DataFrame
    provenance: dict[str, Any]
    converged: bool
    solution: PeriodicSolution | None
    _run: CaseRun

    # ---- plots: each draws into ``ax`` (or a new figure) and returns the Axes --------
    def plot_pv(self, ax: Axes | None = None, log: bool = False) -> Axes:
        """Indicator diagram, cylinder pressure against volume (log-log with ``log``)."""
        return _first_axes(plot_pv(self.cycle, ax=ax, log=log, label=self.case.name), ax)

    def plot_pressure(self, ax: Axes | None = None) -> Axes:
        """Cylinder pressure against crank angle, with the suction and discharge lines."""
        op = self.case.operating_point
        plenum = (op.suction_pressure, op.discharge_pressure)
        return _first_axes(plot_pressure(self.cycle, ax=ax, plenum=plenum), ax)

    def plot_torque(self, ax: Axes | None = None) -> Axes:
        """Driving torque with its gas and inertia parts against crank angle."""
        return _first_axes(plot_torque(self.cycle, ax=ax), ax)

    def plot_valves(self, ax: Axes | None = None) -> Axes:
        """Reed lifts and valve mass flows against crank angle (cylinder scenes)."""
        return _first_axes(plot_valves(self.cycle, ax=ax), ax)

    def plot_bearing_loads(self) -> Any:
        """Force magnitude of every bearing against crank angle; returns the figure's
        array of Axes (one per bearing)."""
        return plot_bearing_loads({self.case.name: self.cycle}).axes

    def plot_orbits(self) -> Any:
        """Journal orbits (flexible mechanics): the bearings on oil films inside their
        clearance circles, else the primary and secondary; returns the figure's Axes."""
        bearings = film_bearings(self.cycle) or ("primary", "secondary")
        return plot_orbits({self.case.name: self.cycle}, bearings=bearings).axes

    def plot_losses(self, ax: Axes | None = None) -> Axes:
        """Where the electrical power goes: the loss chain as a waterfall, from the
        electrical input to the isentropic power of the delivered gas."""
        return _first_axes(plot_loss_breakdown(self.summary, ax=ax, title=self.case.name), ax)

    @property
    def startup(self) -> pd.DataFrame | None:
        """The start-up from rest against time (``startup.csv``: time [s], crank angle,
        speed, motor torque, cylinder and plenum pressures, bearing loads), or None when
        the case does not start from rest (``solver.start = "periodic"``)."""
        if self._run.startup is None:
            return None

        return startup_table(self._run.startup)

    def plot_startup(self) -> Any:
        """Speed, motor torque, pressures and bearing loads against time from standstill
        (a run with ``solver.start = "rest"``); returns the figure's array of Axes."""
        table = self.startup
        if table is None:
            raise ValueError(f"{self.case.name} was not run from rest (solver.start)")
        return plot_startup(table, title=self.case.name).axes

    # ---- report -------------------------------------------------------------------------
    def summary_text(self) -> str:
        """The key figures for a person, in W, bar, C, kg/h and rpm, as the console
        shows them after ``recipsim run`` (a notebook shows them as a table)."""
        return summary_text(self._run.row)

    def _repr_markdown_(self) -> str:
        return summary_markdown(self._run.row, title=False)

    def write(self, directory: str | Path, plots: bool = True) -> Path:
        """Write the report (``summary.csv``, ``cycle.csv``, figures, ``case.toml``,
        ``provenance.json``) into ``directory``, atomically; a directory that recipsim
        did not write is refused (:class:`~recipsim.errors.CaseError`)."""
        return write_case_report(self._run, Path(directory), list(self.case.overrides), plots)


def _first_axes(fig: Any, ax: Axes | None) -> Axes:
    return ax if ax is not None else fig.axes[0]


def load_case(
    path: str | Path,
    overrides: Mapping[str, Any] | Sequence[str] | None = None,
    *,
    allow_external_paths: bool = False,
    progress: bool = True,
) -> Case:
    """Read, override and validate a case file.

    Parameters
    ----------
    path : str or Path
        The TOML case file, or the name of a case (``"reference_r134a_lbp"``): the
        working directory's ``cases/<name>.toml``, else the shipped case of that name.
    overrides : mapping or list of str, optional
        Dotted case keys to values (``{"operating_point.shaft_speed": "3000 rpm"}``), or
        ``KEY=VALUE`` strings as on the command line (``--set``); validated exactly like
        the file.
    allow_external_paths : bool
        Let ``extends`` and ``pressure_curve.file`` name files outside the case file's
        directory (absolute paths, ``..``).
    progress : bool
        Say on standard error what takes seconds the first time (a property table built,
        code compiled: ``recipsim: ...`` lines, through :mod:`logging`, each with the
        time it took last time on this machine); False keeps them off. A program that
        configures :mod:`logging` itself decides instead.

    Returns
    -------
    Case

    Raises
    ------
    CaseError
        With the file, the key and what is allowed.
    """
    with notes_shown(progress):
        return _load_case(path, overrides, allow_external_paths=allow_external_paths)


def simulate(case: Case, *, progress: bool = True) -> Result:
    """Solve ``case`` to its periodic steady state.

    Parameters
    ----------
    case : Case
        From :func:`load_case` (and :meth:`Case.with_`).
    progress : bool
        Say on standard error what takes seconds the first time (a property table built,
        code compiled: ``recipsim: ...`` lines, through :mod:`logging`, each with the
        time it took last time on this machine); False keeps them off. A program that
        configures :mod:`logging` itself decides instead.

    Returns
    -------
    Result

    Raises
    ------
    SolverError
        Naming the crank angle and the state where the integration failed.
    """
    _check_case(case, "simulate", "case")
    with notes_shown(progress):
        run = simulate_case(case)
    return Result(
        case=case,
        summary=pd.Series(run.row, name=case.name),
        cycle=run.cycle,
        provenance=run.meta,
        converged=bool(run.row.get("converged [-]", True)),
        solution=run.solution,
        _run=run,
    )


def compare(a: Case | Result, b: Case | Result, *, progress: bool = True) -> pd.DataFrame:
    """Compare two cases (simulated here if they are not results yet; ``progress`` as
    in :func:`simulate`).

    Returns
    -------
    pandas.DataFrame
        The table of ``recipsim compare``'s ``comparison.csv``: one row per summary
        quantity and per bearing's RMS, peak and orbit; a column per case (named after
        it, suffixed ``_a``/``_b`` when the names are equal); ``difference`` (B - A) and
        ``relative_difference [-]``.
    """
    results = [r if isinstance(r, Result) else simulate(r, progress=progress) for r in (a, b)]
    labels = case_labels(results[0].case.name, results[1].case.name)
    return comparison_table(results[0]._run.row, results[1]._run.row, *labels)


def sweep(
    case: Case,
    axes: Mapping[str, Sequence[Any]],
    *,
    jobs: int | None = 1,
    scheduler: str | None = None,
    directory: str | Path | None = None,
    name: str | None = None,
    plots: bool = False,
    max_points: int | None = None,
    progress: bool = True,
) -> pd.DataFrame:
    """Run ``case`` over a grid of case values: the engine of ``recipsim sweep``.

    Parameters
    ----------
    case : Case
        The base case (its file and the overrides it carries).
    axes : mapping of str to sequence
        Dotted case key to its values, combined as a grid, the first key slowest:
        ``{"operating_point.evaporating_temperature": ["-30 degC", "-20 degC"]}``.
    jobs : int, optional
        Worker processes (``None``: every CPU; 1: this process). Ignored with ``scheduler``.
    scheduler : str, optional
        Address of a Dask distributed scheduler.
    directory : str or Path, optional
        Parent of the sweep's output directory ``<directory>/<name>``; the sweep
        resumes from the points already there. Default: a temporary directory (not
        kept).
    name : str, optional
        Sweep name (default ``<case name>_sweep``).
    plots : bool
        Draw the map plots.
    max_points : int, optional
        Refuse larger grids (default 100 000).
    progress : bool
        Show a progress bar (``tqdm.auto``: a widget in a notebook with ipywidgets, else
        a text bar on standard error, in a notebook or a terminal; nothing when standard
        error is a file) and the notes of :func:`simulate`; False: neither.

    Returns
    -------
    pandas.DataFrame
        One row per point: the axes (SI), ``status``, ``message`` and the summary.

    Raises
    ------
    CaseError
        An unknown key or a grid over the limit, before anything runs.
    """
    _check_case(case, "sweep", "case")
    grid = checked_axes(axes)
    if jobs is not None and (isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1):
        raise CaseError("recipsim.sweep", "jobs", f"{jobs!r}: a whole number >= 1, or None")
    sweep_name = name or f"{case.name}_sweep"
    limit = DEFAULT_MAX_POINTS if max_points is None else max_points
    spec = case_sweep_spec(case, sweep_name, grid, max_points=limit)
    options: dict[str, Any] = {
        "jobs": jobs,
        "scheduler": scheduler,
        "plots": plots,
        "allow_external_paths": case.allow_external_paths,
        "progress": progress,
    }
    with notes_shown(progress), tempfile.TemporaryDirectory(prefix="recipsim-sweep-") as tmp:
        return run_sweep(spec, out=Path(directory or tmp), **options).table


def calibrate(
    case: Case,
    data: str | Path,
    parameters: Sequence[str],
    *,
    points: Sequence[int] | None = None,
    targets: Sequence[str] | None = None,
    directory: str | Path | None = None,
    members: Sequence[str | Member] = (),
    progress: bool = True,
) -> Any:
    """Fit uncertain parameters of ``case`` to measured points: ``recipsim calibrate``
    (of one compressor, or of several of a family at once with ``members``; ``progress``
    as in :func:`simulate`).

    Parameters
    ----------
    case : Case
        The case to calibrate.
    data : str or Path
        CSV of measured points: inputs ``<key> [<unit>]`` (operating-point keys, or any
        dotted key), an optional ``standard``, and the targets (docs/calibration.md); or
        a shipped catalogue's file name (``"danfoss_tles5.7kk.3_r600a.csv"``).
    parameters : sequence of str
        ``KEY=LOWER:UPPER`` (bounds bare in SI or with units), or ``KEY`` for a tenth to
        ten times the case's value.
    points : sequence of int, optional
        Data rows (1-based) to fit on; the others are predicted. Default: all.
    targets : sequence of str, optional
        Target columns; default ``cooling_capacity [W]`` and ``COP [-]``.
    directory : str or Path, optional
        Write the result there (replaced whole): ``parameters.csv``, ``points.csv``,
        ``volumetric.csv`` (where the capacity is a target), ``calibration.json``, the
        calibrated ``case.toml``.
    members : sequence of str or Member
        The family's other compressors, fitted with ``case`` (shared parameters, one fit):
        ``Member(data, bore="26.49 mm")`` (``case`` with another bore), ``Member(data,
        case="other")`` or ``"DATA:bore=26.49mm"``; ``points`` applies unless it has own.

    Returns
    -------
    Calibration
        ``.calibrated`` (the case with the fitted values), ``.parameters`` (fitted
        values, 95 % intervals, plausible ranges, verdicts), ``.points`` (member,
        measured, predicted and error per point) and ``.volumetric`` (each member's
        effective dead volume and other losses, catalogue and model:
        ``docs/calibration.md``) as DataFrames.

    Raises
    ------
    CalibrationError
        An ill-posed fit: more parameters than measured values, a parameter without
        influence, or parameters whose effects cannot be told apart.
    """
    _check_case(case, "calibrate", "case")
    with notes_shown(progress):
        result = calibrate_case(case, data, parameters, points, targets, members=members)
    if directory is not None:
        write_calibration(result, directory)
    return result


def rate(
    case: Case,
    *,
    standard: str | None = None,
    evaporating: Any = None,
    condensing: Any = None,
    catalogue: str | Path | None = None,
    coefficients: str | Path | None = None,
    jobs: int | None = 1,
    scheduler: str | None = None,
    directory: str | Path | None = None,
    progress: bool = True,
) -> Rating:
    """Rate ``case`` as its maker does: ``recipsim rate`` (docs: rating).

    Parameters
    ----------
    case : Case
        The compressor.
    standard : {"EN12900", "AHRI_540", "ASHRAE_LBP"}, optional
        Default: the case's own (or its rating point's), else EN12900; S, D in degC or degF.
    evaporating, condensing : str or sequence of float, optional
        Grid axes in the standard's unit, ``"-35:-10:5"`` or ``[-35, -30, ...]``;
        default: the standard's grid for the case's application.
    catalogue, coefficients : str or Path, optional
        A catalogue CSV to run and compare with; a maker's coefficient CSV to compare with.
    jobs, scheduler : int or None; str, optional
        Worker processes (1: this process; None: every CPU); a Dask scheduler.
    directory, progress : str or Path, optional; bool
        Parent of ``<case>_<standard>/``, where the points are kept (a rerun resumes) and
        the files written (default: a temporary directory, not kept); a progress bar.

    Returns
    -------
    Rating
        ``.ratings``, ``.table``, ``.coefficients``, ``.residuals``, ``.catalogue``,
        ``.maker`` (DataFrames), ``.notes``; ``.evaluate(quantity, t_evap_K, t_cond_K)``,
        ``.plot(quantity)``, ``.plot_envelope()``.

    Raises
    ------
    RatingError
        Fewer than ten good points for capacity or power input (the message says why).
    """
    _check_case(case, "rate", "case")
    name = standard_of(case, standard)
    args = {"standard": name, "evaporating": evaporating, "condensing": condensing}
    args |= {"catalogue": catalogue, "coefficients": coefficients}
    args["sweep_options"] = {"jobs": jobs, "scheduler": scheduler, "progress": progress}
    with notes_shown(progress):
        if directory is None:
            with tempfile.TemporaryDirectory(prefix="recipsim-rate-") as tmp:
                return rate_case(case, Path(tmp) / "rating", **args)
        where = report_dir(Path(directory), f"{case.name}_{name}", case.overrides)
        write_rating(rating := rate_case(case, where, **args))
        return rating


def _check_case(case: Any, function: str, argument: str) -> None:
    """Refuse anything but a :class:`Case` where one is due, naming the argument."""
    if not isinstance(case, Case):
        raise CaseError(
            f"recipsim.{function}",
            argument,
            f"expected a Case (from recipsim.load_case), got {type(case).__name__} {case!r:.60}",
        )


def cases(kind: str | None = None) -> pd.DataFrame:
    """The shipped cases, sweeps and hard cases, as ``recipsim cases`` lists them.

    Parameters
    ----------
    kind : {"case", "sweep", "hard case"}, optional
        Only the files of this kind; default all.

    Returns
    -------
    pandas.DataFrame
        One row per file: ``name`` (what :func:`load_case` and :func:`sweep` take),
        ``kind``, ``description`` (one line) and ``path``.

    Raises
    ------
    ValueError
        An unknown ``kind``.
    """
    return shipped_cases_table((kind,) if kind else tuple(KIND_FOLDERS))
