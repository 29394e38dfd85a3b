"""Moved to bbb.analysis.greenkubo; this path is kept for one release."""

# the public names, explicitly (the * keeps any name added there later)
from .analysis.greenkubo import *  # noqa: F403
from .analysis.greenkubo import (  # noqa: F401
    CollisionJumps,
    GreenKubo,
    cell_jumps,
    collision_jumps,
    expansion,
    period_jumps,
)
