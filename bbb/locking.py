"""Moved to bbb.analysis.locking; this path is kept for one release."""

# the public names, explicitly (the * keeps any name added there later)
from .analysis.locking import *  # noqa: F403
from .analysis.locking import (  # noqa: F401
    CREEP_MARGIN,
    FLIGHT_TOL,
    MAX_QUANTILE,
    MIN_POINTS,
    TMAX_QUANTILE,
    LockingCI,
    LockingEstimate,
    bootstrap_locking,
    creep_speed,
    dominant_peak,
    flight_time_max,
    flight_times,
    locking_estimate,
    spiral_vmax,
)
