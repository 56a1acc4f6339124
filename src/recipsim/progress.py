"""What recipsim says while a user waits, and how long the waits took on this machine.

Every step that may take more than about a second says so before it starts, as one line
through :mod:`logging` (the ``"recipsim"`` logger, level INFO): building a property table,
compiling a piece of recipsim's code (numba), drawing a sweep's maps. The command line
shows these lines on standard error (``recipsim: ...``, off with ``--quiet``); the Python
API shows them on standard error too while a call runs (``progress=False`` keeps them
off), unless the program has configured :mod:`logging` itself, whose settings then
decide (:func:`notes_shown`).

The one-off steps (a property table, numba's compilation of a function: both cached
afterwards, see ``docs/caches.md``) are timed, and their durations kept in
``<recipsim cache>/durations.json``: the next time such a step is needed (another
refrigerant, a new version of recipsim's compiled code, an emptied cache) its line quotes
the duration measured last time on this machine. Without a measurement, no number is
given: a figure measured elsewhere would be wrong here by a factor of several.

Compilation is noticed through numba's compile events (``numba.core.event``), which
numba sends only when a function is not found in its cache: the line comes before the
compilation, and nothing is said when the cache holds the function.
"""

from __future__ import annotations

import json
import logging
import math
import sys
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from functools import cache
from pathlib import Path
from typing import Any

from recipsim.atomic import atomic_file
from recipsim.cache_dirs import cache_dir, private_dir

logger = logging.getLogger("recipsim")

#: Steps shorter than this [s] (as last measured) are noted at DEBUG, not INFO.
NOTE_THRESHOLD = 1.0

#: What recipsim's compiled modules hold, for the notes.
_COMPILED_MODULES = {
    "recipsim.solve.integrator": "the solver",
    "recipsim.model.scene_functions": "the scene's physics",
    "recipsim.physics.thermo.table_solves": "the property table's solver",
    "recipsim.physics.thermo.property_table": "the property table's interpolation",
}
#: Compiled functions known to take more than a second to compile (noted at INFO before
#: their first measurement; any other once measured above :data:`NOTE_THRESHOLD`).
_SLOW_TO_COMPILE = (
    "recipsim.solve.integrator.",
    "recipsim.model.scene_functions.rhs_pointer",
    "recipsim.physics.thermo.table_solves.solve_state",
    "recipsim.physics.thermo.property_table.evaluate_many",
)

_lock = threading.Lock()


# ---- measured durations ------------------------------------------------------------------
def durations_file() -> Path:
    """The file keeping the measured durations: ``<recipsim cache>/durations.json``."""
    return cache_dir() / "durations.json"


def _read_durations() -> dict[str, float]:
    try:
        data = json.loads(durations_file().read_text())
    except (OSError, ValueError):  # none yet, unreadable or not JSON: nothing measured
        return {}
    if not isinstance(data, dict):
        return {}
    return {
        str(k): float(v)
        for k, v in data.items()
        if isinstance(v, (int, float)) and math.isfinite(v) and v > 0.0
    }


def last_duration(key: str) -> float | None:
    """The duration [s] of step ``key`` measured last on this machine, or None."""
    return _read_durations().get(key)


def record_duration(key: str, seconds: float) -> None:
    """Keep ``seconds`` as the last measured duration of step ``key`` (best effort: a
    cache folder that cannot be written is passed over in silence, the step's own cache
    reports it)."""
    with _lock:
        durations = {**_read_durations(), key: float(seconds)}
        text = json.dumps(durations, indent=1, sort_keys=True)
        try:
            path = durations_file()
            private_dir(path.parent)
            with atomic_file(path) as handle:
                handle.write(text)
        except OSError:
            pass


def estimate(key: str, fallback: str | None = None) -> str:
    """``"; 5.4 s last time on this machine"`` from the last measurement of ``key`` (or
    of ``fallback``, a similar step), else ``""``."""
    seconds = last_duration(key)
    if seconds is None and fallback is not None:
        seconds = last_duration(fallback)
    return "" if seconds is None else f"; {seconds:.1f} s last time on this machine"


