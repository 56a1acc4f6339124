"""Scenes the compiled integrator can run, and the one layout they share.

A scene is a right-hand side, its event functions and its event actions. Three exist:

- ``SCENE_CYLINDER``: the CoolProp cylinder on the rigid crank at constant speed
  (:mod:`recipsim.physics.thermo.cylinder_rhs`);
- ``SCENE_MECHANISM``: the flexible crank train driven by a tabulated cylinder
  pressure p(theta) (:mod:`recipsim.physics.mechanics.flexible`);
- ``SCENE_COUPLED``: both in one state vector: the cylinder volume comes from the
  flexible piston's position, the mechanism feels the cylinder's pressure. The
  pressure is a function of the gas state only, so there is no algebraic loop.

One layout for all scenes (built once from the case by :func:`recipsim.model.build.build_model`),
declared in the tables :data:`IPAR`, :data:`PAR` (up to the tables), :data:`STATES`
(one per scene) and :data:`OUTPUTS`, composed of the cylinder's and the mechanism's
(:mod:`recipsim.physics.layout_table`):

- ``par`` = [cylinder block (``cylinder.N_PAR``) | mechanism block (``layout.N_PAR``) |
  scene scalars (``N_SCENE_PAR``) | tables: pressure angles, pressures, drive angles,
  drive torques, bearing tables]; offsets and lengths of the tables in ``ipar``;
- ``y`` = [cylinder states (coupled only) | mechanism states | mechanism quadratures];
- ``aux`` = [cylinder outputs (``cylinder.N_AUX``) | mechanism outputs
  (``layout.N_AUX``)]: every scene fills the cylinder block (pressure, volume,
  piston displacement, torques) so reports read one place.

Events: the cylinder's valve events (``cylinder.N_EVENTS``) and one terminal event,
the crank angle reaching ``par[P_THETA_END]`` (ends a revolution when the speed is
free).
"""

from __future__ import annotations

import math
from typing import Any

from numba import njit, types
from numba.core.errors import TypingError
from numba.extending import overload

from recipsim.physics.layout_table import Layout
from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.flexible import flexible_rhs
from recipsim.physics.mechanics.piston_pose import piston_axial_displacement, piston_lateral_offset
from recipsim.physics.mechanics.tabulated import tabulated_pressure
from recipsim.physics.thermo import cylinder as cyl
from recipsim.physics.thermo.cylinder_events import cylinder_event_action, cylinder_event_values
from recipsim.physics.thermo.cylinder_rhs import cylinder_gas_rhs, cylinder_rhs
from recipsim.physics.thermo.property_slots import STATUS_OK

SCENE_CYLINDER = 0
SCENE_MECHANISM = 1
SCENE_COUPLED = 2

# ---- integer parameters (after the cylinder's own) -----------------------------------
IPAR = Layout("scene integer parameters")
IPAR.include(cyl.IPAR)
I_PTAB = IPAR.add("pressure_table", "index", "offset of the pressure table in par")
I_PTAB_N = IPAR.add("pressure_table_length", "count", "its length")
I_DTAB = IPAR.add("drive_table", "index", "offset of the drive torque table in par")
I_DTAB_N = IPAR.add("drive_table_length", "count", "its length")
I_STOP_ON_ANGLE = IPAR.add("stop_on_angle", "code", "1: the terminal crank-angle event is armed")
I_BTAB = IPAR.add("bearing_tables", "index", "offset of the bearing tables (finite_journal)")
I_BTAB_N = IPAR.add("bearing_tables_length", "count", "their total length (at least 1)")
N_IPAR = IPAR.size

# ---- float parameters (before the tables) --------------------------------------------
PAR = Layout("scene float parameters")
PAR.include(cyl.PAR)
P_MECH = PAR.include(lay.PAR, "mechanism_")  # first entry of the mechanism block
P_SCENE = PAR.size  # first scene scalar
P_THETA_END = PAR.add("theta_end", "rad", "crank angle that ends a revolution")
P_LEAK_CLEARANCE = PAR.add("leak_clearance", "m", "radial piston clearance for the eccentricity")
N_SCENE_PAR = PAR.size - P_SCENE
P_TABLES = PAR.size

