"""The command ends without the interpreter's last full garbage collection."""

from __future__ import annotations

import gc
import importlib
import subprocess
import sys

#: the module (``recipsim.cli.main`` as an attribute is the entry function)
cli_main = importlib.import_module("recipsim.cli.main")


_THREE_COMMANDS = """
import importlib, sys
cli = importlib.import_module("recipsim.cli.main")
freeze = cli._quick_exit
def counted():
    with open(sys.argv[1], "a") as handle:
        handle.write("exit hook\\n")
    freeze()
cli._quick_exit = counted
for _ in range(3):
    try:
        cli.main(["--version"])
    except SystemExit:
        pass
"""


def test_main_registers_the_freeze_once_per_process(tmp_path):
    """However often a process calls main(), the hook runs once, at its exit."""
    log = tmp_path / "hook.log"
    done = subprocess.run(
        [sys.executable, "-c", _THREE_COMMANDS, str(log)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.count("recipsim") == 3
    assert log.read_text().splitlines() == ["exit hook"]


def test_the_freeze_moves_every_object_to_the_permanent_generation():
    try:
        cli_main._quick_exit()
        assert gc.get_freeze_count() > 1000
    finally:
        gc.unfreeze()


def test_a_command_still_flushes_and_exits_with_its_status(tmp_path):
    """What the command prints arrives, and its status is kept, with the hook at exit."""
    done = subprocess.run(
        [sys.executable, "-m", "recipsim", "--version"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0 and "recipsim" in done.stdout
    bad = subprocess.run(
        [sys.executable, "-m", "recipsim", "run", str(tmp_path / "missing.toml"), "--quiet"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert bad.returncode == 2 and "missing.toml" in bad.stderr
