"""Options shared by several ``recipsim`` subcommands (one definition, one help text)."""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Callable
from pathlib import Path

from recipsim.errors import CaseError, RecipsimError


def add_common_options(
    parser: argparse.ArgumentParser,
    out_default: Path | None,
    out_help: str,
    external_paths: bool = True,
) -> None:
    """Add ``--out DIR``, ``--set KEY=VALUE`` (repeatable), ``--no-plots`` and
    ``--allow-external-paths`` to ``parser``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The subcommand's parser.
    out_default : Path or None
        Default of ``--out``; None lets the command choose from its input.
    out_help : str
        What ``--out`` names for this command.
    external_paths : bool
        Offer ``--allow-external-paths`` (commands that load the user's case files).
    """
    parser.add_argument("--out", type=Path, default=out_default, help=out_help)
    parser.add_argument(
        "--set",
        dest="overrides",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="override a case value, KEY a dotted path (e.g. solver.rtol=1e-9); repeatable",
    )
    parser.add_argument("--no-plots", action="store_true", help="write the tables only")
    if not external_paths:
        return
    parser.add_argument(
        "--allow-external-paths",
        action="store_true",
        help=(
            "let case files name files outside their own directory (extends, "
            "pressure_curve.file) with absolute or '..' paths"
        ),
    )


def exit_status(action: Callable[[], int], label: str = "") -> int:
    """Run ``action`` and turn recipsim's errors into a message and an exit status.

    Returns ``action()``'s status, 2 for invalid input (:class:`CaseError`) or 1 for any
    other :class:`RecipsimError` (a solver failure names the crank angle and state) and
    for failures of the environment (:class:`OSError`: disk full, read-only, no
    permission). ``label`` (e.g. the case file) prefixes the message of a failure.
    """
    prefix = f"recipsim: {label}{': ' if label else ''}"
    try:
        return action()
    except CaseError as exc:
        print(f"recipsim: invalid input: {exc}", file=sys.stderr)
        return 2
    except RecipsimError as exc:
        print(f"{prefix}{exc}", file=sys.stderr)
        return 1
    except OSError as exc:
        where = f" ({exc.filename})" if exc.filename else ""
        reason = exc.strerror or type(exc).__name__
        print(f"{prefix}file system error: {reason}{where}", file=sys.stderr)
        return 1
    except RecursionError:
        print(f"{prefix}input nested too deeply", file=sys.stderr)
        return 2


def positive_int(text: str) -> int:
    """argparse type: a whole number >= 1 (e.g. ``--jobs``, ``--repeats``)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, got {value}")
    return value


def positive_float(text: str) -> float:
    """argparse type: a finite number > 0 (e.g. ``--scheduler-timeout``)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(value) or value <= 0.0:
        raise argparse.ArgumentTypeError(f"must be a finite number above 0, got {text}")
    return value
