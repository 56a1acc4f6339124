"""recipsim: reciprocating refrigeration compressor simulator.

The CoolProp real-gas cylinder model and the crank train are solved together, step
by step, with a compiled integrator. The public API (:mod:`recipsim.api`)::

    import recipsim
    case = recipsim.load_case("reference_r134a_lbp", {"operating_point.standard": "EN12900"})
    result = recipsim.simulate(case)
    result.summary["COP [-]"], result.plot_pv(), result.write("reports/run")
"""

from __future__ import annotations

from recipsim.cache_dirs import use_recipsim_numba_cache
from recipsim.progress import watch_compilations
from recipsim.version import __version__

# before any of recipsim's functions is compiled (see recipsim.cache_dirs and
# recipsim.progress: each compilation is announced and timed)
use_recipsim_numba_cache()
watch_compilations()

from recipsim.api import (  # noqa: E402
    Case,
    Member,
    Rating,
    Result,
    calibrate,
    cases,
    compare,
    load_case,
    rate,
    read_coefficients,
    simulate,
    sweep,
)
from recipsim.errors import CaseError, SolverError  # noqa: E402

__all__ = [
    "Case",
    "CaseError",
    "Member",
    "Rating",
    "Result",
    "SolverError",
    "__version__",
    "calibrate",
    "cases",
    "compare",
    "load_case",
    "rate",
    "read_coefficients",
    "simulate",
    "sweep",
]