# ---- states --------------------------------------------------------------------------
#: Mechanism quadratures, after the mechanism states.
MECH_QUAD = Layout("mechanism quadratures")
MQ_DRIVE = MECH_QUAD.add("drive_work", "J", "work of the drive")
MQ_BEARINGS = MECH_QUAD.add("bearing_dissipation", "J", "energy dissipated in the bearings")
MQ_GAS = MECH_QUAD.add("gas_work_on_piston", "J", "work of the gas on the piston")
N_MECH_QUAD = MECH_QUAD.size
MECHANISM_STATES = Layout("mechanism scene states")
_MECH_Y_MECHANISM = MECHANISM_STATES.include(lay.STATES, "mechanism_")
MECHANISM_STATES.include(MECH_QUAD)
COUPLED_STATES = Layout("coupled scene states")
COUPLED_STATES.include(cyl.STATES)
_MECH_Y_COUPLED = COUPLED_STATES.include(lay.STATES, "mechanism_")
COUPLED_STATES.include(MECH_QUAD)
#: State table of each scene, indexed by scene code.
STATES = (cyl.STATES, MECHANISM_STATES, COUPLED_STATES)
#: Offsets of the mechanism block in the state vector of each scene.
MECH_Y = (0, _MECH_Y_MECHANISM, _MECH_Y_COUPLED)  # indexed by scene code (cylinder: unused)


def mechanism_state_offset(scene: int) -> int:
    """Index of the first mechanism state in the scene's state vector."""
    return MECH_Y[scene]


def named_state(scene: int, y: Any) -> Any:
    """The state vector ``y`` of ``scene`` by slot name (:meth:`Layout.bundle` of its
    table in :data:`STATES`): ``named_state(scene, y).suction_mass_in``."""
    return STATES[scene].bundle(y)


def state_size(scene: int) -> int:
    """Length of the state vector of ``scene``."""
    if scene == SCENE_CYLINDER:
        return cyl.N_STATE
    return MECH_Y[scene] + lay.N_STATE + N_MECH_QUAD


# ---- outputs -------------------------------------------------------------------------
OUTPUTS = Layout("scene outputs")
OUTPUTS.include(cyl.OUTPUTS)
A_MECH = OUTPUTS.include(lay.OUTPUTS, "mechanism_")  # first mechanism output
N_AUX = OUTPUTS.size

N_EVENTS = cyl.N_EVENTS + 1
EV_THETA_END = cyl.N_EVENTS


@njit(cache=True)
def _tables(par, ipar):
    p0 = ipar[I_PTAB]
    pn = ipar[I_PTAB_N]
    d0 = ipar[I_DTAB]
    dn = ipar[I_DTAB_N]
    return (
        par[p0 : p0 + pn],
        par[p0 + pn : p0 + 2 * pn],
        par[d0 : d0 + dn],
        par[d0 + dn : d0 + 2 * dn],
    )


@njit(cache=True)
def _bearing_tables(par, ipar):
    b0 = ipar[I_BTAB]
    return par[b0 : b0 + ipar[I_BTAB_N]]


@njit(cache=True)
def leakage_eccentricity(ym, mpar, piston_length: float, clearance: float) -> float:
    """Effective eccentricity ratio of a tilted, offset piston in the bore [-].

    The gap flow per unit pressure drop goes as ``(1 + 1.5 eps^2)`` locally; along the
    land the resistances add in series, so the effective ``eps`` follows from the mean
    of ``1 / (1 + 1.5 eps(s)^2)`` over the length (:func:`series_eccentricity`, exact
    for the linear eps(s) of a rigid tilted piston). The end offsets are clipped at
    +-0.95 of the clearance: the linear bearing law of the piston does not know it.
    """
    if clearance <= 0.0:
        return 0.0
    e_crown = piston_lateral_offset(ym, mpar, 0.0) / clearance
    e_skirt = piston_lateral_offset(ym, mpar, piston_length) / clearance
    return series_eccentricity(min(max(e_crown, -0.95), 0.95), min(max(e_skirt, -0.95), 0.95))


