"""numba's code generator started without scipy.linalg (:mod:`recipsim.physics.compiled_runtime`):
a command-line run does not import it, numba still knows that a BLAS is there, and code
that needs BLAS gets the real module; a library run leaves sys.modules alone."""

from __future__ import annotations

import subprocess
import sys

from helpers import REFERENCE

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
"""


def test_a_run_loads_no_scipy_linalg_and_blas_still_works() -> None:
    out = subprocess.run(
        [sys.executable, "-c", _CHILD], capture_output=True, text=True, check=True
    ).stdout.split("\n")
    assert out[0] == "False False True"  # numba knows BLAS is there, scipy.linalg unloaded
    assert out[1] == "3.0 True"  # np.dot compiles against the real cython_blas


def test_a_library_run_imports_scipy_linalg_as_numba_does() -> None:
    """Without the command line's permission nothing stands in for scipy.linalg."""
    child = _CHILD.replace("compiled_runtime.allow_stand_in()", "pass")
    out = subprocess.run(
        [sys.executable, "-c", child], capture_output=True, text=True, check=True
    ).stdout.split("\n")
    assert out[0] == "True True True"
