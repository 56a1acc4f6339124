"""``--out`` means the same in every subcommand: the parent of the output directory
``<out>/<name>`` (``<name>+<digest of the --set values>`` with overrides), and two runs
with different ``--set`` values never share a directory.

``paper`` and ``bench`` are checked where their outputs are (tests/unit/model/test_scenes.py,
tests/unit/studies/bench/test_bench.py: ``<out>/<case>/table1.csv``, ``<out>/<case>/bench.json``);
here, the cheap subcommands and every ``--help``.
"""

from __future__ import annotations

import contextlib
import io

import pandas as pd
import pytest

from helpers import CASES, REFERENCE
from recipsim.atomic import MARKER
from recipsim.cli.main import _parser, main
from recipsim.report.case_report import overrides_digest, report_name

PAPER = CASES / "paper_tabulated.toml"
QUIET = ["--no-plots", "--quiet"]
BOUNDS = ["solver.max_revolutions=3", "solver.min_revolutions=1", "solver.cycle_tolerance=0.05"]


def _sets(texts: list[str]) -> list[str]:
    return [a for text in texts for a in ("--set", text)]


@pytest.mark.parametrize("command", ["run", "sweep", "compare", "paper", "bench", "check"])
def test_every_help_says_out_is_the_parent(command):
    """The one meaning is written in each subcommand's ``--help``."""
    text = io.StringIO()
    with contextlib.redirect_stdout(text), pytest.raises(SystemExit):
        _parser().parse_args([command, "--help"])
    help_text = " ".join(text.getvalue().split())
    assert "parent directory" in help_text and "OUT/<" in help_text, help_text


def test_digest_is_stable_and_ignores_order_and_spacing():
    """Same changes, same digest (order, spaces, a key set twice: the last wins, as when
    applied); another value or key, another digest."""
    a = overrides_digest(["solver.rtol=1e-7", 'operating_point.shaft_speed="3000 rpm"'])
    b = overrides_digest(['operating_point.shaft_speed = "3000 rpm"', "solver.rtol = 1e-7"])
    c = overrides_digest(["solver.rtol=1e-3", "solver.rtol=1e-7"])
    assert a == b and len(a) == 8 and int(a, 16) >= 0
    assert c == overrides_digest(["solver.rtol=1e-7"]) != a
    assert overrides_digest(["solver.rtol=1e-8"]) != overrides_digest(["solver.rtol=1e-7"])
    assert report_name("case", []) == "case" and report_name("case", ["a=1"]).startswith("case+")


def test_run_keeps_runs_with_different_overrides_apart(tmp_path):
    """``run``: ``<out>/<case>`` without overrides, ``<out>/<case>+<digest>`` with them; two
    speeds give two reports; the same overrides (other order) replace their own report."""
    out = tmp_path / "reports"
    slow = [*BOUNDS, 'operating_point.shaft_speed="2900 rpm"']
    fast = [*BOUNDS, 'operating_point.shaft_speed="3500 rpm"']
    assert main(["run", str(REFERENCE), "--out", str(out), *QUIET, *_sets(slow)]) == 0
    assert main(["run", str(REFERENCE), "--out", str(out), *QUIET, *_sets(fast)]) == 0
    names = sorted(p.name for p in out.iterdir())
    assert names == sorted([report_name("reference_r134a_lbp_ideal", s) for s in (slow, fast)])
    speeds = {n: pd.read_csv(out / n / "summary.csv")["shaft_speed [rpm]"].iloc[0] for n in names}
    assert sorted(round(v) for v in speeds.values()) == [2900, 3500]
    slow_dir = out / report_name("reference_r134a_lbp_ideal", slow)
    (slow_dir / "mine.txt").write_text("left by an earlier report")
    again = ["run", str(REFERENCE), "--out", str(out), *QUIET, *_sets(list(reversed(slow)))]
    assert main(again) == 0
    assert sorted(p.name for p in out.iterdir()) == names  # replaced, not a third
    assert not (slow_dir / "mine.txt").exists() and (slow_dir / MARKER).is_file()


def test_sweep_writes_below_out(tmp_path):
    """``sweep``: ``<out>/<sweep name>/summary.csv``."""
    sweep = tmp_path / "tiny.toml"
    sweep.write_text(
        f'name = "tiny"\nbase = "{REFERENCE.as_posix()}"\n'
        "[set]\n" + "\n".join(BOUNDS) + "\n"
        '[axes]\n"operating_point.shaft_speed" = ["3000 rpm"]\n'
    )
    out = tmp_path / "maps"
    argv = ["sweep", str(sweep), "--out", str(out), "--jobs", "1", *QUIET]
    assert main(argv) == 0
    assert [p.name for p in out.iterdir()] == ["tiny"]
    assert (out / "tiny" / "summary.csv").is_file()


def test_compare_writes_below_out_with_a_digest_per_side(tmp_path):
    """``compare``: ``<out>/<A>_vs_<B>``; ``--set-a`` and ``--set-b`` of the same text are
    different comparisons, so different directories."""
    out = tmp_path / "cmp"
    pinned = ['options.mechanics="pinned"', 'options.drive="constant_speed"']
    for side in ("--set-a", "--set-b"):
        argv = ["compare", str(PAPER), str(PAPER), "--out", str(out), *QUIET]
        assert main([*argv, *[a for t in pinned for a in (side, t)]]) == 0
    names = sorted(p.name for p in out.iterdir())
    assert len(names) == 2 and all(
        n.startswith("paper_tabulated_vs_paper_tabulated+") for n in names
    )
    for name in names:
        assert (out / name / "comparison.csv").is_file()


def test_check_writes_below_out(tmp_path):
    """``check``: ``<out>/<folder name>/check.csv``, in a directory marked as recipsim's."""
    cases = tmp_path / "mycases"
    cases.mkdir()
    (cases / "one.toml").write_text('extends = "reference_r134a_lbp_ideal"\n')
    (cases / "expectations.toml").write_text('[cases.one]\nexpected = "converged"\n')
    out = tmp_path / "checks"
    assert main(["check", str(cases), "--fast", "--out", str(out), "--quiet"]) in (0, 1)
    assert (out / "mycases" / "check.csv").is_file() and (out / "mycases" / MARKER).is_file()
