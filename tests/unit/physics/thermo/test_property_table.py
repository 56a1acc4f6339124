"""The interpolated property table (``options.properties = "table"``) against CoolProp HEOS.

Tables are cached in a temporary ``RECIPSIM_CACHE`` for the session. The R134a table is
the one a run uses (default resolution); the others are small (narrow temperature
range, coarse grid) to keep the file fast: the cell self-check holds every answered
state to the tolerance whatever the resolution, coarse grids just hand more states to
HEOS.
"""

from __future__ import annotations

import math
import shutil

import CoolProp.CoolProp as CP
import numpy as np
import pytest

from helpers import REFERENCE, solve_case
from recipsim.case.load import load_case
from recipsim.model import scenes
from recipsim.model.build import build_model
from recipsim.physics.thermo import cylinder as cyl
from recipsim.physics.thermo.properties import (
    N_PROPS,
    PROP_PRESSURE,
    STATUS_DOMAIN,
    STATUS_OK,
    HeosProperties,
)
from recipsim.physics.thermo.property_table import (
    STATUS_FALLBACK,
    THERMO_SLOTS,
    TableResolution,
    table_props,
)
from recipsim.physics.thermo.property_table_build import measure_error
from recipsim.physics.thermo.property_table_cache import cache_path, load_property_table
from recipsim.results.tables import summary

# R134a limits of refrigerants/R134a.toml (-60 C .. 180 C)
R134A = ("R134a", 213.15, 453.15)
COARSE = TableResolution(dt=2.0, dx=0.08, dt_sat=0.5)

# Target of the issue: relative error <= 1e-4 on p, h and the derivatives. The cells are
# built to 1e-5 at their centres; the bound allows the larger error off-centre.
THERMO_BOUND = 1e-4
# viscosity, conductivity (heat transfer, leakage: correlations good to 10-20 %)
TRANSPORT_BOUND = 1e-3


@pytest.fixture(scope="module")
def cache(tmp_path_factory):
    directory = tmp_path_factory.mktemp("recipsim-cache")
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("RECIPSIM_CACHE", str(directory))
        yield directory


@pytest.fixture(scope="module")
def r134a(cache):
    return load_property_table(*R134A)


def _buffer(table, transport=True):
    return np.concatenate([np.zeros(N_PROPS), table.buffer_tail(transport)])


def _worst(errors, names):
    return max(errors[n]["max"] for n in names if n in errors)


def test_single_phase_near_and_far_from_the_dome(r134a):
    err = measure_error(r134a, n=300, seed=7, regions=("vapour", "near_dew", "supercritical"))
    for region in ("vapour", "near_dew", "supercritical"):
        e = err[region]
        assert _worst(e["errors"], THERMO_SLOTS) <= THERMO_BOUND, (region, e)
        assert _worst(e["errors"], ("viscosity", "conductivity", "c_p")) <= TRANSPORT_BOUND
        # the table answers nearly everywhere away from the critical point
        assert e["fallback"] < 0.05, (region, e["fallback"])
    # the vapour a compressor sees is far better than the bound
    assert _worst(err["vapour"]["errors"], THERMO_SLOTS) < 1e-6


def test_two_phase_reproduces_the_mixture_values(r134a):
    err = measure_error(r134a, n=300, seed=3, regions=("two_phase",))["two_phase"]
    e = err["errors"]
    assert _worst(e, ("p", "h", "c_v", "dp/dT")) <= 1e-5
    assert e["quality"]["max"] <= 1e-6  # absolute
    # the HEOS conventions inside the dome are reproduced exactly
    assert e["kappa"]["max"] == 0.0 and e["k0"]["max"] == 0.0 and e["dp/drho"]["max"] == 0.0
    assert err["fallback"] < 0.05


def test_near_critical_r744_is_accurate_or_handed_to_heos(cache):
    table = load_property_table("CO2", 216.592, 400.0, COARSE)
    err = measure_error(table, n=300, seed=5, regions=("near_critical", "supercritical"))
    near = err["near_critical"]
    assert _worst(near["errors"], THERMO_SLOTS) <= THERMO_BOUND
    # CO2 at the critical point: the table refuses, HEOS answers
    buf = _buffer(table)
    assert table_props(304.2, 467.6, buf) == STATUS_FALLBACK
    assert 0.1 < near["fallback"] < 0.9
    assert _worst(err["supercritical"]["errors"], THERMO_SLOTS) <= THERMO_BOUND


