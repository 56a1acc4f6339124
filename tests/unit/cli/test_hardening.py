"""Hostile and careless input: never lose data, never hang, never a traceback.

Each test runs the command line in-process and asserts the exit status (0 done, 1 a
failure of the solver or the environment, 2 invalid input), that the message is one
line without a traceback, and that nothing outside ``--out`` changed: a sandbox holds
sentinel files beside and above the output directory and is compared afterwards.
"""

from __future__ import annotations

import errno
import os
import socket
import time
from pathlib import Path

import pandas as pd
import pytest

from helpers import CASES, REFERENCE, Sandbox, one_line_error
from recipsim.atomic import MARKER
from recipsim.cli.main import main
from recipsim.report import report_figures
from recipsim.report.case_report import report_name

FAST = ["--no-plots", "--quiet"]
#: few revolutions, for tests that need a report, not a converged one
BOUNDS = ["solver.max_revolutions=3", "solver.min_revolutions=1"]
BOUNDS_ARGS = [a for text in BOUNDS for a in ("--set", text)]


@pytest.fixture
def box(tmp_path: Path) -> Sandbox:
    return Sandbox(tmp_path)


def run(box: Sandbox, case: Path, *extra: str) -> int:
    return main(["run", str(case), "--out", str(box.out), *FAST, *extra])


# ----------------------------------------------------------------------------- data loss


@pytest.mark.parametrize("name", ['""', '"."', '".."', '"/tmp"', '"../src"', '"a/b"', '".hidden"'])
def test_a_case_name_that_is_not_a_plain_file_name_is_refused(box, capsys, name):
    """The name in the file or through --set never becomes a path outside --out."""
    status = run(box, REFERENCE, "--set", f"name={name}")
    err = one_line_error(capsys)
    assert status == 2 and "name" in err and "plain file name" in err
    in_file = box.case(f'extends = "reference_r134a_lbp_ideal"\nname = {name}\n')
    assert run(box, in_file) == 2
    one_line_error(capsys)
    assert box.unchanged()
    assert sorted(p.name for p in box.out.iterdir()) == ["other_report"]


def test_a_case_named_like_its_unsafe_file_gets_a_safe_default_name(box, capsys):
    path = box.case('extends = "reference_r134a_lbp_ideal"\n', name="my case (v2).toml")
    assert run(box, path, *BOUNDS_ARGS)
    assert (box.out / report_name("my_case__v2_", BOUNDS) / MARKER).is_file()
    assert box.unchanged()


def test_run_refuses_to_replace_a_directory_it_did_not_write(box, capsys):
    mine = box.out / "reference_r134a_lbp_ideal"
    mine.mkdir()
    (mine / "thesis.tex").write_text("precious")
    assert run(box, REFERENCE) == 2
    err = one_line_error(capsys)
    assert "not written by recipsim" in err
    assert (mine / "thesis.tex").read_text() == "precious"
    assert box.unchanged()


def test_out_on_a_file_is_refused(box, capsys):
    target = box.work / "beside.txt"  # an existing file
    assert main(["run", str(REFERENCE), "--out", str(target), *FAST]) == 2
    assert "not a directory" in one_line_error(capsys)
    assert box.unchanged()


def test_paper_and_compare_refuse_unsafe_names(box, capsys):
    paper = box.case('extends = "paper_tabulated"\nname = ""\n', name="p.toml")
    assert main(["paper", str(paper), "--no-plots"]) == 2
    one_line_error(capsys)
    bad = box.case('extends = "reference_r134a_lbp_ideal"\nname = "../escape"\n', name="c.toml")
    assert main(["compare", str(REFERENCE), str(bad), "--out", str(box.out / "c"), *FAST]) == 2
    one_line_error(capsys)
    assert box.unchanged()
    assert not (box.work / "escape").exists()


