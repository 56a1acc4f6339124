"""Parameter bundles in compiled code: a float array read at constant indices against a
NamedTuple, measured: the choice of flat arrays for the compiled parameters.

A kernel reads every parameter of a bundle of ``size`` floats (the shapes of the real
layouts: 60 cylinder parameters, 103 mechanism parameters, 165 of the coupled scene)
and is called a million times from a compiled loop, as the right-hand side is called by
the integrator; it is also called from Python, as a revolution's integration is. Each
variant compiles in a fresh interpreter, so neither pays the other's numba start-up.

Run ``python benchmarks/parameter_bundles.py`` from a source checkout for the table.
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
from typing import Any

#: Bundle sizes measured: the cylinder's, the mechanism's and the coupled scene's.
SIZES = (60, 103, 165)

#: Each variant in its own interpreter: compile time, then the loop and the call.
_CHILD = r"""
import json, sys, time
from collections import namedtuple
import numpy as np
from numba import njit

size, variant = int(sys.argv[1]), sys.argv[2]
read = "par[{i}]" if variant == "array" else "par.p{i}"
terms = " + ".join(read.format(i=i) + f" * x ** {i % 3}" for i in range(size))
source = f'''
def kernel(par, x):
    return {terms}

def loop(par, n):
    total = 0.0
    for j in range(n):
        total += kernel(par, 1.0 + j * 1e-9)
    return total
'''
space = {}
exec(source, space)
kernel = space["kernel"] = njit(space["kernel"])
loop = njit(space["loop"])
values = np.linspace(0.1, 1.0, size)
Bundle = namedtuple("Bundle", [f"p{i}" for i in range(size)])
par = values if variant == "array" else Bundle(*values.tolist())
start = time.perf_counter()
value = loop(par, 10)
compile_time = time.perf_counter() - start
loops = []
for _ in range(7):
    start = time.perf_counter()
    loop(par, 1_000_000)
    loops.append(time.perf_counter() - start)
calls = []
for _ in range(5):
    start = time.perf_counter()
    for _ in range(20_000):
        kernel(par, 1.0)
    calls.append((time.perf_counter() - start) / 20_000)
result = {"compile": compile_time, "loop": sorted(loops)[3], "call": sorted(calls)[2]}
print(json.dumps(result | {"value": value}))
"""


def measure_variant(size: int, variant: str) -> dict[str, float]:
    """Compile time [s], a million compiled kernel calls [s] (median of 7) and one call
    from Python [s] (median of 5) of ``variant`` (``"array"`` or ``"namedtuple"``)."""
    done = subprocess.run(
        [sys.executable, "-c", _CHILD, str(size), variant],
        capture_output=True,
        text=True,
        check=True,
    )
    result: dict[str, float] = json.loads(done.stdout.strip().splitlines()[-1])
    return result


def measure_bundles(sizes: tuple[int, ...] = SIZES, repeats: int = 1) -> list[dict[str, Any]]:
    """Both variants at every size of ``sizes``, medians over ``repeats`` fresh processes.

    Returns
    -------
    list of dict
        One row per size and variant: ``size``, ``variant``, ``compile [s]``,
        ``loop_1e6 [ms]``, ``call_from_python [us]`` and ``value`` (the kernel's sum, equal
        for both variants).
    """
    rows = []
    for size in sizes:
        for variant in ("array", "namedtuple"):
            runs = [measure_variant(size, variant) for _ in range(repeats)]
            rows.append(
                {
                    "size": size,
                    "variant": variant,
                    "compile [s]": statistics.median(r["compile"] for r in runs),
                    "loop_1e6 [ms]": 1e3 * statistics.median(r["loop"] for r in runs),
                    "call_from_python [us]": 1e6 * statistics.median(r["call"] for r in runs),
                    "value": runs[0]["value"],
                }
            )
    return rows


def main() -> None:
    """Print the table of :func:`measure_bundles` (three processes per variant)."""
    print(
        f"{'size':>5} {'variant':>11} {'compile [s]':>12} {'1e6 calls [ms]':>15} {'call [us]':>10}"
    )
    for row in measure_bundles(repeats=3):
        print(
            f"{row['size']:5d} {row['variant']:>11} {row['compile [s]']:12.3f} "
            f"{row['loop_1e6 [ms]']:15.2f} {row['call_from_python [us]']:10.2f}"
        )


if __name__ == "__main__":
    main()