@njit(cache=True)
def series_eccentricity(e0: float, e1: float) -> float:
    """Uniform eccentricity ratio with the leakage of a gap whose eccentricity ratio
    varies linearly from ``e0`` to ``e1`` along the land [-].

    ``1 / (1 + 1.5 eps_eff^2) = mean over s of 1 / (1 + 1.5 eps(s)^2)``; for linear
    eps(s) the mean is ``(atan(k e1) - atan(k e0)) / (k (e1 - e0))``, ``k = sqrt(1.5)``.
    """
    k = math.sqrt(1.5)
    de = e1 - e0
    if abs(de) < 1e-6:
        em = 0.5 * (e0 + e1)
        mean = 1.0 / (1.0 + 1.5 * em * em)  # error O(de^2) < 1e-12
    else:
        mean = (math.atan(k * e1) - math.atan(k * e0)) / (k * de)
    return math.sqrt(max((1.0 / mean - 1.0) / 1.5, 0.0))


@njit(cache=True)
def _mechanism_part(t, y, m0, par, ipar, dydt, aux, p_gas) -> None:
    """Mechanism block of a scene: states at ``m0``, quadratures after them."""
    mpar = par[P_MECH : P_MECH + lay.N_PAR]
    _, _, da, dt = _tables(par, ipar)
    ym = y[m0 : m0 + lay.N_STATE]
    bt = _bearing_tables(par, ipar)
    flexible_rhs(t, ym, dydt[m0 : m0 + lay.N_STATE], aux[A_MECH:N_AUX], mpar, p_gas, da, dt, bt)
    q = m0 + lay.N_STATE
    dydt[q + MQ_DRIVE] = aux[A_MECH + lay.A_DRIVE_POWER]
    dydt[q + MQ_BEARINGS] = aux[A_MECH + lay.A_BEARING_POWER]
    dydt[q + MQ_GAS] = aux[A_MECH + lay.A_GAS_POWER]
    # torques in the cylinder block, so every scene reports them in one place and one
    # convention (reports/README.md): positive along the rotation, the gas torque the
    # gas force's power over the crank speed (negative while compressing)
    omega = ym[lay.Y_CRANK_SPEED]
    torque = aux[A_MECH + lay.A_DRIVE_TORQUE]
    gas_torque = aux[A_MECH + lay.A_GAS_POWER] / omega if omega != 0.0 else 0.0
    aux[cyl.A_TORQUE_SHAFT] = torque
    aux[cyl.A_TORQUE_GAS] = gas_torque
    aux[cyl.A_TORQUE_INERTIA] = torque + gas_torque


@njit(cache=True)
def mechanism_rhs(t, y, mode, par, ipar, props, pbuf, dydt, aux) -> int:
    """Flexible mechanism under a tabulated cylinder pressure (no gas state)."""
    mpar = par[P_MECH : P_MECH + lay.N_PAR]
    pa, pp, _, _ = _tables(par, ipar)
    theta = y[lay.Y_CRANK_ANGLE]
    p = tabulated_pressure(theta, pa, pp)
    for i in range(cyl.N_AUX):
        aux[i] = 0.0
    _mechanism_part(t, y, 0, par, ipar, dydt, aux, p)
    x, xdot = piston_axial_displacement(y, mpar)
    aux[cyl.A_THETA] = theta
    aux[cyl.A_PRESSURE] = p
    aux[cyl.A_VOLUME] = par[cyl.C_VC] + par[cyl.C_AP] * x
    aux[cyl.A_DVDT] = par[cyl.C_AP] * xdot
    aux[cyl.A_DISPLACEMENT] = x
    aux[cyl.A_PISTON_VELOCITY] = xdot
    aux[cyl.A_FORCE_GAS] = (p - par[cyl.C_PSHELL]) * par[cyl.C_AP]
    aux[cyl.A_QUALITY] = -1.0
    return STATUS_OK


