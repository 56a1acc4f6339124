"""The shipped cases: installed as the package ``recipsim.shipped_cases`` (this folder
is mapped onto it by ``[tool.setuptools.package-dir]`` in ``pyproject.toml``) and found
with :func:`recipsim.case.files.shipped_dir`. The folder holds data only: the case
files, the sweep files (``sweeps/``) and the hard cases (``hard/``)."""
