"""The report's figures: a chosen subset (``--plots``), fixed margins that keep every
label inside the image, plain-number labels on the log-log p-V diagram."""

from __future__ import annotations

from pathlib import Path

import pytest

from helpers import REFERENCE
from recipsim.cli.main import main
from recipsim.errors import CaseError
from recipsim.report.figure_names import FIGURE_NAMES, check_figure_names
from recipsim.results.loss_breakdown import LOSS_COLUMNS


@pytest.fixture(scope="module")
def cycle():
    from recipsim.case.load import load_case
    from recipsim.pipeline import simulate_case

    return simulate_case(load_case(REFERENCE), []).cycle


def test_run_draws_only_the_figures_asked_for(tmp_path: Path) -> None:
    status = main(
        ["run", str(REFERENCE), "--out", str(tmp_path), "--plots", "p_V,torque", "--quiet"]
    )
    assert status == 0
    report = tmp_path / "reference_r134a_lbp_ideal"
    assert sorted(p.name for p in report.glob("*.png")) == ["p_V.png", "torque.png"]
    assert (report / "summary.csv").is_file()


def test_unknown_figure_is_refused_before_solving(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as info:
        main(["run", str(REFERENCE), "--plots", "p_V,tork"])
    assert info.value.code == 2
    assert "unknown figure; allowed: p_V, p_V_loglog" in capsys.readouterr().err
    with pytest.raises(CaseError):
        check_figure_names(["orbit"])
    assert check_figure_names(FIGURE_NAMES) == FIGURE_NAMES


def test_fixed_margins_keep_every_label_inside(cycle, tmp_path: Path) -> None:
    """Every label of every report figure lies inside the figure (to 1 px): the fixed
    margins replace the constrained layout, so they must leave room for the labels."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from recipsim.report import plotting
    from recipsim.report.loss_plot import plot_loss_breakdown

    title = "reference_r134a_lbp: pinned crank, constant_speed, cylinder model"
    row = {"motor_electrical_power [W]": 110.3, "isentropic_power [W]": 101.0}
    row |= {column: 1.0 for column in LOSS_COLUMNS}
    makers = plotting._figure_makers(cycle, (1.2e5, 1.5e6))
    # the loss waterfall: its title on the axes, fixed margins too (report_figures)
    makers.append(("loss_breakdown", "waterfall", lambda: plot_loss_breakdown(row, title=title)))
    for name, kind, make in makers:
        fig = make()
        if kind is not None:
            plotting.fixed_margins(fig, kind)
        suptitle = fig.suptitle("" if name == "loss_breakdown" else title)
        renderer = FigureCanvasAgg(fig).get_renderer()
        width, height = fig.bbox.width, fig.bbox.height
        renderer.clear()
        fig.draw(renderer)  # places the tick labels
        # each axes' tight box holds what it draws: tick labels, axis labels, title
        boxes = [ax.get_tightbbox(renderer) for ax in fig.axes if ax.get_visible()]
        boxes.append(suptitle.get_window_extent(renderer))
        for box in boxes:
            assert box is not None
            assert box.x0 >= -1 and box.y0 >= -1, (name, box)
            assert box.x1 <= width + 1 and box.y1 <= height + 1, (name, box)


def test_log_log_labels_are_plain_numbers(cycle) -> None:
    """Major labels at 1, 2, 5 x 10^k written as plain numbers, no minor labels."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from recipsim.report.plotting import plot_pv

    fig = plot_pv(cycle, log=True)
    FigureCanvasAgg(fig).draw()
    ax = fig.axes[0]
    labels = [t.get_text() for t in ax.get_xticklabels() if t.get_text()]
    assert labels and all(float(text) > 0 for text in labels)
    mantissas = {f"{float(text):e}"[0] for text in labels}
    assert mantissas <= {"1", "2", "5"}
    assert not [t.get_text() for t in ax.get_xminorticklabels() if t.get_text()]
