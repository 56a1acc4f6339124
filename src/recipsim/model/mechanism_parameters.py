"""Pack a :class:`MechanismSpec` and the slider-crank geometry into the float64
parameter array read by the compiled functions (layout: :mod:`.layout`)."""

from __future__ import annotations

import numpy as np

from recipsim.case.mechanism_spec import CrankGeometry, MechanismSpec
from recipsim.physics.mechanics import layout as lay
from recipsim.physics.mechanics.bearing_laws.registry import BEARING_LAWS
from recipsim.physics.mechanics.drives import CONSTANT_SPEED, DRIVES
from recipsim.physics.motor import MotorSpec

#: Axis of each bearing (the linear law acts normal to it): rotor, eccentric and pin
#: journals turn about Z; the piston slides along X.
_BEARING_AXES = (lay.AXIS_Z, lay.AXIS_Z, lay.AXIS_Z, lay.AXIS_Z, lay.AXIS_X, lay.AXIS_X)


def mechanism_parameters(
    spec: MechanismSpec,
    geometry: CrankGeometry,
    *,
    shell_pressure: float = 0.0,
    speed: float = 0.0,
    drive: str = CONSTANT_SPEED.name,
    motor: MotorSpec | None = None,
) -> np.ndarray:
    """Parameter array of the pinned and flexible models.

    Parameters
    ----------
    spec : MechanismSpec
    geometry : CrankGeometry
    shell_pressure : float
        Pressure acting under the piston [Pa].
    speed : float
        Crank speed of the ``constant_speed`` drive [rad/s] (ignored by other drives).
    drive : str
        A name of :data:`~recipsim.physics.mechanics.drives.DRIVES`.
    motor : MotorSpec, optional
        The torque-speed curve; required by the ``induction_motor`` drive.

    Returns
    -------
    numpy.ndarray
        Shape ``(layout.N_PAR,)``.
    """
    if drive not in DRIVES:
        raise ValueError(f"unknown drive {drive!r}; allowed: {', '.join(DRIVES.names)}")
    par = np.zeros(lay.N_PAR)
    _write_crank_and_drive(par, geometry, shell_pressure, speed, drive, motor)
    _write_bodies(par, spec)
    _write_bearings(par, spec)
    return par


def _write_crank_and_drive(
    par: np.ndarray,
    geometry: CrankGeometry,
    shell_pressure: float,
    speed: float,
    drive: str,
    motor: MotorSpec | None,
) -> None:
    """Write the crank geometry, the shell pressure and the drive into ``par``.

    Parameters
    ----------
    par : numpy.ndarray
        The parameter array (``layout.N_PAR``), written in place.
    geometry, shell_pressure, speed, drive, motor
        As in :func:`mechanism_parameters` (``drive`` already checked).

    Raises
    ------
    ValueError
        If the ``induction_motor`` drive has no motor.
    """
    par[lay.P_CRANK_RADIUS] = geometry.crank_radius
    par[lay.P_ROD_LENGTH] = geometry.rod_length
    par[lay.P_PISTON_AREA] = geometry.piston_area
    par[lay.P_SHELL_PRESSURE] = shell_pressure
    par[lay.P_SPEED] = speed
    par[lay.P_DRIVE] = DRIVES[drive].code
    if DRIVES[drive].motor_curve:
        if motor is None:
            raise ValueError(f"the {drive} drive needs a MotorSpec")
        par[lay.P_MOTOR_SYNC_SPEED] = motor.synchronous_speed
        par[lay.P_MOTOR_BREAKDOWN_TORQUE] = motor.breakdown_torque
        par[lay.P_MOTOR_BREAKDOWN_SLIP] = motor.breakdown_slip
        par[lay.P_MOTOR_BACKWARD_RATIO] = motor.backward_field_ratio


