"""Write a rating: its tables (pandas), figures and provenance, each file atomically, into
the rating's directory beside its ``points/`` sweep.

Files: ``ratings.csv`` (one row per grid point), ``rating_table.csv`` (each quantity as
makers print it: a row per condensing temperature, a column per evaporating
temperature), ``coefficients.csv``, ``residuals.csv``, ``catalogue.csv`` and
``maker.csv`` (with ``--catalogue`` / ``--coefficients``), ``ratings.png`` (capacity and
power input against evaporating temperature), ``envelope.png`` (the grid, failed points
marked) and ``rating.json`` (the standard, the grid, the notes, the wall time).
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import TYPE_CHECKING

import pandas as pd

from recipsim.atomic import atomic_file, atomic_write
from recipsim.report.case_report import json_text
from recipsim.report.plotting import PNG_OPTIONS
from recipsim.results.provenance import git_commit
from recipsim.studies.rate.figures import envelope_figure, rating_figure
from recipsim.studies.rate.run import Rating
from recipsim.studies.rate.tables import rating_table
from recipsim.version import __version__

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def _tables(rating: Rating) -> dict[str, pd.DataFrame]:
    tables = {
        "ratings.csv": rating.ratings,
        "rating_table.csv": rating_table(rating.ratings, rating.grid),
        "coefficients.csv": rating.coefficients,
        "residuals.csv": rating.residuals,
    }
    if rating.catalogue is not None:
        tables["catalogue.csv"] = rating.catalogue
    if rating.maker is not None:
        tables["maker.csv"] = rating.maker
    return tables


def write_rating(rating: Rating, plots: bool = True, argv: list[str] | None = None) -> list[Path]:
    """Write the rating's files into ``rating.directory``; the files written."""
    root = rating.directory
    written = []
    for name, table in _tables(rating).items():

        def write_table(path: Path, table: pd.DataFrame = table) -> None:
            table.to_csv(path, index=False)

        atomic_write(root / name, write_table)
        written.append(root / name)
    if plots:
        title = rating.case.name
        figures = {
            "ratings.png": rating_figure(
                rating.ratings,
                rating.grid,
                rating.polynomials,
                rating.makers,
                rating.catalogue,
                title,
            ),
            "envelope.png": envelope_figure(rating.ratings, rating.grid, rating.polynomials, title),
        }
        for name, fig in figures.items():

            def save(path: Path, fig: Figure = fig) -> None:
                fig.savefig(path, dpi=110, format="png", pil_kwargs=PNG_OPTIONS)

            atomic_write(root / name, save)
            written.append(root / name)
    meta = {
        "recipsim": __version__,
        "git_commit": git_commit(),
        "case": rating.case.path,
        "overrides": list(rating.case.overrides),
        "standard": rating.grid.standard,
        "temperature_unit": rating.grid.temperature_unit,
        "application": rating.grid.application,
        "evaporating": list(rating.grid.evaporating),
        "condensing": list(rating.grid.condensing),
        "points": len(rating.ratings),
        "status_counts": rating.ratings["status"].value_counts().to_dict(),
        "notes": rating.notes,
        **rating.options,
        "jobs": rating.sweep.jobs,
        "scheduler": rating.sweep.scheduler,
        "wall_time_s": rating.wall_time,
        "created": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
        "command": argv or [],
    }
    with atomic_file(root / "rating.json") as handle:
        handle.write(json_text(meta))
    written.append(root / "rating.json")
    return written
