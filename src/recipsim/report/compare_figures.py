"""The figures and tables of a comparison (``recipsim compare``) drawn by report processes.

A comparison holds two case reports (tables and figures each) and the overlay figures of
both cases. In one process they are drawn one after the other (about 2.4 s of CPU for
the reference case against its coupled variant). :func:`submit_compare_figures` shares
them by measured cost between the forked report processes of
:mod:`recipsim.report.figure_process`, as ``recipsim run`` shares one report's
figures, while the parent writes the rest; :func:`draw_compare_share` is what each
process runs. The files are those the in-process writers make, byte for byte.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from recipsim.report.figure_process import FigureProcesses

#: Measured CPU time of each overlay figure of ``recipsim compare`` [s] (the reference
#: case against its coupled variant, medians of 3), as
#: :data:`recipsim.report.figure_costs.FIGURE_COST`.
OVERLAY_COST = {
    "overlay_pressure": 0.10,
    "overlay_pv": 0.23,
    "overlay_torque": 0.10,
    "overlay_bearing_loads": 0.29,
    "overlay_orbits": 0.18,
}

#: What the report processes of a comparison import before their jobs arrive.
COMPARE_PRELOAD = (
    "pandas",
    "recipsim.report.loss_plot",
    "recipsim.report.plotting",
    "recipsim.report.report_figures",
    "recipsim.report.compare_plots",
)

_OVERLAY = "overlay"


def submit_compare_figures(
    figures: FigureProcesses,
    reports: Sequence[Mapping[str, Any]],
    overlay: Mapping[str, Any] | None,
) -> None:
    """Share the reports' tables and figures and the overlay figures between the report
    processes by cost; returns at once (``figures.wait()`` waits for the files).

    Parameters
    ----------
    figures : FigureProcesses
        The forked report processes (one call of this per instance).
    reports : sequence of mapping
        Each report's keyword arguments of
        :func:`recipsim.report.report_figures.write_report_share` (``directory``,
        ``cycle``, ``summary_row``, ``plenum``, ``names``, ``tables``).
    overlay : mapping or None
        Keyword arguments of :func:`recipsim.report.compare_plots.save_overlay_figures`
        (``cycles``, ``out_dir``, ``plenum``, ``names``), or None for no overlays.
    """
    from recipsim.report.figure_costs import FIGURE_COST, TABLES, TABLES_COST

    cost: dict[str, float] = {}
    for k, report in enumerate(reports):
        for name in report["names"]:
            cost[f"{k}:{name}"] = FIGURE_COST.get(name, 0.1)
        if report["tables"]:
            cost[f"{k}:{TABLES}"] = TABLES_COST
    for name in overlay["names"] if overlay is not None else ():
        cost[f"{_OVERLAY}:{name}"] = OVERLAY_COST.get(name, 0.15)
    figures.submit_shared(
        "recipsim.report.compare_figures",
        "draw_compare_share",
        cost,
        lambda share: {"tasks": _tasks(share, reports, overlay)},
    )


def _tasks(
    share: list[str], reports: Sequence[Mapping[str, Any]], overlay: Mapping[str, Any] | None
) -> list[tuple[str, dict[str, Any]]]:
    """One process's calls: per report, its share of that report's tables and figures;
    its share of the overlays."""
    from recipsim.report.figure_costs import TABLES

    owners = [item.split(":", 1) for item in share]
    tasks: list[tuple[str, dict[str, Any]]] = []
    for k, report in enumerate(reports):
        mine = [name for owner, name in owners if owner == str(k)]
        if mine:
            names = tuple(name for name in report["names"] if name in mine)
            tasks.append(("report", {**report, "names": names, "tables": TABLES in mine}))
    overlays = [name for owner, name in owners if owner == _OVERLAY]
    if overlay is not None and overlays:
        names = tuple(name for name in overlay["names"] if name in overlays)
        tasks.append((_OVERLAY, {**overlay, "names": names}))
    return tasks


def draw_compare_share(tasks: list[tuple[str, dict[str, Any]]]) -> None:
    """Run one report process's share (:func:`submit_compare_figures`)."""
    from recipsim.report.compare_plots import save_overlay_figures
    from recipsim.report.report_figures import write_report_share

    for kind, kwargs in tasks:
        if kind == _OVERLAY:
            save_overlay_figures(**kwargs)
        else:
            write_report_share(**kwargs)
