"""Significant local maxima and minima of a noisy curve D(f) with confidence intervals.

Significance comes from the confidence intervals, corrected for looking at many points:

* each value's standard errors below and above are read off its interval,
  s⁻ = (D - lo)/z and s⁺ = (hi - D)/z with z the normal quantile of the interval's level
  (1.96 for 95 %), so asymmetric bootstrap intervals are respected;
* point a is *significantly above* point b when
  (D_a - D_b) / sqrt(s⁻_a² + s⁺_b²) > z_crit  and  D_a - D_b > min_depth,
  where z_crit = Φ⁻¹(1 - alpha / (n (n - 1) / 2)) is Bonferroni-corrected over all pairs of
  the n points (4.36 for n = 124, alpha = 0.05): on a curve of pure noise the chance of
  reporting any extremum is then at most alpha, whereas plain non-overlap of 95 % intervals
  would find spurious extrema in most noisy curves of a hundred points;
* a local maximum is a point c such that, walking away from c to either side, the curve
  reaches a point significantly below c before it reaches a point higher than c; a local
  minimum likewise, mirrored.

:func:`find_extrema` finds them in one pass (a "zigzag" walk: follow the current candidate
maximum while the curve rises, confirm it once a later point lies significantly below it,
then follow the candidate minimum, and so on), so maxima and minima alternate.  Each
extremum carries an uncertainty of its position: the contiguous range [f_lo, f_hi] of
abscissae around it whose intervals overlap the extremum's own, i.e. the points that cannot
be told apart from it even pointwise.  An extremum at either end of the curve is never
reported (the curve is not seen beyond it).

Pure numpy.  Units are the caller's (f in Hz and D in mm²/s in this project).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from statistics import NormalDist

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["Extremum", "Significance", "find_extrema", "critical_z", "nearest"]


@dataclass(frozen=True)
class Extremum:
    """One significant extremum.

    kind          -- "max" or "min"
    index         -- position in the (NaN-free, f-sorted) input
    f, D, lo, hi  -- its abscissa, value and confidence interval
    f_lo, f_hi    -- the contiguous range of abscissae whose intervals overlap [lo, hi]
    z             -- how far it stands out: the smaller over both sides of the z-score of its
                     difference to the nearest significantly lower (for a minimum: higher) point
    """

    kind: str
    index: int
    f: float
    D: float
    lo: float
    hi: float
    f_lo: float
    f_hi: float
    z: float


def critical_z(n: int, alpha: float = 0.05) -> float:
    """z_crit = Φ⁻¹(1 - alpha / (n (n - 1) / 2)): Bonferroni over all pairs of n points."""
    if not 0.0 < alpha < 1.0:
        raise ValueError(f"alpha = {alpha!r}; allowed: 0 < alpha < 1")
    pairs = max(1, n * (n - 1) // 2)
    return NormalDist().inv_cdf(1.0 - alpha / pairs)


@dataclass(frozen=True)
class Significance:
    """The rule "a is significantly above b" for one curve (see the module docstring).

    D, lo, hi -- the curve; ci -- the intervals' level; z_crit -- the critical z-score;
    min_depth -- a difference must also exceed this (D units)
    """

    D: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    ci: float
    z_crit: float
    min_depth: float = 0.0

    def z(self, a: int, b: int) -> float:
        """z-score of D[a] - D[b] from the lower error of a and the upper error of b."""
        zc = NormalDist().inv_cdf(0.5 + self.ci / 2.0)
        diff = self.D[a] - self.D[b]
        s2 = ((self.D[a] - self.lo[a]) / zc) ** 2 + ((self.hi[b] - self.D[b]) / zc) ** 2
        if s2 == 0.0:
            return math.copysign(math.inf, diff) if diff != 0 else 0.0
        return float(diff / math.sqrt(s2))

    def above(self, a: int, b: int) -> bool:
        return self.D[a] - self.D[b] > self.min_depth and self.z(a, b) > self.z_crit


def _clean(f, D, lo, hi):
    f, D, lo, hi = (np.asarray(a, dtype=np.float64).ravel() for a in (f, D, lo, hi))
    if not (f.shape == D.shape == lo.shape == hi.shape):
        raise ValueError(f"f, D, lo, hi must have one length, got {f.size}, {D.size}, {lo.size}, {hi.size}")
    ok = np.isfinite(f) & np.isfinite(D) & np.isfinite(lo) & np.isfinite(hi)
    f, D, lo, hi = f[ok], D[ok], lo[ok], hi[ok]
    if np.any(lo > D) or np.any(hi < D):
        raise ValueError("every interval must contain its value: lo ≤ D ≤ hi")
    order = np.argsort(f, kind="stable")
    return f[order], D[order], lo[order], hi[order]


def _side_z(c: int, step: int, kind: str, sig: Significance) -> float:
    """Walk from c by ``step`` until a point beyond c (higher, for a max) or significantly on
    the other side of c; return that point's z-score in the latter case, else NaN."""
    D = sig.D
    j = c + step
    while 0 <= j < D.size:
        if kind == "max":
            if D[j] > D[c]:
                return math.nan
            if sig.above(c, j):
                return sig.z(c, j)
        else:
            if D[j] < D[c]:
                return math.nan
            if sig.above(j, c):
                return sig.z(j, c)
        j += step
    return math.nan


