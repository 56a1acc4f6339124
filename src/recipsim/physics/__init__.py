"""Physics: one function or compiled kernel per submodel, units in the docstrings.

:mod:`.thermo` (properties from CoolProp or the table, cylinder balances, valve and gap
flow, heat transfer), :mod:`.mechanics` (bodies, bearing laws, pinned inverse dynamics,
flexible Newton-Euler right-hand side, tabulated pressure), :mod:`.kinematics`
(slider-crank), :mod:`.motor` (induction motor torque).
"""