def test_domain_and_fallback_statuses(r134a):
    buf = _buffer(r134a)
    assert table_props(200.0, 5.0, buf) == STATUS_DOMAIN  # below the refrigerant's range
    assert table_props(460.0, 5.0, buf) == STATUS_DOMAIN  # above it
    assert table_props(300.0, -1.0, buf) == STATUS_DOMAIN
    assert table_props(300.0, math.nan, buf) == STATUS_DOMAIN
    assert table_props(math.nan, 10.0, buf) == STATUS_DOMAIN
    assert table_props(260.0, 1400.0, buf) == STATUS_FALLBACK  # compressed liquid
    assert table_props(300.0, 1e-4, buf) == STATUS_FALLBACK  # below the lowest density
    assert table_props(300.0, 20.0, buf) == STATUS_OK  # superheated vapour
    assert table_props(260.0, 100.0, buf) == STATUS_OK  # inside the dome


def test_heos_failures_are_not_papered_over(cache):
    # CoolProp has no saturation derivatives for the pseudo-pure R410A, so the HEOS
    # callback fails inside its dome; the table hands such states to HEOS, not zeros
    table = load_property_table("R410A", 250.0, 320.0, COARSE)
    buf = _buffer(table, transport=False)
    st = CP.AbstractState("HEOS", "R410A")
    st.update(CP.QT_INPUTS, 1.0, 280.0)
    rho_v = st.rhomass()
    assert table_props(280.0, 2.0 * rho_v, buf) == STATUS_FALLBACK
    heos = HeosProperties("R410A", transport=False, t_min=250.0, t_max=320.0)
    assert heos(280.0, 2.0 * rho_v) == STATUS_DOMAIN
    # its vapour is tabulated as for any fluid
    assert table_props(300.0, 0.5 * rho_v, buf) == STATUS_OK


def test_cache_hit_miss_stale_and_corrupt(cache):
    args = ("R134a", 260.0, 300.0, COARSE)
    first = load_property_table(*args)
    assert not first.from_cache and first.path is not None and first.path.is_file()
    assert first.path.parent.parent == cache
    second = load_property_table(*args)
    assert second.from_cache and second.load_time > 0.0
    np.testing.assert_array_equal(second.data, first.data)
    assert second.max_error == first.max_error

    # a corrupt file is rebuilt and replaced
    first.path.write_bytes(b"not an npz file")
    with pytest.warns(UserWarning, match="unreadable"):
        third = load_property_table(*args)
    assert not third.from_cache
    np.testing.assert_array_equal(third.data, first.data)
    assert load_property_table(*args).from_cache

    # a file of another key (another range here, as for a CoolProp update) is stale
    other = cache_path("R134a", 260.0, 310.0, COARSE)
    shutil.copy(first.path, other)
    fresh = load_property_table("R134a", 260.0, 310.0, COARSE)
    assert not fresh.from_cache and fresh.data.size > first.data.size


def test_rhs_falls_back_to_heos_exactly(cache, r134a):
    # the cylinder right-hand side with the table: near the critical point (handed to
    # HEOS) it equals the HEOS model's to the last bit; in the vapour, to the table error
    models = {
        b: build_model(load_case(REFERENCE, [f"options.properties={b}"])) for b in ("heos", "table")
    }
    assert models["table"].ipar[cyl.I_PROPS] == cyl.PROPS_TABLE
    assert models["heos"].ipar[cyl.I_PROPS] == cyl.PROPS_HEOS
    for temp, rho, rtol in ((374.3, 512.0, 0.0), (330.0, 20.0, 1e-6)):
        out = {}
        for b, m in models.items():
            y = m.y0.copy()
            y[cyl.Y_T], y[cyl.Y_RHO] = temp, rho
            dydt = np.zeros_like(y)
            aux = np.zeros(scenes.N_AUX)
            status = scenes.scene_rhs(
                0.0, y, m.mode0.copy(), m.par, m.ipar, m.props, m.props.buffer, dydt, aux
            )
            assert status == STATUS_OK
            out[b] = (aux[cyl.A_PRESSURE], dydt[cyl.Y_T], dydt[cyl.Y_RHO])
        np.testing.assert_allclose(out["table"], out["heos"], rtol=rtol, atol=0.0)
    assert models["table"].props.buffer[PROP_PRESSURE] > 0.0


def test_reference_cycle_table_against_heos(cache, r134a):
    # property errors at the cycle's states are ~1e-7 and the integrator runs at
    # rtol 1e-6: the cycle results must agree far below the 1e-4 asked for
    heos = solve_case(REFERENCE, ["options.properties=heos"])
    table = solve_case(REFERENCE, ["options.properties=table"])
    assert table.model.props.table is not None
    assert table.model.props.table.max_error <= THERMO_BOUND
    a, b = summary(heos), summary(table)
    for key in ("suction_mass_flow [kg/s]", "indicated_power [W]", "COP [-]"):
        assert b[key] == pytest.approx(a[key], rel=1e-5), key
    assert table.revolutions == heos.revolutions
