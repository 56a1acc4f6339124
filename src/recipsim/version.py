"""recipsim's version (one source: read by setuptools and by :mod:`recipsim`)."""

__version__ = "0.1.0"
