"""The documentation site builds in strict mode (every Sphinx warning is an error) and
holds what a user navigates by: every ``docs/*.md`` page, the API reference and the
case-file reference generated from the schema (every declared key of every table), the
gallery's figures and the example notebooks with their outputs (both executed by myst-nb
while the site is built: a cell that fails fails the build)."""

from __future__ import annotations

import re
import subprocess
import sys

import pytest

from helpers import ROOT

DOCS = ROOT / "docs"

pytest.importorskip("sphinx", reason="the docs extra (pip install -e '.[docs]')")
pytest.importorskip("myst_parser")
pytest.importorskip("myst_nb")
pytest.importorskip("numpydoc")


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    out = tmp_path_factory.mktemp("html")
    doctrees = tmp_path_factory.mktemp("doctrees")
    cmd = [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html"]
    cmd += ["-d", str(doctrees), str(DOCS), str(out)]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=1200)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    return out


def test_every_markdown_page_is_in_the_site(site):
    pages = sorted(p.stem for p in [*DOCS.glob("*.md"), *DOCS.glob("*.rst")])
    assert {"index", "getting-started", "caches", "sweeps", "case-reference"} <= set(pages)
    for stem in pages:
        assert (site / f"{stem}.html").is_file(), stem
    index = (site / "index.html").read_text()
    for stem in pages:
        if stem != "index":
            assert f'href="{stem}.html"' in index, f"{stem} is not in the navigation"


def test_case_reference_lists_every_declared_key(site):
    from recipsim.case import case_schema
    from recipsim.case.motor import MOTOR_SPEC
    from recipsim.case.thermal import THERMAL_SPEC
    from recipsim.studies.sweep.spec import SWEEP_SPEC

    html = (site / "case-reference.html").read_text()
    specs = [
        case_schema.OPTION_SPEC,
        case_schema.OPERATING_POINT_SPEC,
        case_schema.GEOMETRY_SPEC,
        case_schema.VALVES_TOP_SPEC,
        case_schema.VALVE_SPEC,
        case_schema.LEAKAGE_SPEC,
        case_schema.HEAT_TRANSFER_SPEC,
        case_schema.SOLVER_SPEC,
        MOTOR_SPEC,
        THERMAL_SPEC,
        SWEEP_SPEC,
    ]
    for spec in specs:
        for key, field in spec.items():
            assert f'<span class="pre">{key}</span>' in html, key
            unit = getattr(field, "unit", None)
            if unit and unit != "dimensionless":
                assert unit.replace("**", "^") in html, (key, unit)
    assert "rad/s" in html and "3.14159" in html  # shaft_speed's unit, max_step's range
    assert "Sweep file: top level" in html and "[1, inf], whole number" in html  # max_points


def test_case_reference_describes_the_mechanism_bearing_and_oil_keys(site):
    """The tables validated in code come from their ``Described`` declarations: every
    key with its unit, range words, default and requirement; no table is left
    "not described"."""
    from html import unescape

    from recipsim.case.lubrication import OIL_SPEC
    from recipsim.case.mechanism_schema import BEARING_SPEC, PISTON_SPEC, ROD_SPEC, ROTOR_SPEC

    html = (site / "case-reference.html").read_text()
    text = " ".join(unescape(html).split())
    assert "not described here yet" not in html
    assert "[oil]" in html
    for spec in (PISTON_SPEC, ROD_SPEC, ROTOR_SPEC, BEARING_SPEC, OIL_SPEC):
        for key, field in spec.items():
            assert f'<span class="pre">{key}</span>' in html, key
            words = {field.allowed, field.allowed.replace("...", "\u2026")}  # smartquotes
            assert any(w in text for w in words), (key, field.allowed)
            if field.unit and field.unit != "dimensionless":
                assert field.unit.replace("**", "^") in html, (key, field.unit)


def test_api_reference_documents_the_public_names(site):
    import recipsim

    html = (site / "api.html").read_text()
    for name in ("load_case", "simulate", "sweep", "compare", "Case", "Result", "CaseError"):
        assert f"recipsim.{name}" in html, name
    assert name in recipsim.__all__


def _images(html: str) -> list[str]:
    """The inline images of a page (the executed cells' figures, base64 PNGs or files)."""
    return re.findall(r'<img [^>]*src="([^"]+)"', html)


def test_the_gallery_shows_the_shipped_cases_figures(site):
    html = (site / "gallery.html").read_text()
    for title in (
        "Indicator diagram (p-V)",
        "Pressure against crank angle (p-theta)",
        "Torque",
        "Bearing orbits",
        "An operating map",
        "Where the power goes",
        "Coupled against tabulated",
    ):
        assert title in html, title
    # p-V (reference; every shipped gas case), p-theta, torque, two orbit figures, two
    # maps, the losses, pressure and orbits coupled against tabulated
    images = _images(html)
    assert len(images) >= 11, images
    for source in images:
        if not source.startswith("data:"):
            assert (site / source).is_file() and (site / source).stat().st_size > 10_000
    assert re.search(r"<td>(<p>)?cooling capacity", html)  # a result's summary, as a table


def test_the_example_notebooks_are_pages_with_their_outputs(site):
    index = (site / "index.html").read_text()
    for notebook in sorted((ROOT / "examples").glob("*.ipynb")):
        page = site / "examples" / f"{notebook.stem}.html"
        assert page.is_file(), notebook.name
        assert f'href="examples/{notebook.stem}.html"' in index
        html = page.read_text()
        assert "cell_output" in html, notebook.name  # executed: every page shows results
    plots = (site / "examples" / "03_pv_and_bearing_plots.html").read_text()
    assert len(_images(plots)) >= 3


def test_model_slot_pages_name_every_column_a_choice_adds(site):
    """The model-slot directive lists each choice's declared report columns (``outputs``)
    on the page that shows its slot: every declared column of every registered slot is on
    the model-slots page or the valves page."""
    import html as html_lib

    from recipsim.physics.friction_models import FRICTION_MODELS
    from recipsim.physics.mechanics.bearing_laws.registry import BEARING_LAWS
    from recipsim.physics.mechanics.crank_trains import CRANK_TRAINS
    from recipsim.physics.thermo.pressure_sources import PRESSURE_SOURCES

    # the words of a literal are spans of their own: the tags out, then the entities
    text = "".join(
        html_lib.unescape(re.sub(r"<[^>]+>", "", (site / f"{page}.html").read_text()))
        for page in ("model-slots", "valves")
    )
    declared = [
        (choice.name, output.column)
        for slot in (BEARING_LAWS, CRANK_TRAINS, FRICTION_MODELS, PRESSURE_SOURCES)
        for choice in slot
        for output in choice.outputs
    ]
    assert declared  # the film laws, the skirt, the flexible crank, the mean friction
    missing = [(name, column) for name, column in declared if column not in text]
    assert not missing, missing
