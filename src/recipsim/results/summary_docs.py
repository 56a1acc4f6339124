"""What each column of ``summary.csv`` means: name, unit and meaning, one entry per
column (or one per bearing or node, :data:`~recipsim.results.column_docs.PLACEHOLDERS`),
in the order ``reports/README.md`` lists them (:mod:`recipsim.report.column_readme`
generates its tables from these).

The meanings are Markdown, as the README shows them. The thermal network's node row
lists the nodes from their table (:data:`recipsim.physics.thermo.shell_nodes.TEMPERATURES`).
The columns that only some choices of a model slot add are documented from those
choices' declarations (:func:`recipsim.results.column_docs.choice_docs`).

Size (over the project's 400 lines): one declaration per summary column, a single table
like a layout's; split, the README's order would live in two places.
"""

from __future__ import annotations

from typing import Any

from recipsim.physics.friction_models import FRICTION_MODELS
from recipsim.physics.motor_models import MOTOR_MODELS
from recipsim.physics.thermo.shell_nodes import TEMPERATURES
from recipsim.results.column_docs import ColumnDoc, choice_docs, choice_names
from recipsim.results.column_docs import column as _c
from recipsim.results.loss_breakdown import COP_COST_COLUMNS
from recipsim.slots import Slot


def _choices(slot: Slot[Any]) -> str:
    """The slot's choice names in backticks, the last after "or"."""
    return choice_names(list(slot.names))


def _nodes() -> str:
    """The network's nodes with what each stands for."""
    return ", ".join(f"`{e.name}` ({e.meaning})" for e in TEMPERATURES.entries)


