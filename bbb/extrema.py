"""Moved to bbb.analysis.extrema; this path is kept for one release."""

# the public names, explicitly (the * keeps any name added there later)
from .analysis.extrema import *  # noqa: F403
from .analysis.extrema import Extremum, Significance, critical_z, find_extrema, nearest  # noqa: F401
