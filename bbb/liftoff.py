"""Moved to bbb.analysis.liftoff; this path is kept for one release."""

# the public names, explicitly (the * keeps any name added there later)
from .analysis.liftoff import *  # noqa: F403
from .analysis.liftoff import liftoff_frequency  # noqa: F401
