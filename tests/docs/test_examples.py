"""The example notebooks cover what the README promises and are committed without outputs
so that their diffs stay readable; the documentation build executes each of them from
top to bottom in a fresh kernel and fails on an error (``tests/docs/test_docs_build.py``),
so they are not run a second time here."""

from __future__ import annotations

import pytest

from helpers import ROOT

nbformat = pytest.importorskip("nbformat", reason="the docs extra (pip install -e '.[docs]')")

NOTEBOOKS = sorted((ROOT / "examples").glob("*.ipynb"))


def test_the_examples_cover_the_promised_topics():
    names = " ".join(p.stem for p in NOTEBOOKS)
    for topic in ("run_one_case", "change_speed", "pv_and_bearing", "sweep", "coupled_vs_tab"):
        assert topic in names, topic


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_is_committed_without_outputs(path):
    book = nbformat.read(path, as_version=4)
    for cell in book.cells:
        if cell.cell_type == "code":
            assert cell.outputs == [] and cell.execution_count is None, path.name