def test_a_report_replaces_its_previous_self_and_cleans_leftovers(box, capsys):
    """A killed run leaves ``.<name>.tmp-<host>-<pid>-<n>`` (and, killed while renaming,
    ``.<name>.old-<pid>-<ns>`` with recipsim's marker): the next run removes those whose
    process is gone and keeps a live one (a concurrent run's). Nothing else beside the
    report is touched: a user's ``.<name>.old-mybackup``, an ``.old-`` folder without the
    marker, one whose process still runs."""
    dead = _dead_pid()
    host = socket.gethostname()
    name = report_name("reference_r134a_lbp_ideal", BOUNDS)
    stale = box.out / f".{name}.tmp-{host}-{dead}-7"
    live = box.out / f".{name}.tmp-{host}-{os.getpid()}-8"
    old = box.out / f".{name}.old-{dead}-1700000000000000000"
    backup = box.out / f".{name}.old-mybackup"
    unmarked = box.out / f".{name}.old-{dead}-1700000000000000001"
    old_live = box.out / f".{name}.old-{os.getpid()}-1700000000000000002"
    for d in (stale, live, old, backup, unmarked, old_live):
        d.mkdir()
        (d / "summary.csv").write_text("half")
    for d in (old, old_live):
        (d / MARKER).write_text("written by recipsim")
    assert run(box, REFERENCE, *BOUNDS_ARGS) in (0, 1)
    assert run(box, REFERENCE, *BOUNDS_ARGS) in (0, 1)  # replaces its own report
    assert not stale.exists() and not old.exists()
    for kept in (live, backup, unmarked, old_live):
        assert (kept / "summary.csv").read_text() == "half", kept
    assert (box.out / name / "summary.csv").is_file()
    assert box.unchanged()


def _dead_pid() -> int:
    pid = 999_999
    while True:
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return pid
        pid -= 1


# ------------------------------------------------------------------- bounded input files


def test_pressure_curve_from_a_device_or_fifo_is_refused_at_once(box, capsys):
    fifo = box.inputs / "curve.csv"
    os.mkfifo(fifo)
    for target in ("curve.csv", "/dev/zero"):
        case = box.case(
            f'extends = "paper_tabulated"\n[pressure_curve]\nfile = "{target}"\n', "t.toml"
        )
        start = time.perf_counter()
        assert run(box, case, "--allow-external-paths") == 2
        assert time.perf_counter() - start < 5.0
        assert "not a regular file" in one_line_error(capsys)
    assert box.unchanged()


def test_oversized_csv_field_is_a_message(box, capsys):
    (box.inputs / "curve.csv").write_text(
        "crank_angle [deg],cylinder_pressure [Pa]\n" + "1" * 200_000 + ",1e5\n"
    )
    case = box.case('extends = "paper_tabulated"\n[pressure_curve]\nfile = "curve.csv"\n')
    assert run(box, case) == 2
    assert "CSV" in one_line_error(capsys)


def test_an_invalid_file_is_never_echoed(box, capsys):
    secret = "hunter2-secret-token"
    (box.inputs / "curve.csv").write_text(f"{secret},x\n{secret},{secret}\n")
    case = box.case('extends = "paper_tabulated"\n[pressure_curve]\nfile = "curve.csv"\n')
    assert run(box, case) == 2
    assert secret not in one_line_error(capsys)
    (box.inputs / "curve.csv").write_text(
        f"crank_angle [deg],cylinder_pressure [Pa]\n{secret},1e5\n"
    )
    assert run(box, case) == 2
    assert secret not in one_line_error(capsys)


