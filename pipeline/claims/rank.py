"""Whether one quantity moves with another across a handful of points: Spearman's rank
correlation ρ with a permutation p-value.

For claims of the kind "the maximum moves with α": n points (x_i, y_i), one per grid line,
each y_i a located feature.  Ranks make the test blind to the shape of the trend (any
monotonic one counts) and to outliers in y; the p-value comes from the permutation
distribution of ρ under "y does not depend on x" -- all n! orders when n ≤ 8, else
:data:`N_PERMUTATIONS` random ones from a fixed seed (so the p-value, and a verdict read off
it, is the same on every machine).  Ties take average ranks.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["N_PERMUTATIONS", "spearman", "rank_trend"]

#: random orders drawn when n > 8 (the p-value's Monte Carlo error is then ≤ 0.0015 at p = 0.05)
N_PERMUTATIONS = 20_000
_SEED = 20041125


def _ranks(v: np.ndarray) -> np.ndarray:
    order = np.argsort(v, kind="stable")
    r = np.empty(v.size, dtype=np.float64)
    r[order] = np.arange(1, v.size + 1)
    for value in np.unique(v):  # ties: the mean of their ranks
        tie = v == value
        if tie.sum() > 1:
            r[tie] = r[tie].mean()
    return r


def _rho(rx: np.ndarray, ry: np.ndarray) -> float:
    a, b = rx - rx.mean(), ry - ry.mean()
    den = math.sqrt(float(a @ a) * float(b @ b))
    return float(a @ b) / den if den > 0 else math.nan


def spearman(x: ArrayLike, y: ArrayLike) -> float:
    """Spearman's ρ of the pairs (x_i, y_i) (NaN pairs dropped); NaN with fewer than 3 pairs or
    a constant x or y."""
    x, y = np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)
    ok = np.isfinite(x) & np.isfinite(y)
    if ok.sum() < 3:
        return math.nan
    return _rho(_ranks(x[ok]), _ranks(y[ok]))


def rank_trend(x: ArrayLike, y: ArrayLike) -> tuple[float, float, int]:
    """(ρ, p, n): Spearman's ρ, its two-sided permutation p-value (the share of orders of y
    whose |ρ| is at least the observed one, the observed order included) and the number of
    finite pairs; p = NaN when ρ is."""
    x, y = np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)
    ok = np.isfinite(x) & np.isfinite(y)
    n = int(ok.sum())
    rho = spearman(x, y)
    if math.isnan(rho):
        return rho, math.nan, n
    rx, ry = _ranks(x[ok]), _ranks(y[ok])
    if n <= 8:
        perms = np.array(list(itertools.permutations(range(n))))
    else:
        rng = np.random.default_rng(_SEED)
        perms = np.array([rng.permutation(n) for _ in range(N_PERMUTATIONS)])
    a = rx - rx.mean()
    b = ry[perms] - ry.mean()  # one row per order
    r = (b @ a) / math.sqrt(float(a @ a) * float(b[0] @ b[0]))
    p = float(np.mean(np.abs(r) >= abs(rho) - 1e-12))
    if n > 8:  # the observed order counts once among the draws (Phipson & Smyth 2010)
        p = (p * N_PERMUTATIONS + 1) / (N_PERMUTATIONS + 1)
    return rho, p, n
