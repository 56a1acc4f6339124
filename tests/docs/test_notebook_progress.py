"""A sweep run from a notebook shows its progress bar in the cell's output (nbclient, a
fresh kernel): a widget where ipywidgets is installed, else tqdm's text bar on the
cell's standard error; ``progress=False`` shows neither."""

from __future__ import annotations

import os

import pytest

from helpers import ROOT

nbformat = pytest.importorskip("nbformat", reason="the docs extra (pip install -e '.[docs]')")
nbclient = pytest.importorskip("nbclient")
pytest.importorskip("ipykernel")

WIDGET = "application/vnd.jupyter.widget-view+json"
SWEEP = """table = recipsim.sweep(
    case, {"operating_point.shaft_speed": ["2500 rpm", "3000 rpm", "3500 rpm"]}, jobs=1%s
)
print(list(table["status"]))"""


def _bar_outputs(cell) -> list[str]:
    """The progress bars among a cell's outputs: widgets (by their model id) and the
    text of tqdm's bars written to standard error."""
    found = []
    for output in cell.outputs:
        if output.output_type == "display_data" and WIDGET in output.get("data", {}):
            found.append("widget")
        if output.output_type == "stream" and output.name == "stderr":
            lines = output.text.replace("\r", "\n").splitlines()
            found += [line for line in lines if "pt/s" in line or "pt]" in line]
    return found


def test_a_sweep_in_a_notebook_shows_its_progress(tmp_path, monkeypatch):
    book = nbformat.v4.new_notebook()
    book.cells = [
        nbformat.v4.new_code_cell(
            'import recipsim\ncase = recipsim.load_case("reference_r134a_lbp")'
        ),
        nbformat.v4.new_code_cell(SWEEP % ""),
        nbformat.v4.new_code_cell(SWEEP % ", progress=False"),
    ]
    src = str(ROOT / "src")
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([src, os.environ.get("PYTHONPATH", "")]))
    monkeypatch.setenv("MPLBACKEND", "Agg")
    client = nbclient.NotebookClient(
        book, timeout=300, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}
    )
    client.execute()
    shown, silent = book.cells[1], book.cells[2]
    for cell in (shown, silent):
        printed = "".join(o.get("text", "") for o in cell.outputs if o.get("name") == "stdout")
        assert printed.count("'ok'") == 3, cell.outputs  # the three points ran
    bars = _bar_outputs(shown)
    assert "widget" in bars or any("3/3" in line for line in bars), shown.outputs
    assert _bar_outputs(silent) == [], silent.outputs
