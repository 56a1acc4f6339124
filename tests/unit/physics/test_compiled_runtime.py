"""numba imported and started without scipy.linalg, cffi or yaml
(:mod:`recipsim.physics.compiled_runtime`): a command-line run imports none of them,
numba still knows that a BLAS is there, code that needs BLAS gets the real module, cffi
and yaml import afterwards, a numba configuration file is still read; a library run
leaves sys.modules alone."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from helpers import REFERENCE, ROOT

_CHILD = f"""
import sys
from recipsim.physics import compiled_runtime
compiled_runtime.allow_stand_in()  # as recipsim's entry point does
from recipsim.case.load import load_case
from recipsim.results.run import simulate_case
run = simulate_case(load_case({str(REFERENCE)!r}), [])
assert run.row["converged [-]"]
import numba.np.arraymath
print("scipy.linalg" in sys.modules, "scipy.linalg.cython_blas" in sys.modules,
      numba.np.arraymath._HAVE_BLAS)
import numpy as np
from numba import njit
@njit
def dot(a, b):
    return np.dot(a, b)
print(dot(np.ones(3), np.ones(3)), hasattr(sys.modules["scipy.linalg.cython_blas"], "__file__"))
from numba.core.typing import cffi_utils
import importlib.util
had_cffi = "cffi" in sys.modules
installed = importlib.util.find_spec("cffi") is not None  # an optional package
if installed:
    import cffi
print(had_cffi, cffi_utils.SUPPORTED, installed and hasattr(cffi, "FFI"), installed)
"""


def test_a_run_loads_no_scipy_linalg_and_blas_still_works() -> None:
    out = subprocess.run(
        [sys.executable, "-c", _CHILD], capture_output=True, text=True, check=True
    ).stdout.split("\n")
    assert out[0] == "False False True"  # numba knows BLAS is there, scipy.linalg unloaded
    assert out[1] == "3.0 True"  # np.dot compiles against the real cython_blas
    # cffi was hidden while numba started (its CFFI support off), and imports afterwards
    installed = out[2].split()[-1]
    assert out[2] == f"False False {installed} {installed}"


def test_a_library_run_imports_scipy_linalg_as_numba_does() -> None:
    """Without the command line's permission nothing stands in for scipy.linalg."""
    child = _CHILD.replace("compiled_runtime.allow_stand_in()", "pass")
    out = subprocess.run(
        [sys.executable, "-c", child], capture_output=True, text=True, check=True
    ).stdout.split("\n")
    assert out[0] == "True True True"
    installed = out[2].split()[-1]  # numba's CFFI support as numba sets it up
    assert out[2] == " ".join([installed] * 4)


_YAML_CHILD = """
import sys
from recipsim.physics import compiled_runtime
compiled_runtime.allow_stand_in()  # as recipsim's entry point does
with compiled_runtime.importing_numba():
    from recipsim.case.load import load_case
import numba.core.config
hidden = "yaml" not in sys.modules
import yaml
print(hidden, numba.core.config._HAVE_YAML, hasattr(yaml, "safe_load"))
"""


@pytest.mark.parametrize("config_file", [False, True])
def test_numba_imports_without_yaml_unless_it_has_a_config_file_to_read(
    tmp_path: Path, config_file: bool
) -> None:
    """Without ``.numba_config.yaml`` in the working directory, numba imports without
    PyYAML (which it would only use to read that file) and yaml imports afterwards; with
    the file, numba has PyYAML to read it, as ever."""
    pytest.importorskip("yaml")  # PyYAML comes with recipsim's dependencies, not numba's
    if config_file:
        (tmp_path / ".numba_config.yaml").write_text("DISABLE_PERFORMANCE_WARNINGS: 1\n")
    out = subprocess.run(
        [sys.executable, "-c", _YAML_CHILD],
        capture_output=True,
        text=True,
        check=True,
        cwd=tmp_path,
        env={**os.environ, "PYTHONPATH": str(ROOT / "src")},
    ).stdout.split()
    assert out == (["False", "True", "True"] if config_file else ["True", "False", "True"])
