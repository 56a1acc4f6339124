"""Finished points on disk and the sweep's tables, all written whole or detected torn.

Layout of a sweep's output directory ``<out>/<name>/``, ``<out>/<name>+<digest>/`` with
``--set`` overrides (:func:`recipsim.report.case_report.report_name`, as ``recipsim run``)::

    overrides.json           the --set overrides the sweep runs with (and their digest)
    points/<run>-<pid>-<n>.jsonl
                             finished points, a line each (status, message, summary),
                             one segment per process that saved them (:mod:`.record_segments`)
    points/<point_id>.json   a finished point saved before record format 4 (still read)
    reports/<point_id>/      per-point reports (with --reports)
    summary.csv              one row per point, in sweep order
    summary.parquet          the same table (with --parquet)
    map_*.png                map plots
    sweep.toml               the sweep file as run
    provenance.json          versions, command, counts and timings

Every file but the segments is written to a temporary file in the same directory and
renamed over its destination (:func:`os.replace`), so a killed sweep leaves either the
old file or the new one, never half of one. A point's record is appended to its
process's segment in one write (:mod:`.record_segments`): a killed sweep leaves at most one line
cut short, which is not trusted. Each record carries the point's inputs (its overrides,
whose case its id hashes), when it was saved and a SHA-256 checksum of its content: a
record that cannot be read, whose checksum does not match (a hand edit, an injected
column) or whose inputs are not the planned point's counts as missing and the point is
computed again; of two records of a point (``--retry-failed``), the later counts.
Nothing on disk is trusted that recipsim did not write for this point.
"""

from __future__ import annotations

import hashlib
import json
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from recipsim.atomic import atomic_file, clean_stale_temporary_files
from recipsim.errors import CaseError
from recipsim.report.case_report import overrides_digest
from recipsim.studies.sweep import record_segments
from recipsim.studies.sweep.worker import STATUSES, PointTask, run_point

#: A point file larger than this is not read (it was not written by recipsim) [bytes]: the
#: limit of a segment's line.
_MAX_RECORD_BYTES = record_segments.MAX_LINE_BYTES

#: format of a point record: 4, a line of a segment (:mod:`.record_segments`); files of one point
#: each, 3 (checksum over the keys in order) and 2 (over the keys sorted), are still read
FORMAT = 4


def _canonical(body: dict[str, Any], sort_keys: bool = False) -> str:
    """A record's JSON as its checksum reads it: ASCII, NaN allowed, other objects as
    str; keys in their order (the summary's column order is kept), or sorted (records
    of format 2)."""
    return json.dumps(body, sort_keys=sort_keys, allow_nan=True, default=str, ensure_ascii=True)


def record_checksum(record: dict[str, Any]) -> str:
    """SHA-256 of a point record's JSON (:func:`_canonical`), its ``checksum`` field left
    out (keys sorted for a record of format 2)."""
    body = {k: v for k, v in record.items() if k != "checksum"}
    return hashlib.sha256(_canonical(body, record.get("format") == 2).encode()).hexdigest()


def record_bytes(record: dict[str, Any]) -> bytes:
    """A point record as its file holds it: its JSON with the ``checksum`` of that text
    (:func:`record_checksum`) added as the last key, encoded once."""
    text = _canonical(record)
    checksum = hashlib.sha256(text.encode()).hexdigest()
    return f'{text[:-1]}, "checksum": "{checksum}"}}'.encode()


