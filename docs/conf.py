"""Sphinx configuration of the recipsim documentation.

Build (strict: every warning is an error), as ``tests/docs/test_docs_build.py`` does::

    python -m sphinx -W --keep-going -b html docs docs/_build/html

Sphinx rather than MkDocs: the docstrings are numpydoc, which Sphinx renders natively
(autodoc + numpydoc); MyST reads the Markdown pages as they are, so every ``docs/*.md``
joins the site without conversion.

The gallery (``gallery.md``, a MyST notebook) and the example notebooks
(``examples/*.ipynb``, copied into ``docs/examples/`` for the build) are executed by
myst-nb while the site is built, so their figures and tables are those of the code as
it is; a cell that fails fails the build. Their kernels import recipsim from this
checkout (``PYTHONPATH``) and draw with matplotlib's inline backend (``MPLBACKEND``,
which a test run may have set to Agg).
"""

from __future__ import annotations

import os
import shutil
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))
sys.path.insert(0, str(HERE.parent / "src"))
# the kernels that execute the notebooks: this checkout's recipsim, inline figures
os.environ["PYTHONPATH"] = os.pathsep.join(
    [str(HERE.parent / "src"), *filter(None, [os.environ.get("PYTHONPATH")])]
)
os.environ["MPLBACKEND"] = "module://matplotlib_inline.backend_inline"
# the example notebooks, pages of the site (docs/examples/ is generated, not committed)
shutil.rmtree(HERE / "examples", ignore_errors=True)
shutil.copytree(HERE.parent / "examples", HERE / "examples", ignore=shutil.ignore_patterns(".*"))

import recipsim  # noqa: E402

project = "recipsim"
author = "The recipsim developers"
copyright = "The recipsim developers"  # noqa: A001
version = release = recipsim.__version__

extensions = [
    "sphinx.ext.autodoc",
    "numpydoc",
    "myst_nb",  # MyST Markdown (myst-parser) and notebooks, executed at build time
    "case_reference",
    "model_slots",
]
source_suffix = {".md": "myst-nb", ".ipynb": "myst-nb", ".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "_ext", "**.ipynb_checkpoints"]
myst_heading_anchors = 3
myst_enable_extensions = ["colon_fence"]
nb_execution_mode = "force"  # every build runs them: outputs of the code as it is
nb_execution_timeout = 600  # [s] per cell: a first run builds tables and compiles
nb_execution_raise_on_error = True
nb_execution_in_temp = True  # whatever a notebook writes lands in a temporary folder
nb_output_stderr = "remove"  # progress notes and bars belong to a terminal, not a page
nb_merge_streams = True
nb_render_markdown_format = "myst"  # a result's summary is a Markdown table

autodoc_member_order = "bysource"
autodoc_typehints = "none"  # the numpydoc sections give the types
numpydoc_show_class_members = False
numpydoc_validation_checks: set[str] = set()
nitpicky = False

html_theme = "alabaster"
html_title = f"recipsim {release}"
