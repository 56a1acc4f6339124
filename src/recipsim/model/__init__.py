"""Model: a case's compiled parameter arrays, initial state and scales, and the scenes
(cylinder, mechanism, coupled) that dispatch the right-hand side and events.

:mod:`.build` (``build_model``), :mod:`.scenes` (scene layout and dispatch),
:mod:`.mechanism_parameters` (mechanism data to the parameter array).
"""
