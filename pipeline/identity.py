"""Moved to :mod:`pipeline.workflow.identity`; kept for one release (code in pipeline/ imports
the new path, tests/test_layout.py)."""

from .workflow.identity import *  # noqa: F403
