"""D of the moving particles and the share that moves, with their intervals, for one window of
one ensemble under each definition of :mod:`.moving` (D in mm²/s, shares in [0, 1]).

Per definition (``all``, ``displaced``, ``moving_time``) :func:`decompose` returns one
:class:`Decomposition`:

* share -- ``all``: 1 exactly (no interval: share_lo, share_hi NaN); ``displaced``: k / n
  with the Wilson score interval (never of zero width, also at k = 0 or n); ``moving_time``:
  mean φ_i with the percentile bootstrap over particles, or, when every φ_i is the same
  (all 0 or all 1: the bootstrap has no spread), the Wilson interval of the particles with
  any moving block (all 0) or with every block moving (all 1), which bounds mean φ from
  above or below;
* D -- ``all``: bbb reduce's D = mean D_i with its interval and status
  (:func:`bbb.analysis.stats.interval.d_interval`: bootstrap over particles, rare-mover rule);
  ``displaced``: the same over the displaced particles (fewer than 2: status
  :data:`TOO_FEW`, D NaN); ``moving_time``: mean D_i / mean φ_i with the paired percentile
  bootstrap of the ratio over particles (no moving block at all: :data:`NO_TIME`; a ratio CI
  below 0: ``estimator failed``);
* D_all, and the check of D_all = share · D: ``residual`` = D_all − share · D, ``bound`` the
  most the still particles can contribute ((1 − share) · :func:`.moving.still_bound` for
  ``displaced``, 0 up to rounding for the others), ``holds`` = |residual| ≤ bound; where
  ``moving_time`` has no D (fewer than 2 particles with a moving block) there is nothing to
  check: residual NaN, holds False.

Every bootstrap draws from its own child of ``seed`` (one per definition), so the result is
a function of (positions, dt, S, T, n_resamples, seed) alone.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .moving import DEFINITIONS, displaced, moving_share, still_bound, window
from .stats.bootstrap import bootstrap_mean_unchecked
from .stats.fit import DEFAULT_DISCARD, fit_regime, per_particle_fit
from .stats.interval import FAILED, OK, d_interval
from .stats.proportion import wilson

__all__ = ["TOO_FEW", "NO_TIME", "Decomposition", "decompose"]

#: status of a D that cannot be estimated: fewer than two moving particles
TOO_FEW = "too few movers"
#: status of ``moving_time``'s D when no particle has a moving block
NO_TIME = "no moving time"


class Decomposition(NamedTuple):
    """One definition's numbers at one window (module docstring): shares in [0, 1], D in
    mm²/s; ``status`` says what D's interval means (bbb.analysis.stats.interval's statuses,
    :data:`TOO_FEW`, :data:`NO_TIME`)."""

    definition: str
    n: int
    n_moving: int
    share: float
    share_lo: float
    share_hi: float
    D: float
    D_lo: float
    D_hi: float
    status: str
    D_all: float
    D_all_lo: float
    D_all_hi: float
    residual: float
    bound: float
    holds: bool


def _ratio_ci(d: np.ndarray, phi: np.ndarray, n_resamples: int, ci: float,
              rng: np.random.Generator) -> tuple[float, float]:
    idx = rng.integers(0, d.size, size=(n_resamples, d.size))
    num, den = d[idx].mean(axis=1), phi[idx].mean(axis=1)
    r = np.divide(num, den, out=np.full(n_resamples, np.nan), where=den > 0)
    lo, hi = np.nanquantile(r, [(1 - ci) / 2, (1 + ci) / 2])
    return float(lo), float(hi)


def _time_share(phi: np.ndarray, n_resamples: int, ci: float,
                rng: np.random.Generator) -> tuple[float, float, float]:
    n = phi.size
    if np.ptp(phi) > 0:
        b = bootstrap_mean_unchecked(phi, n_resamples, ci, rng, "percentile")
        return float(phi.mean()), b.lo, b.hi
    k = int(np.count_nonzero(phi > 0)) if phi[0] == 0 else int(np.count_nonzero(phi >= 1))
    _, lo, hi = wilson(k, n, ci)
    return float(phi.mean()), (0.0 if phi[0] == 0 else lo), (hi if phi[0] == 0 else 1.0)


def decompose(x: ArrayLike, dt: float, S: float, T: float, *, n_resamples: int, seed,
              ci: float = 0.95, discard: float = DEFAULT_DISCARD) -> list[Decomposition]:
    """The three :class:`Decomposition` (order :data:`~.moving.DEFINITIONS`) of the window
    of the first ``T`` s of positions ``x`` (n_particles ≥ 2, n_samples; mm) sampled every
    ``dt`` s, S the arc period (mm); bootstrap over particles with ``n_resamples`` resamples
    from ``seed`` (int or SeedSequence)."""
    xw = window(x, dt, T)
    if xw.ndim != 2 or xw.shape[0] < 2:
        raise ValueError("decompose needs positions (n_particles >= 2, n_samples)")
    n = xw.shape[0]
    times = np.arange(xw.shape[1]) * dt
    reg = fit_regime(xw.shape[1], times, None, None, discard)
    d_i, _ = per_particle_fit(xw, reg)
    ss = seed if isinstance(seed, np.random.SeedSequence) else np.random.SeedSequence(seed)
    rngs = [np.random.default_rng(s) for s in ss.spawn(len(DEFINITIONS))]
    tiny = 1e-9 * max(1.0, float(np.abs(d_i).max()))

    all_i = d_interval(d_i, bootstrap_mean_unchecked(d_i, n_resamples, ci, rngs[0],
                                                     "percentile"), ci)
    D_all = (all_i.D, all_i.lo, all_i.hi)
    out = [Decomposition("all", n, n, 1.0, math.nan, math.nan, *D_all, all_i.status, *D_all, 0.0, tiny,
                         True)]

    mask = displaced(xw, S, discard)
    k = int(mask.sum())
    share = wilson(k, n, ci)
    if k >= 2:
        di = d_interval(d_i[mask], bootstrap_mean_unchecked(d_i[mask], n_resamples, ci,
                                                            rngs[1], "percentile"), ci)
        D, status = (di.D, di.lo, di.hi), di.status
        res = all_i.D - share[0] * di.D
    else:
        D, status = (math.nan, math.nan, math.nan), TOO_FEW
        res = all_i.D - (float(d_i[mask].sum()) / n)  # D_all - share * D over the k movers
    bound = (1 - share[0]) * still_bound(S, reg.lag_lo, reg.lag_hi, dt) + tiny
    out.append(Decomposition("displaced", n, k, *share, *D, status, *D_all, res, bound,
                             bool(abs(res) <= bound)))

    phi = moving_share(xw, dt, S, discard=discard)
    tshare = _time_share(phi, n_resamples, ci, rngs[2])
    k_t = int(np.count_nonzero(phi > 0))
    if tshare[0] <= 0 or k_t < 2:  # nothing to decompose: not checked (residual NaN)
        D, status, res = (math.nan, math.nan, math.nan), NO_TIME if k_t == 0 else TOO_FEW, math.nan
    else:
        r = float(d_i.mean() / phi.mean())
        lo, hi = _ratio_ci(d_i, phi, n_resamples, ci, rngs[2])
        status = FAILED if hi < 0 else OK
        D = (r, lo, hi) if status == OK else (math.nan, math.nan, math.nan)
        res = all_i.D - tshare[0] * r
    out.append(Decomposition("moving_time", n, k_t, *tshare, *D, status, *D_all, res, tiny,
                             bool(abs(res) <= tiny)))
    return out