@contextmanager
def timed_step(
    key: str, doing: str, detail: str = "once per installation", fallback: str | None = None
) -> Iterator[None]:
    """Say ``"<doing> (<detail>[; <estimate>])"`` at INFO (:func:`estimate`), run the
    block, and record its duration under ``key`` (and ``fallback``) when it ends without
    an error."""
    logger.info("%s (%s%s)", doing, detail, estimate(key, fallback))
    start = time.perf_counter()
    yield
    elapsed = time.perf_counter() - start
    record_duration(key, elapsed)
    if fallback is not None:
        record_duration(fallback, elapsed)


# ---- numba's compilations ----------------------------------------------------------------
def compile_key(qualified_name: str) -> str:
    """The key of a function's compilation in ``durations.json``."""
    return f"compile {qualified_name}"


def watch_compilations() -> None:
    """Note and time every compilation of a recipsim function by numba (once per
    process; called as ``recipsim`` is imported)."""
    _compile_listener()


@cache
def _compile_listener() -> Any:
    from numba.core import event

    class CompileListener(event.Listener):
        """Notes the outermost compilation of a recipsim function (those it calls are
        compiled inside it, and counted in its time) and records its duration."""

        def __init__(self) -> None:
            self.local = threading.local()

        def on_start(self, ev: Any) -> None:
            depth = getattr(self.local, "depth", 0)
            self.local.depth = depth + 1
            if depth == 0:
                function = getattr(ev.data.get("dispatcher"), "py_func", None)
                module = getattr(function, "__module__", None) or ""
                name = f"{module}.{getattr(function, '__name__', '')}"
                self.local.started = (name, time.perf_counter())
                if module.startswith("recipsim."):
                    _note_compilation(name)

        def on_end(self, ev: Any) -> None:
            self.local.depth = max(getattr(self.local, "depth", 1) - 1, 0)
            started = getattr(self.local, "started", None)
            if self.local.depth == 0 and started is not None:
                self.local.started = None
                name, start = started
                if name.startswith("recipsim."):  # (a failed compilation ends the run)
                    record_duration(compile_key(name), time.perf_counter() - start)

    listener = CompileListener()
    event.register("numba:compile", listener)
    return listener


def _note_compilation(name: str) -> None:
    """The line before compiling ``name``: INFO where it took a second or more last time,
    or was never measured and is one of :data:`_SLOW_TO_COMPILE`; DEBUG otherwise."""
    module, function = name.rsplit(".", 1)
    last = last_duration(compile_key(name))
    slow = last >= NOTE_THRESHOLD if last is not None else name.startswith(_SLOW_TO_COMPILE)
    what = _COMPILED_MODULES.get(module)
    logger.log(
        logging.INFO if slow else logging.DEBUG,
        "compiling %s (%sonce per installation%s)",
        what or name,
        f"{function}; " if what else "",
        estimate(compile_key(name)),
    )


# ---- showing the notes -------------------------------------------------------------------
class StandardErrorHandler(logging.StreamHandler):  # type: ignore[type-arg]
    """Writes ``recipsim: <message>`` to the standard error of the moment (a notebook or
    a test may replace it)."""

    def __init__(self) -> None:
        super().__init__()
        self.setFormatter(logging.Formatter("recipsim: %(message)s"))

    @property  # type: ignore[override]
    def stream(self) -> Any:
        return sys.stderr

    @stream.setter
    def stream(self, value: Any) -> None:
        pass


def show_notes(show: bool) -> None:
    """Show recipsim's notes on standard error from now on (the command line), or only
    its warnings (``show`` False: ``--quiet``)."""
    if not any(isinstance(h, StandardErrorHandler) for h in logger.handlers):
        logger.addHandler(StandardErrorHandler())
    logger.setLevel(logging.INFO if show else logging.WARNING)


@contextmanager
def notes_shown(show: bool = True) -> Iterator[None]:
    """Show recipsim's notes on standard error while the block runs (an API call), where
    nothing else decides: the program has configured no logging handler (on the root
    logger or recipsim's) and set no level on recipsim's logger. ``show`` False keeps
    the notes off (warnings still show, as Python shows them by default)."""
    configured = logger.handlers or logging.getLogger().handlers or logger.level
    if configured or not show:
        yield
        return
    handler = StandardErrorHandler()
    logger.addHandler(handler)
    logger.setLevel(logging.INFO)
    try:
        yield
    finally:
        logger.removeHandler(handler)
        logger.setLevel(logging.NOTSET)