#: ``summary.csv``.
SUMMARY_DOCS: tuple[ColumnDoc, ...] = (
    _c("case", "case name (file name unless the case sets `name`)"),
    _c("refrigerant", "refrigerant name of the case (`refrigerants/<name>.toml`)"),
    _c(
        "pressure",
        "pressure source: `cylinder` (CoolProp gas) or `tabulated` (p(theta) from a CSV)",
    ),
    _c("mechanics", "crank train: `pinned` (rigid) or `flexible` (visco-elastic bearings)"),
    _c("drive", "`constant_speed` or `torque_profile` (pinned driving torque applied, speed free)"),
    _c("valves", "valve model: `ideal`, `quasi_static` or `reed`"),
    _c("heat_transfer", "heat-transfer model: `adiabatic`, `annand` or `adair`"),
    _c("leakage", "leakage model: `none` or `piston_gap`"),
    _c("evaporating_temperature [K]", "dew-point temperature at the suction pressure"),
    _c(
        "condensing_temperature [K]",
        "bubble-point temperature at the discharge pressure; empty (NaN) when transcritical",
    ),
    _c("suction_pressure [Pa]", "suction plenum pressure"),
    _c("suction_temperature [K]", "suction gas temperature at the compressor inlet"),
    _c("discharge_pressure [Pa]", "discharge plenum pressure"),
    _c(
        "liquid_temperature [K]",
        "liquid (or gas-cooler outlet) temperature at the expansion device, for the capacity",
    ),
    _c("pressure_ratio [-]", "discharge over suction pressure"),
    _c("shaft_speed [rpm]", "crank speed"),
    _c("swept_volume [m3]", "piston area times stroke"),
    _c("clearance_volume [m3]", "cylinder volume at top dead centre"),
    _c(
        "suction_mass_flow [kg/s]",
        "net mass into the cylinder through the suction valve per second",
    ),
    _c(
        "discharge_mass_flow [kg/s]",
        "net mass out through the discharge valve per second (the flow delivered to the system)",
    ),
    _c(
        "leakage_mass_flow [kg/s]",
        "net mass out of the cylinder through the piston-cylinder gap per second",
    ),
    _c(
        "suction_backflow_mass_flow [kg/s]",
        "mass flowing back out through the suction valve per second (part of the net flow)",
    ),
    _c(
        "discharge_backflow_mass_flow [kg/s]",
        "mass flowing back in through the discharge valve per second",
    ),
    _c(
        "cooling_capacity [W]",
        "discharge mass flow times (h of the suction gas at the suction pressure and suction "
        "temperature - h of the liquid at the discharge pressure and liquid temperature; "
        "saturated liquid at the bubble point), the temperatures being the rating standard's "
        "where the case names one (`operating_point.standard`); the compressor inlet, not "
        'the heated gas the valve draws with `thermal = "network"` (so are the volumetric '
        "and isentropic efficiencies)",
    ),
    _c(
        "discharge_backflow_fraction [-]",
        "mass that flowed back in through the discharge valve / mass that left through it, "
        "over the converged revolution (cumulative quadratures); above 0.03 the run logs a "
        "warning (`recipsim: <case>: x % of the gas through the discharge valve flows back "
        "...`)",
    ),
    _c(
        "suction_backflow_fraction [-]",
        "mass pushed back out through the suction valve / mass that came in through it; same "
        "warning above 0.03",
    ),
    _c(
        "indicated_power [W]",
        "-integral of p dV over the revolution times the revolutions per second",
    ),
    _c(
        "shaft_power [W]",
        "integral of driving torque times speed over the revolution, per second (the rigid "
        "crank has no friction, so it equals the indicated power; on flexible bearings it "
        "also pays the bearing dissipation), plus `friction_power` with `options.friction = "
        '"mean"`',
    ),
    _c(
        "standard",
        "the operating point's rating standard (`none`, `ASHRAE_LBP`, `EN12900`, `AHRI_540`)",
    ),
    _c(
        "ambient_temperature [K]",
        "air around the compressor shell (the standard's, or "
        "`operating_point.ambient_temperature`)",
    ),
    _c("friction", f"`options.friction`: {_choices(FRICTION_MODELS)}"),
    _c("motor", f"`options.motor`: {_choices(MOTOR_MODELS)}"),
    _c(
        "friction_power [W]",
        "mechanical friction of the bearings and the piston: 0 for `off`; for `mean` the sum "
        "of the Petroff journals, the viscous skirt, the thrust bearing and the oil pump "
        "below (added to the shaft power; a heat source of the thermal network); for "
        "`films` the sum of the films' `friction_power_<name>` and `piston_friction_power` "
        "(already in the shaft power)",
    ),
    _c(
        "motor_electrical_power [W]",
        "electrical input: the shaft power (lossless motor) or the shaft power plus the "
        "equivalent circuit's losses at the load torque shaft power / mean speed",
    ),
    _c("motor_efficiency [-]", "shaft power / electrical power (1 for the lossless motor)"),
    _c(
        "motor_power_factor [-]",
        "active over apparent input power of the circuit at that load (NaN: lossless)",
    ),
    _c("motor_loss_power [W]", "electrical - shaft power: the sum of the six loss columns below"),
    _c("motor_main_copper_loss_power [W]", "main-winding copper loss R1m I_m^2"),
    _c(
        "motor_auxiliary_copper_loss_power [W]",
        "auxiliary (run-capacitor) winding copper loss (0 for RSIR)",
    ),
    _c(
        "motor_rotor_copper_loss_power [W]",
        "rotor copper loss of the forward and backward fields, s P_f + (2 - s) P_b",
    ),
    _c("motor_core_loss_power [W]", "core loss G_c V^2"),
    _c("motor_stray_loss_power [W]", "stray-load loss, a fraction of the output"),
    _c("motor_windage_loss_power [W]", "the rotor's friction and windage in the shell gas"),
    _c("motor_current [A]", "line current, rms (NaN: lossless)"),
    _c(
        "motor_speed_at_load [rpm]",
        "speed at which the circuit delivers the load torque; at constant speed the cycle "
        'itself runs at `shaft_speed`, which equals it with `options.speed = "motor_slip"` '
        "(NaN: lossless)",
    ),
    _c("loss_motor [W]", "loss chain (docs/electrical.md): electrical - shaft power"),
    _c(
        "loss_mechanical [W]",
        "shaft - indicated power: journal and skirt friction, bearing damping",
    ),
    _c(
        "loss_suction_valve [W]",
        "p-V area below the suction plenum pressure while the suction valve passes gas, per second",
    ),
    _c(
        "loss_discharge_valve [W]",
        "p-V area above the discharge plenum pressure while the discharge valve passes gas, "
        "per second",
    ),
    _c(
        "loss_mufflers [W]",
        "flow work of the mufflers' pressure drops, m (dp_s / rho_s + dp_d / rho_d)",
    ),
    _c(
        "loss_leakage [W]",
        "leaked mass flow times the isentropic enthalpy rise from the compressor inlet",
    ),
    _c(
        "loss_suction_heating [W]",
        "delivered mass flow times the extra isentropic enthalpy rise of gas drawn at the "
        "cylinder-inlet temperature instead of the compressor inlet's",
    ),
    _c(
        "loss_cylinder_heat_and_other [W]",
        "indicated - isentropic power - the named thermodynamic losses: cylinder heat "
        "exchange, re-expansion, valve dynamics (the remainder: with `isentropic_power` the "
        "loss columns add up to `motor_electrical_power`)",
    ),
    _c(
        "capacity_loss_suction_heating [W]",
        "cooling capacity lost to suction heating: the capacity at the cylinder-inlet "
        "density scaled to the compressor inlet's, less the capacity (same volumetric "
        "efficiency)",
    ),
    _c(
        "capacity_loss_mufflers [W]",
        "cooling capacity lost to the suction muffler's pressure drop (plenum density "
        "against the line's at the cylinder-inlet temperature)",
    ),
    _c(
        "capacity_loss_leakage [W]",
        "cooling capacity of the leaked mass flow (at the capacity's enthalpy difference)",
    ),
    *(
        _c(
            cost,
            f"COP gained by removing `{loss.removesuffix(' [W]')}` alone (and the capacity "
            "it costs, if any): (Q + dQ) / (W - L) - Q / W with the electrical power W",
        )
        for loss, cost in COP_COST_COLUMNS.items()
    ),
    _c(
        "bearing_dissipation_power [W]",
        "power absorbed by the bearings, -(sum F.de/dt + T_journal w_journal + T_bushing "
        "w_bushing) averaged over the revolution: the oil films' friction and squeeze "
        "dissipation, the contact friction, the piston film's friction and, for linear "
        "bearings, the damper dissipation (at the periodic state their spring part "
        "integrates to zero; on an unconverged revolution it also holds the change of spring "
        "energy); 0 for the pinned crank",
    ),
    # the columns only some choices add (the flexible crank's, the film bearings', the
    # mean friction's), from their declarations
    *choice_docs("summary").values(),
    _c(
        "motor_input_power [W]",
        "induction motor drive: air-gap power, synchronous speed x time-mean motor torque "
        "(the electrical input less the stator losses, which are not modelled); NaN for "
        "other drives",
    ),
    _c(
        "motor_rotor_loss_power [W]",
        "induction motor drive: rotor copper loss, air-gap power - shaft power (= slip x "
        "air-gap power at constant torque); NaN for other drives",
    ),
    _c(
        "motor_slip [-]",
        "induction motor drive: 1 - mean crank speed / synchronous speed; with the "
        "equivalent-circuit motor under another drive, the circuit's slip at the cycle's "
        "load (1 - motor_speed_at_load / synchronous speed, the slip the cycle runs at with "
        'options.speed = "motor_slip"); NaN otherwise',
    ),
    _c("isentropic_power [W]", "discharge mass flow times (h(p_d, s_suction) - h_suction)"),
    _c(
        "heat_to_wall [W]",
        "mean heat flow from the gas to the cylinder wall (negative when the wall heats the gas)",
    ),
    _c(
        "COP [-]",
        "cooling capacity over motor electrical power (the electrical COP; equal to capacity "
        "/ shaft power with the lossless motor)",
    ),
    _c("indicated_COP [-]", "cooling capacity over indicated power"),
    _c(
        "volumetric_efficiency [-]",
        "discharge mass flow over (suction density x swept volume x revolutions per second)",
    ),
    _c("isentropic_efficiency [-]", "isentropic power over shaft power"),
    _c("indicated_isentropic_efficiency [-]", "isentropic power over indicated power"),
    _c(
        "discharge_temperature [K]",
        "temperature at the discharge pressure and the mass-weighted enthalpy of the gas "
        "that left through the discharge valve",
    ),
    _c(
        "mass_balance_residual [-]",
        "(suction - discharge - leakage mass) / suction mass over the converged revolution; "
        "below a volumetric efficiency of about 1 % the scale is 1 % of the swept mass "
        "(suction density x swept volume) instead, the larger of the two "
        "(`recipsim.solve.residual.closures`). The cycle residual includes this closure / "
        "10, so a converged run has it below 10 x `solver.cycle_tolerance` (1e-3 by "
        "default); `no_delivery` rows carry their own (see `status`)",
    ),
    _c(
        "energy_balance_residual [-]",
        "(indicated work - (enthalpy rise of the through-flow - heat into the gas)) / "
        "indicated work; the scale is at least 1 % of (discharge - suction pressure) x swept "
        "volume; below 10 x `solver.cycle_tolerance` on a converged run, like the mass "
        "closure",
    ),
    _c("thermal", "`options.thermal`: `fixed_wall` or `network`"),
    _c(
        "cylinder_inlet_temperature [K]",
        "temperature of the suction plenum the suction valve draws from: the inlet "
        "`suction_temperature` with `fixed_wall`, the suction muffler node with `network`",
    ),
    _c(
        "suction_plenum_pressure [Pa]",
        "pressure of that plenum: the suction line pressure less the suction muffler's drop "
        "K rho v^2 / 2 (`network`)",
    ),
    _c(
        "discharge_plenum_pressure [Pa]",
        "discharge plenum pressure: the line pressure plus the discharge muffler's drop "
        "(`network`)",
    ),
    _c(
        "shell_heat_rejection [W]",
        "heat from the shell to the ambient, UA (T_shell - T_ambient) (`network`; NaN with "
        "`fixed_wall`)",
    ),
    _c(
        "node_temperature_<node> [K]",
        f"temperature of each network node (`network`): {_nodes()}",
    ),
    _c(
        "discharge_line_temperature [K]",
        "temperature of the gas leaving the compressor (the discharge muffler node at the "
        "line pressure)",
    ),
    _c(
        "thermal_balance_residual [-]",
        "largest over the nodes of abs(sum of the node's energy balance terms) / largest "
        "term, the terms (links, sources, streams as m (h_upstream - h_node)) evaluated with "
        "the converged revolution's own flows",
    ),
    _c(
        "thermal_energy_balance_residual [-]",
        "whole compressor: (indicated power + friction + motor loss - delivered flow x "
        "(h_outlet - h_inlet) - shell heat) / (indicated power + friction + motor loss)",
    ),
    _c(
        "revolutions [-]",
        "revolutions integrated until the cycle residual fell below the tolerance",
    ),
    _c(
        "cycle_residual [-]",
        "largest relative change over the last revolution (states and cycle integrals, see "
        "`solve/periodic.py`), or the mass or energy closure over 10 if larger "
        "(`solve/residual.py`)",
    ),
    _c(
        "converged [-]",
        "`True` when the cycle residual reached `solver.cycle_tolerance` within "
        "`solver.max_revolutions`",
    ),
    _c(
        "status",
        'how the run ended (the words of sweeps, `docs/sweeps.md`, "Statuses and the '
        'envelope"): `ok`; `no_delivery` (converged, the discharge valve never opens: '
        "discharge temperature, capacity, COP and isentropic efficiencies NaN by design, "
        "volumetric efficiency 0, closures on the suction side and the gross p dV work); "
        "`subharmonic` (a period of n revolutions: flows, powers and closures are "
        "n-revolution averages); `not_converged`",
    ),
    _c(
        "status_message",
        "empty for `ok`; what `no_delivery` / `subharmonic` leave out, or the diagnosis of a "
        "`not_converged` run (residual history, the states that drift)",
    ),
    _c("rhs_evaluations [-]", "right-hand-side evaluations over all revolutions"),
    _c("steps [-]", "accepted integrator steps over all revolutions"),
    _c(
        "rejected_steps [-]",
        "rejected integrator steps (error too large or state outside the property range)",
    ),
    _c(
        "events [-]",
        "located events (valve openings, impacts on seat and stop, closings) over all revolutions",
    ),
    _c(
        "wall_time [s]",
        "wall time of the periodic solution (without loading, start-up and report writing)",
    ),
    _c(
        "periodic_method",
        "how the periodic state was found: `revolutions` (revolution iteration), `shooting` "
        "(Newton on the one-revolution map, `auto` having handed over or asked for), "
        "`shooting, fell back to revolutions`, `revolutions, shooting's period-1 orbit "
        "repels` (one-revolution shooting found an orbit with a real Floquet multiplier "
        "below -1.05, rejected: `solve/periodic.py`), `shooting on the n-revolution map` (a "
        "`subharmonic` run that `auto` handed over while it approached a period of n "
        "revolutions: `solve/subharmonic.py`), `none` (nothing integrated)",
    ),
    _c("newton_iterations [-]", "Newton steps of the shooting solver (0 for revolution iteration)"),
    _c(
        "suction_valve_opening_angle [deg]",
        "crank angle at which the suction valve opens (start of the longest open interval, "
        "to the sample resolution)",
    ),
    _c("suction_valve_closing_angle [deg]", "crank angle of the last open sample of that interval"),
    _c("discharge_valve_opening_angle [deg]", "as above for the discharge valve"),
    _c("discharge_valve_closing_angle [deg]", "as above for the discharge valve"),
    _c("peak_cylinder_pressure [Pa]", "highest sampled cylinder pressure"),
    _c("minimum_cylinder_pressure [Pa]", "lowest sampled cylinder pressure"),
    _c("discharge_overpressure [-]", "peak cylinder pressure / discharge pressure - 1"),
    _c("suction_underpressure [-]", "1 - minimum cylinder pressure / suction pressure"),
    _c(
        "mean_shaft_torque [N m]",
        "shaft work per revolution / 2 pi (with the mean friction's torque)",
    ),
    _c("peak_shaft_torque [N m]", "highest sampled driving torque"),
    _c("minimum_shaft_torque [N m]", "lowest sampled driving torque"),
    _c(
        "bearing_rms_<name> [N]",
        "RMS over crank angle of the force magnitude of bearing `<name>` (one column per bearing)",
    ),
    _c("bearing_max_<name> [N]", "largest force magnitude of bearing `<name>` over the revolution"),
    _c(
        "orbit_radius_max_<name> [m]",
        "largest journal displacement of bearing `<name>` from its centred position (0 when "
        "pinned)",
    ),
    _c(
        "mean_crank_speed [rpm]",
        "mean crank speed over the revolution, time-averaged (revolutions per unit time; the "
        "harmonic mean of the speed over crank angle)",
    ),
    _c(
        "crank_speed_ripple [-]",
        "(largest - smallest crank speed) / mean crank speed (0 at constant speed)",
    ),
)

