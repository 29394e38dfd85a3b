"""Moved to :mod:`pipeline.execute.run`; kept for one release (code in pipeline/ imports the
new path, tests/test_layout.py)."""

from .execute.run import *  # noqa: F403
from .execute.run import connect  # noqa: F401  (imported from pipeline.run before the move)
