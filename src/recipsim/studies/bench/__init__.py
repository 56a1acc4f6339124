"""``recipsim bench``: speed against error.

A ladder of settings (integrator, tolerances, property backend, periodic solver,
model fidelity) is run on one case and compared with a tight-tolerance reference of
the same case: median wall time of the solve after start-up against the relative
error of mass flow, indicated power, COP, every bearing's RMS and peak load and the
RMS error of the pressure trace. Modules:

- :mod:`.ladder`: the rungs (name, overrides, integrator) and the reference settings;
- :mod:`.ivp`: the periodic iteration driven by ``scipy.integrate.solve_ivp``;
- :mod:`.measure`: one rung run in this process, timed, its compared quantities;
- :mod:`.baseline`: the pure-Python ``solve_ivp`` baseline in a process without numba;
- :mod:`.errors`: relative errors against the reference;
- :mod:`.report`: ``work_precision.csv``, ``work_precision.png``, ``bench.json``;
- the ``recipsim bench`` subcommand is :mod:`recipsim.cli.bench`.
"""
