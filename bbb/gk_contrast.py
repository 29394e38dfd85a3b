"""Moved to bbb.analysis.gk_contrast; this path is kept for one release."""

# the public names, explicitly (the * keeps any name added there later)
from .analysis.gk_contrast import *  # noqa: F403
from .analysis.gk_contrast import (  # noqa: F401
    CARRIERS,
    RULE_FILE,
    SPLITS,
    Contrast,
    calibrated_rule,
    carrier,
    combine_sides,
    contrast,
)
