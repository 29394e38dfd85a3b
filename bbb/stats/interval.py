"""Moved to bbb.analysis.stats.interval; this path is kept for one release."""

# the public names, explicitly (the * keeps any name added there later)
from ..analysis.stats.interval import *  # noqa: F403
from ..analysis.stats.interval import (  # noqa: F401
    CALIBRATION,
    FAILED,
    NO_MOVER,
    NO_SPREAD,
    OK,
    RARE,
    STATUSES,
    DInterval,
    d_interval,
    rare_coverage,
)