class PointStore:
    """The ``points/`` directory of one sweep.

    Parameters
    ----------
    root : Path
        The sweep's output directory ``<out>/<name>``.
    """

    def __init__(self, root: Path) -> None:
        self.root = Path(root)
        self.points = self.root / "points"
        self.reports = self.root / "reports"
        self._index: dict[str, dict[str, Any]] | None = None  # segments' records, read once
        self._point_files = False  # whether points/ holds files of earlier formats

    def path(self, point_id: str) -> Path:
        """File of a point as a sweep saved it before record format 4 (still read)."""
        return self.points / f"{point_id}.json"

    def report_dir(self, point_id: str) -> Path:
        """Per-point report directory."""
        return self.reports / point_id

    def check_links(self) -> None:
        """Refuse output folders that are symbolic links (``points/``, ``reports/``):
        recipsim writes and cleans only inside the folder the user pointed to.

        Raises
        ------
        CaseError
            Naming the folder.
        """
        for folder in (self.points, self.reports):
            if folder.is_symlink():
                raise CaseError(
                    str(folder),
                    "--out",
                    "is a symbolic link; recipsim does not follow links inside its output "
                    "folders (remove the link, or point --out elsewhere)",
                )

    def clean_temporaries(self) -> None:
        """Remove the temporary files that sweeps killed while writing left in
        ``points/``: only names recipsim makes (``.<stem>.<pid>-<n><suffix>.tmp``), only
        regular files, only where that process is gone."""
        if self.points.is_dir() and not self.points.is_symlink():
            clean_stale_temporary_files(self.points)

    def claim(self, overrides: Sequence[str], fresh: bool = False) -> None:
        """Record the sweep's ``--set`` overrides in ``overrides.json``, refusing to
        resume into a directory that recorded other ones.

        Overrides are compared by their digest
        (:func:`recipsim.report.case_report.overrides_digest`: order, spacing and
        repetition do not matter). A directory without the file (new, or written
        before it existed) is claimed. ``fresh`` (every point recomputed) claims a
        directory whatever it recorded.

        Raises
        ------
        CaseError
            The directory holds a sweep run with other overrides (and not ``fresh``).
        """
        path = self.root / "overrides.json"
        digest = overrides_digest(overrides)
        try:
            recorded = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            recorded = None
        if isinstance(recorded, dict) and recorded.get("digest") != digest and not fresh:
            raise CaseError(
                str(self.root),
                "--set",
                f"this sweep directory was run with other overrides "
                f"({recorded.get('overrides')!r}, not {list(overrides)!r}): refusing to "
                "resume into it; choose another --out, or --fresh to recompute every point",
            )
        with atomic_file(path) as handle:
            json.dump({"overrides": list(overrides), "digest": digest}, handle, indent=2)

    def clear(self) -> None:
        """Forget every finished point (``--fresh``)."""
        record_segments.close_segments(self.points)
        self._index = None
        if self.points.is_dir():
            for path in [*self.points.glob("*.json"), *record_segments.segments(self.points)]:
                path.unlink(missing_ok=True)

    def close(self) -> None:
        """Close this process's segments (the end of a sweep's computing)."""
        record_segments.close_segments(self.points)

    def load(self, point_id: str, overrides: Sequence[str]) -> dict[str, Any] | None:
        """The stored record of a point, or ``None`` if it is not finished.

        Parameters
        ----------
        point_id : str
        overrides : sequence of str
            The planned point's overrides: a record made for other inputs is ignored.
        """
        if self._index is None:
            self._index = _segment_records(self.points)
            self._point_files = self.points.is_dir() and any(self.points.glob("*.json"))
        record = self._index.get(point_id)
        if record is None and self._point_files:
            record = _point_file(self.path(point_id))
        if (
            record is None
            or record.get("point_id") != point_id
            or record.get("overrides") != list(overrides)
            or record.get("status") not in STATUSES
            or not isinstance(record.get("summary"), dict)
        ):
            return None
        return record

    def save(self, point_id: str, record: dict[str, Any]) -> None:
        """Append a point's record to this process's segment (``format``, ``point_id``,
        ``saved_ns`` and ``checksum`` are added)."""
        data = {"format": FORMAT, "point_id": point_id, **record, "saved_ns": time.time_ns()}
        data.pop("checksum", None)
        self._index = None  # read again at the next load
        line = record_bytes(data) + b"\n"
        record_segments.append_record(self.points, str(record.get("run", "run")), line)


def _checked(record: Any, formats: tuple[int, ...]) -> dict[str, Any] | None:
    """``record`` if it is a dictionary of one of ``formats`` whose checksum matches."""
    if (
        isinstance(record, dict)
        and record.get("format") in formats
        and record.get("checksum") == record_checksum(record)
    ):
        return record
    return None


def _segment_records(directory: Path) -> dict[str, dict[str, Any]]:
    """The records in the segments of ``directory`` by point id; of two records of one
    point, the one saved later."""
    found: dict[str, dict[str, Any]] = {}
    for line in record_segments.record_lines(directory):
        try:
            record = _checked(json.loads(line), (FORMAT,))
        except ValueError:
            continue
        if record is None or not isinstance(record.get("saved_ns"), int):
            continue
        pid = record.get("point_id")
        if not isinstance(pid, str):
            continue
        if pid not in found or found[pid]["saved_ns"] <= record["saved_ns"]:
            found[pid] = record
    return found


def _point_file(path: Path) -> dict[str, Any] | None:
    """The record of a point file (formats 2 and 3), or None."""
    try:
        if path.stat().st_size > _MAX_RECORD_BYTES:
            return None
        return _checked(json.loads(path.read_text(encoding="utf-8")), (2, 3))
    except (OSError, ValueError):
        return None


def point_record(task: PointTask, result: dict[str, Any], run_id: str) -> dict[str, Any]:
    """The record of a point that :class:`PointStore` keeps: its result (``status``,
    ``message``, ``summary``), its overrides, the run that computed it and when it
    finished."""
    return {
        "status": result["status"],
        "message": result["message"],
        "summary": result["summary"],
        "overrides": list(task.overrides),
        "run": run_id,
        "finished": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
    }


@dataclass(frozen=True)
class SolveAndSave:
    """Solve a point and write its record into the sweep's store, where it was solved.

    Used by the local process pool, whose workers share the parent's file system: each
    worker appends its own points' records to its own segment (:mod:`.record_segments`), so the
    parent only collects them: one process encoding, checksumming and writing the
    records of every worker would limit how fast many workers finish a map.

    Attributes
    ----------
    store : str
        The sweep's output directory (:class:`~recipsim.studies.sweep.store.PointStore`).
    run_id : str
        The identifier of the sweep run that computes the point.
    """

    store: str
    run_id: str

    def __call__(self, task: PointTask) -> dict[str, Any]:
        """Solve ``task`` (:func:`run_point`), save its record and return it."""
        record = point_record(task, run_point(task), self.run_id)
        PointStore(Path(self.store)).save(task.point_id, record)
        return record