@njit(cache=True)
def coupled_rhs(t, y, mode, par, ipar, props, pbuf, dydt, aux) -> int:
    """Cylinder gas and flexible mechanism in one state vector."""
    m0 = cyl.N_STATE
    mpar = par[P_MECH : P_MECH + lay.N_PAR]
    ym = y[m0 : m0 + lay.N_STATE]
    x, xdot = piston_axial_displacement(ym, mpar)
    ecc = leakage_eccentricity(ym, mpar, par[cyl.C_PISTON_LEN], par[P_LEAK_CLEARANCE])
    status = cylinder_gas_rhs(
        ym[lay.Y_CRANK_ANGLE],
        ym[lay.Y_CRANK_SPEED],
        x,
        xdot,
        ecc,
        y[:m0],
        mode,
        par,
        ipar,
        props,
        pbuf,
        dydt[:m0],
        aux,
    )
    if status != STATUS_OK:
        return status
    _mechanism_part(t, y, m0, par, ipar, dydt, aux, aux[cyl.A_PRESSURE])
    dydt[cyl.Q_SHAFT] = aux[A_MECH + lay.A_DRIVE_POWER]
    return STATUS_OK


@njit(cache=True)
def scene_rhs(t, y, mode, par, ipar, props, pbuf, dydt, aux) -> int:
    """Dispatch to the right-hand side of the scene in ``ipar[I_SCENE]`` (compiles every
    scene; the integrator calls :func:`rhs_for` instead)."""
    scene = ipar[cyl.I_SCENE]
    if scene == SCENE_MECHANISM:
        return mechanism_rhs(t, y, mode, par, ipar, props, pbuf, dydt, aux)
    if scene == SCENE_COUPLED:
        return coupled_rhs(t, y, mode, par, ipar, props, pbuf, dydt, aux)
    return cylinder_rhs(t, y, mode, par, ipar, props, pbuf, dydt, aux)


@njit(cache=True)
def _cylinder_event_values(y, mode, par, ipar, aux, g) -> None:
    cylinder_event_values(y, mode, par, ipar, aux, g)
    g[EV_THETA_END] = -1.0


@njit(cache=True)
def _mechanism_event_values(y, mode, par, ipar, aux, g) -> None:
    for k in range(cyl.N_EVENTS):
        g[k] = -1.0
    g[EV_THETA_END] = -1.0
    if ipar[I_STOP_ON_ANGLE] != 0:
        g[EV_THETA_END] = y[MECH_Y[SCENE_MECHANISM] + lay.Y_CRANK_ANGLE] - par[P_THETA_END]


@njit(cache=True)
def _coupled_event_values(y, mode, par, ipar, aux, g) -> None:
    cylinder_event_values(y[: cyl.N_STATE], mode, par, ipar, aux, g)
    g[EV_THETA_END] = -1.0
    if ipar[I_STOP_ON_ANGLE] != 0:
        g[EV_THETA_END] = y[MECH_Y[SCENE_COUPLED] + lay.Y_CRANK_ANGLE] - par[P_THETA_END]


@njit(cache=True)
def scene_event_values(y, mode, par, ipar, aux, g) -> None:
    """Event functions of the scene in ``ipar[I_SCENE]``; an event fires when g goes
    from <= 0 to > 0 (compiles every scene; the integrator calls
    :func:`event_values_for`)."""
    scene = ipar[cyl.I_SCENE]
    if scene == SCENE_MECHANISM:
        _mechanism_event_values(y, mode, par, ipar, aux, g)
    elif scene == SCENE_COUPLED:
        _coupled_event_values(y, mode, par, ipar, aux, g)
    else:
        _cylinder_event_values(y, mode, par, ipar, aux, g)


@njit(cache=True)
def _cylinder_event_action(k, y, mode, par, ipar, aux) -> bool:
    if k == EV_THETA_END:
        return True
    cylinder_event_action(k, y, mode, par, ipar, aux)
    return False


@njit(cache=True)
def _mechanism_event_action(k, y, mode, par, ipar, aux) -> bool:
    # the cylinder's events never fire in this scene (their functions stay at -1)
    return k == EV_THETA_END