#: The start-up columns of ``summary.csv`` (``solver.start = "rest"`` only).
STARTUP_SUMMARY_DOCS: tuple[ColumnDoc, ...] = (
    _c(
        "standstill_pressure [Pa]",
        "equalised pressure of the cylinder and the plenums at standstill "
        "(`solver.standstill_pressure`, default saturation at the ambient temperature)",
    ),
    _c("startup_time [s]", "time from standstill to the end of the settled revolution"),
    _c(
        "startup_revolutions [-]",
        "windows of the transient (the first is the 3/4 turn from top dead centre to 270 deg)",
    ),
    _c(
        "startup_settled [-]",
        "whether the cycle residual fell below `solver.cycle_tolerance` after the pull-down ramp",
    ),
    _c("startup_wall_time [s]", "wall time of the transient"),
    _c("startup_motor_work [J]", "work of the motor torque over the transient"),
    _c(
        "startup_kinetic_energy_gained [J]",
        "kinetic energy of the crank train at the end less at standstill",
    ),
    _c(
        "startup_gas_work [J]",
        "work of the piston on the gas, net of the shell side, integral of (p - p_shell) dV",
    ),
    _c(
        "startup_dissipation [J]",
        "energy dissipated in the bearings (work they absorb less the elastic energy they store)",
    ),
    _c(
        "startup_energy_closure [-]",
        "abs(motor work - kinetic energy gained - gas work - dissipation) / motor work",
    ),
    _c(
        "startup_flow_difference [-]",
        "relative difference of the mean net suction mass flow, last revolution of the "
        "transient against the periodic solution",
    ),
    _c("startup_power_difference [-]", "same for the mean drive power"),
)
