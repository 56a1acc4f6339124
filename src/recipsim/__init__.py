"""recipsim: reciprocating refrigeration compressor simulator.

The CoolProp real-gas cylinder model and the crank train are solved together, step
by step, with a compiled integrator. The public API (:mod:`recipsim.api`)::

    import recipsim
    case = recipsim.load_case("reference_r134a_lbp", {"operating_point.shaft_speed": "3000 rpm"})
    result = recipsim.simulate(case)
    result.summary["COP [-]"], result.plot_pv(), result.write("reports/run")

The names are loaded on first use, so ``import recipsim`` stays cheap.
"""

from __future__ import annotations

import hashlib
import os
import sys
from pathlib import Path

__version__ = "0.1.0"

__all__ = [
    "Case",
    "CaseError",
    "Result",
    "SolverError",
    "__version__",
    "calibrate",
    "cases",
    "compare",
    "load_case",
    "simulate",
    "sweep",
]

_API = {
    "Case": "recipsim.api",
    "Result": "recipsim.api",
    "load_case": "recipsim.api",
    "simulate": "recipsim.api",
    "sweep": "recipsim.api",
    "compare": "recipsim.api",
    "calibrate": "recipsim.api",
    "cases": "recipsim.api",
    "CaseError": "recipsim.errors",
    "SolverError": "recipsim.errors",
}


def __getattr__(name: str) -> object:
    """The public API, imported when first asked for (PEP 562)."""
    if name in _API:
        import importlib

        return getattr(importlib.import_module(_API[name]), name)
    raise AttributeError(f"module 'recipsim' has no attribute {name!r}")


#: Modules holding compiled code or the layout constants compiled code reads.
_COMPILED_SOURCES = ("physics", "model", "solve")


def _compiled_sources_digest() -> str:
    root = Path(__file__).parent
    digest = hashlib.blake2b(digest_size=8)
    for entry in _COMPILED_SOURCES:
        path = root / entry
        files = sorted(path.rglob("*.py")) if path.is_dir() else [path]
        for file in files:
            digest.update(file.relative_to(root).as_posix().encode())
            digest.update(file.read_bytes())
    return digest.hexdigest()


def _isolate_numba_cache() -> None:
    """Key numba's on-disk cache by the content of recipsim's compiled sources.

    numba invalidates a cached function only when *its own* file changes, not when a
    constant it reads from another module does (e.g. a parameter-layout index in
    ``mechanics/layout.py``): a stale cache would then silently read the wrong slots.
    A cache directory per source digest rules that out. Honours ``NUMBA_CACHE_DIR``
    (used as the parent); default ``<recipsim cache>/numba``
    (:func:`recipsim.cache_dirs.cache_dir`).
    """
    if os.environ.get("NUMBA_DISABLE_JIT") == "1":
        return
    base = os.environ.get("NUMBA_CACHE_DIR")
    if base is not None and Path(base).name.startswith("recipsim-"):
        base = str(Path(base).parent)  # set by a parent recipsim process
    if base is None:
        from recipsim.cache_dirs import cache_dir, private_dir

        base = str(cache_dir() / "numba")
        try:
            private_dir(Path(base))  # numba's cache is pickled: keep it private
        except OSError:
            pass  # numba falls back to its own handling of an unwritable cache
    path = str(Path(base) / f"recipsim-{_compiled_sources_digest()}")
    numba = sys.modules.get("numba")
    if numba is not None:
        numba.config.CACHE_DIR = path  # numba already read its environment
    else:
        os.environ["NUMBA_CACHE_DIR"] = path


_isolate_numba_cache()
