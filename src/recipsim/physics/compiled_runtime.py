"""numba imported and its code generator started without scipy.linalg, cffi or yaml.

Before numba loads the first compiled function of a process (from its cache or by
compiling it) it initialises its code generator once: it imports its implementation
modules, among them ``numba.np.arraymath``, which checks that a BLAS is at hand by
importing ``scipy.linalg.cython_blas``. That import runs ``scipy.linalg``'s package
(0.1-0.2 s: scipy's array-API layer, numpy's f2py), a fifth to a third of numba's start
and more than a warm solve; recipsim's compiled code calls no BLAS (its linear algebra
is written out in :mod:`recipsim.solve.stiff`). :func:`start_compiled_runtime` runs
that initialisation with a stand-in for the module while the check imports it; numba
still reads scipy's BLAS integer width from ``scipy.__config__``, and code that does
need BLAS later imports the real module (the stand-in is gone by then), as numba's
lowering of ``np.dot`` and ``np.linalg`` imports it again.

The same initialisation imports numba's CFFI support, which imports ``cffi`` and makes
an ``FFI()``, whose C parser compiles its lexer's regular expressions: 12 ms of every
run, for a feature recipsim's compiled code does not use (it calls no CFFI function).
While the stand-in is in place, ``cffi`` is also hidden (numba then works as it does
where cffi is not installed: no CFFI calls in compiled code, in that process only);
``cffi`` imports normally afterwards.

numba's own import reads a configuration file, ``.numba_config.yaml`` in the working
directory, with PyYAML, which it imports whether or not there is such a file (12 ms).
:func:`importing_numba` hides ``yaml`` while numba imports where there is none (with
the file, numba reads it as ever).

Only the command line does this (:func:`allow_stand_in`, called by ``recipsim``'s
entry point): a library does not touch ``sys.modules`` behind its caller's back, and a
notebook pays numba's start once per session anyway.
"""

from __future__ import annotations

import os
import sys
import types
from collections.abc import Iterator
from contextlib import contextmanager

from recipsim import start_up_collector

#: The module numba imports only to see that it imports.
_BLAS_MODULE = "scipy.linalg.cython_blas"
#: The module numba's CFFI support imports (hidden while numba starts).
_CFFI_MODULE = "cffi"
#: The module numba's import reads its configuration file with, and that file's name.
_YAML_MODULE = "yaml"
_NUMBA_CONFIG_FILE = ".numba_config.yaml"

_started = False
_allowed = False


def allow_stand_in() -> None:
    """Let :func:`start_compiled_runtime` use the stand-in in this process (the command
    line's choice, never a library's)."""
    global _allowed
    _allowed = True


@contextmanager
def importing_numba() -> Iterator[None]:
    """A block that imports numba for the first time, without PyYAML where numba would
    not use it (no ``.numba_config.yaml`` in the working directory; see the module
    docstring); ``yaml`` imports normally after the block. Does nothing unless the
    command line allowed it (:func:`allow_stand_in`), nor where numba or yaml is
    already imported."""
    hide = (
        _allowed
        and "numba" not in sys.modules
        and _YAML_MODULE not in sys.modules
        and not os.path.isfile(_NUMBA_CONFIG_FILE)
    )
    if hide:
        sys.modules[_YAML_MODULE] = None  # type: ignore[assignment]  # ImportError
    try:
        yield
    finally:
        if hide and sys.modules.get(_YAML_MODULE, 0) is None:
            del sys.modules[_YAML_MODULE]


def start_compiled_runtime() -> None:
    """Initialise numba's code generator without importing ``scipy.linalg`` (see the
    module docstring); once per process, before the first compiled call.

    Does nothing unless the command line allowed it (:func:`allow_stand_in`), where
    numba's implementation modules or scipy.linalg are already imported, under
    ``NUMBA_DISABLE_JIT=1``, or without scipy (numba then finds no BLAS on its own, as
    it would have).
    """
    global _started
    if _started or not _allowed:
        return
    _started = True
    try:
        _start()
    finally:  # the start-up is over: its objects frozen, the collector on again
        start_up_collector.resume()


def _start() -> None:
    if (
        os.environ.get("NUMBA_DISABLE_JIT") == "1"
        or "numba.np.arraymath" in sys.modules
        or _BLAS_MODULE in sys.modules
    ):
        return
    import importlib.util

    if importlib.util.find_spec("scipy") is None:
        return
    from numba.core.registry import cpu_target

    from recipsim import timeline

    timeline.mark("numba imported")
    stand_in = types.ModuleType(_BLAS_MODULE)
    sys.modules[_BLAS_MODULE] = stand_in
    hide_cffi = _CFFI_MODULE not in sys.modules
    if hide_cffi:
        sys.modules[_CFFI_MODULE] = None  # type: ignore[assignment]  # ImportError
    try:
        cpu_target.target_context.refresh()  # what numba's first dispatch would do
    finally:
        if sys.modules.get(_BLAS_MODULE) is stand_in:
            del sys.modules[_BLAS_MODULE]
        if hide_cffi and sys.modules.get(_CFFI_MODULE, 0) is None:
            del sys.modules[_CFFI_MODULE]
    timeline.mark("numba started")
