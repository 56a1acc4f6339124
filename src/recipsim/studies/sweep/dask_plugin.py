"""Dask worker plugin of sweeps (imports ``distributed``: loaded only for ``--scheduler``)."""

from __future__ import annotations

from typing import Any

from distributed.diagnostics.plugin import WorkerPlugin

from recipsim.studies.sweep.worker import prepare_worker


class PrepareWorker(WorkerPlugin):  # type: ignore[misc]
    """Prepare each worker once, when it starts or joins the cluster: the solver's
    modules, the sweep's base case and its property table
    (:func:`recipsim.studies.sweep.worker.prepare_worker`), not at its first point.

    Parameters
    ----------
    case : str
        Absolute path of the sweep's base case.
    allow_external_paths : bool
        See :func:`recipsim.case.load.load_case`.
    """

    idempotent = True

    def __init__(self, case: str, allow_external_paths: bool) -> None:
        self.case = case
        self.allow_external_paths = allow_external_paths

    def setup(self, worker: Any) -> None:
        """Called by Dask on each worker; an error here shows again at the points."""
        try:
            prepare_worker(self.case, self.allow_external_paths)
        except Exception:  # an invalid base case: each point reports it
            pass
