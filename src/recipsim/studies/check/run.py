"""Check a set of cases, one after the other or in worker processes (``recipsim check``)."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from pathlib import Path

from recipsim.studies.check.expectations import Expectation, expectations_for, find_cases
from recipsim.studies.check.judge import CheckRow, check_case


def _check_job(args: tuple[Path, Expectation, tuple[str, ...], bool]) -> CheckRow:
    return check_case(*args)


def run_check(
    paths: Iterable[Path],
    overrides: Sequence[str] = (),
    fast: bool = False,
    jobs: int = 1,
    expectations_file: Path | None = None,
    progress: Callable[[CheckRow], None] | None = None,
) -> list[CheckRow]:
    """Check every case named by ``paths`` (files or directories), in file order.

    Parameters
    ----------
    paths : iterable of Path
        Case files or directories of case files.
    overrides : sequence of str
        ``KEY=VALUE`` applied to every case (after the fast settings).
    fast : bool
        Apply the fast settings
        (:data:`~recipsim.studies.check.expectations.FAST_OVERRIDES` and the
        expectations' ``fast``).
    jobs : int
        Worker processes; 1 runs every case in this process, one after the other.
    expectations_file : Path, optional
        Instead of the ``expectations.toml`` beside the cases.
    progress : callable, optional
        Called with each row as it is finished.

    Raises
    ------
    CaseError
        For missing paths or an invalid expectations file (cases themselves never raise).
    """
    files = find_cases(paths)
    expectations = expectations_for(files, expectations_file)
    tasks = [(f, e, tuple(overrides), fast) for f, e in zip(files, expectations, strict=True)]
    rows: list[CheckRow] = []
    if jobs <= 1 or len(tasks) == 1:
        for task in tasks:
            rows.append(_check_job(task))
            if progress is not None:
                progress(rows[-1])
        return rows
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(max_workers=min(jobs, len(tasks))) as pool:
        for row in pool.map(_check_job, tasks):
            rows.append(row)
            if progress is not None:
                progress(row)
    return rows
