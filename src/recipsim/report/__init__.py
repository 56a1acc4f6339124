"""Reports: CSV tables, figures (never choosing a matplotlib backend... see
:mod:`.plotting`), provenance, written atomically.

:mod:`.case_report` (one case's report and its provenance), :mod:`.plotting`,
:mod:`.mechanics_plots`, :mod:`.compare_plots` (figures).
"""
