"""``recipsim sweep`` under hostile input: bounded work, honest resumes, one-line errors.

Every test asserts the exit status, a one-line message without a traceback, and (where
the sweep could write) that nothing outside ``--out`` changed.
"""

from __future__ import annotations

import json
import os
import socket
import subprocess
import sys
import time
import tracemalloc
from pathlib import Path

import pandas as pd
import pytest

from helpers import REFERENCE, Sandbox, one_line_error
from recipsim.atomic import MARKER
from recipsim.cli.main import main
from recipsim.studies.sweep.engine import TIMING_COLUMNS
from recipsim.studies.sweep.spec import load_sweep
from recipsim.studies.sweep.store import record_checksum

SMALL = """
[set]
solver.max_revolutions = 40
[axes]
operating_point.evaporating_temperature = ["-30 degC", "-20 degC"]
"""


def write(tmp_path: Path, body: str, name: str = "small") -> Path:
    path = tmp_path / "inputs" / f"{name}.toml"
    path.parent.mkdir(exist_ok=True)
    path.write_text(f'name = "{name}"\nbase = "reference_r134a_lbp"\n{body}')
    return path


def test_a_huge_grid_is_refused_before_anything_is_built(tmp_path, capsys):
    """1e9 points: refused from the axis lengths in milliseconds, nothing allocated."""
    values = ", ".join(f'"{t} rpm"' for t in range(2000, 3000))
    body = (
        "[axes]\n"
        f"operating_point.shaft_speed = [{values}]\n"
        f"valves.suction.preload = [{', '.join(str(i / 10) for i in range(1000))}]\n"
        f"valves.discharge.preload = [{', '.join(str(i / 10) for i in range(1000))}]\n"
    )
    sweep = write(tmp_path, body)
    assert load_sweep(sweep).size == 10**9
    box = Sandbox(tmp_path)
    out = box.out
    tracemalloc.start()
    start = time.perf_counter()
    status = main(["sweep", str(sweep), "--out", str(out), "--quiet", "--no-plots"])
    elapsed = time.perf_counter() - start
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    err = one_line_error(capsys)
    assert status == 2 and "1,000,000,000 points" in err and "max_points" in err
    assert elapsed < 2.0 and peak < 50e6
    assert [p.name for p in out.iterdir()] == ["other_report"] and box.unchanged()


def test_the_limit_is_configurable_in_the_file_and_on_the_command_line(tmp_path, capsys):
    sweep = write(tmp_path, "max_points = 1\n" + SMALL)
    out = tmp_path / "out"
    assert main(["sweep", str(sweep), "--out", str(out), "--quiet", "--no-plots"]) == 2
    assert "2 points, more than the limit of 1" in one_line_error(capsys)
    argv = ["sweep", str(sweep), "--out", str(out), "--quiet", "--no-plots", "--max-points", "2"]
    assert main(argv) == 0
    bad = write(tmp_path, "max_points = 0\n" + SMALL, "bad")
    assert main(["sweep", str(bad), "--out", str(out), "--quiet"]) == 2
    assert "max_points" in one_line_error(capsys)


def test_a_large_sweep_starts_without_validating_every_point(tmp_path, monkeypatch):
    """Planning 20 000 points builds one case (for the keys), not 20 000."""
    import recipsim.studies.sweep.plan as plan

    calls = []
    real = plan.point_case
    monkeypatch.setattr(plan, "point_case", lambda *a, **k: calls.append(1) or real(*a, **k))
    values = ", ".join(str(i / 1000) for i in range(20_000))
    sweep = write(tmp_path, f"[axes]\nvalves.suction.preload = [{values}]\n")
    start = time.perf_counter()
    planned = plan.plan_sweep(load_sweep(sweep))
    assert len(planned) == 20_000 and len(calls) == 1
    assert time.perf_counter() - start < 30.0


def test_scheduler_that_is_not_a_url_is_invalid_input(tmp_path, capsys):
    sweep = write(tmp_path, SMALL)
    argv = ["sweep", str(sweep), "--out", str(tmp_path / "o"), "--scheduler", "not a url"]
    assert main(argv) == 2
    assert "not a scheduler address" in one_line_error(capsys)
    assert not (tmp_path / "o" / "small" / "points").exists()


def test_a_silent_server_is_not_waited_for(tmp_path, capsys):
    """An open port that is not Dask: exit 1 within the timeout, one line."""
    sweep = write(tmp_path, SMALL)
    with socket.socket() as server:
        server.bind(("127.0.0.1", 0))
        server.listen()
        address = f"tcp://127.0.0.1:{server.getsockname()[1]}"
        argv = ["sweep", str(sweep), "--out", str(tmp_path / "o"), "--scheduler", address]
        start = time.perf_counter()
        assert main([*argv, "--scheduler-timeout", "1", "--quiet"]) == 1
        assert time.perf_counter() - start < 15.0
    assert "no Dask scheduler answers" in one_line_error(capsys)


