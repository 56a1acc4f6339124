"""First run on a fresh machine: compile the solver in a second process while this one
loads the case and builds its refrigerant's property table.

With nothing of the solver in numba's cache, the command line (``recipsim run``) starts
one child process that reads the case's options and solver settings alone
(:func:`recipsim.case.load.load_case_settings`: no refrigerant, no CoolProp, no table)
and compiles the solver's entry that the case starts with
(:func:`recipsim.solve.scene_entries.entry_name`) for the argument types every run
passes (:data:`~recipsim.solve.scene_entries.ENTRY_SIGNATURE`) into numba's cache, from
which the parent then loads it. The parent meanwhile loads the case, builds the property
table and its model (which compiles the table's own functions), then compiles the cycle
table's sample outputs and pinned reactions (:func:`compile_outputs_while_waiting`), and
waits for the child only then, before it integrates (:func:`wait_for_compile_ahead`).
The child only pays where it has a core to itself: it starts when the machine has two
cores that other work leaves idle now (:func:`recipsim.machine_load.idle_cores`, as for
the figure processes), nothing of the solver is cached and ``RECIPSIM_COMPILE_AHEAD`` is
not ``0`` (``1`` starts it whatever the load). Forced on at a load average of 2 on 2
cores (no idle core) it saved no wall time and cost up to 8 s of CPU. A child that fails
changes nothing: the parent then compiles as it would have. Measured first runs: README,
"Time to answer", and docs/speed.md.
"""

from __future__ import annotations

import json
import logging
import os
import subprocess
import sys
import time
from pathlib import Path
from typing import TYPE_CHECKING

from recipsim import timeline
from recipsim.cache_dirs import numba_cache_lacks

if TYPE_CHECKING:
    from recipsim.model.build import Model

logger = logging.getLogger(__name__)

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


#: Looks at the load before the child is given up: a task runnable for a moment (the end
#: of the command before, 1 % of the reads on a quiet machine) must not keep a child
#: that saves 6 s from starting; work that keeps a core busy shows in every look.
_LOOKS = 5


def _idle_cores() -> float:
    """Cores other work leaves idle now (:func:`recipsim.machine_load.idle_cores`; 0
    where the load is unknown): the most of up to :data:`_LOOKS` looks 5 ms apart."""
    from recipsim.machine_load import idle_cores

    idle = 0
    for look in range(_LOOKS):
        if look:
            time.sleep(0.005)
        idle = max(idle, idle_cores(2, unknown=0))
        if idle >= 2:
            break
    return float(idle)


def wait_for_compile_ahead() -> None:
    """Wait for the compiling child, if one was started (at most :data:`WAIT_LIMIT`)."""
    if not _pending:
        return
    timeline.mark("waiting for the compiling child")
    while _pending:
        child = _pending.pop()
        try:
            child.wait(timeout=WAIT_LIMIT)
        except subprocess.TimeoutExpired:
            child.kill()
            child.wait()
    timeline.mark("compiling child done")


def compile_outputs_while_waiting(model: Model) -> None:
    """While the compiling child compiles the solver, compile here what the cycle table
    runs after the solve: the scene's sample outputs and, on the rigid crank, the pinned
    reactions, by evaluating them once at the model's start state (the same argument
    types as the cycle table's): this process, which has built its table and would only
    wait, spends that time (1.9 s of CPU for the default case) before the solve instead
    of after it. Nothing when no child is pending."""
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
    timeline.mark("outputs compiled ahead")


def compile_in_child() -> None:
    """The child's work (``sys.argv``: case, JSON list of overrides, ``1`` to allow
    external paths): compile the entry the case starts with (its options and solver
    settings alone, :func:`recipsim.case.load.load_case_settings`) for the argument types
    every run passes (:data:`recipsim.solve.scene_entries.ENTRY_SIGNATURE`), without
    loading the rest of the case or its refrigerant (CoolProp's import alone is 1.9 s).
    Any failure ends it quietly (the parent compiles then)."""
    from recipsim.case.load import load_case_settings
    from recipsim.solve.scene_entries import compile_entry, entry_name

    timeline.mark("imports")
    try:
        path, overrides, external = sys.argv[1], json.loads(sys.argv[2]), sys.argv[3] == "1"
        name = entry_name(*load_case_settings(path, overrides, allow_external_paths=external))
        if name is not None:
            compile_entry(name)
            timeline.mark(f"{name} compiled")
    except Exception:
        status = 1
    else:
        status = 0
    timeline.flush("compiling child")
    # the entry is in numba's cache: skip the interpreter's teardown of numba's and
    # LLVM's objects (0.5-0.7 s that the parent waited for)
    os._exit(status)
