"""Solve one sweep point; this is the function that runs in the worker processes.

:func:`run_point` is a top-level function of an importable module taking and
returning plain picklable data, so it runs unchanged in a local process pool, in the
calling process and on Dask workers (which need recipsim installed). It never raises
for a point that goes wrong: the error becomes the point's ``status`` and
``message``.

Statuses (:mod:`recipsim.results.outcome`, shared with ``recipsim run``'s summary):
``ok`` (converged), ``no_delivery`` (converged, the discharge valve never opens:
discharge quantities NaN by design), ``subharmonic`` (a period of n revolutions; the row
holds n-revolution averages), ``not_converged`` (``solver.max_revolutions`` spent; the
message holds the diagnosis, the row the last revolution's values),
``outside_envelope`` (refused before integrating: :mod:`recipsim.case.envelope`),
``invalid`` (the case cannot be built: :class:`~recipsim.errors.CaseError`), ``failed``
(the integration or a property evaluation failed: :class:`~recipsim.errors.SolverError`,
another :class:`~recipsim.errors.RecipsimError`, or a library's ValueError or
ArithmeticError, with the stage it came from) and ``error`` (any other exception, a bug).
"""

from __future__ import annotations

import os
import signal
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any

from recipsim.case.case import Case
from recipsim.case.envelope import OutsideEnvelopeError
from recipsim.case.load import load_case
from recipsim.errors import CaseError, RecipsimError
from recipsim.pipeline import simulate_case, simulate_row
from recipsim.report.case_report import write_case_report
from recipsim.results.outcome import (
    FAILED,
    NO_DELIVERY,
    NOT_CONVERGED,
    OK,
    OUTSIDE_ENVELOPE,
    SUBHARMONIC,
)
from recipsim.studies.point_warnings import kept_warnings
from recipsim.version import __version__

INVALID = "invalid"
ERROR = "error"
STATUSES = (OK, NO_DELIVERY, SUBHARMONIC, NOT_CONVERGED, OUTSIDE_ENVELOPE, INVALID, FAILED, ERROR)
#: statuses whose row holds a solved revolution's values
SOLVED = (OK, NO_DELIVERY, SUBHARMONIC, NOT_CONVERGED)


@dataclass(frozen=True)
class PointTask:
    """What a worker needs to solve one point.

    Attributes
    ----------
    index : int
        Position of the point in the sweep.
    point_id : str
        Stable identifier of the point.
    case : str
        Absolute path of the base case file.
    overrides : tuple of str
        ``KEY=VALUE`` overrides applied to the base case.
    report_dir : str or None
        Write the point's report (as ``recipsim run`` does) into this directory.
    plots : bool
        With ``report_dir``: also draw the report's figures.
    allow_external_paths : bool
        See :func:`recipsim.case.load.load_case`.
    """

    index: int
    point_id: str
    case: str
    overrides: tuple[str, ...]
    report_dir: str | None = None
    plots: bool = False
    allow_external_paths: bool = False


def _plain(value: Any) -> Any:
    """numpy scalars to Python ones, so that a row pickles small and writes as JSON."""
    item = getattr(value, "item", None)
    if item is not None and not isinstance(value, (str, bytes)):
        try:
            return item()
        except (TypeError, ValueError):
            return value
    return value


def run_point(task: PointTask) -> dict[str, Any]:
    """Solve one point.

    Parameters
    ----------
    task : PointTask

    Returns
    -------
    dict
        ``status`` (see the module docstring), ``message`` (what went wrong, then the
        warnings the point's solve logged, :mod:`recipsim.studies.point_warnings`,
        joined by ``"; "``; ``""`` for an ``ok`` point without warnings) and
        ``summary``, the summary row of :func:`recipsim.results.tables.summary` (units
        in the keys; empty when the point could not be solved).
    """
    with kept_warnings() as warned:
        result = _solved_point(task)
    if warned:  # after the status's own message, if any
        result["message"] = "; ".join(m for m in (result["message"], *warned) if m)
    return result


