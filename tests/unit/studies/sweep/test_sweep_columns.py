"""A sweep's summary table kept as columns: the DataFrame pandas would build from its
rows, made only when asked for, and a command line whose own process never imports
pandas (0.3 s before the first point: `recipsim sweep throughput_100 --jobs 2
--no-plots` 1.39 -> 1.14 s, medians of 7 in turn on the 2-core machine).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from helpers import REFERENCE
from recipsim.studies.sweep.engine import run_sweep
from recipsim.studies.sweep.outputs import ID_COLUMNS
from recipsim.studies.sweep.plan import plan_sweep
from recipsim.studies.sweep.spec import load_sweep

#: Two converged points, one not converged (2 revolutions), two invalid (the evaporating
#: temperature above the condensing one): ok rows with every column, rows without.
BODY = """
[axes]
solver.max_revolutions = [2, 60]
operating_point.evaporating_temperature = ["-30 degC", "-25 degC", "70 degC"]
"""


def _sweep(tmp_path: Path) -> Path:
    path = tmp_path / "mixed.toml"
    path.write_text(f'name = "mixed"\nbase = "{REFERENCE.as_posix()}"\n{BODY}')
    return path


def _records(points: Path) -> dict[str, dict]:
    """The stored record of each point id (the later of two)."""
    found: dict[str, dict] = {}
    for segment in sorted(points.glob("*.jsonl")):
        for line in segment.read_bytes().splitlines():
            record = json.loads(line)
            earlier = found.get(record["point_id"])
            if earlier is None or earlier["saved_ns"] <= record["saved_ns"]:
                found[record["point_id"]] = record
    return found


def _table_from_rows(path: Path, records: dict[str, dict]) -> pd.DataFrame:
    """The summary table as pandas builds it from one dict per point (the sweep's table
    before it was kept as columns): the oracle of the columns' dtypes and values."""
    planned = plan_sweep(load_sweep(path))
    axes = list(dict.fromkeys(c for p in planned for c in p.columns))
    seen = set(axes) | set(ID_COLUMNS)
    names: list[str] = []
    in_order = [records[p.point_id] for p in planned]
    for record in sorted(in_order, key=lambda r: r["status"] != "ok"):
        for column in record["summary"]:
            if column not in seen:
                seen.add(column)
                names.append(column)
    rows = []
    for point, record in zip(planned, in_order, strict=True):
        row = {"point": point.index, **{c: point.columns.get(c) for c in axes}}
        row |= {"status": record["status"], "message": record["message"]}
        row |= {c: record["summary"].get(c) for c in names}
        rows.append(row | {"point_id": point.point_id})
    return pd.DataFrame(rows, columns=["point", *axes, "status", "message", *names, "point_id"])


def test_columns_hold_what_pandas_builds_from_the_rows(tmp_path):
    """Every column has the dtype and the values pandas gives the table built from one
    dict per point (ints, floats with NaN where an invalid point has none, text), and
    ``summary.csv`` is that table's ``to_csv``."""
    path = _sweep(tmp_path)
    outcome = run_sweep(path, out=tmp_path / "out", jobs=1, plots=False)
    assert sorted(outcome.counts.items()) == [("invalid", 2), ("not_converged", 2), ("ok", 2)]
    assert outcome.n_points == 6 and outcome.n_ok == 2 and outcome.n_failed == 4
    assert outcome._table is None  # no DataFrame made by the sweep itself

    expected = _table_from_rows(path, _records(outcome.directory / "points"))
    pd.testing.assert_frame_equal(outcome.table, expected)
    kinds = {name: np.asarray(values).dtype.kind for name, values in outcome.columns.items()}
    assert kinds["point"] == "i" and kinds["cooling_capacity [W]"] == "f"
    assert kinds["revolutions [-]"] == "f"  # ints, NaN where an invalid point has none
    assert isinstance(outcome.columns["status"], list)
    written = (outcome.directory / "summary.csv").read_text(encoding="utf-8")
    assert written == expected.to_csv(index=False)
    expected_solves = expected["wall_time [s]"].fillna(0.0).to_numpy()
    assert outcome.solve_seconds == sum(expected_solves.tolist())
    assert outcome.solve_seconds > 0.0


def test_the_command_line_sweeps_without_importing_pandas(tmp_path):
    """``recipsim sweep`` never imports pandas in its own process: not with
    ``--no-plots``, and not where forked processes draw the map plots (they import it
    themselves); the closing lines are printed from the columns. numba is imported
    without PyYAML, as by ``recipsim run`` (no ``.numba_config.yaml`` here)."""
    path = _sweep(tmp_path)
    code = (
        "import sys\n"
        "from recipsim.cli.main import main\n"
        f"args = ['sweep', {str(path)!r}, '--jobs', '2', '--out', {str(tmp_path / 'out')!r}]\n"
        "first = main([*args, '--no-plots'])\n"
        "again = main([*args, '--fresh'])\n"
        "print(first, again, *(m in sys.modules for m in ('pandas', 'matplotlib', 'yaml')))\n"
    )
    env = {**os.environ, "RECIPSIM_FIGURE_PROCESSES": "1"}
    out = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        timeout=600,
        env=env,
        cwd=tmp_path,
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.split()[-5:] == ["1", "1", "False", "False", "False"]  # some not ok
    assert out.stdout.count("6 points: 2 ok, 4 failed (2 invalid, 2 not_converged)") == 2
    assert "point 0 [not_converged]" in out.stdout
    plots = sorted(p.name for p in (tmp_path / "out" / "mixed").glob("map_*.png"))
    assert "map_COP.png" in plots and "map_cooling_capacity.png" in plots
