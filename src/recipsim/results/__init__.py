"""Results of a solved case: the cycle table, the summary row, closures, bearing metrics.

:mod:`.run` (``simulate_case``: case -> solution -> tables), :mod:`.tables` (cycle
table and summary), :mod:`.bearings` (bearing columns and per-bearing metrics).
"""
