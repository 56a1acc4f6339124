"""Property evaluation for the compiled right-hand side.

The compiled integrator calls a *first-class function* ``props(T, rho) -> status``
that fills a shared buffer (layout below) with the properties of the cylinder gas.
For ``properties = "heos"`` that function is a C callback into one reused CoolProp
``AbstractState`` (``DmassT`` inputs); it is
passed to the compiled code as an argument, so the compiled integrator stays in
numba's on-disk cache.

Two-phase states: CoolProp's ``cvmass()`` and ``(dp/dT)_rho`` inside the dome are the
single-phase equation of state's values, wrong by orders of magnitude (see
``references/thermo-notes.md`` H1). Inside the dome the callback returns the
mixture values instead: ``(dp/dT)_rho = dp_sat/dT`` and
``c_v = (du/dT)_v`` of the saturated mixture from saturation-curve derivatives.

Status codes: 0 success; 1 the state is outside the equation of state (the trial
step is rejected and retried with a smaller step).
"""

from __future__ import annotations

import ctypes
import signal
import threading
import weakref
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any

import numba.experimental.function_type  # noqa: F401  (registers typeof for WAP objects)
import numpy as np
from numba import types
from numba.extending import typeof_impl

from recipsim.physics.thermo.property_slots import (
    N_PROPS,
    PROP_CONDUCTIVITY,
    PROP_CP,
    PROP_CV,
    PROP_DPDRHO,
    PROP_DPDT,
    PROP_ENTHALPY,
    PROP_K0,
    PROP_KAPPA,
    PROP_PRESSURE,
    PROP_QUALITY,
    PROP_VISCOSITY,
    SIGNAL_CHECK,
    STATUS_DOMAIN,
    STATUS_INTERRUPTED,
    STATUS_OK,
)

if TYPE_CHECKING:
    import CoolProp.CoolProp as CP

    from recipsim.physics.thermo.property_table import PropertyTable

PROPS_SIGNATURE = types.int32(types.float64, types.float64)

#: numba's type of every property callback (:class:`HeosProperties`), made once
PROPS_TYPE = types.FunctionType(PROPS_SIGNATURE)


