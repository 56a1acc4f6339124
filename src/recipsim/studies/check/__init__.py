"""Stability checks: run a set of (hard) cases and compare each outcome with its expectation.

``recipsim check hard`` runs every case file of a directory (see
:mod:`recipsim.cli.check`), one row per case, and never stops at a failing case:

- outcome ``converged`` / ``not_converged``: the run went to its end (the periodic
  steady state was, or was not, reached within ``solver.max_revolutions``); the message
  is the run's status message (:mod:`recipsim.results.outcome`: the diagnosis of a
  ``not_converged`` run, what ``no_delivery`` or ``subharmonic`` leave out);
- ``refused``: the case was rejected before integrating (:class:`CaseError`, the
  refrigerant's envelope included);
- ``failed``: the integration stopped (:class:`SolverError`, crank angle and state in
  the message), or an internal error (its type is named).

Each case's expectation comes from ``expectations.toml`` beside the case files
(:mod:`.expectations`); the closures it bounds are defined in :mod:`.metrics`.

Modules: :mod:`.expectations` finds the case files and reads what each is expected to do,
:mod:`.metrics` measures a run (closures, non-finite results, reed openings),
:mod:`.judge` runs one case and judges it, :mod:`.run` checks a set of cases (in worker
processes with ``jobs``) and :mod:`.table` writes the text table and ``check.csv``.
"""
