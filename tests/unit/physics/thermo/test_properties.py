"""The compiled-path property callback against CoolProp, including the two-phase dome."""

import CoolProp.CoolProp as CP
import numpy as np
import pytest

from recipsim.physics.thermo.properties import (
    PROP_CV,
    PROP_DPDRHO,
    PROP_DPDT,
    PROP_ENTHALPY,
    PROP_KAPPA,
    PROP_PRESSURE,
    PROP_QUALITY,
    STATUS_DOMAIN,
    STATUS_OK,
    HeosProperties,
)


def test_single_phase_matches_coolprop():
    props = HeosProperties("R134a", transport=True, t_min=200.0, t_max=450.0)
    assert props(350.0, 30.0) == STATUS_OK
    st = CP.AbstractState("HEOS", "R134a")
    st.update(CP.DmassT_INPUTS, 30.0, 350.0)
    b = props.buffer
    assert b[PROP_PRESSURE] == pytest.approx(st.p(), rel=1e-12)
    assert b[PROP_ENTHALPY] == pytest.approx(st.hmass(), rel=1e-12)
    assert b[PROP_CV] == pytest.approx(st.cvmass(), rel=1e-12)
    assert b[PROP_KAPPA] == pytest.approx(30.0 * st.speed_sound() ** 2 / st.p(), rel=1e-12)
    assert b[PROP_QUALITY] == -1.0
    # (dp/drho)_T from the identity used in the callback, against CoolProp's derivative
    assert b[PROP_DPDRHO] == pytest.approx(
        st.first_partial_deriv(CP.iP, CP.iDmass, CP.iT), rel=1e-8
    )


def test_two_phase_values_are_mixture_values():
    # thermo-notes H1: R134a at 263.15 K, 668.58 kg/m3 (x = 0.0075): CoolProp's own
    # cvmass is 8.8e8 and (dp/dT)_rho -2.35e10; the mixture values are 1355.5 and 7919
    props = HeosProperties("R134a", transport=False, t_min=200.0, t_max=450.0)
    assert props(263.15, 668.58) == STATUS_OK
    b = props.buffer
    assert b[PROP_CV] == pytest.approx(1355.5, rel=1e-3)
    assert b[PROP_DPDT] == pytest.approx(7919.0, rel=1e-3)
    assert 0.0 < b[PROP_QUALITY] < 0.01


def test_two_phase_cv_equals_internal_energy_derivative_at_constant_volume():
    # c_v = (du/dT)_v of the mixture: central difference of CoolProp's (correct) mixture u
    props = HeosProperties("Isobutane", transport=False, t_min=150.0, t_max=450.0)
    st = CP.AbstractState("HEOS", "Isobutane")
    for rho, t in ((20.0, 280.0), (300.0, 300.0)):
        props(t, rho)
        dt = 1e-3
        st.update(CP.DmassT_INPUTS, rho, t + dt)
        up = st.umass()
        st.update(CP.DmassT_INPUTS, rho, t - dt)
        um = st.umass()
        assert props.buffer[PROP_CV] == pytest.approx((up - um) / (2 * dt), rel=1e-5)


def test_outside_domain_is_a_status_not_an_exception():
    props = HeosProperties("R134a", transport=False, t_min=200.0, t_max=450.0)
    assert props(100.0, 5.0) == STATUS_DOMAIN
    assert props(300.0, -1.0) == STATUS_DOMAIN
    assert props(300.0, np.nan) == STATUS_DOMAIN


def test_ctrl_c_inside_the_property_callback_stops_the_solve():
    """A SIGINT lands while the compiled integrator is in the CoolProp callback (where
    nearly all Python bytecode of a solve runs); ctypes would swallow it and return a
    stale buffer as success. It must surface as KeyboardInterrupt, promptly."""
    import os
    import signal
    import threading
    import time

    from helpers import REFERENCE
    from recipsim.case.load import load_case
    from recipsim.model.build import build_model
    from recipsim.solve.periodic import solve_periodic

    # HEOS: the compiled code calls the CoolProp callback at every evaluation
    endless = [
        "solver.min_revolutions=1000",
        "solver.max_revolutions=1000",
        "options.properties=heos",
    ]
    model = build_model(load_case(REFERENCE, endless))
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        solve_periodic(model)
    timer.cancel()
    # 1000 revolutions take seconds; stopping shortly after the signal means it was seen
    assert time.perf_counter() - start < 0.3 + 2.0
    # the callback is re-armed: solving works normally afterwards
    assert solve_periodic(build_model(load_case(REFERENCE))).converged


def test_numba_types_every_callback_once_as_its_own_rule_would():
    """The registered typeof returns one cached FunctionType, equal to what numba's
    generic rule for function-address objects builds at every call, so compiled code
    finds the same overloads."""
    from numba.core.typing.typeof import Purpose, typeof
    from numba.experimental.function_type import typeof_function_type

    from recipsim.physics.thermo.properties import PROPS_TYPE

    first = HeosProperties("R134a", transport=False, t_min=200.0, t_max=450.0)
    second = HeosProperties("R600a", transport=False, t_min=200.0, t_max=450.0)
    assert typeof(first, Purpose.argument) is PROPS_TYPE
    assert typeof(second, Purpose.argument) is PROPS_TYPE
    assert typeof_function_type(first, None) == PROPS_TYPE