@pytest.mark.parametrize("what", ["case", "refrigerant", "csv"])
def test_files_that_are_not_utf8_are_refused(box, capsys, what):
    garbage = b"\xff\xfe\x00name = \x81\n"
    if what == "case":
        case = box.inputs / "latin.toml"
        case.write_bytes(garbage)
    elif what == "refrigerant":
        (box.inputs / "refrigerants").mkdir()
        (box.inputs / "refrigerants" / "Rbad.toml").write_bytes(garbage)
        case = box.case('extends = "reference_r134a_lbp_ideal"\nrefrigerant = "Rbad"\n')
    else:
        (box.inputs / "curve.csv").write_bytes(garbage)
        case = box.case('extends = "paper_tabulated"\n[pressure_curve]\nfile = "curve.csv"\n')
    assert run(box, case) == 2
    assert "not UTF-8" in one_line_error(capsys)
    assert box.unchanged()


def test_deep_toml_and_deep_or_circular_extends_are_refused(box, capsys):
    deep = box.case("x = " + "[" * 5000 + "]" * 5000 + "\n", "deep.toml")
    assert run(box, deep) == 2
    assert "nested deeper" in one_line_error(capsys)
    table = box.case("a = " + "{b = " * 40 + "1" + "}" * 40 + "\n", "table.toml")
    assert run(box, table) == 2
    assert "nested deeper" in one_line_error(capsys)
    for i in range(30):
        parent = f'extends = "chain{i + 1}.toml"\n' if i < 29 else 'extends = "reference"\n'
        box.case(parent, f"chain{i}.toml")
    box.case('extends = "reference_r134a_lbp_ideal"\n', "reference.toml")
    assert run(box, box.inputs / "chain0.toml") == 2
    assert "chain of extends deeper" in one_line_error(capsys)
    box.case('extends = "loop_b.toml"\n', "loop_a.toml")
    box.case('extends = "loop_a.toml"\n', "loop_b.toml")
    assert run(box, box.inputs / "loop_a.toml") == 2
    assert "circular" in one_line_error(capsys)
    assert box.unchanged()


# ------------------------------------------------------------------ silently wrong input


@pytest.mark.parametrize(
    ("override", "key", "fragment"),
    [
        ("operating_point.shell_pressure=inf", "shell_pressure", "not a finite number"),
        ("operating_point.shell_pressure=nan", "shell_pressure", "not a finite number"),
        ('operating_point.shell_pressure="1e6 bar"', "shell_pressure", "out of range"),
        ('operating_point.shell_pressure="2000 bar"', "shell_pressure", "pressure range"),
        ('valves.discharge.port_diameter="30 mm"', "port_diameter", "narrower than the bore"),
        ('valves.suction.reed_width="5 mm"', "reed_width", "cannot cover its port"),
        ('geometry.liner_length="15 mm"', "liner_length", "too short"),
        ("output.plots=false", "output", "unknown key"),
        ('refrigerant="../refrigerants/R134a"', "refrigerant", "plain file name"),
    ],
)
def test_absurd_or_inconsistent_values_are_refused(box, capsys, override, key, fragment):
    status = run(box, REFERENCE, "--set", override)
    err = one_line_error(capsys)
    assert status == 2 and key in err and fragment in err, err
    assert box.unchanged()


def test_a_suction_pressure_below_the_fluids_range_is_refused(box, capsys):
    text = REFERENCE.read_text()
    explicit = (
        "[operating_point]\n"
        'suction_pressure = "1 Pa"\ncondensing_temperature = "54.4 degC"\n'
        'suction_temperature = "32.2 degC"\nliquid_temperature = "32.2 degC"\n'
        'shaft_speed = "3500 rpm"\n'
    )
    start = text.index("[operating_point]")
    end = text.index("[geometry]")
    case = box.case(text[:start] + explicit + "\n" + text[end:])
    assert run(box, case) == 2
    err = one_line_error(capsys)
    assert "suction_pressure" in err and "saturation pressure at the lowest temperature" in err
    assert box.unchanged()


def test_a_refrigerant_file_with_malformed_rating_points_is_a_message(box, capsys):
    (box.inputs / "refrigerants").mkdir()
    (box.inputs / "refrigerants" / "Rodd.toml").write_text(
        'name = "Rodd"\ncoolprop_name = "R134a"\nrating_points = 5\n'
    )
    case = box.case('extends = "reference_r134a_lbp_ideal"\nrefrigerant = "Rodd"\n')
    assert run(box, case) == 2
    assert "rating_points" in one_line_error(capsys)