class HeosProperties(types.WrapperAddressProtocol):
    """CoolProp HEOS properties of one fluid as a compiled-callable function.

    Parameters
    ----------
    coolprop_name : str
        CoolProp fluid name.
    transport : bool
        Also evaluate viscosity, conductivity and c_p (needed by heat transfer and
        leakage); skipped otherwise because it costs as much as the update itself.
    t_min, t_max : float
        Temperature range accepted [K]; outside it the call returns ``STATUS_DOMAIN``.
    tail : numpy.ndarray, optional
        Data appended to the buffer after its ``N_PROPS`` outputs: a property table
        (:meth:`recipsim.physics.thermo.property_table.PropertyTable.buffer_tail`) that the
        compiled code evaluates instead of this callback where it can.
    buffer : numpy.ndarray, optional
        The whole buffer, outputs and tail, made by the caller
        (:meth:`recipsim.physics.thermo.property_table.PropertyTable.property_buffer`,
        which reuses memory); replaces ``tail``.

    Attributes
    ----------
    buffer : numpy.ndarray
        The array the callback fills; pass it to the compiled code with the object.
    table : PropertyTable or None
        The property table whose data is the buffer's tail (set by the model).
    """

    def __init__(
        self,
        coolprop_name: str,
        transport: bool,
        t_min: float,
        t_max: float,
        backend: str = "HEOS",
        tail: np.ndarray | None = None,
        buffer: np.ndarray | None = None,
    ) -> None:
        self.coolprop_name = coolprop_name
        self.backend = backend
        if buffer is not None:
            self.buffer = buffer
        else:
            self.buffer = (
                np.zeros(N_PROPS) if tail is None else np.concatenate([np.zeros(N_PROPS), tail])
            )
        self.table: PropertyTable | None = None
        self.calls = 0
        self.failures = 0
        # ctypes keeps the callback below in a reference cycle, freed only by the cyclic
        # collector: held weakly, the buffer (11 MB with a table) is freed, or reused by
        # PropertyTable.property_buffer, as soon as this object goes
        buffer_ref = weakref.ref(self.buffer)
        # A Ctrl-C that arrives while this callback runs would be swallowed by ctypes
        # (it returns 0: "success" with a stale buffer). Catch it, fail this and every
        # later call so the integrator stops, and let the caller re-raise it.
        interrupted = self._interrupted = [False]
        callback, load_coolprop, coolprop_state = _coolprop_callback(
            coolprop_name, backend, transport, t_min, t_max, buffer_ref, interrupted
        )
        self._python_callback = callback
        self._load_coolprop = load_coolprop
        self._coolprop_state = coolprop_state
        self._cfunc = ctypes.CFUNCTYPE(ctypes.c_int32, ctypes.c_double, ctypes.c_double)(callback)

    @contextmanager
    def interrupts_deferred(self) -> Iterator[None]:
        """While the compiled integrator runs, a Ctrl-C sets the callback's flag instead
        of raising; :meth:`raise_if_interrupted` raises it once the integrator returns.

        Catching the interrupt inside the callback is not enough: Python may raise it at
        the callback's first bytecode, before its ``try``, and ctypes then swallows it
        (rarely, but the solve would then go on). Only in the main thread and under
        Python's default handler; where a caller has its own (a sweep finishing its
        point first), that handler is left alone.
        """
        if (
            threading.current_thread() is not threading.main_thread()
            or signal.getsignal(signal.SIGINT) is not signal.default_int_handler
        ):
            yield
            return
        flag = self._interrupted

        def defer(signum: int, frame: Any) -> None:
            flag[0] = True

        previous = signal.signal(signal.SIGINT, defer)
        try:
            yield
        finally:
            signal.signal(signal.SIGINT, previous)

    def raise_if_interrupted(self) -> None:
        """Re-raise a Ctrl-C caught inside the callback (and re-arm the callback)."""
        if self._interrupted[0]:
            self._interrupted[0] = False
            raise KeyboardInterrupt

    def __wrapper_address__(self) -> int:
        addr = ctypes.cast(self._cfunc, ctypes.c_void_p).value
        assert addr is not None
        return addr

    def signature(self) -> Any:
        return PROPS_SIGNATURE

    def __call__(self, temperature: float, density: float) -> int:
        """Evaluate from Python (fills :attr:`buffer`), as the compiled code does: from
        the table in the buffer's tail where it answers, else HEOS."""
        if self.table is not None:
            from recipsim.physics.thermo.property_table import STATUS_FALLBACK, table_props

            status = int(table_props(temperature, density, self.buffer))
            if status != STATUS_FALLBACK:
                return status
        status = int(self._python_callback(temperature, density))
        self.raise_if_interrupted()
        return status


@typeof_impl.register(HeosProperties)
def _typeof_properties(val: HeosProperties, c: Any) -> types.FunctionType:
    """numba's type of a property callback: :data:`PROPS_TYPE`, made once. numba's own
    rule for a function-address object builds a new ``FunctionType`` from its signature
    at every compiled call it is passed to (a few calls per revolution)."""
    return PROPS_TYPE


def _fill_two_phase(
    sat: CP.AbstractState,
    temperature: float,
    density: float,
    p: float,
    h: float,
    q: float,
    buf: np.ndarray,
) -> None:
    """Mixture properties inside the saturation dome at (T, rho).

    ``c_v = (du/dT)_v`` of the mixture, from u = u_l + x (u_v - u_l) and
    x = (v - v_l)/(v_v - v_l) with the derivatives of u_l, u_v, v_l, v_v along the
    saturation curve; ``(dp/dT)_rho = dp_sat/dT`` (Clapeyron).
    """
    import CoolProp.CoolProp as CP  # loaded by the callback already

    sat.update(CP.QT_INPUTS, 0.0, temperature)
    rho_l = sat.rhomass()
    u_l = sat.umass()
    du_l = sat.first_saturation_deriv(CP.iUmass, CP.iT)
    drho_l = sat.first_saturation_deriv(CP.iDmass, CP.iT)
    sat.update(CP.QT_INPUTS, 1.0, temperature)
    rho_v = sat.rhomass()
    u_v = sat.umass()
    du_v = sat.first_saturation_deriv(CP.iUmass, CP.iT)
    drho_v = sat.first_saturation_deriv(CP.iDmass, CP.iT)
    dpsat = sat.first_saturation_deriv(CP.iP, CP.iT)
    mu_v, k_v, cp_v = sat.viscosity(), sat.conductivity(), sat.cpmass()
    v, v_l, v_v = 1.0 / density, 1.0 / rho_l, 1.0 / rho_v
    dv_l = -drho_l / rho_l**2
    dv_v = -drho_v / rho_v**2
    x = (v - v_l) / (v_v - v_l)
    dx = (-dv_l * (v_v - v_l) - (v - v_l) * (dv_v - dv_l)) / (v_v - v_l) ** 2
    cv = du_l + x * (du_v - du_l) + (u_v - u_l) * dx
    buf[PROP_PRESSURE] = p
    buf[PROP_ENTHALPY] = h
    buf[PROP_CV] = cv
    buf[PROP_DPDT] = dpsat
    buf[PROP_KAPPA] = 1.0
    buf[PROP_K0] = 1.0
    buf[PROP_QUALITY] = q
    # at constant T inside the dome the pressure does not depend on density
    buf[PROP_DPDRHO] = 0.0
    # transport of the mixture approximated by the saturated vapour's
    buf[PROP_VISCOSITY] = mu_v
    buf[PROP_CONDUCTIVITY] = k_v
    buf[PROP_CP] = cp_v


