"""Where a map's overhead goes: the stages of a sweep around its solves, per point.

:func:`recipsim.studies.bench.system_time.measure_map_after_startup` gives the overhead
ratio of a sweep on one worker after start-up (everything but the solves, over the
solves) as one number. :func:`measure_map_overhead` splits it: the same sweep, run in an
interpreter that has started (recipsim imported, numba's cache loaded by one solve of
the base case, one unmeasured sweep for the lazy imports), with a timer around each
stage of a point and of the sweep.

Per point:

- ``case``: the point's case, the base case with its overrides
  (:func:`recipsim.studies.sweep.worker.point_case`);
- ``model_build``: the compiled model's arrays (:func:`recipsim.solve.drive.build_model_for`);
- ``solve_call``: :func:`recipsim.solve.periodic.solve_periodic` less the solve's own
  timer (the point's ``wall_time [s]``, the denominator of the ratio): the model's
  working copy;
- ``sampled_outputs``: the scene's outputs at the samples of the converged revolution
  (compiled; :func:`recipsim.solve.revolution.sample_outputs`);
- ``summary``: the summary row less ``sampled_outputs``
  (:func:`recipsim.results.tables.summary_row`);
- ``record``: the point's record saved (:meth:`recipsim.studies.sweep.store.PointStore.save`).

Per sweep: ``plan`` (the points planned and their ids), ``tables`` (the summary table
built and written) and ``other``, the rest of the wall time (the engine's bookkeeping,
the classification of each point, the store's directory).

Each stage is reported as milliseconds per point and as its share of the solves; the
shares add up to the overhead ratio. The timers are wrappers installed in the measuring
interpreter only (about a microsecond per call, eight calls a point); a stage whose
function has moved makes the measurement fail, naming it, rather than report less.
"""

from __future__ import annotations

import functools
import importlib
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

from recipsim.errors import RecipsimError

#: stage -> (module, attribute) of the function it times (``Class.method`` for a method)
STAGE_FUNCTIONS: dict[str, tuple[str, str]] = {
    "case": ("recipsim.studies.sweep.worker", "point_case"),
    "model_build": ("recipsim.solve.drive", "build_model_for"),
    "solve_call": ("recipsim.solve.periodic", "solve_periodic"),
    "sampled_outputs": ("recipsim.results.cycle", "sample_outputs"),
    "summary": ("recipsim.results.tables", "summary_row"),
    "record": ("recipsim.studies.sweep.store", "PointStore.save"),
    "plan": ("recipsim.studies.sweep.engine", "_plan"),
    "tables": ("recipsim.studies.sweep.engine", "_outcome"),
}
#: stages reported per point (the others once per sweep, and ``other``)
POINT_STAGES = ("case", "model_build", "solve_call", "sampled_outputs", "summary", "record")
SWEEP_STAGES = ("plan", "tables", "other")
#: stages that contain another: the inner one's time is taken out of the outer's
_NESTED = {"summary": "sampled_outputs"}

_CHILD = r"""
import json, sys
from recipsim.studies.bench.map_overhead import stage_seconds_here
print(json.dumps(stage_seconds_here(sys.argv[1], int(sys.argv[2]))))
"""


@contextmanager
def _stage_timers(spent: dict[str, float]) -> Iterator[None]:
    """Wrap each function of :data:`STAGE_FUNCTIONS` so that its wall time adds to
    ``spent[stage]`` [s] while the block runs; the originals are put back after."""
    installed: list[tuple[Any, str, Any]] = []

    def timed(stage: str, function: Callable[..., Any]) -> Callable[..., Any]:
        @functools.wraps(function)
        def wrapper(*args: Any, **kwargs: Any) -> Any:
            start = time.perf_counter()
            try:
                return function(*args, **kwargs)
            finally:
                spent[stage] += time.perf_counter() - start

        return wrapper

    try:
        for stage, (module_name, path) in STAGE_FUNCTIONS.items():
            owner: Any = importlib.import_module(module_name)
            *parents, name = path.split(".")
            try:
                for parent in parents:
                    owner = getattr(owner, parent)
                original = getattr(owner, name)
            except AttributeError:
                gone = f"map overhead: {module_name}.{path} is gone; update the bench"
                raise RecipsimError(gone) from None
            installed.append((owner, name, original))
            setattr(owner, name, timed(stage, original))
        yield
    finally:
        for owner, name, original in reversed(installed):
            setattr(owner, name, original)


