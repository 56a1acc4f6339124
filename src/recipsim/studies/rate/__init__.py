"""Rate a compressor as its maker does: a rating table over evaporating and condensing
temperatures at a standard's conditions (EN 12900, AHRI 540, ASHRAE LBP), the ten
coefficients of each quantity's polynomial, and the comparison with a maker's catalogue
and coefficients.

Modules: :mod:`.polynomial` (the ten-term polynomial, its fit, the sources of its form),
:mod:`.coefficients` (coefficient files written and read), :mod:`.grid` (the grid and its
defaults), :mod:`.tables` (the points in the standard's units, fits, residuals),
:mod:`.compare` (catalogue and maker), :mod:`.run` (end to end, through the sweep
engine), :mod:`.figures` and :mod:`.report` (the files). The command line is
:mod:`recipsim.cli.rate`; the Python API :func:`recipsim.rate`.
"""
