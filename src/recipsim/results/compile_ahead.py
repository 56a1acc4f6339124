"""First run on a fresh machine: compile the solver in a second process while this one
loads the case and builds its refrigerant's property table.

With nothing of the solver in numba's cache, the command line (``recipsim run``) starts
one child process that loads the same case with the CoolProp properties (no table to
build) and solves one revolution of it, which compiles the case's scene and the tables'
compiled code into numba's cache: the property callback has the same numba type with
either property source, so the parent then loads what the child compiled. The parent
meanwhile builds the property table and its model (which compiles the table's own
functions, which the child never needs), then compiles what the child would compile
last, the cycle table's sample outputs and pinned reactions
(:func:`compile_outputs_while_waiting`), and waits for the child only then, before it
integrates (:func:`wait_for_compile_ahead`). The child only pays where it has a core to itself:
it starts when the machine has two cores that other work leaves idle now
(:func:`recipsim.machine_load.idle_cores`, as for the figure processes), nothing of the solver is
cached and ``RECIPSIM_COMPILE_AHEAD`` is not ``0`` (``1`` starts it whatever the load).
Forced on at a load average of 2 on 2 cores (no idle core) it saved no wall time and
cost up to 8 s of CPU. On the quiet 2-core machine a first run with the child took
22.8-24.1 s (33.5 s of CPU), with the outputs compiled by the parent 24.2-27.2 s (median
24.7 s) against 26.1-32.4 s (median 31.0 s) without, runs alternating: the machine's
speed varied between runs more than the 1.9 s of the child's CPU this moves. A child
that fails changes nothing: the parent then compiles as it would have.
"""

from __future__ import annotations

import json
import logging
import os
import subprocess
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from recipsim.cache_dirs import numba_cache_lacks

if TYPE_CHECKING:
    from recipsim.model.build import Model

logger = logging.getLogger(__name__)

#: The child's overrides on top of the case's own: CoolProp properties, one revolution.
_CHILD_OVERRIDES = [
    "options.properties=heos",
    "solver.min_revolutions=1",
    "solver.max_revolutions=1",
]
#: Longest wait for the child [s]; it is then stopped and the parent compiles itself.
WAIT_LIMIT = 600.0
_CHILD = "from recipsim.results.compile_ahead import compile_in_child; compile_in_child()"

_pending: list[subprocess.Popen[bytes]] = []


def start_compile_ahead(path: str | Path, overrides: list[str], allow_external: bool) -> bool:
    """Start the compiling child for the case ``path`` with ``overrides`` if the solver
    is not in numba's cache at all and two cores are idle (see the module docstring);
    returns whether it did."""
    setting = os.environ.get("RECIPSIM_COMPILE_AHEAD")
    if _pending or setting == "0" or not numba_cache_lacks("integrator"):
        return False
    if setting != "1" and _idle_cores() < 2:
        return False
    argv = [sys.executable, "-c", _CHILD, str(path), json.dumps(list(overrides))]
    argv.append("1" if allow_external else "0")
    quiet = subprocess.DEVNULL
    _pending.append(subprocess.Popen(argv, stdin=quiet, stdout=quiet, stderr=quiet))
    return True


def _idle_cores() -> float:
    """Cores other work leaves idle now (:func:`recipsim.machine_load.idle_cores`; 0
    where the load is unknown)."""
    from recipsim.machine_load import idle_cores

    return float(idle_cores(2, unknown=0))


def wait_for_compile_ahead() -> None:
    """Wait for the compiling child, if one was started (at most :data:`WAIT_LIMIT`)."""
    while _pending:
        child = _pending.pop()
        try:
            child.wait(timeout=WAIT_LIMIT)
        except subprocess.TimeoutExpired:
            child.kill()
            child.wait()


def compile_outputs_while_waiting(model: Model) -> None:
    """While the compiling child compiles the solver, compile here what the cycle table
    runs after the solve: the scene's sample outputs and, on the rigid crank, the pinned
    reactions, by evaluating them once at the model's start state (the same argument
    types as the cycle table's). The child then loads them from numba's cache instead of
    compiling them (1.9 s of its CPU for the default case), and this process, which has
    built its table and would only wait, spends that time instead. Nothing when no child
    is pending."""
    if not _pending:
        return
    import numpy as np

    from recipsim.model.build import case_mechanism_parameters, scenes
    from recipsim.results.bearings import pinned_columns
    from recipsim.solve.scene_outputs import evaluate_samples

    work = model.for_solve()
    out = np.zeros((1, scenes.N_AUX))
    try:
        evaluate_samples(
            np.zeros(1),
            work.y0[None, :].copy(),
            work.mode0[None, :].copy(),
            work.detailed_output_par(),
            work.ipar,
            work.props,
            work.props.buffer,
            out,
        )
        if model.scene == scenes.SCENE_CYLINDER:
            op = model.case.operating_point
            pressure = np.full(1, op.suction_pressure)
            par = case_mechanism_parameters(model.case)
            pinned_columns(np.zeros(1), pressure, op.shaft_speed, par, False)
    except Exception:  # noqa: BLE001 - a head start only: the cycle table compiles them anyway
        logger.debug("compiling the sample outputs ahead failed", exc_info=True)


def compile_in_child() -> None:
    """The child's work (``sys.argv``: case, JSON list of overrides, ``1`` to allow
    external paths); any failure ends it quietly (the parent compiles then)."""
    # the solve and the cycle table, as simulate_case runs them (importing
    # recipsim.results.run here would close an import cycle: it imports this module)
    from recipsim.case.load import load_case
    from recipsim.results.cycle import cycle_table
    from recipsim.solve.drive import build_model_for
    from recipsim.solve.periodic import solve_periodic

    try:
        overrides = json.loads(sys.argv[2]) + _CHILD_OVERRIDES
        case = load_case(sys.argv[1], overrides, allow_external_paths=sys.argv[3] == "1")
        cycle_table(solve_periodic(build_model_for(case)))
    except Exception:
        sys.exit(1)
