"""Operating maps: a base case swept over a grid of case values, run in parallel.

A sweep file (``cases/sweeps/*.toml``, see ``docs/sweeps.md``) names a base case,
fixed overrides, axes (a dotted case key and a list of values each, combined as a
grid) and optional explicit points. ``recipsim sweep`` runs every point in worker
processes (or on a Dask cluster), writes each finished point to disk as it finishes,
resumes an interrupted sweep without recomputing finished points and assembles
``summary.csv`` and the map plots.

Modules: :mod:`.spec` reads sweep files, :mod:`.plan` expands and validates the
points, :mod:`.worker` solves one point, :mod:`.runner` distributes the points,
:mod:`.store` keeps finished points, :mod:`.outputs` writes the summary table, map plots
and provenance, :mod:`.plots` draws the maps and :mod:`.engine` ties them together. The
command line is :mod:`recipsim.cli.sweep`: it imports nothing heavy at module level, so
``recipsim run`` does not pay for the sweep machinery (nor for Dask).
"""
