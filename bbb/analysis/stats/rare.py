"""The rare-mover rule: D's CI when a few particles carry nearly all of D, mm²/s.

When almost no particle moves (creeping frequencies), D = mean(D_i) is a sum over a handful
of movers, and the bootstrap over particles is anti-conservative: resampling k movers gives
a Poisson(k)-like spread that ignores the uncertainty of k itself (k = 0 gives a CI of zero
width).  The rule (calibrated in docs/statistics.md, ``benchmarks/calibrations/rare_movers.py``):

* ``n_eff = (Σ c_i)² / Σ c_i²`` over the positive contributions c_i = max(D_i, 0) — the
  number of equal movers that would give the same relative spread (k equal movers: k);
* when ``n_eff < min(RARE_N_EFF, RARE_SHARE N)`` (40, and 25 % of the N particles) the CI
  becomes the hull of the bootstrap CI and the gamma interval of Fay & Feuer (1997, Stat.
  Med. 16, 791) for a weighted sum of Poisson counts, with y = Σ c_i, v = Σ c_i² − y² / N
  (the Bernoulli variance: each particle moves or not) and w = max c_i (the next, unseen
  mover as large as the largest seen):

      lo = (v / y)               G⁻¹(α/2;     y² / v)
      hi = ((v + w²) / (y + w))  G⁻¹(1 − α/2; (y + w)² / (v + w²))

  divided by N and shifted by Σ min(D_i, 0) / N (G⁻¹: quantile of the unit-scale Gamma).
  k movers of equal size w among many particles give Garwood's exact Poisson interval
  (hi = 5.57 w / N for k = 1).

What no rule on the data can do: when no mover is in the sample the data hold no mover size,
so the coverage at an expected number of movers m is at most 1 − e^(−m) (0.39 at m = 0.5).
With no positive D_i at all, the data bound the *share* of movers (:func:`mover_share_bound`:
no mover among N ⇒ share < 1 − (1 − ci)^(1/N) ≈ 3/N at 95 %), not D: the interval's upper
end is NaN (not bounded by the data), never a zero-width [D, D].
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

__all__ = ["RARE_N_EFF", "RARE_SHARE", "effective_movers", "is_rare", "rare_mover_interval",
           "mover_share_bound", "gamma_quantile"]

#: Below this n_eff the D CI is widened to the Fay-Feuer gamma interval (docs/statistics.md) ...
RARE_N_EFF = 40.0
#: ... if also n_eff < RARE_SHARE * N: a few particles carry D, the rest could have moved and
#: did not (when most particles move there are no unseen movers to allow for).
RARE_SHARE = 0.25


def is_rare(d_i: NDArray[np.float64]) -> bool:
    """Whether the rule applies to per-particle D_i (mm²/s): n_eff < min(RARE_N_EFF,
    RARE_SHARE * N)."""
    return effective_movers(d_i) < min(RARE_N_EFF, RARE_SHARE * np.asarray(d_i).size)


def effective_movers(d_i: NDArray[np.float64]) -> float:
    """n_eff = (Σ c_i)² / Σ c_i² of c_i = max(D_i, 0) (D_i in mm²/s); 0 when no c_i > 0."""
    c = np.maximum(np.asarray(d_i, dtype=np.float64), 0.0)
    v = float(c @ c)
    return float(c.sum()) ** 2 / v if v > 0 else 0.0


def rare_mover_interval(d_i: NDArray[np.float64], ci: float) -> tuple[float, float]:
    """(lo, hi), mm²/s: the Fay-Feuer gamma interval at level ``ci`` for mean(D_i) (module
    docstring); (mean, NaN) when no D_i is positive: no mover was seen, and the data bound
    their share (:func:`mover_share_bound`), not D; (NaN, NaN) when all N are equal movers
    (no spread; the rule never applies there)."""
    d = np.asarray(d_i, dtype=np.float64)
    n = d.size
    c = np.maximum(d, 0.0)
    shift = float(np.minimum(d, 0.0).sum()) / n
    y, w = float(c.sum()), float(c.max())
    # Σ c_i² less (Σ c_i)² / N: the variance of a sum of N Bernoulli(p) x size terms, not of
    # Poisson counts (which would overstate it by 1 / (1 - n_eff / N) when many move).
    v = float(c @ c) - y * y / n
    if y <= 0.0:
        return shift, math.nan
    if v <= 0.0:  # every particle the same mover: no spread to scale a gamma by (never rare)
        return math.nan, math.nan
    alpha = 1.0 - ci
    lo = (v / y) * gamma_quantile(alpha / 2.0, y * y / v)
    hi = ((v + w * w) / (y + w)) * gamma_quantile(1.0 - alpha / 2.0, (y + w) ** 2 / (v + w * w))
    return lo / n + shift, hi / n + shift


def mover_share_bound(n: int, ci: float) -> float:
    """One-sided upper ``ci`` bound of the share of movers when none of ``n`` particles moved
    (dimensionless): the p with (1 - p)^n = 1 - ci, i.e. 1 - (1 - ci)^(1/n) (≈ 3/n at 95 %,
    the rule of three; exact for independent particles)."""
    if n < 1 or not 0.0 < ci < 1.0:
        raise ValueError(f"mover_share_bound needs n ≥ 1 and 0 < ci < 1, got {n!r}, {ci!r}")
    return -math.expm1(math.log1p(-ci) / n)


def gamma_quantile(q: float, shape: float) -> float:
    """x with P(shape, x) = q for the unit-scale Gamma(shape) (dimensionless); bisection in
    log x on the regularised incomplete gamma, to ~1e-12 relative."""
    if not (0.0 < q < 1.0 and shape > 0.0):
        raise ValueError(f"gamma_quantile needs 0 < q < 1 and shape > 0, got {q!r}, {shape!r}")
    lo, hi = -750.0, math.log(shape + 50.0 * math.sqrt(shape) + 100.0)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if _gammainc(shape, math.exp(mid)) < q:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-13:
            break
    return math.exp(0.5 * (lo + hi))


def _gammainc(a: float, x: float) -> float:
    """Regularised lower incomplete gamma P(a, x): series below a + 1, continued fraction
    above (the standard pair; both converge fast in their ranges)."""
    if x <= 0.0:
        return 0.0
    log_pre = a * math.log(x) - x - math.lgamma(a)
    if x < a + 1.0:
        term = total = 1.0 / a
        ap = a
        for _ in range(10_000):
            ap += 1.0
            term *= x / ap
            total += term
            if abs(term) < abs(total) * 1e-16:
                break
        return min(1.0, total * math.exp(log_pre))
    tiny = 1e-300
    b = x + 1.0 - a
    c, d = 1.0 / tiny, 1.0 / b
    h = d
    for i in range(1, 10_000):
        an = -i * (i - a)
        b += 2.0
        d = an * d + b
        d = tiny if abs(d) < tiny else d
        c = b + an / c
        c = tiny if abs(c) < tiny else c
        d = 1.0 / d
        delta = d * c
        h *= delta
        if abs(delta - 1.0) < 1e-16:
            break
    return max(0.0, 1.0 - math.exp(log_pre) * h)
