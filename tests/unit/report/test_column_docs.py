"""reports/README.md documents every report column from the declarations (issue 13, item 2):
its column tables are what :mod:`recipsim.report.column_readme` generates from the layout
tables and the summary's table, and every column a run writes is in them."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from helpers import CASES, REFERENCE, ROOT
from recipsim.cli.main import main
from recipsim.physics.mechanics import layout as mlay
from recipsim.physics.thermo import cylinder as cyl
from recipsim.report.column_readme import TABLES, markdown_table, render
from recipsim.results.column_docs import (
    CYCLE_DOCS,
    STARTUP_DOCS,
    ColumnDoc,
    choice_docs,
    column,
    documented,
    from_entry,
)
from recipsim.results.startup import startup_table
from recipsim.results.summary_docs import STARTUP_SUMMARY_DOCS, SUMMARY_DOCS
from recipsim.solve import startup as su

README = ROOT / "reports" / "README.md"


def test_readme_column_tables_are_generated() -> None:
    """Regenerate with ``python -m recipsim.report.column_readme`` when this fails."""
    text = README.read_text(encoding="utf-8")
    assert render(text) == text, "run: python -m recipsim.report.column_readme"


def test_render_keeps_the_prose_and_refuses_unknown_tables() -> None:
    text = README.read_text(encoding="utf-8")
    emptied = text.replace(markdown_table(CYCLE_DOCS)[2], "| `stale` | gone |")
    assert emptied != text and render(emptied) == text
    with pytest.raises(ValueError, match="no column table"):
        render(text.replace("columns: cycle", "columns: cycles"))
    with pytest.raises(ValueError, match="expected each"):
        render("no markers at all\n")


def test_declarations_are_unique_and_tabulable() -> None:
    for key, docs in TABLES.items():
        columns = [d.column for d in docs]
        assert len(set(columns)) == len(columns), f"{key}: a column declared twice"
        for doc in docs:
            assert doc.meaning.strip(), f"{key}: {doc.column} has no meaning"
            assert "|" not in doc.meaning.replace("\\|", ""), f"{key}: {doc.column}"


def test_layout_columns_are_the_layouts_entries() -> None:
    """The cycle table's output columns carry their layout entry's name, unit and meaning
    (followed, for those only some choices write, by the choices)."""
    by_column = {d.column: d for d in CYCLE_DOCS}
    added = choice_docs("cycle")
    for entry in cyl.OUTPUTS.entries:
        if entry.column in by_column:
            meaning = by_column[entry.column].meaning
            if entry.column in added:
                assert meaning == added[entry.column].meaning
                assert meaning.startswith(f"{entry.meaning} (with `options.pressure` = ")
            else:
                assert meaning == entry.meaning
    force_z = mlay.OUTPUTS.entries[mlay.A_BEARING_FORCE + 3 * mlay.B_PIN + 2]
    assert from_entry(force_z) == ColumnDoc("bearing_force_<name>_z", "N", force_z.meaning)
    assert by_column["bearing_force_<name>_z [N]"].meaning == force_z.meaning
    assert column("case", "m").unit is None and column("COP [-]", "m").unit == "-"
    assert ColumnDoc("bearing_rms_<name>", "N", "m").columns()[-1] == "bearing_rms_piston_skirt [N]"


def test_startup_table_columns_are_documented() -> None:
    run = SimpleNamespace(transient=SimpleNamespace(trace=np.ones((3, su.N_TRACE))))
    written = list(startup_table(run).columns)  # type: ignore[arg-type]
    assert set(written) == documented(STARTUP_DOCS)
    assert written == [c for d in STARTUP_DOCS for c in d.columns()]  # in the file's order


@pytest.fixture(scope="module")
def reports(tmp_path_factory) -> list:
    out = tmp_path_factory.mktemp("reports")
    cases = (REFERENCE, CASES / "reference_r134a_lbp_coupled.toml")
    assert main(["run", *map(str, cases), "--out", str(out), "--no-plots", "--quiet"]) == 0
    return [out / case.stem for case in cases]


def test_every_column_a_run_writes_is_documented(reports) -> None:
    summary_docs = documented(SUMMARY_DOCS + STARTUP_SUMMARY_DOCS)
    cycle_docs = documented(CYCLE_DOCS)
    for report in reports:
        summary = pd.read_csv(report / "summary.csv")
        cycle = pd.read_csv(report / "cycle.csv")
        missing = [c for c in summary.columns if c not in summary_docs]
        assert not missing, f"{report.name}: summary columns not documented: {missing}"
        missing = [c for c in cycle.columns if c not in cycle_docs]
        assert not missing, f"{report.name}: cycle columns not documented: {missing}"
