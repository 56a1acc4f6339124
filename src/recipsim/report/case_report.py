"""Per-case report: CSV tables (the contract), figures, the case as run, provenance.

A report directory is built beside its destination and swapped in with renames, so a
reader never sees a half-written report and an interrupted run leaves the previous
one intact.
"""

from __future__ import annotations

import hashlib
import io
import json
import math
from collections.abc import Collection, Mapping, Sequence
from pathlib import Path
from typing import Any

import pandas as pd

from recipsim.atomic import atomic_directory, check_replaceable, checked_name, normalised
from recipsim.case.overrides import parse_override
from recipsim.errors import CaseError
from recipsim.report.report_figures import (
    draw_report_figures,
    report_figure_names,
    write_tables,
)
from recipsim.report.report_figures import run_title as run_title  # re-exported
from recipsim.report.resolved_case import resolved_case
from recipsim.report.startup_plot import plot_startup
from recipsim.results.case_run import CaseRun
from recipsim.results.startup import startup_table


def write_report(
    out_dir: Path,
    summary_row: dict[str, Any],
    cycle: pd.DataFrame,
    case_text: str,
    overrides: list[str],
    meta: dict[str, Any],
    plenum: tuple[float, float] | None = None,
    plots: bool | Collection[str] = True,
    files: Mapping[str, bytes] | None = None,
) -> Path:
    """Write one case's report into ``out_dir`` atomically.

    ``out_dir`` is replaced whole if it is a recipsim output directory (or empty);
    any other existing directory is refused (:func:`recipsim.atomic.atomic_directory`).
    ``case_text`` becomes ``case.toml`` (headed by the overrides when it does not name
    them itself); ``files`` (relative path to content) are written beside it.
    ``plots``: every figure (True), none (False) or those named
    (:data:`recipsim.report.figure_names.FIGURE_NAMES`).

    Returns
    -------
    Path
        ``out_dir``.
    """
    out_dir = Path(out_dir)
    with atomic_directory(out_dir) as tmp:
        write_tables(tmp, summary_row, cycle)
        header = "".join(f"# --set {o}\n" for o in overrides if f"# --set {o}" not in case_text)
        (tmp / "case.toml").write_text(
            ("# overrides applied on top of this file:\n" + header if header else "") + case_text
        )
        for name, content in (files or {}).items():
            (tmp / name).parent.mkdir(parents=True, exist_ok=True)
            (tmp / name).write_bytes(content)
        (tmp / "provenance.json").write_text(json_text(meta))
        names = report_figure_names(cycle, summary_row, plots)
        if names:
            draw_report_figures(tmp, cycle, summary_row, plenum, names)
    return out_dir


def json_text(value: Any) -> str:
    """``value`` as strict JSON text (indented): a number that is not finite (NaN,
    infinity) becomes ``null``; anything JSON has no type for is written as its text."""
    return json.dumps(_finite(value), indent=2, default=str, allow_nan=False)


def _finite(value: Any) -> Any:
    """``value`` with every non-finite float replaced by None, inside lists and dicts."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, Mapping):
        return {key: _finite(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(item) for item in value]
    return value


def write_case_report(
    run: CaseRun,
    out_dir: Path,
    overrides: list[str],
    plots: bool | Collection[str] = True,
) -> Path:
    """Write the report of ``run`` atomically into ``out_dir`` (see reports/README.md).

    Its ``case.toml`` is the case fully resolved (:mod:`recipsim.report.resolved_case`),
    with the refrigerant file and a tabulated pressure curve beside it.
    """
    op = run.case.operating_point
    text, files = resolved_case(run.case)
    if run.startup is not None:  # the start-up from rest: startup.csv and startup.png
        files = {**files, **startup_files(run, plots)}
    return write_report(
        out_dir,
        run.row,
        run.cycle,
        text,
        overrides,
        run.meta,
        plenum=(op.suction_pressure, op.discharge_pressure),
        plots=plots,
        files=files,
    )


def startup_files(run: CaseRun, plots: bool | Collection[str] = True) -> dict[str, bytes]:
    """``startup.csv`` and (unless ``plots`` leaves it out) ``startup.png`` of a run
    from rest, as file contents (reports/README.md, "startup.csv")."""
    assert run.startup is not None
    table = startup_table(run.startup)
    out = {"startup.csv": table.to_csv(index=False).encode()}
    if plots is True or (plots and "startup" in plots):
        buffer = io.BytesIO()
        plot_startup(table, title=f"{run.case.name}: start-up from rest").savefig(
            buffer, format="png", dpi=120
        )
        out["startup.png"] = buffer.getvalue()
    return out


def overrides_digest(overrides: Sequence[str]) -> str:
    """A short, stable digest of ``KEY=VALUE`` overrides (8 hexadecimal digits).

    The same changes give the same digest whatever their order, spacing or repetition
    (the last value of a key wins, as when they are applied).
    """
    values: dict[str, Any] = {}
    for text in overrides:
        path, value = parse_override(text)
        values[".".join(path)] = value
    canonical = json.dumps(sorted(values.items()), default=str, ensure_ascii=False)
    return hashlib.sha256(canonical.encode()).hexdigest()[:8]


def report_name(name: str, overrides: Sequence[str]) -> str:
    """Directory name of a case's output: ``<name>``, or ``<name>+<digest>`` with overrides
    (:func:`overrides_digest`), so runs with other ``--set`` values never share one."""
    return f"{name}+{overrides_digest(overrides)}" if overrides else name


def report_dir(parent: Path, name: str, overrides: Sequence[str], file: str = "--out") -> Path:
    """``parent/<report_name>``, checked to be replaceable by recipsim.

    Parameters
    ----------
    parent : Path
        The directory the user pointed to (``--out``).
    name : str
        Case (or study) name, a plain file name (:func:`recipsim.atomic.checked_name`).
    overrides : sequence of str
        ``KEY=VALUE`` overrides of the run.
    file : str
        Where ``parent`` came from, for messages.

    Raises
    ------
    CaseError
        ``parent`` is not a directory, or the target exists and is neither empty nor a
        recipsim output.
    """
    parent = normalised(parent)
    if parent.exists() and not parent.is_dir():
        raise CaseError(str(parent), file, "exists and is not a directory")
    target = parent / report_name(checked_name(name, file), overrides)
    check_replaceable(target)
    return target