def _solved_point(task: PointTask) -> dict[str, Any]:
    """:func:`run_point`'s result before the point's warnings are added to its message."""
    try:
        argv = ["recipsim", "sweep", f"point {task.point_id}"]
        case = point_case(task.case, task.overrides, task.allow_external_paths)
        if task.report_dir is None:  # only the summary row is kept: no cycle table
            row = {k: _plain(v) for k, v in simulate_row(case).items()}
        else:
            run = simulate_case(case, argv)
            row = {k: _plain(v) for k, v in run.row.items()}
            write_case_report(run, Path(task.report_dir), list(task.overrides), task.plots)
    except OutsideEnvelopeError as exc:
        return {"status": OUTSIDE_ENVELOPE, "message": exc.message, "summary": {}}
    except CaseError as exc:
        return {"status": INVALID, "message": str(exc), "summary": {}}
    except RecipsimError as exc:
        return {"status": FAILED, "message": str(exc), "summary": {}}
    except (ValueError, ArithmeticError) as exc:  # a library's error outside the guarded stages
        return {"status": FAILED, "message": f"{type(exc).__name__}: {exc}", "summary": {}}
    except Exception as exc:  # a bug: keep the sweep going, say what it was
        return {"status": ERROR, "message": f"{type(exc).__name__}: {exc}", "summary": {}}
    # the row's status and its message become the sweep's own columns
    status = str(row.pop("status", OK if row.get("converged [-]") else NOT_CONVERGED))
    return {"status": status, "message": str(row.pop("status_message", "")), "summary": row}


def run_points(
    tasks: list[PointTask], solve: Callable[[PointTask], dict[str, Any]] = run_point
) -> list[dict[str, Any]]:
    """Solve a batch of points in order with ``solve`` (default :func:`run_point`); one
    round trip to a worker for several points."""
    return [solve(task) for task in tasks]


def point_case(path: str, overrides: tuple[str, ...], allow_external_paths: bool) -> Case:
    """The case of one point: the base case, read and validated once per process, with
    the point's overrides applied and validated (:meth:`~recipsim.case.load.Case.with_`,
    which validates again only the sections the overrides reach).

    Equal to ``load_case(path, overrides)`` (same values, same errors), without reading
    and validating the whole case at every point: the base file, its ``extends`` chain
    and its refrigerant file are read once (again when the base file or its refrigerant
    file changes). A base case
    that is invalid by itself (a point's overrides may complete it) is loaded whole at
    every point instead.

    Raises
    ------
    CaseError
        As :func:`recipsim.case.load.load_case`.
    """
    base = _base_case(path, allow_external_paths, _stamp(path))
    if base is not None and _stamp(base[0].refrigerant.path) != base[1]:
        _base_case.cache_clear()  # the refrigerant file changed: read everything again
        base = _base_case(path, allow_external_paths, _stamp(path))
    if base is None:
        return load_case(path, list(overrides), allow_external_paths=allow_external_paths)
    return base[0].with_(list(overrides))


def _stamp(path: str) -> tuple[int, int]:
    """Modification time and size of a file (0, 0 if unreadable): a base case edited
    during a long sweep is read again."""
    try:
        info = os.stat(path)
    except OSError:
        return (0, 0)
    return (info.st_mtime_ns, info.st_size)


@lru_cache(maxsize=8)
def _base_case(
    path: str, allow_external_paths: bool, stamp: tuple[int, int]
) -> tuple[Case, tuple[int, int]] | None:
    """The base case without overrides and the stamp of its refrigerant file, or None if
    the case is invalid by itself."""
    del stamp  # part of the cache key only
    try:
        case = load_case(path, allow_external_paths=allow_external_paths)
    except CaseError:
        return None
    return case, _stamp(case.refrigerant.path)


def prepare_worker(case: str, allow_external_paths: bool) -> None:
    """Load the solver's modules, the base case and its property table in this process
    (a Dask worker as it starts, see :mod:`recipsim.studies.sweep.dask_plugin`)."""
    _base_case(case, allow_external_paths, _stamp(case))


def worker_version() -> str:
    """recipsim version of a (remote) worker, checked before a Dask sweep starts."""
    return __version__


def init_worker() -> None:
    """Initializer of the local worker processes.

    Ctrl-C is left to the parent (which stops submitting and collects the points in
    progress); a worker whose parent died (killed sweep) exits by itself within a
    second instead of lingering.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    parent = os.getppid()

    def watch() -> None:
        while True:
            time.sleep(0.5)
            if os.getppid() != parent:
                os._exit(1)

    threading.Thread(target=watch, name="recipsim-parent-watch", daemon=True).start()
