"""Valve events of the cylinder: the event functions of the current modes and the
actions (mode switches, seat and stop impacts with restitution) at an event
(layout: :mod:`recipsim.physics.thermo.cylinder`).

Modes (``mode[0]`` suction, ``mode[1]`` discharge): ideal 0 closed / 1 open; reed
0 seated / 1 free / 2 at the stop.
"""

from __future__ import annotations

from numba import njit

from recipsim.physics.thermo import cylinder as cyl
from recipsim.physics.thermo.valve_models import moves_reeds


@njit(cache=True)
def cylinder_event_values(y, mode, par, ipar, aux, g) -> None:
    """Event functions of the current modes; an event fires when g goes from <= 0 to > 0."""
    for k in range(cyl.N_EVENTS):
        g[k] = -1.0
    valves = ipar[cyl.I_VALVES]
    if valves == cyl.VALVES_IDEAL:
        p = aux[cyl.A_PRESSURE]
        if mode[0] == 1:
            g[0] = -aux[cyl.A_MDOT_SUC]
        elif mode[1] == 1:
            g[2] = -aux[cyl.A_MDOT_DIS]
        else:
            g[0] = (par[cyl.C_PS] - p) / par[cyl.C_PS]
            g[2] = (p - par[cyl.C_PD]) / par[cyl.C_PD]
    elif moves_reeds(valves):
        for i in range(2):
            base = cyl.C_VALVE0 + i * cyl.VALVE_BLOCK
            ix = cyl.Y_XS + 2 * i
            force = aux[cyl.A_FORCE_REED_S] if i == 0 else aux[cyl.A_FORCE_REED_D]
            if mode[i] == 0:
                g[2 * i] = force
            elif mode[i] == 1:
                g[2 * i] = -y[ix] / par[base + cyl.V_STOP]
                g[2 * i + 1] = (y[ix] - par[base + cyl.V_STOP]) / par[base + cyl.V_STOP]
            else:
                g[2 * i] = -(force - par[base + cyl.V_STIFF] * par[base + cyl.V_STOP])


@njit(cache=True)
def cylinder_event_action(k, y, mode, par, ipar, aux) -> None:
    """Apply event ``k`` at the event time: switch modes, impacts with restitution."""
    valves = ipar[cyl.I_VALVES]
    i = k // 2
    if valves == cyl.VALVES_IDEAL:
        mode[i] = 1 - mode[i]
        return
    base = cyl.C_VALVE0 + i * cyl.VALVE_BLOCK
    ix = cyl.Y_XS + 2 * i
    stop = par[base + cyl.V_STOP]
    v_stick = par[cyl.C_VSTICK]
    force = aux[cyl.A_FORCE_REED_S] if i == 0 else aux[cyl.A_FORCE_REED_D]
    if mode[i] == 0:  # seated -> free
        mode[i] = 1
        y[ix] = 0.0
        y[ix + 1] = 0.0
    elif mode[i] == 2:  # leaves the stop
        mode[i] = 1
        y[ix] = stop
        y[ix + 1] = 0.0
    elif k % 2 == 0:  # hits the seat
        v_new = -par[base + cyl.V_REST] * y[ix + 1]
        y[ix] = 0.0
        if force > 0.0:  # gas already pushes it open again: leave from the seat
            y[ix + 1] = max(v_new, 0.0)
        elif v_new < v_stick:  # a slow impact against a closing force sticks
            mode[i] = 0
            y[ix + 1] = 0.0
        else:
            y[ix + 1] = v_new
    else:  # hits the stop
        v_new = -par[base + cyl.V_REST] * y[ix + 1]
        y[ix] = stop
        net = force - par[base + cyl.V_STIFF] * stop
        if net > 0.0 and -v_new < v_stick:  # held against the stop
            mode[i] = 2
            y[ix + 1] = 0.0
        else:
            y[ix + 1] = min(v_new, 0.0)
