"""Case files to a validated :class:`~recipsim.case.load.Case`, in SI (first stage).

Modules: :mod:`.files` (reading input files safely, references between them),
:mod:`.units` (unit strings with pint, at load time only), :mod:`.schema` (declared
keys: unit, default, range), :mod:`.refrigerant` (refrigerant files), :mod:`.mechanism`
(mechanism and bearing tables), :mod:`.load` (the case: ``load_case``).
"""