# --------------------------------------------------------------------- paths in case files


def test_paths_outside_the_case_directory_need_the_opt_in(box, capsys):
    sub = box.inputs / "sub"
    sub.mkdir()
    (box.inputs / "base.toml").write_text('extends = "reference_r134a_lbp_ideal"\n')
    child = sub / "child.toml"
    child.write_text('extends = "../base.toml"\nname = "child"\n')
    assert run(box, child) == 2
    assert "--allow-external-paths" in one_line_error(capsys)
    absolute = sub / "absolute.toml"
    absolute.write_text(f'extends = "{REFERENCE.parent / "paper_tabulated.toml"}"\n')
    # the shipped cases are always readable, by name or by path
    fast = ["--set", "solver.max_revolutions=3", "--set", "solver.min_revolutions=1"]
    assert run(box, absolute, *fast) in (0, 1)
    capsys.readouterr()
    (box.inputs / "elsewhere").mkdir()
    outside = box.inputs / "elsewhere" / "outside.csv"
    outside.write_text((CASES / "paper_tabulated_pressure.csv").read_text())
    curve = sub / "curve.toml"
    curve.write_text(f'extends = "paper_tabulated"\n[pressure_curve]\nfile = "{outside}"\n')
    assert run(box, curve) == 2
    one_line_error(capsys)
    assert run(box, curve, "--allow-external-paths") == 0
    assert run(box, child, "--allow-external-paths", *fast) in (0, 1)
    assert box.unchanged()


# ---------------------------------------------------------------------- honest exit status


def test_run_exits_1_when_the_case_does_not_converge_and_keeps_the_report(box, capsys):
    status = run(
        box,
        REFERENCE,
        "--set",
        "solver.max_revolutions=2",
        "--set",
        "solver.min_revolutions=1",
        "--set",
        "solver.cycle_tolerance=1e-12",
    )
    err = one_line_error(capsys)
    assert status == 1 and "did not reach its periodic state in 2 revolutions" in err
    sets = ["solver.max_revolutions=2", "solver.min_revolutions=1", "solver.cycle_tolerance=1e-12"]
    summary = pd.read_csv(box.out / report_name("reference_r134a_lbp_ideal", sets) / "summary.csv")
    assert not bool(summary["converged [-]"].iloc[0])


def test_a_full_disk_is_one_line_exit_1_and_the_previous_report_survives(box, capsys, monkeypatch):
    fast = BOUNDS_ARGS
    run(box, REFERENCE, *fast)
    capsys.readouterr()
    report = box.out / report_name("reference_r134a_lbp_ideal", BOUNDS)
    before = (report / "summary.csv").read_bytes()

    def full(*args, **kwargs):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), "cycle.csv")

    monkeypatch.setattr(report_figures.pd.DataFrame, "to_csv", full)
    assert run(box, REFERENCE, *fast) == 1
    assert "No space left on device" in one_line_error(capsys)
    assert (report / "summary.csv").read_bytes() == before
    assert sorted(p.name for p in box.out.iterdir()) == ["other_report", report.name]
    assert box.unchanged()


def test_out_under_proc_is_one_line(capsys):
    assert main(["run", str(REFERENCE), "--out", "/proc/recipsim-nope", *FAST]) == 1
    assert "file system error" in one_line_error(capsys)


def test_shipped_hard_cases_name_their_base_by_name():
    """No shipped case climbs out of its directory (they load without the opt-in)."""
    for path in sorted(CASES.rglob("*.toml")):
        assert '"../' not in path.read_text(), path


# ------------------------------------------------------------------- property-based input

_LEAVES = None


