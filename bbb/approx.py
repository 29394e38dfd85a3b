"""Moved to bbb.analysis.approx; this path is kept for one release."""

# the public names, explicitly (the * keeps any name added there later)
from .analysis.approx import *  # noqa: F403
from .analysis.approx import floor_t0, locking_ratio, spiral, spiral_of  # noqa: F401
