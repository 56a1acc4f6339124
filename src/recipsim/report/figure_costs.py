"""What each figure of a report costs to draw, and how figures are shared by cost between
the report processes (:mod:`recipsim.report.figure_process`)."""

from __future__ import annotations

from collections.abc import Collection, Mapping

#: Measured cost of each figure of the default case [s]: wall time in the report
#: processes of a warm ``recipsim run`` on the 2-core machine (two drawing processes,
#: the figures in the order :meth:`.figure_process.FigureProcesses.draw` gave them, 3
#: runs; the orbits, which the default case does not draw, measured alone). Used only to
#: share the figures evenly between the processes. A one-panel figure drawn after another
#: in the same process costs less (it reuses its Axes,
#: :func:`recipsim.report.plotting.save_cycle_figures`).
FIGURE_COST = {
    "p_V": 0.045,
    "p_V_loglog": 0.052,
    "p_theta": 0.064,
    "torque": 0.065,
    "valves": 0.091,
    "bearing_loads": 0.19,
    "orbits": 0.25,
    "loss_breakdown": 0.080,
}

#: Measured cost of a report's tables, ``summary.csv`` and ``cycle.csv`` [s] (as
#: :data:`FIGURE_COST`), shared with the figures.
TABLES_COST = 0.048

#: The tables' name among the figures' when they are shared.
TABLES = "(tables)"


def share_by_cost(names: Collection[str], parts: int, cost: Mapping[str, float]) -> list[list[str]]:
    """``names`` shared into at most ``parts`` non-empty lists of about equal total
    ``cost`` (largest first, each to the lightest list; unknown names cost 0.1)."""
    shares: list[list[str]] = [[] for _ in range(parts)]
    loads = [0.0] * parts
    for name in sorted(names, key=lambda n: -cost.get(n, 0.1)):
        lightest = loads.index(min(loads))
        shares[lightest].append(name)
        loads[lightest] += cost.get(name, 0.1)
    return [share for share in shares if share]