@njit(cache=True)
def _coupled_event_action(k, y, mode, par, ipar, aux) -> bool:
    if k == EV_THETA_END:
        return True
    cylinder_event_action(k, y[: cyl.N_STATE], mode, par, ipar, aux)
    return False


@njit(cache=True)
def scene_event_action(k, y, mode, par, ipar, aux) -> bool:
    """Apply event ``k`` of the scene in ``ipar[I_SCENE]``; returns True when the event
    ends the integration (compiles every scene; the integrator calls
    :func:`event_action_for`)."""
    scene = ipar[cyl.I_SCENE]
    if scene == SCENE_MECHANISM:
        return _mechanism_event_action(k, y, mode, par, ipar, aux)
    if scene == SCENE_COUPLED:
        return _coupled_event_action(k, y, mode, par, ipar, aux)
    return _cylinder_event_action(k, y, mode, par, ipar, aux)


# ---- one scene at a time ---------------------------------------------------------------
# ``rhs_for(code, ...)``, ``event_values_for(code, ...)`` and ``event_action_for(code,
# ...)`` take the scene as a compile-time constant (numba's ``Literal[int]``: a global
# such as ``SCENE_CYLINDER`` passed down from a compiled caller) and resolve to that
# scene's function while numba types the caller, so the caller contains, and compiles,
# only its own scene's code (the cylinder scene alone needs about half the functions of
# all three): each scene's functions compiled on their own
# (:mod:`recipsim.model.scene_functions`, which also overloads these three for the
# integrator, to call those functions through pointers).
_BY_SCENE = {
    "rhs": (cylinder_rhs, mechanism_rhs, coupled_rhs),
    "event_values": (_cylinder_event_values, _mechanism_event_values, _coupled_event_values),
    "event_action": (_cylinder_event_action, _mechanism_event_action, _coupled_event_action),
}


def _scene_function(kind: str, code: Any) -> Any:
    """The compiled ``kind`` function of the scene whose code is the literal type
    ``code`` (a typing error for a scene not known at compile time)."""
    if not isinstance(code, types.IntegerLiteral):
        raise TypingError(f"the scene of {kind}_for must be a compile-time constant")
    return _BY_SCENE[kind][code.literal_value]


# The plain-Python bodies run only without the JIT (``NUMBA_DISABLE_JIT=1``: the
# pure-Python baseline); compiled code gets the overloads below.
def rhs_for(code, t, y, mode, par, ipar, props, pbuf, dydt, aux):  # type: ignore[no-untyped-def]
    """Right-hand side of scene ``code`` (a compile-time constant in compiled code)."""
    return _BY_SCENE["rhs"][code](t, y, mode, par, ipar, props, pbuf, dydt, aux)


def event_values_for(code, y, mode, par, ipar, aux, g):  # type: ignore[no-untyped-def]
    """Event functions of scene ``code`` (a compile-time constant in compiled code)."""
    return _BY_SCENE["event_values"][code](y, mode, par, ipar, aux, g)


def event_action_for(code, k, y, mode, par, ipar, aux):  # type: ignore[no-untyped-def]
    """Action of event ``k`` of scene ``code`` (a compile-time constant in compiled code)."""
    return _BY_SCENE["event_action"][code](k, y, mode, par, ipar, aux)


@overload(rhs_for)
def _rhs_for(code, t, y, mode, par, ipar, props, pbuf, dydt, aux):  # type: ignore[no-untyped-def]
    fn = _scene_function("rhs", code)
    return lambda code, t, y, mode, par, ipar, props, pbuf, dydt, aux: fn(
        t, y, mode, par, ipar, props, pbuf, dydt, aux
    )


@overload(event_values_for)
def _event_values_for(code, y, mode, par, ipar, aux, g):  # type: ignore[no-untyped-def]
    fn = _scene_function("event_values", code)
    return lambda code, y, mode, par, ipar, aux, g: fn(y, mode, par, ipar, aux, g)


@overload(event_action_for)
def _event_action_for(code, k, y, mode, par, ipar, aux):  # type: ignore[no-untyped-def]
    fn = _scene_function("event_action", code)
    return lambda code, k, y, mode, par, ipar, aux: fn(k, y, mode, par, ipar, aux)