def _coolprop_callback(
    coolprop_name: str,
    backend: str,
    transport: bool,
    t_min: float,
    t_max: float,
    buffer_ref: weakref.ref[np.ndarray],
    interrupted: list[bool],
) -> tuple[Callable[[float, float], int], Callable[[], None], Callable[[], Any]]:
    """The Python callback that fills the buffer from CoolProp, the loader of CoolProp
    (called at the first state), and a getter of its ``AbstractState`` (``None`` until
    loaded). ``interrupted[0]`` is set by a Ctrl-C caught inside the callback.
    """
    # CoolProp is loaded at the first call (with the fluid's gas constant and critical
    # temperature): with a property table in the buffer's tail the compiled code may
    # never need it
    state: Any = None
    sat: Any = None
    dmasst = i_p = i_t = i_d = twophase = 0
    r_gas = t_crit = 0.0

    def load_coolprop() -> None:
        nonlocal state, sat, dmasst, i_p, i_t, i_d, twophase, r_gas, t_crit
        import CoolProp.CoolProp as CP

        state = CP.AbstractState(backend, coolprop_name)
        sat = CP.AbstractState(backend, coolprop_name)
        dmasst, twophase = CP.DmassT_INPUTS, CP.iphase_twophase
        i_p, i_t, i_d = CP.iP, CP.iT, CP.iDmass
        r_gas = state.gas_constant() / state.molar_mass()  # [J/(kg K)]
        t_crit = state.T_critical()  # [K]

    def callback(temperature: float, density: float) -> int:
        try:
            if temperature == SIGNAL_CHECK:  # the integrator asks whether to stop
                return STATUS_INTERRUPTED if interrupted[0] else STATUS_OK
            if interrupted[0]:
                return STATUS_DOMAIN
            if not (t_min <= temperature <= t_max) or not (density > 0.0):
                return STATUS_DOMAIN
            buf = buffer_ref()
            if buf is None:  # the object is gone: nothing to fill
                return STATUS_DOMAIN
            if state is None:
                load_coolprop()
            state.update(dmasst, density, temperature)
            p = state.p()
            if temperature < t_crit and state.phase() == twophase:
                _fill_two_phase(sat, temperature, density, p, state.hmass(), state.Q(), buf)
            else:
                buf[PROP_PRESSURE] = p
                buf[PROP_ENTHALPY] = state.hmass()
                cv = state.cvmass()
                dpdt = state.first_partial_deriv(i_p, i_t, i_d)
                buf[PROP_CV] = cv
                buf[PROP_DPDT] = dpdt
                c = state.speed_sound()
                buf[PROP_KAPPA] = density * c * c / p
                cp0 = state.cp0mass()
                buf[PROP_K0] = cp0 / (cp0 - r_gas)
                buf[PROP_QUALITY] = -1.0
                # (dp/drho)_T = c^2 - T (dp/dT)^2 / (rho^2 c_v)
                buf[PROP_DPDRHO] = c * c - temperature * dpdt * dpdt / (density**2 * cv)
                if transport:
                    buf[PROP_VISCOSITY] = state.viscosity()
                    buf[PROP_CONDUCTIVITY] = state.conductivity()
                    buf[PROP_CP] = state.cpmass()
        except Exception:
            return STATUS_DOMAIN
        except BaseException:  # KeyboardInterrupt, SystemExit
            interrupted[0] = True
            return STATUS_DOMAIN
        return STATUS_OK

    return callback, load_coolprop, lambda: state
