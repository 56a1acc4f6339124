"""Compare every value of the summary tables of two report trees.

    python benchmarks/compare_summaries.py OLD_DIR NEW_DIR [--rtol 1e-12]

Each ``summary.csv`` below ``OLD_DIR`` is matched with the file at the same relative
path below ``NEW_DIR``; rows are matched in order (a sweep's rows by ``point_id``). Text
cells must be equal; numbers equal, or within ``--rtol`` relative where a float's last
digit may be printed differently; NaN matches NaN. Columns that time the run
(``wall_time [s]``) are skipped. Prints the count of values compared and every
difference; exits 1 if there is one.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import pandas as pd

SKIPPED = {"wall_time [s]"}


def compare_tables(old: pd.DataFrame, new: pd.DataFrame, rtol: float) -> tuple[int, list[str]]:
    """Values compared and the differences found between two summary tables."""
    problems: list[str] = []
    if "point_id" in old and "point_id" in new:
        old, new = old.set_index("point_id"), new.set_index("point_id")
        new = new.reindex(old.index)
    if list(old.columns) != list(new.columns):
        gone = [c for c in old.columns if c not in new.columns]
        added = [c for c in new.columns if c not in old.columns]
        problems.append(f"columns differ: missing {gone}, added {added}")
    count = 0
    for column in old.columns:
        if column in SKIPPED or column not in new.columns:
            continue
        for row, (a, b) in enumerate(zip(old[column], new[column], strict=True)):
            count += 1
            if not _same(a, b, rtol):
                problems.append(f"row {row}, {column}: {a!r} != {b!r}")
    return count, problems


def _same(a: object, b: object, rtol: float) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        if math.isnan(a) or math.isnan(b):
            return math.isnan(a) and math.isnan(b)
        return a == b or abs(a - b) <= rtol * max(abs(a), abs(b))
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return _same(float(a), float(b), rtol)
    return (pd.isna(a) and pd.isna(b)) if (pd.isna(a) or pd.isna(b)) else str(a) == str(b)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("old", type=Path)
    parser.add_argument("new", type=Path)
    parser.add_argument("--rtol", type=float, default=1e-12)
    args = parser.parse_args(argv)
    total, failures = 0, 0
    for old_file in sorted(args.old.rglob("summary.csv")):
        relative = old_file.relative_to(args.old)
        new_file = args.new / relative
        if not new_file.is_file():
            print(f"{relative}: missing in {args.new}")
            failures += 1
            continue
        count, problems = compare_tables(pd.read_csv(old_file), pd.read_csv(new_file), args.rtol)
        total += count
        failures += len(problems)
        print(f"{relative}: {count} values, {len(problems)} differences")
        for problem in problems[:20]:
            print(f"  {problem}")
    print(f"{total} values compared, {failures} differences")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
