"""Moved to bbb.analysis.stats; this path is kept for one release.  Of its submodules only
bootstrap, ergodicity and interval keep their old paths (pipeline imports them).  The helpers
fit_regime and per_particle_fit also answer to their old names _regime and _per_particle_fit
(pipeline.studies.accuracy reads them)."""

# the public names, explicitly (the * keeps any name added there later)
from ..analysis.stats import *  # noqa: F403
from ..analysis.stats import (  # noqa: F401
    DEFAULT_CV_MAX,
    DEFAULT_DISCARD,
    DEFAULT_EB_TOLERANCE,
    DEFAULT_FIT_FROM,
    DEFAULT_FIT_TO,
    DEFAULT_RULE,
    RULE_ERROR_RATES,
    RULES,
    BootstrapCI,
    DiffusionEstimate,
    ErgodicVerdict,
    bootstrap_D,
    bootstrap_mean,
    calibrated_error_rates,
    diffusion_coefficient,
    eb_brownian,
    ergodic_verdict,
    ergodicity_breaking,
    fit_diffusion,
    msd_time_averaged,
    per_particle_D,
    tamsd,
    unit_means,
)
from ..analysis.stats import fit_regime as _regime  # noqa: F401
from ..analysis.stats import per_particle_fit as _per_particle_fit  # noqa: F401
