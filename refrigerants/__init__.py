"""The shipped refrigerant files: installed as the package
``recipsim.shipped_refrigerants`` (this folder is mapped onto it by
``[tool.setuptools.package-dir]`` in ``pyproject.toml``) and found with
:func:`recipsim.case.files.shipped_dir`. The folder holds data only."""
