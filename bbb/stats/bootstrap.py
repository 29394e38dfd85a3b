"""Moved to bbb.analysis.stats.bootstrap; this path is kept for one release.  The helper
bootstrap_mean_unchecked also answers to its old name _bootstrap_mean (tests/pipeline use it)."""

# the public names, explicitly (the * keeps any name added there later)
from ..analysis.stats.bootstrap import *  # noqa: F403
from ..analysis.stats.bootstrap import (  # noqa: F401
    BootstrapCI,
    bootstrap_D,
    bootstrap_mean,
    unit_means,
    with_rare_movers,
)
from ..analysis.stats.bootstrap import bootstrap_mean_unchecked as _bootstrap_mean  # noqa: F401
