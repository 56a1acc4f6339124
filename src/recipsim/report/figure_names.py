"""Names of the figures of a case report and of a comparison, checked without importing
matplotlib (the command line checks ``--plots`` before it solves anything)."""

from __future__ import annotations

from collections.abc import Iterable

from recipsim.errors import CaseError

#: Names of the report's figures (file ``<name>.png``), in the order they are drawn;
#: ``valves`` needs the simulated gas, ``bearing_loads`` the crank train's forces and
#: ``orbits`` its flexible bearings, ``loss_breakdown`` the gas (the loss chain's waterfall),
#: ``startup`` a run from rest (``solver.start = "rest"``).
FIGURE_NAMES = (
    "p_V", "p_V_loglog", "p_theta", "torque", "valves", "bearing_loads", "orbits",
    "loss_breakdown", "startup",
)  # fmt: skip

#: Overlay figures of ``recipsim compare`` (file ``<name>.png``), in the order they are
#: drawn; ``overlay_orbits`` only where a case has flexible bearings.
OVERLAY_NAMES = (
    "overlay_pressure", "overlay_pv", "overlay_torque", "overlay_bearing_loads",
    "overlay_orbits",
)  # fmt: skip


#: Title position, axes fraction: given, it spares matplotlib placing each title above the
#: axes' top decorations at every draw, which these figures do not have, so the images
#: are the same to the byte.
TITLE_Y = 1.0


def check_figure_names(names: Iterable[str], where: str = "--plots") -> tuple[str, ...]:
    """``names`` checked against :data:`FIGURE_NAMES`.

    Raises
    ------
    CaseError
        Naming an unknown figure and the allowed ones.
    """
    names = tuple(names)
    for name in names:
        if name not in FIGURE_NAMES:
            raise CaseError(where, name, f"unknown figure; allowed: {', '.join(FIGURE_NAMES)}")
    return names