def _leaf_keys() -> list[str]:
    """Dotted keys of every value of the reference case (and its tables) but the solver's."""
    global _LEAVES
    if _LEAVES is None:
        from recipsim.case.load import load_case

        raw = load_case(REFERENCE).raw
        keys: list[str] = []

        def walk(node: dict, prefix: str) -> None:
            for key, value in node.items():
                dotted = f"{prefix}.{key}" if prefix else key
                if isinstance(value, dict):
                    walk(value, dotted)
                elif not dotted.startswith("solver."):
                    keys.append(dotted)

        walk(raw, "")
        _LEAVES = keys + ["name", "extends", "pressure_curve.file", "output.x", "geometry.extra"]
    return _LEAVES


def _toml_values():
    from hypothesis import strategies as st

    numbers = st.one_of(
        st.floats(allow_nan=True, allow_infinity=True),
        st.integers(min_value=-(10**30), max_value=10**30),
        st.sampled_from([0, -1, 1e-300, 1e300, 2**63]),
    )
    units = st.sampled_from(["mm", "bar", "degC", "K", "rpm", "kg", "Pa", "m^3", "furlong", ""])
    quantity = st.builds(lambda x, u: f'"{x!r} {u}"', st.floats(allow_nan=False), units)
    text = st.text(max_size=30).map(lambda t: '"' + t.replace("\\", "/").replace('"', "'") + '"')
    literal = st.one_of(
        numbers.map(repr),
        quantity,
        text,
        st.sampled_from(["true", "[]", "[1, 2]", "{}", "{a = 1}", '"../x"', "nonsense bare"]),
    )
    return literal


def test_mutated_cases_exit_0_1_or_2_never_a_traceback_never_outside_out(tmp_path_factory):
    """Random overrides of any key (and random edits of the file's text) end in exit 0, 1
    or 2 with at most one line per message, write nothing outside ``--out``, and finish
    within 60 s each (the solver is capped at 3 revolutions)."""
    from hypothesis import HealthCheck, given, settings
    from hypothesis import strategies as st

    mutation = st.lists(
        st.tuples(st.sampled_from(_leaf_keys()), _toml_values()), min_size=1, max_size=3
    )
    edit = st.one_of(
        st.none(),
        st.tuples(st.integers(0, 4000), st.integers(0, 200), st.binary(max_size=20)),
    )

    @settings(
        max_examples=int(os.environ.get("RECIPSIM_FUZZ_EXAMPLES", "40")),
        deadline=None,
        derandomize=os.environ.get("RECIPSIM_FUZZ_RANDOM") is None,
        suppress_health_check=[HealthCheck.too_slow],
    )
    @given(mutation, edit)
    def check(changes: list[tuple[str, str]], text_edit) -> None:
        box = Sandbox(tmp_path_factory.mktemp("fuzz"))
        case = box.inputs / "mutant.toml"
        data = REFERENCE.read_bytes()
        if text_edit is not None:
            at, cut, insert = text_edit
            data = data[:at] + insert + data[at + cut :]
        case.write_bytes(data)
        overrides = [a for key, value in changes for a in ("--set", f"{key}={value}")]
        bounds = ["--set", "solver.max_revolutions=3", "--set", "solver.min_revolutions=1"]
        bounds += ["--set", "solver.cycle_tolerance=0.05"]
        start = time.perf_counter()
        import contextlib
        import io

        err = io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            status = main(["run", str(case), "--out", str(box.out), *FAST, *overrides, *bounds])
        assert status in (0, 1, 2)
        assert "Traceback" not in err.getvalue()
        assert time.perf_counter() - start < 60.0
        assert box.unchanged()

    check()


def test_python_m_recipsim_and_version():
    import subprocess
    import sys

    from recipsim import __version__

    out = subprocess.run(
        [sys.executable, "-m", "recipsim", "--version"], capture_output=True, text=True
    )
    assert out.returncode == 0 and out.stdout.strip() == f"recipsim {__version__}"
