"""Moved to :mod:`pipeline.tables.reduce` (the tables themselves: :mod:`pipeline.tables.diffusion`,
:mod:`pipeline.tables.counters`); kept for one release (code in pipeline/ imports the new
paths, tests/test_layout.py)."""

from .tables.counters import counters_table  # noqa: F401
from .tables.diffusion import diffusion_table  # noqa: F401
from .tables.reduce import *  # noqa: F403
