"""The sign of a drift curve: where v is significantly positive or negative, and where it
changes sign -- the rules of the transport and ratchet claims, fixed before the data and
calibrated on synthetic curves (tests/pipeline/claims/test_signs.py and each study's cases).

significant v   v ≠ 0 at a point of a curve when |v| exceeds z_n standard errors (read off its
                CI side towards 0, as bbb.analysis.extrema does), z_n = Φ⁻¹(1 − α / (2 n))
                Bonferroni over the n points of the curve, α = 0.05: on a curve with v ≡ 0 the
                chance of calling any point significant is ≤ 5 %; and |v| > V_MIN = 1e-6 mm/s
                (a particle at rest has |v| ~ 1e-16 mm/s with a CI of rounding size).
reversal        a sign change between consecutive significant points (those in between not
                significant); located as the interval from the last significant point of one
                sign to the first of the other (:func:`reversal_intervals`), or by its midpoint
                (:func:`reversals`).  A curve is v along f at a fixed floor, or v along the
                throw ψ at a fixed floor and f.
steady only     a curve holds only the points whose drift is steady (bbb.analysis.transport,
                the table's ``steady`` column): :func:`steady_rows`.
a sum           v1 + v2 of two estimates (a drift and its mirror image's), its interval from
                the two CIs' sides in quadrature (:func:`sum_interval`): the estimates taken
                as independent.
"""

from __future__ import annotations

from statistics import NormalDist

import numpy as np
import pandas as pd

__all__ = ["ALPHA", "V_MIN", "significant_signs", "reversals", "reversal_intervals", "sum_interval",
           "steady_rows"]

ALPHA = 0.05
V_MIN = 1e-6  # mm/s


def significant_signs(v, lo, hi, ci: float = 0.95, alpha: float = ALPHA) -> np.ndarray:
    """+1 / −1 where v is significantly positive / negative (Bonferroni over the n points,
    module docstring), 0 elsewhere."""
    v, lo, hi = (np.asarray(a, dtype=float) for a in (v, lo, hi))
    z_ci = NormalDist().inv_cdf(0.5 + ci / 2.0)
    z_n = NormalDist().inv_cdf(1.0 - alpha / (2.0 * max(1, v.size)))
    s_below, s_above = (v - lo) / z_ci, (hi - v) / z_ci  # standard errors, each side
    pos = (v > z_n * s_below) & (v > V_MIN)
    neg = (-v > z_n * s_above) & (-v > V_MIN)
    return np.where(pos, 1, np.where(neg, -1, 0))


def reversal_intervals(x, signs) -> list[tuple[float, float, int]]:
    """(x_a, x_b, sign after) of every sign change between consecutive significant points:
    x_a the last significant point of one sign, x_b the first of the other (the sign change
    lies in between), in the order of ``x``."""
    out, prev = [], None
    for xi, s in zip(x, signs, strict=True):
        if s == 0:
            continue
        if prev is not None and s != prev[1]:
            out.append((float(prev[0]), float(xi), int(s)))
        prev = (xi, s)
    return out


def reversals(f, signs) -> list[float]:
    """Frequencies (midpoints) where consecutive significant signs differ."""
    return [0.5 * (a + b) for a, b, _ in reversal_intervals(f, signs)]


def steady_rows(t: pd.DataFrame | None) -> pd.DataFrame | None:
    """The rows of a diffusion table with a steady drift, sorted by f (attrs["unsteady"]: the
    f of the accelerating ones, whose v's CI is blank); rows without v's CI (no mover) are
    left out; None without the transport columns."""
    if t is None or "v" not in t:
        return None
    t = t.dropna(subset=["v"]).sort_values("f")
    ok = t["steady"].fillna(True).astype(bool) if "steady" in t else pd.Series(True, t.index)
    out = t[ok].dropna(subset=["v_lo", "v_hi"]).copy()
    out.attrs["unsteady"] = t["f"][~ok].tolist()
    return out


def sum_interval(v1, lo1, hi1, v2, lo2, hi2, ci: float = 0.95
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(s, lo, hi): the sum s = v1 + v2 of two estimates with a ``ci`` interval whose sides
    are each side's standard errors (read off the CIs as :func:`significant_signs` does) in
    quadrature -- the two estimates taken as independent.  NaN where either is blank."""
    v1, lo1, hi1, v2, lo2, hi2 = (np.asarray(a, dtype=float) for a in (v1, lo1, hi1, v2, lo2, hi2))
    s = v1 + v2
    below = np.hypot(v1 - lo1, v2 - lo2)
    above = np.hypot(hi1 - v1, hi2 - v2)
    return s, s - below, s + above
