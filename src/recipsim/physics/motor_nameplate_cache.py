"""Circuits fitted to motor nameplates, kept on disk.

:func:`recipsim.physics.motor_nameplate.motor_circuit_from_nameplate` fits four circuit
values to the rated point with ``scipy.optimize.least_squares``: the fit takes about
15 ms, importing ``scipy.optimize`` 0.25-0.4 s, paid by every process that loads a case
giving its motor by nameplate (every run of the catalogue case, every sweep worker).
:func:`nameplate_circuit` keeps each fitted circuit in
``<cache>/motor_circuits/<digest>.json``, the digest covering the nameplate's values and
the source of the fit (so changed code fits again), written atomically. A cached
circuit is used only if it has exactly the circuit's fields with finite values and
reproduces the nameplate's rated shaft power, input power and power factor to 1e-9
(one circuit evaluation, no import); otherwise it is fitted again and replaced.
"""

from __future__ import annotations

import hashlib
from dataclasses import asdict, fields
from functools import lru_cache
from pathlib import Path

from recipsim.cache_dirs import cache_dir
from recipsim.physics import bracketed_root, motor_circuit, motor_nameplate
from recipsim.physics.json_cache import read_record, write_record
from recipsim.physics.motor_circuit import MotorCircuit, motor_operating_point
from recipsim.physics.motor_nameplate import MotorNameplate, motor_circuit_from_nameplate

#: a cached circuit reproduces the rated figures to this (the fit reaches 1e-10)
_REPRODUCED = 1e-9


@lru_cache(maxsize=1)
def _fit_source_digest() -> str:
    """Digest of the modules whose code decides the fitted circuit (recipsim's version
    where a module's source cannot be read, e.g. an installation without sources)."""
    from recipsim.version import __version__

    digest = hashlib.blake2b(digest_size=16)
    for module in (motor_nameplate, motor_circuit, bracketed_root):
        try:
            digest.update(Path(str(module.__file__)).read_bytes())
        except OSError:
            digest.update(f"{module.__name__} {__version__}".encode())
    return digest.hexdigest()


def _path(plate: MotorNameplate) -> Path:
    digest = hashlib.blake2b(digest_size=16)
    digest.update(_fit_source_digest().encode())
    digest.update(repr(plate).encode())  # every field, floats exactly
    return cache_dir() / "motor_circuits" / f"{digest.hexdigest()}.json"


def nameplate_circuit(plate: MotorNameplate) -> MotorCircuit:
    """The circuit of ``plate``: from the cache, else fitted
    (:func:`~recipsim.physics.motor_nameplate.motor_circuit_from_nameplate`) and cached.

    Raises
    ------
    ValueError
        As the fit: inconsistent nameplate data.
    """
    path = _path(plate)
    cached = _read_circuit(path, plate)
    if cached is not None:
        return cached
    circuit = motor_circuit_from_nameplate(plate)
    try:
        write_record(path, asdict(circuit))
    except OSError:
        pass  # an unwritable cache costs the fit next time, nothing else
    return circuit


def _read_circuit(path: Path, plate: MotorNameplate) -> MotorCircuit | None:
    """The cached circuit, or None if missing, malformed or not this nameplate's."""
    data = read_record(path, [f.name for f in fields(MotorCircuit)], ("variant",))
    if data is None or data["variant"] != plate.variant:
        return None
    try:
        circuit = MotorCircuit(**data)
        point = motor_operating_point(circuit, plate.rated_speed)
    except (TypeError, ValueError, ArithmeticError):
        return None
    misfit = (
        point.shaft_power / plate.rated_output - 1.0,
        point.electrical_power / plate.input_power - 1.0,
        point.power_factor - plate.power_factor,
    )
    return circuit if all(abs(m) < _REPRODUCED for m in misfit) else None
