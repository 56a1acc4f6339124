"""Valve back-flow over the converged revolution, and the warning when it is large.

``discharge_backflow_fraction [-]`` is the mass that flowed back into the cylinder
through the discharge valve over the mass that left through it; ``suction_backflow_
fraction [-]`` the mass pushed back out through the suction valve over the mass that
came in through it. Both come from the cylinder's cumulative quadratures
(``Q_MDIS_IN / Q_MDIS_OUT`` and ``Q_MSUC_OUT / Q_MSUC_IN``), integrated with the cycle,
so they are as accurate as the mass balance. A reed that closes late (soft, or with a
high stop) lets delivered gas flow back; above :data:`BACKFLOW_WARNING` the run is
flagged with a warning on the ``recipsim`` logger (``recipsim: <case>: ...`` on the
command line's standard error, also under ``--quiet``; Python's own last-resort
handler prints it when the API is used without a logging configuration).
"""

from __future__ import annotations

import logging
import math
from typing import TYPE_CHECKING, Any

from recipsim.model.scenes import named_state

if TYPE_CHECKING:
    from recipsim.solve.periodic import PeriodicSolution

#: back-flow fraction above which a run is flagged [-]
BACKFLOW_WARNING = 0.03

BACKFLOW_COLUMNS = ("discharge_backflow_fraction [-]", "suction_backflow_fraction [-]")

logger = logging.getLogger(__name__)


def _fraction(back: float, forward: float) -> float:
    return back / forward if forward > 0.0 else math.nan


def backflow_fractions(quadratures: Any) -> dict[str, float]:
    """Back-flow fractions of both valves over one revolution.

    Parameters
    ----------
    quadratures : NamedTuple or None
        The scene's states by name at the end of the converged revolution
        (:func:`recipsim.model.scenes.named_state`: the cumulative masses through the
        valves); None when no gas was integrated (the fractions are then NaN).

    Returns
    -------
    dict
        ``discharge_backflow_fraction [-]`` = back-flow in / delivered out through the
        discharge valve, ``suction_backflow_fraction [-]`` = back-flow out / inflow
        through the suction valve; NaN where nothing flowed forward.
    """
    if quadratures is None:
        return dict.fromkeys(BACKFLOW_COLUMNS, math.nan)
    y = quadratures
    return {
        "discharge_backflow_fraction [-]": _fraction(y.discharge_mass_in, y.discharge_mass_out),
        "suction_backflow_fraction [-]": _fraction(y.suction_mass_out, y.suction_mass_in),
    }


def warn_large_backflow(case_name: str, fractions: dict[str, float]) -> list[str]:
    """Log a warning for each valve whose back-flow exceeds :data:`BACKFLOW_WARNING`.

    Returns
    -------
    list of str
        The messages logged (empty when none).
    """
    messages = []
    for column, value in fractions.items():
        if value > BACKFLOW_WARNING:  # NaN compares False
            valve = column.split("_", 1)[0]
            messages.append(
                f"{case_name}: {value:.1%} of the gas through the {valve} valve flows back "
                f"(above {BACKFLOW_WARNING:.0%}): the reed closes late; check its "
                f"stiffness, stop height and preload"
            )
    for message in messages:
        logger.warning(message)
    return messages


def valve_summary(case_name: str, solution: PeriodicSolution | None) -> dict[str, float]:
    """The back-flow columns of the summary over the converged revolution of
    ``solution`` (NaN without a gas model), warning about large ones."""
    y = None
    if solution is not None and solution.model.has_gas:
        y = named_state(solution.model.scene, solution.final.y_end)
    fractions = backflow_fractions(y)
    warn_large_backflow(case_name, fractions)
    return fractions
