"""Moved to bbb.analysis.transport; this path is kept for one release."""

# the public names, explicitly (the * keeps any name added there later)
from .analysis.transport import *  # noqa: F403
from .analysis.transport import (  # noqa: F401
    CURVATURE_TOL,
    INDEPENDENT,
    PAIRING,
    PAIRS,
    RULES,
    STEADY_ABS,
    STEADY_REL,
    STEADY_SE,
    SYMMETRY,
    TransportEstimate,
    drift_change,
    drift_velocity,
    msd_slope_ratio,
    per_particle_drift,
    steady_tolerance,
    transport,
)
