"""The documentation site builds in strict mode (every Sphinx warning is an error) and
holds what a user navigates by: every ``docs/*.md`` page, the API reference and the
case-file reference generated from the schema (every declared key of every table)."""

from __future__ import annotations

import subprocess
import sys

import pytest

from helpers import ROOT

DOCS = ROOT / "docs"

pytest.importorskip("sphinx", reason="the docs extra (pip install -e '.[docs]')")
pytest.importorskip("myst_parser")
pytest.importorskip("numpydoc")


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    out = tmp_path_factory.mktemp("html")
    doctrees = tmp_path_factory.mktemp("doctrees")
    cmd = [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html"]
    cmd += ["-d", str(doctrees), str(DOCS), str(out)]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
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
