"""A library never chooses the user's matplotlib backend (a notebook's ``plt.show()``
must keep working after ``import recipsim...``)."""

from __future__ import annotations

import os
import subprocess
import sys

from helpers import REFERENCE

_CHILD = f"""
import importlib, pkgutil
import matplotlib
matplotlib.use("svg")
import recipsim
names = [m.name for m in pkgutil.walk_packages(recipsim.__path__, "recipsim.")]
for name in names:
    if not name.endswith("__main__"):
        importlib.import_module(name)
from recipsim.case.load import load_case
from recipsim.pipeline import simulate_case
from recipsim.report.plotting import plot_pv
run = simulate_case(load_case({str(REFERENCE)!r}, ["solver.max_revolutions=2",
                                                    "solver.min_revolutions=1"]))
fig = plot_pv(run.cycle)
print(len(names), matplotlib.get_backend())
"""


def test_importing_and_plotting_leave_the_backend_alone():
    env = {k: v for k, v in os.environ.items() if k != "MPLBACKEND"}
    out = subprocess.run(
        [sys.executable, "-c", _CHILD], env=env, capture_output=True, text=True, timeout=300
    )
    assert out.returncode == 0, out.stderr[-3000:]
    count, backend = out.stdout.split()
    assert int(count) > 50
    assert backend == "svg"