def stage_seconds_here(sweep: str, repeats: int) -> dict[str, Any]:
    """Run ``sweep`` on one worker in this interpreter, after a warm-up, ``repeats``
    times with the stage timers on (:func:`measure_map_overhead` runs it in a child).

    Returns
    -------
    dict
        ``points``; ``runs``: one entry per repeat with ``wall [s]``, ``solve_sum [s]``
        (the points' ``wall_time [s]``) and ``stages``: stage -> seconds [s] over the
        sweep (``summary`` without ``sampled_outputs``, ``solve_call`` without the solves).
    """
    from recipsim.case.load import load_case
    from recipsim.results.run import simulate_case
    from recipsim.studies.sweep.engine import run_sweep
    from recipsim.studies.sweep.spec import load_sweep

    spec = load_sweep(sweep)
    simulate_case(load_case(str(spec.base), []), [])  # numba's cache loaded
    runs = []
    with tempfile.TemporaryDirectory(prefix="recipsim-overhead-") as tmp:
        run_sweep(spec, jobs=1, out=os.path.join(tmp, "warm"), plots=False)  # lazy imports
        for repeat in range(repeats):
            spent = dict.fromkeys(STAGE_FUNCTIONS, 0.0)
            with _stage_timers(spent):
                start = time.perf_counter()
                outcome = run_sweep(spec, jobs=1, out=os.path.join(tmp, str(repeat)), plots=False)
                wall = time.perf_counter() - start
            solves = outcome.solve_seconds
            for outer, inner in _NESTED.items():
                spent[outer] -= spent[inner]
            spent["solve_call"] -= solves
            runs.append({"wall [s]": wall, "solve_sum [s]": solves, "stages": spent})
    return {"points": outcome.n_points, "runs": runs}


def overhead_stages(measured: dict[str, Any]) -> dict[str, Any]:
    """The medians over the repeats of :func:`stage_seconds_here`'s result, per point and
    as shares of the solves.

    Returns
    -------
    dict
        ``points``, ``wall [s]``, ``solve_sum [s]``, ``overhead_ratio [-]`` (medians);
        ``per_point [ms]``: ``solve`` and each stage of :data:`POINT_STAGES`;
        ``per_sweep [ms]``: each of :data:`SWEEP_STAGES`; ``share_of_solves [-]``: each
        stage's median time over the median solves (they add up to the ratio, ``other``
        taking what the medians leave).
    """
    runs, n = measured["runs"], measured["points"]
    wall = statistics.median(r["wall [s]"] for r in runs)
    solves = statistics.median(r["solve_sum [s]"] for r in runs)
    stage = {s: statistics.median(r["stages"][s] for r in runs) for s in STAGE_FUNCTIONS}
    stage["other"] = wall - solves - sum(stage.values())
    ratio = (wall - solves) / solves if solves > 0 else None
    return {
        "points": n,
        "wall [s]": wall,
        "solve_sum [s]": solves,
        "overhead_ratio [-]": ratio,
        "per_point [ms]": {
            "solve": solves / n * 1e3,
            **{s: stage[s] / n * 1e3 for s in POINT_STAGES},
        },
        "per_sweep [ms]": {s: stage[s] * 1e3 for s in SWEEP_STAGES},
        "share_of_solves [-]": {s: stage[s] / solves if solves > 0 else None for s in stage},
    }


def measure_map_overhead(sweep: str, repeats: int = 3) -> dict[str, Any]:
    """The overhead of ``sweep`` on one worker after start-up, stage by stage
    (module docstring): :func:`overhead_stages` of a child's :func:`stage_seconds_here`.

    Raises
    ------
    RecipsimError
        If the child failed (with its last line).
    """
    out = subprocess.run(
        [sys.executable, "-c", _CHILD, sweep, str(repeats)], capture_output=True, text=True
    )
    if out.returncode != 0:
        last = (out.stderr.strip() or out.stdout.strip() or "no output").splitlines()[-1]
        raise RecipsimError(
            f"map overhead of {sweep}: the child exited with {out.returncode}: {last}"
        )
    return overhead_stages(json.loads(out.stdout.splitlines()[-1]))


def format_overhead_stages(stages: dict[str, Any]) -> list[str]:
    """Console lines of :func:`overhead_stages`: the ratio as the sum of its stages'
    shares (largest first), then the times per point and per sweep."""
    shares = {k: v for k, v in stages["share_of_solves [-]"].items() if v is not None}
    ranked = sorted(shares.items(), key=lambda item: -item[1])
    per_point = ", ".join(f"{k} {v:.3f}" for k, v in stages["per_point [ms]"].items())
    per_sweep = ", ".join(f"{k} {v:.1f}" for k, v in stages["per_sweep [ms]"].items())
    ratio = stages["overhead_ratio [-]"]
    return [
        f"  overhead by stage (1 worker, after start-up, {stages['points']} points): "
        + (f"{ratio:.2f} = " if ratio is not None else "")
        + " + ".join(f"{k} {v:.3f}" for k, v in ranked),
        f"    per point [ms]: {per_point}",
        f"    per sweep [ms]: {per_sweep}",
    ]
