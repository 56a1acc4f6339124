"""A rating from end to end: plan the grid (and the catalogue's points), run them as one
sweep (parallel, resumable, each failed point a row), fit the ten coefficients of every
quantity on the good points, compare with a catalogue and a maker's coefficients, and
return everything as a :class:`Rating` (:mod:`.report` writes it).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from recipsim.atomic import mark_output
from recipsim.case.case import Case
from recipsim.errors import CaseError
from recipsim.report.figure_kit import new_figure
from recipsim.studies.calibrate.data import MeasuredPoint
from recipsim.studies.rate.coefficients import Polynomial, read_coefficients
from recipsim.studies.rate.compare import (
    catalogue_note,
    catalogue_table,
    maker_table,
    read_catalogue,
)
from recipsim.studies.rate.figures import envelope_figure, plot_quantity
from recipsim.studies.rate.grid import RatingGrid, rating_grid
from recipsim.studies.rate.polynomial import PolynomialFit, RatingError
from recipsim.studies.rate.tables import (
    GRID_TOLERANCE,
    Sources,
    add_fit_columns,
    coefficients_table,
    fit_quantities,
    fitted_polynomials,
    quantity_sources,
    rating_table,
    ratings_table,
    residuals_table,
)
from recipsim.studies.sweep.engine import run_sweep
from recipsim.studies.sweep.outputs import SweepOutcome
from recipsim.studies.sweep.spec import Assignment, case_sweep_spec

#: Name of the rating's sweep (its points' folder inside the rating's directory).
SWEEP_NAME = "points"


@dataclass
class Rating:
    """A compressor rated the makers' way.

    Attributes
    ----------
    case : Case
        The case rated.
    grid : RatingGrid
        The standard and the evaporating and condensing temperatures run.
    ratings : pandas.DataFrame
        ``ratings.csv``: one row per grid point, the standard's quantities in the makers'
        units, its status and message, the polynomial and its relative residual.
    coefficients : pandas.DataFrame
        ``coefficients.csv``: C1 .. C10 of every quantity, its range of validity and source.
    residuals : pandas.DataFrame
        ``residuals.csv``: largest and RMS residual per quantity, absolute and relative.
    polynomials : dict of str to Polynomial
        The fitted polynomials (evaluate with ``.si(evaporating_K, condensing_K)``).
    catalogue, maker : pandas.DataFrame or None
        Model and polynomial against a catalogue's points; model against a maker's
        coefficients at the grid points.
    makers : dict of str to Polynomial
        The maker's polynomials, if a coefficient file was given.
    notes : list of str
        What the reader must know: quantities left out, fits beyond 1 %, failed points.
    sweep : SweepOutcome
        The sweep that ran the points.
    directory : Path
        Where the rating is written.
    wall_time : float
        Seconds from the start to the tables [s].
    """

    case: Case
    grid: RatingGrid
    ratings: pd.DataFrame
    coefficients: pd.DataFrame
    residuals: pd.DataFrame
    polynomials: dict[str, Polynomial]
    catalogue: pd.DataFrame | None
    maker: pd.DataFrame | None
    makers: dict[str, Polynomial]
    notes: list[str]
    sweep: SweepOutcome
    directory: Path
    wall_time: float
    options: dict[str, Any] = field(default_factory=dict)

    @property
    def table(self) -> pd.DataFrame:
        """``rating_table.csv``: each quantity as makers print it, a row per condensing
        temperature and a column per evaporating temperature."""
        return rating_table(self.ratings, self.grid)

    def plot(self, quantity: str = "cooling_capacity", ax: Any = None) -> Any:
        """``quantity`` against evaporating temperature, a line per condensing
        temperature (model points, polynomial, catalogue and maker where given), drawn
        into ``ax`` (or a new figure's); returns the Axes."""
        if ax is None:
            ax = new_figure(figsize=(6.0, 4.4), layout="constrained").add_subplot()
        plot_quantity(ax, quantity, self.ratings, self.grid, self.polynomials, self.makers,
                      self.catalogue)  # fmt: skip
        ax.legend(title="condensing", fontsize="small")
        return ax

    def plot_envelope(self) -> Any:
        """The grid, the failed points marked, and the polynomial's range; the Axes."""
        return envelope_figure(self.ratings, self.grid, self.polynomials, self.case.name).axes[0]

    def evaluate(self, quantity: str, evaporating: Any, condensing: Any) -> np.ndarray:
        """The fitted polynomial of ``quantity`` in SI at dew points [K] (nan outside its
        range of validity)."""
        return self.polynomials[quantity].si(
            np.asarray(evaporating, dtype=float), np.asarray(condensing, dtype=float)
        )


def check_grid_point(case: Case, grid: RatingGrid) -> None:
    """Build the first grid point's case, so that a case the standard contradicts
    (explicit suction-gas or liquid keys, a suction pressure) is refused before any point
    runs, with the case loader's message naming the key."""
    first = grid.overrides()
    if not first:
        raise CaseError("--condensing", "", "no grid point has condensing above evaporating")
    case.with_(dict(first[0]))


def rate_case(
    case: Case,
    directory: str | Path,
    *,
    standard: str | None = None,
    evaporating: Any = None,
    condensing: Any = None,
    application: str | None = None,
    catalogue: str | Path | None = None,
    coefficients: str | Path | None = None,
    sweep_options: dict[str, Any] | None = None,
) -> Rating:
    """Rate ``case`` over a grid at a standard's conditions (``recipsim rate``).

    Parameters
    ----------
    case : Case
        The compressor.
    directory : str or Path
        The rating's directory: its points are kept in ``<directory>/points/`` (a rerun
        resumes) and :func:`.report.write_rating` writes the tables there.
    standard, evaporating, condensing, application
        See :func:`.grid.rating_grid`.
    catalogue : str or Path, optional
        A catalogue file to run and compare with (:mod:`.compare`).
    coefficients : str or Path, optional
        A maker's coefficient file to compare with (:mod:`.coefficients`).
    sweep_options : dict, optional
        Passed to :func:`recipsim.studies.sweep.engine.run_sweep`: ``jobs``,
        ``scheduler``, ``progress``, ``fresh``, ``retry_failed``, ``argv``...

    Raises
    ------
    CaseError
        A bad option or file, a case the standard contradicts.
    RatingError
        Fewer than ten good points for capacity or power input.
    """
    start = time.perf_counter()
    grid = rating_grid(case, standard, evaporating, condensing, application)
    check_grid_point(case, grid)
    makers = read_coefficients(coefficients) if coefficients is not None else {}
    measured = read_catalogue(catalogue) if catalogue is not None else []
    root = Path(directory)
    mark_output(root)
    outcome = _run_points(case, grid, measured, root, sweep_options or {})
    n_grid = len(grid.points())
    rows = outcome.table.iloc[:n_grid].reset_index(drop=True)
    sources = quantity_sources(case)
    ratings, si = ratings_table(case, grid, rows, sources)
    fits = _fits(grid, ratings, si, sources, root)
    add_fit_columns(ratings, grid, fits, si)
    table = coefficients_table(grid, fits, si, sources)
    polynomials = fitted_polynomials(grid, table)
    compared = None
    notes = _notes(grid, ratings, fits, sources.notes)
    if measured:
        extra = outcome.table.iloc[n_grid:].reset_index(drop=True)
        compared = catalogue_table(measured, extra, grid, polynomials)
        notes.append(catalogue_note(compared))
    return Rating(
        case=case,
        grid=grid,
        ratings=ratings,
        coefficients=table,
        residuals=residuals_table(grid, fits),
        polynomials=polynomials,
        catalogue=compared,
        maker=maker_table(makers, grid, si) if makers else None,
        makers=makers,
        notes=notes,
        sweep=outcome,
        directory=root,
        wall_time=time.perf_counter() - start,
        options={"catalogue": str(catalogue or ""), "coefficients": str(coefficients or "")},
    )


def _fits(
    grid: RatingGrid,
    ratings: pd.DataFrame,
    si: dict[str, np.ndarray],
    sources: Sources,
    root: Path,
) -> dict[str, PolynomialFit | str]:
    """:func:`.tables.fit_quantities`; a refusal says how the grid's points ended."""
    try:
        return fit_quantities(grid, si, sources)
    except RatingError as exc:
        counts = ", ".join(f"{n} {s}" for s, n in ratings["status"].value_counts().items())
        where = root / SWEEP_NAME / "summary.csv"
        raise RatingError(f"{exc}; the grid's {len(ratings)} points: {counts} ({where})") from None


def _run_points(
    case: Case,
    grid: RatingGrid,
    measured: list[MeasuredPoint],
    root: Path,
    options: dict[str, Any],
) -> SweepOutcome:
    """The grid's points, then the catalogue's, as one sweep into ``root/points``."""
    points: list[Assignment] = list(grid.overrides())
    points += [tuple(p.overrides.items()) for p in measured]
    spec = case_sweep_spec(
        case,
        SWEEP_NAME,
        points=tuple(points),
        description=f"rating of {case.name} ({grid.standard})",
    )
    options = {"plots": False, **options, "allow_external_paths": case.allow_external_paths}
    return run_sweep(spec, out=root, **options)


def _notes(
    grid: RatingGrid,
    ratings: pd.DataFrame,
    fits: dict[str, PolynomialFit | str],
    sources: dict[str, str],
) -> list[str]:
    """The lines a reader must see: failed points, fits beyond 1 %, quantities left out."""
    notes = [f"power input: {sources['power_input']}"]
    unit = grid.temperature_unit
    evap, cond = f"evaporating_temperature [{unit}]", f"condensing_temperature [{unit}]"
    failed = ratings[ratings["status"] != "ok"]
    if len(failed):
        listed = ", ".join(
            f"{row[evap]:g}/{row[cond]:g} {unit} {row['status']}" for _, row in failed.iterrows()
        )
        notes.append(
            f"{len(failed)} of {len(ratings)} points failed and are left out of the fit: {listed}"
        )
    for quantity, result in fits.items():
        if not isinstance(result, PolynomialFit):
            notes.append(f"{quantity}: {result}")
        elif quantity in ("cooling_capacity", "power_input") and result.max_rel > GRID_TOLERANCE:
            worst = int(np.argmax(np.abs(result.relative)))
            good = ratings[ratings[f"{quantity}_residual [-]"].notna()].iloc[worst]
            notes.append(
                f"{quantity}: the polynomial misses its own grid by up to "
                f"{result.max_rel:.2%} (at {good[evap]:g}/{good[cond]:g} {unit}), more than "
                f"{GRID_TOLERANCE:.0%}"
            )
    return notes
