"""recipsim: reciprocating refrigeration compressor simulator.

The CoolProp real-gas cylinder model and the crank train are solved together, step
by step, with a compiled integrator. See the README for the two commands a
newcomer needs and ``docs`` in the repository for the physics.
"""

__version__ = "0.1.0"