def test_a_tampered_point_record_is_recomputed(tmp_path, capsys):
    """COP 99 and an injected column in a finished point: not trusted, recomputed, and
    the table equals a clean run's."""
    from helpers import stored_points

    sweep = write(tmp_path, SMALL)
    out = tmp_path / "out"
    points = out / "small" / "points"
    argv = ["sweep", str(sweep), "--out", str(out), "--quiet", "--no-plots", "--jobs", "1"]
    assert main(argv) == 0
    clean = pd.read_csv(out / "small" / "summary.csv")
    (segment,) = points.glob("*.jsonl")
    lines = segment.read_bytes().splitlines(keepends=True)
    record = json.loads(lines[0])
    pid = record["point_id"]
    assert record["checksum"] == record_checksum(record)
    record["summary"]["COP [-]"] = 99.0
    record["summary"]["injected [-]"] = 1.0
    segment.write_bytes(json.dumps(record).encode() + b"\n" + b"".join(lines[1:]))
    assert main(argv) == 0
    again = pd.read_csv(out / "small" / "summary.csv")
    assert "injected [-]" not in again.columns and (again["COP [-]"] < 10).all()
    timing = [c for c in TIMING_COLUMNS if c in clean]
    pd.testing.assert_frame_equal(clean.drop(columns=timing), again.drop(columns=timing))
    assert json.loads(stored_points(points)[pid])["summary"]["COP [-]"] < 10  # saved again
    # a forged checksum does not help when the inputs are not the point's
    record = json.loads(stored_points(points)[pid])
    record["overrides"] = ["operating_point.shaft_speed=1.0"]
    record["saved_ns"] += 1  # the point's latest record
    record["checksum"] = record_checksum(record)
    with open(segment, "ab") as handle:
        handle.write(json.dumps(record).encode() + b"\n")
    assert main(argv) == 0
    assert json.loads(stored_points(points)[pid])["overrides"] != record["overrides"]


def test_unsafe_sweep_names_and_foreign_directories_are_refused(tmp_path, capsys):
    box = Sandbox(tmp_path)
    out = box.out
    for name in ('""', '".."', '"../x"', '"/tmp"'):
        sweep = tmp_path / "inputs" / "bad.toml"
        sweep.parent.mkdir(exist_ok=True)
        sweep.write_text(f'name = {name}\nbase = "reference_r134a_lbp"\n{SMALL}')
        assert main(["sweep", str(sweep), "--out", str(out), "--quiet"]) == 2
        assert "name" in one_line_error(capsys)
    foreign = out / "small"
    foreign.mkdir()
    (foreign / "thesis.tex").write_text("mine")
    sweep = write(tmp_path, SMALL)
    assert main(["sweep", str(sweep), "--out", str(out), "--quiet", "--no-plots"]) == 2
    assert "not written by recipsim" in one_line_error(capsys)
    assert sorted(p.name for p in foreign.iterdir()) == ["thesis.tex"]
    assert main(["sweep", str(sweep), "--out", str(out / "x" / ".."), "--quiet"]) == 2
    one_line_error(capsys)
    assert box.unchanged()


def test_base_outside_the_sweep_directory_needs_the_opt_in(tmp_path, capsys):
    (tmp_path / "base.toml").write_text(f'extends = "{REFERENCE.as_posix()}"\n')
    sweep = tmp_path / "inputs" / "s.toml"
    sweep.parent.mkdir()
    sweep.write_text(f'base = "../base.toml"\n{SMALL}')
    argv = ["sweep", str(sweep), "--out", str(tmp_path / "o"), "--quiet", "--no-plots"]
    assert main(argv) == 2
    assert "--allow-external-paths" in one_line_error(capsys)
    assert main([*argv, "--allow-external-paths", "--jobs", "1"]) == 0
    assert (tmp_path / "o" / "s" / MARKER).is_file()


def test_out_on_a_file_is_one_line(tmp_path, capsys):
    sweep = write(tmp_path, SMALL)
    target = tmp_path / "file.txt"
    target.write_text("x")
    assert main(["sweep", str(sweep), "--out", str(target), "--quiet"]) == 2
    assert "not a directory" in one_line_error(capsys)
    assert target.read_text() == "x"


@pytest.mark.parametrize("folder", ["points", "reports"])
def test_an_output_folder_that_is_a_link_is_refused_and_its_target_untouched(
    tmp_path, capsys, folder
):
    """``points/`` or ``reports/`` as a symbolic link: exit 2 naming it, and nothing in
    the link's target is written or deleted (a hidden ``.*.tmp`` file there survives)."""
    sweep = write(tmp_path, SMALL)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    precious = elsewhere / ".draft.tmp"
    precious.write_text("mine")
    root = tmp_path / "o" / "small"
    root.mkdir(parents=True)
    (root / MARKER).write_text("written by recipsim")  # an earlier sweep's directory
    (root / folder).symlink_to(elsewhere)
    assert main(["sweep", str(sweep), "--out", str(tmp_path / "o"), "--jobs", "1"]) == 2
    assert "symbolic link" in one_line_error(capsys)
    assert sorted(p.name for p in elsewhere.iterdir()) == [".draft.tmp"]
    assert precious.read_text() == "mine"


def test_only_recipsims_own_stale_temporaries_are_cleaned(tmp_path):
    """In ``points/``: a temporary file of a dead process is removed; one of a live
    process, a user's hidden ``.notes.tmp`` and a link named like a temporary are kept."""
    from recipsim.studies.sweep.store import PointStore

    store = PointStore(tmp_path)
    store.points.mkdir()
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    stale = store.points / f".abc.{dead.pid}-3.json.tmp"
    live = store.points / f".abc.{os.getpid()}-4.json.tmp"
    notes = store.points / ".notes.tmp"
    target = tmp_path / "target.txt"
    target.write_text("x")
    link = store.points / f".lnk.{dead.pid}-5.json.tmp"
    for path in (stale, live, notes):
        path.write_text("x")
    link.symlink_to(target)
    store.clean_temporaries()
    assert not stale.exists()
    assert live.exists() and notes.exists() and link.is_symlink() and target.exists()
