"""Sweeps that scale: batches sized to the measured point time, a warm first point in
the parent, the same table as in one process, and only the map plots asked for."""

from __future__ import annotations

from pathlib import Path

import pytest

from helpers import REFERENCE
from recipsim.errors import CaseError
from recipsim.studies.sweep.engine import TIMING_COLUMNS, run_sweep
from recipsim.studies.sweep.plots import MAP_NAMES
from recipsim.studies.sweep.runner import CHUNK_SECONDS, chunk_size


def test_chunk_size_follows_the_point_time_and_keeps_workers_busy() -> None:
    """About CHUNK_SECONDS of work per batch, never fewer than four batches a worker,
    never an empty batch."""
    assert chunk_size(0.025, 1000, 2) == int(CHUNK_SECONDS / 0.025)  # 10 points: 0.25 s
    assert chunk_size(0.025, 40, 2) == 5  # 40 points / (4 x 2 workers)
    assert chunk_size(2.0, 1000, 16) == 1  # slow points go one by one
    assert chunk_size(0.001, 3, 16) == 1
    assert chunk_size(0.0, 100, 2) == 12  # unknown time: only the four-batch rule


def _sweep(tmp_path: Path) -> Path:
    path = tmp_path / "batches.toml"
    path.write_text(
        f'name = "batches"\nbase = "{REFERENCE.as_posix()}"\n'
        "[axes]\n"
        'operating_point.shaft_speed = ["2500 rpm", "3500 rpm", "4500 rpm"]\n'
        'operating_point.evaporating_temperature = ["-30 degC", "-20 degC", "-10 degC", '
        '"70 degC"]\n'
    )
    return path


def test_batched_pool_equals_one_process(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """12 points (3 invalid) on 2 workers in batches of 3, after a first point in the
    parent: every row equals the row computed in one process, to the last digit."""
    from recipsim.studies.sweep import runner

    sizes: list[int] = []

    def three(*args: object) -> int:
        sizes.append(3)
        return 3

    monkeypatch.setattr(runner, "chunk_size", three)
    sweep = _sweep(tmp_path)
    pool = run_sweep(sweep, out=tmp_path / "pool", jobs=2, plots=("COP",))
    inline = run_sweep(sweep, out=tmp_path / "inline", jobs=1, plots=False)
    drop = [c for c in TIMING_COLUMNS if c in pool.table]
    assert sizes  # the batches were sized from the first point's time
    assert pool.counts == {"ok": 9, "invalid": 3}
    assert pool.table.drop(columns=drop).equals(inline.table.drop(columns=drop))
    assert [p.name for p in pool.files if p.suffix == ".png"] == ["map_COP.png"]
    assert not [p for p in inline.files if p.suffix == ".png"]


def test_unknown_map_plot_is_refused_before_any_point(tmp_path: Path) -> None:
    with pytest.raises(CaseError) as info:
        run_sweep(_sweep(tmp_path), out=tmp_path / "x", jobs=1, plots=("cop",))
    assert "unknown map plot; allowed: " + ", ".join(MAP_NAMES) in str(info.value)
    assert not (tmp_path / "x").exists()


def test_bearing_map_has_one_legend_below_the_panels() -> None:
    """One figure legend with a line per group (4 groups: 2 refrigerants x 2 condensing
    temperatures), below every panel's tick labels and inside the figure."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from test_sweep_plots import AXES, synthetic

    from recipsim.studies.sweep.plots import group_columns, plot_bearing_loads, x_column

    table = synthetic(bearings=True)
    ok = table[table["status"] == "ok"]
    x = x_column(ok, AXES)
    assert x is not None
    fig = plot_bearing_loads(ok, x, group_columns(ok, AXES, x))
    assert fig is not None
    renderer = FigureCanvasAgg(fig).get_renderer()
    fig.draw(renderer)
    assert [ax.get_legend() for ax in fig.axes] == [None] * len(fig.axes)
    assert len(fig.legends) == 1 and len(fig.legends[0].get_texts()) == 4
    legend = fig.legends[0].get_window_extent(renderer)
    assert legend.y0 >= -1 and legend.x0 >= -1 and legend.x1 <= fig.bbox.width + 1
    boxes = [ax.get_tightbbox(renderer) for ax in fig.axes if ax.get_visible()]
    lowest = min(box.y0 for box in boxes if box is not None)
    assert legend.y1 <= lowest + 1


def test_pool_workers_save_their_own_points(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """On the local pool each point's record is written by the process that solved it:
    the parent writes only the first point (solved here before the workers fork), so
    saving is not a serial step of the parent. Every record reads back with a valid
    checksum and the table is that of one process."""
    import os

    from recipsim.studies.sweep.store import PointStore

    writers = tmp_path / "writers.txt"
    save = PointStore.save

    def noting_save(self: PointStore, point_id: str, record: dict) -> None:
        with open(writers, "a") as handle:
            handle.write(f"{os.getpid()}\n")
        save(self, point_id, record)

    monkeypatch.setattr(PointStore, "save", noting_save)
    pool = run_sweep(_sweep(tmp_path), out=tmp_path / "pool", jobs=2, plots=False)
    pids = writers.read_text().split()
    assert len(pids) == 12
    assert pids.count(str(os.getpid())) == 1  # the warm first point
    # each process appended to a segment of its own
    segments = sorted(p.name.split("-")[1] for p in (pool.directory / "points").glob("*.jsonl"))
    assert segments == sorted(set(pids))
    store = PointStore(pool.directory)
    for pid, overrides in zip(pool.table["point_id"], _overrides(pool), strict=True):
        assert store.load(pid, overrides) is not None  # checksum and overrides match
    writers.unlink()
    inline = run_sweep(_sweep(tmp_path), out=tmp_path / "inline", jobs=1, plots=False)
    assert writers.read_text().split() == [str(os.getpid())] * 12
    drop = list(TIMING_COLUMNS)
    assert pool.table.drop(columns=drop).equals(inline.table.drop(columns=drop))


def _overrides(outcome: object) -> list[list[str]]:
    """Each point's overrides, as its record holds them."""
    import json

    from helpers import stored_points

    records = stored_points(outcome.directory / "points")  # type: ignore[attr-defined]
    table = outcome.table  # type: ignore[attr-defined]
    return [json.loads(records[pid])["overrides"] for pid in table["point_id"]]
