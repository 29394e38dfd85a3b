"""Moved to bbb.analysis.stats.ergodicity; this path is kept for one release."""

# the public names, explicitly (the * keeps any name added there later)
from ..analysis.stats.ergodicity import *  # noqa: F403
from ..analysis.stats.ergodicity import (  # noqa: F401
    DEFAULT_CV_MAX,
    DEFAULT_EB_TOLERANCE,
    DEFAULT_RULE,
    RULE_ERROR_RATES,
    RULES,
    ErgodicVerdict,
    calibrated_error_rates,
    cv2_ci_coverage,
    eb_brownian,
    ergodic_verdict,
    ergodicity_breaking,
)
