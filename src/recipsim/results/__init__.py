"""Results of a solved case: the cycle table, the summary row, closures, bearing metrics.

:mod:`.case_run` (a solved case post-processed: cycle table, summary and provenance),
:mod:`.tables` (the summary), :mod:`.cycle` (the cycle table's columns), :mod:`.bearings`
(bearing columns and per-bearing metrics).
"""
