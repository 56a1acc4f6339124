"""The column tables of ``reports/README.md``, generated from the column documentation.

Each table sits between two markers::

    <!-- columns: cycle (generated: python -m recipsim.report.column_readme) -->

    | column | meaning |
    ...

    <!-- end of columns -->

and is written from the table the marker names (:data:`TABLES`: the summary's
:mod:`recipsim.results.summary_docs`, the cycle's and the start-up's
:mod:`recipsim.results.column_docs`, whose layout columns take their meaning from the
layout tables). Everything outside the markers is the README's own prose and stays as
written.

``python -m recipsim.report.column_readme [README]`` rewrites the file (default
``reports/README.md``); with ``--check`` it writes nothing and exits 1 when the file is
not what the tables give.
"""

from __future__ import annotations

import argparse
import re
import sys
from collections.abc import Sequence
from pathlib import Path

from recipsim.results.column_docs import CYCLE_DOCS, STARTUP_DOCS, ColumnDoc
from recipsim.results.summary_docs import STARTUP_SUMMARY_DOCS, SUMMARY_DOCS

#: Tables by the key their marker gives.
TABLES: dict[str, tuple[ColumnDoc, ...]] = {
    "summary": SUMMARY_DOCS,
    "startup-summary": STARTUP_SUMMARY_DOCS,
    "startup": STARTUP_DOCS,
    "cycle": CYCLE_DOCS,
}
BEGIN = "<!-- columns: {key} (generated: python -m recipsim.report.column_readme) -->"
END = "<!-- end of columns -->"
_BLOCK = re.compile(r"^<!-- columns: (\S+) [^\n]*-->\n.*?^<!-- end of columns -->$", re.M | re.S)


def markdown_table(docs: Sequence[ColumnDoc]) -> list[str]:
    """Lines of the Markdown table ``| column | meaning |`` of ``docs``."""
    lines = ["| column | meaning |", "|---|---|"]
    for doc in docs:
        meaning = " ".join(doc.meaning.split())
        lines.append(f"| `{doc.column}` | {meaning} |")
    return lines


def render(text: str) -> str:
    """``text`` (a README) with every marked table written from its declarations.

    Raises
    ------
    ValueError
        If a marker names no table, or a table has no marker or more than one.
    """
    seen: list[str] = []

    def block(match: re.Match[str]) -> str:
        key = match.group(1)
        if key not in TABLES:
            raise ValueError(f"README marker names no column table: {key!r}")
        seen.append(key)
        return "\n".join([BEGIN.format(key=key), "", *markdown_table(TABLES[key]), "", END])

    out = _BLOCK.sub(block, text)
    if sorted(seen) != sorted(TABLES):
        raise ValueError(f"README column markers {sorted(seen)}, expected each of {sorted(TABLES)}")
    return out


def main(argv: Sequence[str] | None = None) -> int:
    """Rewrite (or ``--check``) the README; returns the exit status."""
    parser = argparse.ArgumentParser(prog="python -m recipsim.report.column_readme")
    parser.add_argument("readme", nargs="?", default="reports/README.md", type=Path)
    parser.add_argument("--check", action="store_true", help="write nothing; 1 if it differs")
    args = parser.parse_args(argv)
    text = args.readme.read_text(encoding="utf-8")
    new = render(text)
    if args.check:
        if new != text:
            print(f"{args.readme}: column tables differ from the declarations", file=sys.stderr)
            return 1
        return 0
    if new != text:
        args.readme.write_text(new, encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
