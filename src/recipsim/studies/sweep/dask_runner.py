"""Run sweep points on an existing Dask distributed cluster.

Like the local runners of :mod:`recipsim.studies.sweep.runner` (whose callbacks,
batches and :class:`~recipsim.studies.sweep.runner.WorkerLost` it shares), it calls
``on_result(task, result)`` in the calling process once per point as soon as that point
is finished. The cluster's workers need not share this machine's file system, so the
caller saves every record.
"""

from __future__ import annotations

import re
import sys
from collections.abc import Sequence
from typing import Any

from recipsim.errors import CaseError, RecipsimError
from recipsim.studies.sweep.dask_plugin import PrepareWorker
from recipsim.studies.sweep.runner import (
    ResultCallback,
    StartCallback,
    WorkerLost,
    chunk_size,
    nothing,
)
from recipsim.studies.sweep.worker import FAILED, PointTask, run_points, worker_version
from recipsim.version import __version__

_SCHEDULER_ADDRESS = re.compile(r"(tcp|tls|ws|wss|inproc|ucx)://[^\s/]+(:\d+)?/?")


def _prepare_dask_workers(client: Any, first: PointTask) -> None:
    """Register :class:`~recipsim.studies.sweep.dask_plugin.PrepareWorker` on the
    cluster: every worker, present or joining later, loads the solver and the base case
    once."""
    plugin = PrepareWorker(first.case, first.allow_external_paths)
    register = getattr(client, "register_plugin", None) or client.register_worker_plugin
    try:
        register(plugin, name="recipsim-prepare")
    except Exception as exc:  # a worker that cannot prepare fails its points, said there
        print(f"recipsim: could not prepare the Dask workers ({exc})", file=sys.stderr)


def check_scheduler_address(address: str) -> None:
    """Refuse an address that is not ``PROTOCOL://HOST[:PORT]`` before connecting.

    Raises
    ------
    CaseError
        Naming ``--scheduler`` and the allowed form.
    """
    if not _SCHEDULER_ADDRESS.fullmatch(address):
        raise CaseError(
            "--scheduler",
            "",
            f"{address!r} is not a scheduler address; expected PROTOCOL://HOST:PORT, e.g. "
            "tcp://127.0.0.1:8786",
        )


def probe_scheduler(address: str, timeout: float) -> None:
    """Check that a ``tcp://`` address answers like a Dask scheduler within ``timeout``.

    A Dask scheduler sends its handshake as soon as a connection opens; a server that
    accepts the connection and stays silent (not Dask) would leave ``Client`` waiting
    for minutes. Other protocols are left to ``Client``'s own timeout.

    Raises
    ------
    RecipsimError
        Nothing listens there, or what listens sends nothing within ``timeout`` [s].
    """
    import socket

    protocol, _, location = address.partition("://")
    if protocol != "tcp":
        return
    host, _, port = location.rstrip("/").rpartition(":")
    if not port.isdigit():
        host, port = location.rstrip("/"), "8786"
    try:
        with socket.create_connection((host.strip("[]"), int(port)), timeout=timeout) as sock:
            sock.settimeout(timeout)
            if not sock.recv(1):
                raise RecipsimError(f"the server at {address} closed the connection: not Dask")
    except TimeoutError:
        raise RecipsimError(
            f"no Dask scheduler answers at {address} within {timeout:g} s (--scheduler-timeout)"
        ) from None
    except OSError as exc:
        raise RecipsimError(
            f"cannot reach the Dask scheduler at {address}: {exc.strerror or exc}"
        ) from None


def _check_worker_version(client: Any, address: str) -> None:
    """Refuse workers that cannot import recipsim or run another version of it."""
    try:
        remote = client.submit(worker_version, pure=False).result(timeout=120)
    except Exception as exc:
        raise RecipsimError(
            f"the Dask workers at {address} cannot run recipsim ({type(exc).__name__}: "
            f"{exc}); install recipsim {__version__} in the workers' environment"
        ) from None
    if remote != __version__:
        raise RecipsimError(
            f"the Dask workers run recipsim {remote}, this is {__version__}; results "
            "would not be comparable"
        )


def _collect(client: Any, futures: dict[Any, list[PointTask]], on_result: ResultCallback) -> None:
    """Hand each finished batch's results to ``on_result``; a batch whose worker was
    killed is retried point by point, and a point that kills its worker repeatedly is
    ``failed``.

    Raises
    ------
    WorkerLost
        When the cluster fails during the sweep.
    """
    from dask.distributed import as_completed
    from distributed.scheduler import KilledWorker

    pending = as_completed(futures, loop=client.loop)
    for future in pending:
        batch = futures[future]
        try:
            results = future.result()
        except KilledWorker as exc:
            if len(batch) > 1:  # find the point that kills: one by one
                for task in batch:
                    single = client.submit(
                        run_points, [task], key=f"recipsim-point-{task.point_id}"
                    )
                    futures[single] = [task]
                    pending.add(single)
                continue
            results = [
                {
                    "status": FAILED,
                    "message": f"the point killed its Dask worker repeatedly ({exc})",
                    "summary": {},
                }
            ]
        except Exception as exc:
            raise WorkerLost(
                f"the Dask cluster failed during the sweep ({type(exc).__name__}: {exc})"
            ) from None
        for task, result in zip(batch, results, strict=True):
            on_result(task, result)


def run_dask(
    tasks: Sequence[PointTask],
    address: str,
    on_result: ResultCallback,
    on_start: StartCallback = nothing,
    connect_timeout: float = 10.0,
) -> None:
    """Run the points on an existing Dask distributed cluster.

    Parameters
    ----------
    tasks : sequence of PointTask
    address : str
        Scheduler address, e.g. ``tcp://127.0.0.1:8786``.
    on_result, on_start : callable
        See the module docstring.
    connect_timeout : float
        Seconds to wait for the scheduler [s].

    Raises
    ------
    RecipsimError
        When Dask is not installed, the scheduler cannot be reached, or the workers
        cannot import this version of recipsim.
    WorkerLost
        When the cluster goes away during the sweep.
    """
    try:
        from dask.distributed import Client
    except ImportError:
        raise RecipsimError(
            "--scheduler needs Dask distributed: pip install 'dask[distributed]' "
            "(or pip install 'recipsim[dask]')"
        ) from None
    check_scheduler_address(address)
    probe_scheduler(address, connect_timeout)
    try:
        client = Client(address, timeout=connect_timeout, set_as_default=False)
    except Exception as exc:  # OSError on a timeout, ValueError on a malformed address
        reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise RecipsimError(
            f"cannot reach the Dask scheduler at {address} within {connect_timeout:g} s: {reason}"
        ) from None
    try:
        _check_worker_version(client, address)
        if tasks:
            _prepare_dask_workers(client, tasks[0])
        workers = max(1, len(client.scheduler_info().get("workers", {})))
        size = chunk_size(0.0, len(tasks), workers)
        futures = {}
        for start in range(0, len(tasks), size):
            batch = list(tasks[start : start + size])
            key = f"recipsim-points-{batch[0].point_id}-{len(batch)}"
            futures[client.submit(run_points, batch, key=key, pure=False)] = batch
        on_start()
        try:
            _collect(client, futures, on_result)
        except BaseException:
            client.cancel([f for f in futures if not f.done()])
            raise
    finally:
        client.close()
