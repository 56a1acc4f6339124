"""The plain ``solve_ivp`` baseline: the same model in pure Python, as a user would write it.

The baseline runs in a separate process with ``NUMBA_DISABLE_JIT=1``: every function of
the model that is compiled elsewhere (right-hand side, valve flow, kinematics, mechanism,
event functions and actions) then runs as ordinary Python, the properties come from the
CoolProp ``AbstractState`` called from Python (``HeosProperties.__call__``), and
``scipy.integrate.solve_ivp`` integrates with the periodic iteration of :mod:`.ivp`
(same revolutions, residual and events as the compiled path). Nothing needs a shim: the
first-class property function is an ordinary callable without the JIT, and numba's
``jitclass`` returns the plain class.

What is timed (same as every rung): the whole periodic solve from the model's initial
state to the converged revolution, after imports and model building; each repeat builds
a fresh model. Repeats stop once their total exceeds the budget. Errors are those of the
baseline's own converged revolution.

Run as ``python -m recipsim.studies.bench.baseline --case CASE --method RK45 --out OUT.json
[--set KEY=VALUE ...] [--repeats N] [--budget SECONDS]`` (the parent sets the
environment); :func:`run_baseline` does that and reads the result back.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

import numpy as np

from recipsim.case.case import Case
from recipsim.case.load import load_case
from recipsim.errors import CaseError, RecipsimError
from recipsim.results.tables import cycle_table, summary
from recipsim.solve.drive import build_model_for
from recipsim.studies.bench.errors import compared_quantities
from recipsim.studies.bench.ivp import solve_periodic_ivp
from recipsim.studies.bench.ladder import Rung, case_settings, fidelity
from recipsim.studies.bench.measure import (
    FAILED,
    OK,
    UNAVAILABLE,
    UNCONVERGED,
    Outcome,
    load_rung,
    pressure_trace,
)

#: Largest wall time of one baseline process [s].
TIMEOUT = 3600.0


def run_baseline(
    path: Path,
    base_overrides: list[str],
    rung: Rung,
    base: Case,
    repeats: int,
    budget: float = 120.0,
    timeout: float = TIMEOUT,
) -> Outcome:
    """Run a baseline rung in a child process without numba and collect its outcome."""
    loaded = load_rung(path, base_overrides, rung, base)
    if isinstance(loaded, Outcome):
        return loaded
    settings = case_settings(loaded, rung.integrator)
    out = Outcome(rung, settings, fidelity(base, settings), OK)
    with tempfile.TemporaryDirectory() as tmp:
        result = Path(tmp) / "baseline.json"
        cmd = [
            sys.executable,
            "-m",
            "recipsim.studies.bench.baseline",
            "--case",
            str(path),
            "--method",
            rung.integrator,
            "--repeats",
            str(max(repeats, 1)),
            "--budget",
            str(budget),
            "--out",
            str(result),
        ]
        for text in list(base_overrides) + list(rung.overrides):
            cmd += ["--set", text]
        env = dict(os.environ, NUMBA_DISABLE_JIT="1")
        # the child imports the same recipsim as this process, whatever is installed
        source = str(Path(__file__).resolve().parents[3])
        env["PYTHONPATH"] = os.pathsep.join(p for p in (source, env.get("PYTHONPATH")) if p)
        try:
            proc = subprocess.run(
                cmd, env=env, capture_output=True, text=True, timeout=timeout, check=False
            )
        except subprocess.TimeoutExpired:
            out.status, out.message = FAILED, f"baseline process timed out after {timeout:.0f} s"
            return out
        if not result.exists():
            tail = (proc.stderr or proc.stdout).strip().splitlines()[-3:]
            out.status = FAILED
            out.message = f"baseline process exited with {proc.returncode}: " + " | ".join(tail)
            return out
        data = json.loads(result.read_text())
    out.status = data["status"]
    out.message = data.get("message", "")
    out.wall_times = data.get("wall_times", [])
    out.cpu_times = data.get("cpu_times", [])
    out.build_times = data.get("build_times", [])
    out.rhs_evaluations = int(data.get("rhs_evaluations", 0))
    out.revolutions = int(data.get("revolutions", 0))
    out.residual = float(data.get("residual", math.nan))
    out.periodic_used = "revolutions"
    out.quantities = {k: float(v) for k, v in data.get("quantities", {}).items()}
    if "trace" in data:
        out.trace = (np.asarray(data["trace"][0]), np.asarray(data["trace"][1]))
    return out


def _child(args: argparse.Namespace) -> dict[str, Any]:
    """Body of the baseline process: solve, time, and describe the result."""
    import time

    from numba.core import config as numba_config

    if not getattr(numba_config, "DISABLE_JIT", False):
        return {"status": FAILED, "message": "the baseline must run with NUMBA_DISABLE_JIT=1"}
    try:
        case = load_case(args.case, args.overrides)
        walls: list[float] = []
        cpus: list[float] = []
        builds: list[float] = []
        solution = None
        for _ in range(args.repeats):
            t0 = time.perf_counter()
            model = build_model_for(case)
            builds.append(time.perf_counter() - t0)
            t0, c0 = time.perf_counter(), time.process_time()
            solution = solve_periodic_ivp(model, args.method)
            walls.append(time.perf_counter() - t0)
            cpus.append(time.process_time() - c0)
            if sum(walls) > args.budget:
                break
        assert solution is not None
        cycle = cycle_table(solution)
        row = summary(solution, cycle)
    except CaseError as exc:
        return {"status": UNAVAILABLE, "message": str(exc)}
    except RecipsimError as exc:
        return {"status": FAILED, "message": str(exc)}
    angles, pressure = pressure_trace(cycle)
    converged = bool(solution.converged)
    return {
        "status": OK if converged else UNCONVERGED,
        "message": ""
        if converged
        else f"cycle residual {solution.residual:.2e} after {solution.revolutions} revolutions",
        "wall_times": walls,
        "cpu_times": cpus,
        "build_times": builds,
        "rhs_evaluations": int(solution.nfev),
        "revolutions": int(solution.revolutions),
        "residual": float(solution.residual),
        "quantities": compared_quantities(row),
        "trace": [angles.tolist(), pressure.tolist()],
        "numba_disable_jit": True,
    }


def main(argv: list[str] | None = None) -> int:
    """Entry point of the baseline process (writes its JSON to ``--out``)."""
    parser = argparse.ArgumentParser(prog="python -m recipsim.studies.bench.baseline")
    parser.add_argument("--case", type=Path, required=True)
    parser.add_argument("--method", required=True)
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--budget", type=float, default=120.0)
    parser.add_argument("--out", type=Path, required=True)
    parser.add_argument("--set", dest="overrides", action="append", default=[])
    args = parser.parse_args(argv)
    data = _child(args)
    args.out.write_text(json.dumps(data))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
