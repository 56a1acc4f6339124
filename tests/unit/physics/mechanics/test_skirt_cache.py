"""The skirt film's cache in the outputs (``piston_skirt_forces``): the Jacobian's columns
of states that do not move the piston take the film's results from the last two
evaluations, bit for bit, and nothing else does."""

from __future__ import annotations

import numpy as np

from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.bearing_forces import piston_skirt_forces
from recipsim.physics.mechanics.bearing_laws import skirt_film

LENGTH = 0.0115  # film length between the stations [m]


def _par(detailed: bool = False) -> np.ndarray:
    """Mechanism parameters with the reference piston's skirt film (19 mm bore, 10 um)."""
    par = np.zeros(lay.N_PAR)
    row = lay.P_BEARINGS + lay.B_PISTON_SKIRT * lay.N_BEARING_PAR
    par[row + lay.BP_LAW] = skirt_film.CODE
    par[row + lay.BP_DIAMETER] = 0.019
    par[row + lay.BP_CLEARANCE] = 10e-6
    par[row + lay.BP_VISCOSITY] = 4.6e-3
    par[row + lay.BP_CONTACT_FILM] = 1e-6
    par[row + lay.BP_CONTACT_STIFFNESS] = 1e10
    par[row + lay.BP_CONTACT_FRICTION] = 0.1
    par[lay.P_DETAILED_OUTPUTS] = float(detailed)
    return par


def _states(n: int, seed: int) -> list[tuple[float, ...]]:
    """Random station offsets (inside 0.9 of the clearance, some in contact range),
    rates and sliding speeds."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        e = rng.uniform(-9.5e-6, 9.5e-6, 2)
        v = rng.uniform(-0.02, 0.02, 2)
        out.append((e[0], e[1], v[0], v[1], rng.uniform(-5.0, 5.0), LENGTH))
    return out


def _recorded(aux: np.ndarray) -> np.ndarray:
    """What the report reads of the two stations and the friction."""
    out = lay.OUTPUTS.bundle(aux)
    return np.array(
        [
            out.bearing_force_piston_top_y,
            out.bearing_force_piston_skirt_y,
            out.bearing_power_loss_piston_top,
            out.bearing_power_loss_piston_skirt,
            out.contact_force_piston_top,
            out.contact_force_piston_skirt,
            out.piston_friction_force,
        ]
    )


def test_a_jacobian_like_sequence_gives_the_results_of_fresh_evaluations() -> None:
    """The order of a finite-difference Jacobian: a base state, a column that moves the
    piston (a new state), the base again, and so on; each result equals a fresh
    evaluation's bit for bit (the cache changes no number of the solve), the recorded
    outputs too."""
    par = _par()
    aux = np.zeros(lay.N_AUX)
    states = _states(12, 3)
    base = states[0]
    sequence = [base]
    for column in states[1:]:
        sequence += [column, base, base]
    for state in sequence:
        cached = piston_skirt_forces(par, aux, *state)
        fresh_aux = np.zeros(lay.N_AUX)
        fresh = piston_skirt_forces(par, fresh_aux, *state)
        assert cached == fresh
        assert np.array_equal(_recorded(aux), _recorded(fresh_aux))


def test_the_last_two_argument_sets_are_read_from_the_cache() -> None:
    """After A then B, both come from the cache (a marked result in its row comes back);
    a third set C evicts the one used longest ago (A), not B."""
    par = _par()
    aux = np.zeros(lay.N_AUX)
    a, b, c = _states(3, 7)
    piston_skirt_forces(par, aux, *a)
    piston_skirt_forces(par, aux, *b)
    rows = [lay.A_SKIRT_CACHE_ROWS + k * lay.N_FILM_CACHE for k in range(2)]
    for row in rows:
        aux[row + lay.FC_RESULTS + 2] = 123.0  # the friction, marked
    assert piston_skirt_forces(par, aux, *a)[2] == 123.0
    assert piston_skirt_forces(par, aux, *b)[2] == 123.0
    piston_skirt_forces(par, aux, *c)  # evicts a (b was used last)
    assert piston_skirt_forces(par, aux, *b)[2] == 123.0
    assert piston_skirt_forces(par, aux, *a)[2] != 123.0


def test_another_film_or_the_detailed_outputs_are_never_served_from_the_cache() -> None:
    """Another viscosity with the same motion misses (every argument of the film is part
    of the key); with the detailed outputs the film is evaluated for its peak pressure."""
    par = _par()
    aux = np.zeros(lay.N_AUX)
    state = _states(1, 11)[0]
    first = piston_skirt_forces(par, aux, *state)
    thicker = par.copy()
    thicker[lay.P_BEARINGS + lay.B_PISTON_SKIRT * lay.N_BEARING_PAR + lay.BP_VISCOSITY] *= 2.0
    assert piston_skirt_forces(thicker, aux, *state)[0] != first[0]
    piston_skirt_forces(_par(detailed=True), aux, *state)
    assert lay.OUTPUTS.bundle(aux).film_peak_pressure_piston_skirt > 0.0
