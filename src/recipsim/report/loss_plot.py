"""The loss chain as a waterfall: from the electrical input down to the isentropic power
of the delivered gas (:mod:`recipsim.results.loss_breakdown`)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from recipsim.physics.motor_models import LOSSLESS
from recipsim.report.figure_kit import fewer_ticks, new_figure
from recipsim.report.figure_names import TITLE_Y
from recipsim.results.loss_breakdown import COP_COST_COLUMNS, LOSS_COLUMNS

if TYPE_CHECKING:
    from matplotlib.figure import Figure

_LABELS = {
    "loss_motor [W]": "motor",
    "loss_mechanical [W]": "friction, bearings",
    "loss_suction_valve [W]": "suction valve",
    "loss_discharge_valve [W]": "discharge valve",
    "loss_mufflers [W]": "mufflers",
    "loss_leakage [W]": "leakage",
    "loss_suction_heating [W]": "suction heating",
    "loss_cylinder_heat_and_other [W]": "cylinder heat, other",
}


def plot_loss_breakdown(row: Mapping[str, Any], ax: Any = None, title: str = "") -> Figure:
    """Horizontal waterfall of the loss chain of one summary row [W]: the electrical
    input on top (the shaft's, so labelled, when the case has no motor model), each
    loss as a bar stepping down (its share of the input and the COP it costs written
    beside it), the isentropic power of the delivered gas at the bottom."""
    if ax is None:
        fig = new_figure(figsize=(6.4, 4.4), layout="constrained")
        ax = fig.add_subplot()
    else:
        fig = ax.figure
    total = float(row["motor_electrical_power [W]"])
    electrical = (
        row.get("motor", LOSSLESS.name) != LOSSLESS.name or float(row["loss_motor [W]"]) > 0
    )
    top = "electrical input" if electrical else "shaft input (no motor model)"
    labels, lefts, widths, colours = [top], [0.0], [total], ["tab:blue"]
    costs: list[float] = [float("nan")]
    level = total
    for column in LOSS_COLUMNS:
        loss = float(row[column])
        level -= loss
        labels.append(_LABELS[column])
        lefts.append(level)
        widths.append(loss)
        colours.append("tab:red" if loss >= 0.0 else "tab:green")
        costs.append(float(row.get(COP_COST_COLUMNS[column], float("nan"))))
    costs.append(float("nan"))
    labels.append("isentropic, delivered gas")
    lefts.append(0.0)
    widths.append(float(row["isentropic_power [W]"]))
    colours.append("tab:blue")
    y = list(range(len(labels)))[::-1]
    ax.barh(y, widths, left=lefts, color=colours)
    for yi, left, width, cost in zip(y, lefts, widths, costs, strict=True):
        text = f"{width:.1f} W ({width / total:.0%})"
        if cost == cost:  # not NaN: the COP this loss costs
            text += f", COP -{cost:.3f}"
        ax.text(max(left, left + width) + 0.01 * total, yi, text, va="center", fontsize=8)
    ax.set_yticks(y, labels)
    ax.set_xlim(0.0, 1.45 * total)
    ax.set_xlabel("power [W]")
    fewer_ticks(ax, y=False)
    ax.set_title(title or f"where the {top.split()[0]} power goes", fontsize=9, y=TITLE_Y)
    ax.grid(True, axis="x", alpha=0.3)
    return fig
