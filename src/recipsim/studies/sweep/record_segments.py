"""A sweep's point records as lines appended to segment files, one segment per process.

Creating a file is the costliest step of saving a point, far costlier than appending the
same record to a file already open, so each process that saves points appends to
segments of its own, ``points/<run>-<pid>-<n>.jsonl``: created exclusively and opened
once, never shared with another process and never opened again once closed. A record is
one line (its JSON text with its checksum,
:func:`recipsim.studies.sweep.store.record_bytes`) handed to the system in one write. A
process killed while writing leaves at most the last line of its own segment cut short;
that line fails to parse or its checksum, is skipped, and its point is computed again. A
write that fails closes the segment: the next record starts a new one rather than follow
a partial line.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path

from recipsim.atomic import create_new_file, write_all

#: A line longer than this is not read (recipsim did not write it) [bytes].
MAX_LINE_BYTES = 10_000_000

#: Open segments of this process: (process id, points directory, run) -> descriptor.
_OPEN: dict[tuple[int, str, str], int] = {}


def append_record(directory: Path, run: str, line: bytes) -> None:
    """Append ``line`` (a record ending in a newline) to this process's segment of
    ``run`` in ``directory``, opening one (and the directory) first if needed."""
    key = (os.getpid(), str(directory), run)
    fd = _OPEN.get(key)
    if fd is None:
        fd = _OPEN[key] = _open_segment(directory, run)
    try:
        write_all(fd, line)
    except BaseException:
        del _OPEN[key]
        os.close(fd)
        raise


def _open_segment(directory: Path, run: str) -> int:
    """A new segment ``<run>-<pid>-<n>.jsonl`` in ``directory``, created exclusively,
    readable by its owner only, open for appending."""
    pid = os.getpid()
    fd, _ = create_new_file(lambda n: str(directory / f"{run}-{pid}-{n}.jsonl"), os.O_APPEND)
    return fd


def close_segments(directory: Path) -> None:
    """Close this process's open segments in ``directory`` (what they hold stays)."""
    pid, where = os.getpid(), str(directory)
    for key in [k for k in _OPEN if k[0] == pid and k[1] == where]:
        os.close(_OPEN.pop(key))


def segments(directory: Path) -> list[Path]:
    """The segment files in ``directory``, by name."""
    return sorted(directory.glob("*.jsonl")) if directory.is_dir() else []


def record_lines(directory: Path) -> Iterator[bytes]:
    """Every whole line of every segment in ``directory`` (without its newline); a line
    longer than :data:`MAX_LINE_BYTES` is skipped, a segment that cannot be read is
    passed over."""
    for path in segments(directory):
        try:
            with open(path, "rb") as handle:
                while line := handle.readline(MAX_LINE_BYTES + 1):
                    if line.endswith(b"\n"):
                        yield line[:-1]
                    elif len(line) > MAX_LINE_BYTES:  # skip the rest of an oversized line
                        while (rest := handle.readline(MAX_LINE_BYTES + 1)) and not rest.endswith(
                            b"\n"
                        ):
                            pass
                    # else: the segment's last line, cut short; not trusted
        except OSError:
            continue
