"""Moved to bbb.analysis.lyapunov; this path is kept for one release."""

# the public names, explicitly (the * keeps any name added there later)
from .analysis.lyapunov import *  # noqa: F403
from .analysis.lyapunov import Lyapunov, flat_floor_jacobian, flat_floor_tangent_exponent, lyapunov  # noqa: F401
