"""The warnings logged while one of many points is solved, kept with the point.

A point's physics can warn (a reed valve that lets more than 3 % of its gas flow back,
:func:`recipsim.results.valve_metrics.warn_large_backflow`). ``recipsim run`` prints
such a warning for its one case; a sweep of many points keeps each warning with the
point it belongs to rather than printing a line per warning that names no point. Inside
:func:`kept_warnings` the records of :data:`POINT_LOGGERS` go to a list instead of the
log: a sweep point's ``message`` column carries them
(:func:`recipsim.studies.sweep.worker.run_point`), a calibration drops those of its
trial parameter sets and keeps those of the calibrated case's points in ``points.csv``
(:mod:`recipsim.studies.calibrate`).

Per thread (a Dask worker may solve points in several threads at once); outside
:func:`kept_warnings` the loggers log as usual.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Iterator
from contextlib import contextmanager

#: The loggers whose warnings belong to the point being solved.
POINT_LOGGERS = ("recipsim.results.valve_metrics",)


class _KeepPerThread(logging.Filter):
    """A logger filter that keeps a record in the current thread's list, if it has one,
    instead of letting it through."""

    def __init__(self) -> None:
        super().__init__()
        self.local = threading.local()

    def filter(self, record: logging.LogRecord) -> bool:
        kept: list[str] | None = getattr(self.local, "kept", None)
        if kept is None or record.levelno < logging.WARNING:
            return True
        kept.append(record.getMessage())
        return False


_KEEP = _KeepPerThread()
_INSTALL = threading.Lock()


def _install() -> None:
    with _INSTALL:
        for name in POINT_LOGGERS:
            logger = logging.getLogger(name)
            if _KEEP not in logger.filters:
                logger.addFilter(_KEEP)


@contextmanager
def kept_warnings() -> Iterator[list[str]]:
    """Keep, in the list yielded, the warnings (and errors) that :data:`POINT_LOGGERS`
    log in this thread meanwhile, instead of logging them."""
    _install()
    outer = getattr(_KEEP.local, "kept", None)
    kept: list[str] = []
    _KEEP.local.kept = kept
    try:
        yield kept
    finally:
        _KEEP.local.kept = outer
