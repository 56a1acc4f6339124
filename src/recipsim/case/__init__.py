"""Case files to a validated :class:`~recipsim.case.case.Case`, in SI (first stage).

Modules: :mod:`.files` (reading input files safely, references between them),
:mod:`.units` (unit strings with pint, at load time only), :mod:`.schema` (declared
keys: unit, default, range), :mod:`.refrigerant` (refrigerant files), :mod:`.mechanism`
(mechanism and bearing tables), :mod:`.load` (the case: ``load_case``), which reads the
file through :mod:`.extends` and :mod:`.overrides` and validates it with :mod:`.case`
(``Case``), :mod:`.build` (one builder per table, keys declared in
:mod:`.case_schema`), :mod:`.operating_point`, :mod:`.consistency` (checks across
sections), :mod:`.sections` (the sections' dataclasses) and :mod:`.shipped` (the list of
shipped cases, ``recipsim cases``).
"""
