"""Sphinx configuration of the recipsim documentation.

Build (strict: every warning is an error), as ``tests/docs/test_docs_build.py`` does::

    python -m sphinx -W --keep-going -b html docs docs/_build/html

Sphinx rather than MkDocs: the docstrings are numpydoc, which Sphinx renders natively
(autodoc + numpydoc); MyST reads the Markdown pages as they are, so every ``docs/*.md``
joins the site without conversion.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))
sys.path.insert(0, str(HERE.parent / "src"))

import recipsim  # noqa: E402

project = "recipsim"
author = "The recipsim developers"
copyright = "The recipsim developers"  # noqa: A001
version = release = recipsim.__version__

extensions = [
    "sphinx.ext.autodoc",
    "numpydoc",
    "myst_parser",
    "case_reference",
]
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "_ext", "**.ipynb_checkpoints"]
myst_heading_anchors = 3
myst_enable_extensions = ["colon_fence"]

autodoc_member_order = "bysource"
autodoc_typehints = "none"  # the numpydoc sections give the types
numpydoc_show_class_members = False
numpydoc_validation_checks: set[str] = set()
nitpicky = False

html_theme = "alabaster"
html_title = f"recipsim {release}"
