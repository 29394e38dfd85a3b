"""Moved to bbb.analysis.stationarity; this path is kept for one release."""

# the public names, explicitly (the * keeps any name added there later)
from .analysis.stationarity import *  # noqa: F403
from .analysis.stationarity import D_FLOOR, TOLERANCE, Stationarity, half_run_diffusion, stationarity  # noqa: F401
