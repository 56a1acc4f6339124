"""Start-up time of ``recipsim run``: what a run costs before its solve.

Measured in fresh interpreters, as a user meets it: interpreter start, the imports of
the ``run`` path, case loading (units, refrigerant, saturation states), model building
(plenum states, property table) and the load of numba's compilation cache. The cache
load happens inside the first solve, so it is taken as the first solve's time minus a
second, warm solve of the same model in the same process. Caches (numba, property
table, fluid constants, pint) are warm: one unmeasured run fills them first.
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

# runs in the child: the imports and calls of `recipsim run` up to its solve
_CHILD = """
import json, sys, time
cpu0 = time.process_time()
import recipsim.cli.main
from recipsim.case.load import load_case
from recipsim.solve.drive import build_model_for
from recipsim.solve.periodic import solve_periodic
import recipsim.pipeline  # simulate_case and its imports
import recipsim.results.tables
t_import, cpu_import = time.monotonic(), time.process_time()
case = load_case(sys.argv[1], sys.argv[2:])
model = build_model_for(case)
t_model, cpu_model = time.monotonic(), time.process_time()
solve_periodic(model)
t_first, cpu_first = time.monotonic(), time.process_time()
model2 = build_model_for(case)
t_build2, cpu_build2 = time.monotonic(), time.process_time()
solve_periodic(model2)
t_warm, cpu_warm = time.monotonic(), time.process_time()
print(json.dumps({
    "t_import": t_import, "t_model": t_model,
    "first_solve": t_first - t_model, "warm_solve": t_warm - t_build2,
    "cpu_import": cpu_import, "cpu_model": cpu_model,
    "cpu_first_solve": cpu_first - cpu_model, "cpu_warm_solve": cpu_warm - cpu_build2,
    "coolprop_imported": "CoolProp" in sys.modules,
}))
"""


def _one(case: Path, overrides: list[str]) -> dict[str, Any]:
    start = time.monotonic()  # CLOCK_MONOTONIC: the same clock in the child on Linux
    out = subprocess.run(
        [sys.executable, "-c", _CHILD, str(case), *overrides],
        capture_output=True,
        text=True,
        check=True,
    )
    r = json.loads(out.stdout.strip().splitlines()[-1])
    cache_load = max(r["first_solve"] - r["warm_solve"], 0.0)
    cpu_cache_load = max(r["cpu_first_solve"] - r["cpu_warm_solve"], 0.0)
    return {
        "imports [s]": r["t_import"] - start,
        "case_and_model [s]": r["t_model"] - r["t_import"],
        "numba_cache_load [s]": cache_load,
        "startup [s]": r["t_model"] - start + cache_load,
        "startup_cpu [s]": r["cpu_model"] + cpu_cache_load,
        "coolprop_imported": r["coolprop_imported"],
    }


def measure_startup(
    case: Path, overrides: list[str] | None = None, repeats: int = 5
) -> dict[str, Any]:
    """Median start-up of ``recipsim run CASE`` over ``repeats`` fresh interpreters.

    Parameters
    ----------
    case : Path
        The case file.
    overrides : list of str, optional
        ``KEY=VALUE`` overrides (as ``--set``).
    repeats : int
        Timed interpreters (after one that warms the caches).

    Returns
    -------
    dict
        Medians of ``startup [s]`` (wall: interpreter start to the solve, plus the
        numba cache load), ``startup_cpu [s]``, and its parts ``imports [s]``,
        ``case_and_model [s]``, ``numba_cache_load [s]``; ``coolprop_imported`` (any
        run imported CoolProp) and ``repeats``.
    """
    overrides = overrides or []
    _one(case, overrides)  # fill the caches
    runs = [_one(case, overrides) for _ in range(repeats)]
    result: dict[str, Any] = {
        key: statistics.median(r[key] for r in runs)
        for key in runs[0]
        if key != "coolprop_imported"
    }
    result["coolprop_imported"] = any(r["coolprop_imported"] for r in runs)
    result["repeats"] = repeats
    return result
