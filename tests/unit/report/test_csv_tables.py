"""A report's tables written without pandas are the bytes pandas' ``to_csv`` writes: the
cycle tables and summary rows of every kind of scene (rigid crank, flexible crank
coupled, on oil films, under a tabulated pressure) and the edge values of each column
type; and a report written from a run's columns never imports pandas (its report
processes would pay 0.3 s of CPU for it)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from helpers import CASES, REFERENCE
from recipsim.report.csv_tables import (
    record_column,
    write_columns_csv,
    write_records_csv,
    write_row_csv,
)


@pytest.fixture(scope="module", params=["rigid", "coupled", "lubricated", "tabulated"])
def run(request):
    from recipsim.case.load import load_case
    from recipsim.results.run import simulate_case

    path = {
        "rigid": REFERENCE,
        "coupled": CASES / "reference_r134a_lbp_coupled.toml",
        "lubricated": CASES / "reference_r134a_lbp_lubricated.toml",
        "tabulated": CASES / "paper_tabulated.toml",
    }[request.param]
    return simulate_case(load_case(path), [])


def test_a_runs_tables_are_the_bytes_pandas_writes(run, tmp_path: Path) -> None:
    table = run.table
    columns = table if isinstance(table, dict) else {c: table[c].to_numpy() for c in table.columns}
    write_columns_csv(tmp_path / "ours.csv", columns)
    pd.DataFrame(columns).to_csv(tmp_path / "pandas.csv", index=False)
    assert (tmp_path / "ours.csv").read_bytes() == (tmp_path / "pandas.csv").read_bytes()
    write_row_csv(tmp_path / "row.csv", run.row)
    pd.DataFrame([dict(run.row)]).to_csv(tmp_path / "pandas_row.csv", index=False)
    assert (tmp_path / "row.csv").read_bytes() == (tmp_path / "pandas_row.csv").read_bytes()


EDGE_COLUMNS = {
    "float": [0.1, -0.0, np.inf, -np.inf, np.nan, 1e16, 1e-5, 1.2345678901234568e17, 5e-324, 2.5],
    "float32": np.array(
        [0.1, -0.0, np.inf, np.nan, 1e16, 1e-5, 3.4e38, 1e-45, 2.5, 7.0], dtype=np.float32
    ),
    "int": np.arange(-3, 7, dtype=np.int64),
    "bool": np.array([True, False] * 5),
    "text": ["a,b", 'say "x"', "two\nlines", "", None, "plain", "x", "é", " lead", np.nan],
}


def test_edge_values_are_written_as_pandas_writes_them(tmp_path: Path) -> None:
    write_columns_csv(tmp_path / "ours.csv", EDGE_COLUMNS)
    pd.DataFrame(EDGE_COLUMNS).to_csv(tmp_path / "pandas.csv", index=False)
    assert (tmp_path / "ours.csv").read_bytes() == (tmp_path / "pandas.csv").read_bytes()


def test_any_float64_is_written_as_pandas_writes_it(tmp_path: Path) -> None:
    """Python's repr (the float64 path) against pandas' text on doubles drawn from random
    bit patterns (every exponent, subnormals, NaN payloads, both signs of zero) and of a
    report's magnitudes."""
    rng = np.random.default_rng(17)
    bits = rng.integers(0, 2**64, 20_000, dtype=np.uint64)
    # and the magnitudes of a report, across the positional/scientific switch (1e-4, 1e16)
    scaled = rng.standard_normal(20_000) * 10.0 ** rng.integers(-8, 20, 20_000)
    values = np.concatenate([bits.view(np.float64), scaled, np.round(scaled, 3)])
    write_columns_csv(tmp_path / "ours.csv", {"x": values})
    pd.DataFrame({"x": values}).to_csv(tmp_path / "pandas.csv", index=False)
    assert (tmp_path / "ours.csv").read_bytes() == (tmp_path / "pandas.csv").read_bytes()


@pytest.mark.parametrize(
    "row",
    [
        {"a": None},
        {"a": np.nan, "b": "s"},
        {"a": np.float64(1.5), "b": True, "c": 3, "d": np.int64(4), "e": "x,y"},
    ],
)
def test_a_row_is_written_as_pandas_writes_it(row, tmp_path: Path) -> None:
    write_row_csv(tmp_path / "ours.csv", row)
    pd.DataFrame([row]).to_csv(tmp_path / "pandas.csv", index=False)
    assert (tmp_path / "ours.csv").read_bytes() == (tmp_path / "pandas.csv").read_bytes()


def test_records_are_written_as_pandas_writes_them(tmp_path: Path) -> None:
    """Records with different keys (a column one record lacks, one that appears later):
    the columns in the order they first appear, the missing cells empty."""
    records = [
        {"label": "a", "converged [-]": True, "x": 1.5},
        {"label": "b", "extra": "y,z", "converged [-]": False},
        {"label": "c", "x": None, "late": 3},
    ]
    write_records_csv(tmp_path / "ours.csv", records)
    pd.DataFrame.from_records(records).to_csv(tmp_path / "pandas.csv", index=False)
    assert (tmp_path / "ours.csv").read_bytes() == (tmp_path / "pandas.csv").read_bytes()


@pytest.mark.parametrize(
    "cells",
    [
        [1, 2, 3],
        [1, None, 3],
        [1, 2.5, None],
        [0.5, float("nan"), np.float64(2.0)],
        [True, False],
        [True, None],
        [True, 1],
        ["ok", None, "invalid"],
        ["text", 1.5],
        [None, None],
    ],
)
def test_a_record_column_is_held_as_pandas_holds_it(cells: list) -> None:
    """The dtype and values pandas gives a column built from records, one value each
    (numbers with a missing one as floats, booleans with a missing one as objects)."""
    ours = pd.DataFrame({"c": record_column(cells)})
    theirs = pd.DataFrame.from_records([{"c": v} for v in cells])
    pd.testing.assert_frame_equal(ours, theirs)


@pytest.mark.parametrize(("case", "figures"), [(REFERENCE, 7), (CASES / "paper_tabulated.toml", 6)])
def test_a_report_from_a_runs_columns_never_imports_pandas(
    tmp_path: Path, case: Path, figures: int
) -> None:
    """What ``recipsim run``'s parent and report processes run: the solve (or, under a
    tabulated pressure, the pinned mechanism's inverse dynamics), the tables and every
    figure (here in one fresh interpreter), without pandas."""
    code = (
        "import sys\n"
        "from recipsim.case.load import load_case\n"
        "from recipsim.report.figure_process import REPORT_PRELOAD\n"
        "from recipsim.report.report_figures import report_figure_names, write_report_share\n"
        "from recipsim.results.run import simulate_case\n"
        "import importlib\n"
        "for module in REPORT_PRELOAD: importlib.import_module(module)\n"
        f"run = simulate_case(load_case({str(case)!r}), [])\n"
        "names = report_figure_names(run.table, run.row)\n"
        f"write_report_share({str(tmp_path)!r}, run.table, run.row, None, names, tables=True)\n"
        "print(','.join(names), 'pandas' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    names, imported = out.stdout.split()
    assert imported == "False"
    assert len(names.split(",")) == figures
    assert sorted(p.stem for p in tmp_path.glob("*.png")) == sorted(names.split(","))
    assert (tmp_path / "cycle.csv").is_file() and (tmp_path / "summary.csv").is_file()
