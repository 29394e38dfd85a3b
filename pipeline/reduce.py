"""Moved to :mod:`pipeline.tables.reduce`; kept for one release (code in pipeline/ imports the
new path, tests/test_layout.py)."""

from .tables.reduce import *  # noqa: F403
