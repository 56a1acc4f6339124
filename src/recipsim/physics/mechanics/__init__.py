"""Crank train on visco-elastic bearings (after Kurka, Paulino & Izuka, ISMA 2010).

Modules, one job each:

- :mod:`.layout`: index constants of the parameter array, state vector and outputs;
- :mod:`.bodies`: rigid-body kinematics of rotor, rod and piston markers;
- :mod:`.bearings`: bearing laws (``linear``, ``short_journal``, ``finite_journal``),
  dispatched per bearing;
- :mod:`.pinned`: rigid slider-crank inverse dynamics (bearing reactions, torque);
- :mod:`.flexible`: compiled right-hand side of the flexible model, outputs,
  initial state, state accessors;
- :mod:`.tabulated`: periodic interpolation of p(theta), ideal-cycle curve.

The mechanism data and its case tables are in :mod:`recipsim.case.mechanism`, the
parameter array built from them in :mod:`recipsim.model.mechanism_parameters`.
"""
