"""Statistical versus systematic error of the accuracy study, measured on the reference store
alone: D's spread and CI half-width against the number of particles N (expected to fall like
N^-1/2), and the finite-time bias of D against the duration t_max (paired, same particles).
D in mm²/s, times in s; relative quantities are fractions of the reference's D.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import pandas as pd

__all__ = ["SCALING_COLUMNS", "per_particle_D", "scaling_table"]

#: statistical (N) and finite-time (t_max) behaviour measured on the reference store
SCALING_COLUMNS = (
    "f", "family", "axis", "value",           # axis "N" (particles) or "T" (t_max, s)
    "sd_rel",         # N: spread of D over disjoint subsets / D_ref; T: se of the bias
    "hw_rel",         # mean 95 % CI half-width / D (percentile bootstrap over particles)
    "bias_rel",       # T: mean over particles of D_i(T) - D_i(t_ref), / D_ref (paired)
    "exponent",       # N: fitted slope of log sd_rel vs log N (expect -1/2), same per group
)


def per_particle_D(x: np.ndarray, times: np.ndarray, analysis) -> np.ndarray:
    """Each particle's own TAMSD slope D_i, mm²/s (``bbb reduce``'s D is their mean), with
    the workflow's discard and fractional fit lags."""
    from bbb.analysis import stats

    T = analysis.duration(times[-1] - times[0])
    # bbb.analysis.stats' own per-particle fit, so that these are exactly the estimator's D_i
    reg = stats.fit_regime(x.shape[1], times, analysis.fit_from * T, analysis.fit_to * T,
                        analysis.discard)
    return stats.per_particle_fit(np.asarray(x, dtype=float), reg)[0]


def scaling_table(ref_store, n_values: Sequence[int] | None = None,
                  t_values: Sequence[float] | None = None, n_resamples: int = 400,
                  seed: int = 5) -> pd.DataFrame:
    """Statistical versus systematic error, measured on the reference store alone.

    N axis: the reference's particles split into disjoint subsets of n; the spread of D over
    subsets (relative to the full D) should fall like n^-1/2, and so should the bootstrap
    half-width.  T axis: each particle's D_i over the first T seconds minus its D_i over the
    whole run (paired: same particles), averaged -- the finite-time bias of the fit at
    fractional lags -- with its standard error, and the half-width at that T.
    """
    from bbb.analysis import stats

    study = ref_store.study
    g = ref_store.group()
    times = study.sample_times()
    n_all, t_all = study.accuracy.n_particles, study.accuracy.t_max
    n_values = n_values or [n for n in (16, 32, 64, 128, 256, 512) if n <= n_all // 4]
    t_values = t_values or [t for t in (12.5, 25.0, 50.0, 100.0) if t < t_all]
    rng = np.random.default_rng(seed)
    rows = []
    for fi, f in enumerate(study.frequencies):
        for mi, fam in enumerate(study.families):
            x = np.asarray(g["positions"][fi, mi])
            d_all = per_particle_D(x, times, study.analysis)
            D = d_all.mean()
            if not D > 2 * d_all.std(ddof=1) / math.sqrt(d_all.size):
                continue  # D not significantly > 0: no relative errors to scale
            group = []
            for n in n_values:
                subs = d_all[rng.permutation(n_all)[: (n_all // n) * n]].reshape(-1, n).mean(1)
                hw = _hw(stats, x[:n], times, study, n_resamples, seed)
                group.append(dict(f=f, family=fam.name, axis="N", value=float(n),
                                  sd_rel=float(subs.std(ddof=1) / D), hw_rel=hw / D,
                                  bias_rel=float((subs.mean() - D) / D)))
            if len(group) >= 2:
                k = np.polyfit(np.log([r["value"] for r in group]),
                               np.log([r["sd_rel"] for r in group]), 1)[0]
                for r in group:
                    r["exponent"] = float(k)
            rows += group
            for T in t_values:
                n_t = int(np.searchsorted(times, T + 1e-9))
                d_t = per_particle_D(x[:, :n_t], times[:n_t], study.analysis)
                diff = d_t - d_all
                hw = _hw(stats, x[:, :n_t], times[:n_t], study, n_resamples, seed)
                rows.append(dict(f=f, family=fam.name, axis="T", value=float(T),
                                 sd_rel=float(diff.std(ddof=1) / math.sqrt(diff.size) / D),
                                 hw_rel=hw / D, bias_rel=float(diff.mean() / D),
                                 exponent=math.nan))
    return pd.DataFrame(rows, columns=list(SCALING_COLUMNS))


def _hw(stats, x, times, study, n_resamples, seed) -> float:
    an = study.analysis
    T = an.duration(times[-1] - times[0])
    ci = stats.bootstrap_D(x, times, n_resamples=n_resamples, ci=an.ci, seed=seed,
                           fit_from=an.fit_from * T, fit_to=an.fit_to * T, discard=an.discard)
    return float((ci.hi - ci.lo) / 2)
