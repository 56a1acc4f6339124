"""How a sweep scales with workers once the program has started.

:func:`recipsim.studies.bench.system_time.measure_map` times ``recipsim sweep`` end to
end: each run pays the interpreter's start, the imports and numba's cache load in the
parent before any worker exists, a serial part that no worker count shortens (the
``S`` of ``T(J) = S + P / J``). :func:`measure_map_scaling` runs the same sweep with
each worker count inside one interpreter that has already started (recipsim imported,
numba's cache loaded by one solve of the base case), as a notebook or a long-lived
service meets it: what is left serial is the sweep's own work in the parent (planning,
the first point solved before the workers fork, saving each point's record, the
tables), and the parallel efficiency ``T(1) / (J T(J))`` measures the pool itself.

Both figures are reported side by side; neither replaces the other.
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
from typing import Any

from recipsim.errors import RecipsimError

# runs in the child: the sweep after start-up with each worker count, no map plots
_SCALING_CHILD = r"""
import json, os, sys, tempfile, time
from recipsim.case.load import load_case
from recipsim.results.run import simulate_case
from recipsim.studies.sweep.engine import run_sweep
from recipsim.studies.sweep.spec import load_sweep
spec = load_sweep(sys.argv[1])
jobs = [int(j) for j in sys.argv[2].split(",")]
repeats = int(sys.argv[3])
simulate_case(load_case(str(spec.base), []), [])
result = {}
with tempfile.TemporaryDirectory() as tmp:
    run_sweep(spec, jobs=1, out=os.path.join(tmp, "warm"), plots=False)  # lazy imports done
    for count in jobs:
        walls, cpus = [], []
        for repeat in range(repeats):
            out = os.path.join(tmp, f"{count}-{repeat}")  # a new map: nothing to resume or clear
            start, cpu = time.perf_counter(), time.process_time()
            outcome = run_sweep(spec, jobs=count, out=out, plots=False)
            walls.append(time.perf_counter() - start)
            cpus.append(time.process_time() - cpu)
        solves = outcome.solve_seconds
        result[count] = [walls, cpus, solves, outcome.n_points, outcome.n_ok]
print(json.dumps(result))
"""


def measure_map_scaling(sweep: str, jobs: list[int], repeats: int = 1) -> dict[str, Any]:
    """A sweep with each worker count of ``jobs``, after start-up, without map plots.

    Parameters
    ----------
    sweep : str
        Sweep file or shipped sweep name (e.g. ``throughput_1000``).
    jobs : list of int
        Worker counts, e.g. ``[1, 2, 4, 8, 16]``; the efficiency is taken against the
        smallest.
    repeats : int
        Runs per worker count (median wall time).

    Returns
    -------
    dict
        ``points``; ``runs``: worker count to ``wall [s]`` (median), ``parent_cpu [s]``
        (the parent's own CPU time: planning, the first point, saving records, tables),
        ``solve_sum [s]`` (the points' solve times added up), ``points_per_second``,
        ``ok`` (points that ended ``ok``), ``efficiency [-]`` =
        ``J0 T(J0) / (J T(J))`` with ``J0`` the smallest worker count,
        ``solve_slowdown [-]``, the solves' sum over that with ``J0`` workers (above 1
        where the workers running at once slow each other's solves down: shared caches
        and memory), and ``efficiency_ceiling [-]`` = ``1 / solve_slowdown``, the
        efficiency were everything but the solves free.
    """
    command = [sys.executable, "-c", _SCALING_CHILD, sweep, ",".join(map(str, jobs)), str(repeats)]
    out = subprocess.run(command, capture_output=True, text=True)
    if out.returncode != 0:
        last = (out.stderr.strip() or "no output").splitlines()[-1]
        raise RecipsimError(
            f"the sweep {sweep} after start-up exited with {out.returncode}: {last}"
        )
    measured = json.loads(out.stdout.strip().splitlines()[-1])
    runs: dict[str, dict[str, float]] = {}
    points = 0
    for count, (walls, cpus, solves, points, ok) in measured.items():
        wall = statistics.median(walls)
        runs[count] = {
            "wall [s]": wall,
            "parent_cpu [s]": statistics.median(cpus),
            "solve_sum [s]": solves,
            "points_per_second": points / wall,
            "ok": ok,
        }
    low = min(jobs)
    reference = low * runs[str(low)]["wall [s]"]
    solves = runs[str(low)]["solve_sum [s]"]
    for count, timing in runs.items():
        timing["efficiency [-]"] = reference / (int(count) * timing["wall [s]"])
        slowdown = timing["solve_sum [s]"] / solves if solves > 0 else float("nan")
        timing["solve_slowdown [-]"] = slowdown
        timing["efficiency_ceiling [-]"] = 1.0 / slowdown if slowdown > 0 else float("nan")
    return {"sweep": sweep, "points": points, "runs": runs}
