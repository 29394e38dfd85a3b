"""Diffusion statistics of an ensemble of trajectories: MSD, D, bootstrap CIs, ergodicity.

Everything here takes plain arrays and returns plain numbers or arrays.  Units follow
the rest of ``bbb``: positions in mm, times and lags in s, D in mm²/s, MSD in mm².

Positions ``x`` are always a float array of shape ``(n_particles, n_samples)``: the
horizontal position of each particle at equally spaced sample times ``sample_times``
(shape ``(n_samples,)``, spacing ``dt``).  A 1-D ``x`` is read as a single particle.

Conventions
-----------
* A lag is an integer number of sample spacings ``L``; in seconds it is ``L * dt``.
* The time-averaged MSD (TAMSD) of one trajectory at lag ``L`` is the average over all
  ``n_samples - L`` time origins (sliding windows) ``δ²(L) = mean_i (x[i+L] - x[i])²``;
  the ensemble MSD is the mean of δ² over particles (as kinisi and MDAnalysis do).
* D comes from an ordinary least-squares fit ``MSD(Δ) = 2 D Δ + c`` over a linear regime
  of lags (see :func:`diffusion_coefficient` for the default regime and why).
* Ensemble quantities weight every particle equally.

Modules (every public name is re-exported here, so ``from bbb.analysis.stats import X`` works):

=============== ==========================================================================
``msd``         time-averaged MSD of each trajectory and of the ensemble
``fit``         D from the MSD slope, the fit regime (transient, lag range), D_last
``bootstrap``   bootstrap CIs for D over particles (percentile, basic, BCa)
``rare``        the rare-mover rule: D's CI when a few particles carry D (used by bootstrap)
``ergodicity``  EB, its Brownian value, and the calibrated ergodicity verdict
``inputs``      shape and finiteness checks shared by the above
``proportion``  Wilson interval of a share, Newcombe's of a difference of two shares
=============== ==========================================================================
"""

from __future__ import annotations

from .bootstrap import BootstrapCI, bootstrap_D, bootstrap_mean, unit_means
from .ergodicity import (
    DEFAULT_CV_MAX,
    DEFAULT_EB_TOLERANCE,
    DEFAULT_RULE,
    RULE_ERROR_RATES,
    RULES,
    ErgodicVerdict,
    calibrated_error_rates,
    eb_brownian,
    ergodic_verdict,
    ergodicity_breaking,
)
from .fit import (
    DEFAULT_DISCARD,
    DEFAULT_FIT_FROM,
    DEFAULT_FIT_TO,
    DiffusionEstimate,
    diffusion_coefficient,
    fit_diffusion,
    fit_regime,  # noqa: F401  (not in __all__: a helper, used by pipeline.studies.accuracy)
    per_particle_D,
    per_particle_fit,  # noqa: F401  (not in __all__: a helper, used by pipeline.studies.accuracy)
)
from .msd import msd_time_averaged, tamsd

__all__ = [
    "DEFAULT_DISCARD",
    "DEFAULT_FIT_FROM",
    "DEFAULT_FIT_TO",
    "DEFAULT_EB_TOLERANCE",
    "DEFAULT_CV_MAX",
    "DEFAULT_RULE",
    "RULES",
    "RULE_ERROR_RATES",
    "calibrated_error_rates",
    "BootstrapCI",
    "DiffusionEstimate",
    "ErgodicVerdict",
    "tamsd",
    "msd_time_averaged",
    "fit_diffusion",
    "diffusion_coefficient",
    "per_particle_D",
    "bootstrap_D",
    "bootstrap_mean",
    "unit_means",
    "ergodicity_breaking",
    "eb_brownian",
    "ergodic_verdict",
]
