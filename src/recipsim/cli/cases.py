"""``recipsim cases [--kind cases|sweeps|hard]``: list what is shipped.

Prints one row per shipped case, sweep and hard case file (name, kind, description;
:func:`recipsim.case.shipped.shipped_cases`). A case runs by its name
(``recipsim run NAME``), a sweep too (``recipsim sweep NAME``), the hard cases together
(``recipsim check hard``); a file ``./cases/NAME.toml`` (``./cases/sweeps/NAME.toml``)
of the working directory is found before the shipped one. This module imports nothing
heavy.
"""

from __future__ import annotations

import argparse
from typing import Any

from recipsim.case.shipped import KIND_FOLDERS, shipped_cases
from recipsim.cli.options import exit_status

#: ``--kind`` choices: the kinds of :data:`recipsim.case.shipped.KIND_FOLDERS` they list.
KIND_CHOICES = {"cases": "case", "sweeps": "sweep", "hard": "hard case"}


def add_cases_parser(sub: Any) -> argparse.ArgumentParser:
    """Add the ``cases`` subcommand to the subparsers ``sub`` of the ``recipsim`` parser."""
    parser: argparse.ArgumentParser = sub.add_parser(
        "cases",
        help="list the shipped cases, sweeps and hard cases",
        description=(
            "List the shipped cases, sweeps and hard cases: name, kind and description. "
            "Run a case by name with 'recipsim run NAME', a sweep with 'recipsim sweep "
            "NAME', the hard cases with 'recipsim check hard'. A file ./cases/NAME.toml "
            "(./cases/sweeps/NAME.toml) of the working directory is found before the "
            "shipped one of the same name."
        ),
    )
    parser.add_argument(
        "--kind",
        choices=tuple(KIND_CHOICES),
        default=None,
        help="list only the cases, the sweeps or the hard cases (default: all)",
    )
    parser.set_defaults(handler=run_cases_command)
    return parser


def run_cases_command(args: argparse.Namespace, argv: list[str] | None = None) -> int:
    """Handler of ``recipsim cases``; returns the exit status."""
    return exit_status(lambda: print_cases(args.kind))


def print_cases(kind: str | None = None) -> int:
    """Print the table of shipped files (those of ``kind``, a key of
    :data:`KIND_CHOICES`, or all); returns 0."""
    kinds = (KIND_CHOICES[kind],) if kind else tuple(KIND_FOLDERS)
    rows = [("name", "kind", "description")]
    rows += [(c.name, c.kind, c.description) for c in shipped_cases(kinds)]
    widths = [max(len(row[i]) for row in rows) for i in range(2)]
    for name, kind_, description in rows:
        print(f"{name:<{widths[0]}}  {kind_:<{widths[1]}}  {description}".rstrip())
    return 0
