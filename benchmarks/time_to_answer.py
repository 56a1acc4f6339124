"""Wall time of the commands a user waits for, for one or more installed versions in turn.

    python benchmarks/time_to_answer.py [--recipsim PATH ...] [--repeats 5] [--first-run]

Each ``--recipsim`` is a ``recipsim`` executable (default: the one on PATH); the versions
are run one after the other for every repeat, so that a change in the machine's speed
during the measurement touches all of them alike. Scenarios: a warm
``recipsim run reference_r134a_lbp`` with its figures and with ``--no-plots``, and
``recipsim sweep throughput_100 --jobs 2 --fresh`` with and without its map plots; with
``--first-run`` also the first run of the reference case with empty caches (a fresh
``RECIPSIM_CACHE``), which compiles the solver and builds the property table.

Prints the median and the range of each scenario per version. Not part of the test suite
and not shipped: speed claims come from measurements such as this one and from
``recipsim bench`` (speed against error).
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

SCENARIOS = {
    "run": ["run", "reference_r134a_lbp", "--quiet"],
    "run --no-plots": ["run", "reference_r134a_lbp", "--quiet", "--no-plots"],
    "sweep --jobs 2": ["sweep", "throughput_100", "--jobs", "2", "--fresh", "--quiet"],
    "sweep --jobs 2 --no-plots": [
        "sweep",
        "throughput_100",
        "--jobs",
        "2",
        "--fresh",
        "--quiet",
        "--no-plots",
    ],
}


def timed(command: list[str], env: dict[str, str], cwd: Path) -> float:
    """Wall time of one command [s]; raises if it fails."""
    start = time.perf_counter()
    subprocess.run(command, env=env, cwd=cwd, check=True, capture_output=True)
    return time.perf_counter() - start


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--recipsim", action="append", default=None, metavar="PATH")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--first-run", action="store_true")
    parser.add_argument("--only", action="append", default=None, help="scenario names")
    args = parser.parse_args(argv)
    executables = args.recipsim or [shutil.which("recipsim") or "recipsim"]
    scenarios = {k: v for k, v in SCENARIOS.items() if not args.only or k in args.only}
    times: dict[tuple[str, str], list[float]] = {}
    with tempfile.TemporaryDirectory(prefix="recipsim-timing-") as tmp:
        work = Path(tmp)
        env = dict(os.environ)
        for exe in executables:  # warm the caches of every version first (not timed)
            timed([exe, *SCENARIOS["run"], "--out", str(work / "warm")], env, work)
        for _ in range(args.repeats):
            for name, words in scenarios.items():
                for exe in executables:
                    out = work / "out" / Path(exe).parent.name
                    seconds = timed([exe, *words, "--out", str(out)], env, work)
                    times.setdefault((name, exe), []).append(seconds)
        if args.first_run:
            for _ in range(max(1, args.repeats // 3)):
                for exe in executables:
                    cache = work / "cache" / str(time.time_ns())
                    fresh = {**env, "RECIPSIM_CACHE": str(cache)}
                    fresh.pop("NUMBA_CACHE_DIR", None)
                    words = [*SCENARIOS["run"], "--out", str(work / "first")]
                    times.setdefault(("first run, empty caches", exe), []).append(
                        timed([exe, *words], fresh, work)
                    )
                    shutil.rmtree(cache, ignore_errors=True)
    for (name, exe), values in times.items():
        print(
            f"{name:<28} {exe}: median {statistics.median(values):.2f} s "
            f"(range {min(values):.2f}-{max(values):.2f} s, {len(values)} runs)"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