def _write_bodies(par: np.ndarray, spec: MechanismSpec) -> None:
    """Write the rotor, connecting rod and piston of ``spec`` into ``par``.

    Parameters
    ----------
    par : numpy.ndarray
        The parameter array (``layout.N_PAR``), written in place.
    spec : MechanismSpec
        The mechanism.

    Raises
    ------
    ValueError
        If the piston_top or piston_skirt bearing has no ``position_from_crown``.
    """
    rotor = spec.rotor
    par[lay.P_ROTOR_MASS] = rotor.mass
    par[lay.P_ROTOR_POLAR_INERTIA] = rotor.polar_inertia
    par[lay.P_ROTOR_TRANSVERSE_INERTIA] = rotor.transverse_inertia
    par[lay.P_ROTOR_COM_Z] = rotor.centre_of_mass_z
    par[lay.P_PRIMARY_Z] = rotor.primary_z
    par[lay.P_SECONDARY_Z] = rotor.secondary_z
    par[lay.P_COUNTERWEIGHT_MASS] = rotor.counterweight_mass
    par[lay.P_COUNTERWEIGHT_RADIUS] = rotor.counterweight_radius
    par[lay.P_COUNTERWEIGHT_ANGLE] = rotor.counterweight_angle
    par[lay.P_COUNTERWEIGHT_Z] = rotor.counterweight_z

    rod = spec.connecting_rod
    par[lay.P_ROD_MASS] = rod.mass
    par[lay.P_ROD_COM_FRACTION] = rod.centre_of_mass_fraction
    par[lay.P_ROD_INERTIA] = rod.inertia

    piston = spec.piston
    com = piston.centre_of_mass_from_crown
    par[lay.P_PISTON_MASS] = piston.mass
    par[lay.P_PISTON_INERTIA] = piston.transverse_inertia
    par[lay.P_PISTON_PIN_U] = com - piston.pin_offset_from_crown
    par[lay.P_PISTON_CROWN_U] = com
    top = spec.bearings[lay.B_PISTON_TOP].position_from_crown
    skirt = spec.bearings[lay.B_PISTON_SKIRT].position_from_crown
    if top is None or skirt is None:
        raise ValueError("piston_top and piston_skirt need position_from_crown")
    par[lay.P_PISTON_TOP_U] = com - top
    par[lay.P_PISTON_SKIRT_U] = com - skirt
    par[lay.P_PIN_FROM_CROWN] = piston.pin_offset_from_crown


def _write_bearings(par: np.ndarray, spec: MechanismSpec) -> None:
    """Write each bearing's row (law, axis, linear law, table offset, film) into ``par``.

    Parameters
    ----------
    par : numpy.ndarray
        The parameter array (``layout.N_PAR``), written in place.
    spec : MechanismSpec
        The mechanism.

    Raises
    ------
    KeyError
        If a bearing's law is not in the bearing laws' registry.
    """
    offsets = _table_offsets(spec)
    for i, (bearing, axis) in enumerate(zip(spec.bearings, _BEARING_AXES, strict=True)):
        row = lay.P_BEARINGS + i * lay.N_BEARING_PAR
        law = BEARING_LAWS[bearing.law]
        par[row + lay.BP_LAW] = law.code
        par[row + lay.BP_AXIS] = axis
        par[row + lay.BP_STIFFNESS] = bearing.stiffness
        par[row + lay.BP_DAMPING] = bearing.damping
        par[row + lay.BP_TABLE] = offsets[i]
        film = bearing.film
        if film is not None and law.film:
            par[row + lay.BP_DIAMETER] = film.diameter
            par[row + lay.BP_LENGTH] = film.length
            par[row + lay.BP_CLEARANCE] = film.radial_clearance
            par[row + lay.BP_VISCOSITY] = film.viscosity
            par[row + lay.BP_CONTACT_FILM] = film.contact_film
            par[row + lay.BP_CONTACT_STIFFNESS] = film.contact_stiffness
            par[row + lay.BP_CONTACT_FRICTION] = film.contact_friction


def _law_tables(spec: MechanismSpec) -> list[np.ndarray | None]:
    """The table of each bearing whose law keeps one (None for the others)."""
    tables: list[np.ndarray | None] = []
    for bearing in spec.bearings:
        build = BEARING_LAWS[bearing.law].table
        if build is not None and bearing.film is not None:
            tables.append(build(bearing.film.length / bearing.film.diameter))
        else:
            tables.append(None)
    return tables


def _table_offsets(spec: MechanismSpec) -> list[int]:
    """Offset of each bearing's table in :func:`bearing_tables` (-1: none)."""
    offsets = []
    position = 0
    for table in _law_tables(spec):
        offsets.append(-1 if table is None else position)
        position += 0 if table is None else table.size
    return offsets


def bearing_tables(spec: MechanismSpec) -> np.ndarray:
    """The bearing laws' tables of ``spec`` in bearing order, one flat float64 array
    (a single zero when there are none), as the compiled mechanism reads them."""
    tables = [t for t in _law_tables(spec) if t is not None]
    return np.concatenate(tables) if tables else np.zeros(1)
