"""Finished points on disk and the sweep's tables, all written atomically.

Layout of a sweep's output directory ``<out>/<name>/``::

    points/<point_id>.json   one file per finished point (status, message, summary)
    reports/<point_id>/      per-point reports (with --reports)
    summary.csv              one row per point, in sweep order
    summary.parquet          the same table (with --parquet)
    map_*.png                map plots
    sweep.toml               the sweep file as run
    provenance.json          versions, command, counts and timings

Every file is written to a temporary file in the same directory and renamed over its
destination (:func:`os.replace`), so a killed sweep leaves either the old file or the
new one, never half of one. A point file that cannot be read (which only a hand
edit can cause) counts as missing and the point is computed again.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from ..atomic import atomic_file
from .worker import STATUSES

FORMAT = 1


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

    def path(self, point_id: str) -> Path:
        """Result file of a point."""
        return self.points / f"{point_id}.json"

    def report_dir(self, point_id: str) -> Path:
        """Per-point report directory."""
        return self.reports / point_id

    def clean_temporaries(self) -> None:
        """Remove temporary files left by a sweep killed while writing."""
        if self.points.is_dir():
            for tmp in self.points.glob(".*.tmp"):
                tmp.unlink(missing_ok=True)

    def clear(self) -> None:
        """Forget every finished point (``--fresh``)."""
        if self.points.is_dir():
            for path in self.points.glob("*.json"):
                path.unlink(missing_ok=True)

    def load(self, point_id: str) -> dict[str, Any] | None:
        """The stored record of a point, or ``None`` if it is not finished."""
        try:
            record = json.loads(self.path(point_id).read_text())
        except (OSError, ValueError):
            return None
        if (
            not isinstance(record, dict)
            or record.get("format") != FORMAT
            or record.get("point_id") != point_id
            or record.get("status") not in STATUSES
            or not isinstance(record.get("summary"), dict)
        ):
            return None
        return record

    def save(self, point_id: str, record: dict[str, Any]) -> None:
        """Write a point's record atomically (``format`` and ``point_id`` are added)."""
        data = {"format": FORMAT, "point_id": point_id, **record}
        with atomic_file(self.path(point_id)) as handle:
            json.dump(data, handle, indent=1, allow_nan=True)
