"""The example notebooks run from top to bottom (nbclient, a fresh kernel each), and are
committed without outputs so that their diffs stay readable."""

from __future__ import annotations

import os

import pytest

from helpers import ROOT

nbformat = pytest.importorskip("nbformat", reason="the docs extra (pip install -e '.[docs]')")
nbclient = pytest.importorskip("nbclient")
pytest.importorskip("ipykernel")

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


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs(path, tmp_path, monkeypatch):
    """Every cell runs without an error, in a scratch directory (nothing is written into
    the checkout); the kernel sees this interpreter's recipsim (PYTHONPATH passed on)."""
    book = nbformat.read(path, as_version=4)
    src = str(ROOT / "src")
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([src, os.environ.get("PYTHONPATH", "")]))
    monkeypatch.setenv("MPLBACKEND", "Agg")
    client = nbclient.NotebookClient(
        book, timeout=120, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}
    )
    client.execute()
    errors = [o for c in book.cells for o in c.get("outputs", []) if o.output_type == "error"]
    assert not errors