def _plateau(c: int, f, lo, hi) -> tuple[float, float]:
    """The contiguous abscissa range around c whose intervals overlap c's."""
    a = c
    while a - 1 >= 0 and lo[a - 1] <= hi[c] and hi[a - 1] >= lo[c]:
        a -= 1
    b = c
    while b + 1 < f.size and lo[b + 1] <= hi[c] and hi[b + 1] >= lo[c]:
        b += 1
    return float(f[a]), float(f[b])


def find_extrema(f: ArrayLike, D: ArrayLike, lo: ArrayLike, hi: ArrayLike, *, ci: float = 0.95,
                 alpha: float = 0.05, min_depth: float = 0.0) -> list[Extremum]:
    """The significant local maxima and minima of D(f), in order of f.

    f         -- abscissae (any order; rows with a NaN are dropped)
    D         -- values
    lo, hi    -- each value's confidence interval at level ``ci`` (lo ≤ D ≤ hi)
    alpha     -- family-wise error rate of the pairwise comparisons (Bonferroni)
    min_depth -- smallest difference (D units) that counts, whatever its z-score
    """
    if not 0.0 < ci < 1.0:
        raise ValueError(f"ci = {ci!r}; allowed: 0 < ci < 1")
    f, D, lo, hi = _clean(f, D, lo, hi)
    n = D.size
    if n < 3:
        return []
    sig = Significance(D, lo, hi, ci, critical_z(n, alpha), float(min_depth))
    candidates: list[tuple[str, int]] = []
    direction = 0  # +1: following a rising run (candidate max), -1: a falling one
    imax = imin = cand = 0
    for i in range(1, n):
        if direction == 0:
            imax = i if D[i] > D[imax] else imax
            imin = i if D[i] < D[imin] else imin
            if sig.above(imax, imin):
                # the later of the two is the live candidate; the earlier one is a boundary
                direction = 1 if imin < imax else -1
                cand = imax if direction == 1 else imin
        elif direction == 1:
            if D[i] > D[cand]:
                cand = i
            elif sig.above(cand, i):
                candidates.append(("max", cand))
                direction, cand = -1, i
        else:
            if D[i] < D[cand]:
                cand = i
            elif sig.above(i, cand):
                candidates.append(("min", cand))
                direction, cand = 1, i
    out = []
    for kind, c in candidates:
        # Both sides re-checked: with unequal intervals the walk alone does not guarantee it.
        left, right = _side_z(c, -1, kind, sig), _side_z(c, +1, kind, sig)
        if math.isnan(left) or math.isnan(right):
            continue
        z = min(left, right)
        f_lo, f_hi = _plateau(c, f, lo, hi)
        out.append(Extremum(kind, int(c), float(f[c]), float(D[c]), float(lo[c]), float(hi[c]),
                            f_lo, f_hi, float(z)))
    return out


def nearest(extrema: list[Extremum], kind: str, f0: float, window: float) -> Extremum | None:
    """The extremum of ``kind`` ("max" or "min") whose position range [f_lo, f_hi] comes
    closest to f0, if that distance is at most ``window``; else None."""
    if kind not in ("max", "min"):
        raise ValueError(f"kind = {kind!r}; allowed: 'max', 'min'")
    best, best_d = None, np.inf
    for e in extrema:
        if e.kind != kind:
            continue
        d = 0.0 if e.f_lo <= f0 <= e.f_hi else min(abs(e.f_lo - f0), abs(e.f_hi - f0))
        d = min(d, abs(e.f - f0))
        if d < best_d or (d == best_d and best is not None and abs(e.f - f0) < abs(best.f - f0)):
            best, best_d = e, d
    return best if best is not None and best_d <= window else None
