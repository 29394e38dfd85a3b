"""Intervals for a share k / n (a binomial proportion) and for the difference of two shares.

Wilson's score interval (Wilson 1927) covers close to its nominal level down to n ~ 10 and
never has zero width or leaves [0, 1], unlike the Wald interval p ± z sqrt(p(1−p)/n) (zero
width at k = 0 or n).  The difference of two independent shares takes Newcombe's hybrid score
interval (Newcombe 1998, Stat. Med. 17, 873, method 10), built from the two Wilson intervals.
"""

from __future__ import annotations

import math
from statistics import NormalDist

__all__ = ["wilson", "share_difference"]


def _z(ci: float) -> float:
    if not 0.0 < ci < 1.0:
        raise ValueError(f"ci = {ci!r} must lie in (0, 1)")
    return NormalDist().inv_cdf(0.5 + ci / 2.0)


def wilson(k: int, n: int, ci: float = 0.95) -> tuple[float, float, float]:
    """(k / n, lo, hi): the share and its Wilson score interval at level ``ci``; NaNs when n = 0."""
    if n < 0 or not 0 <= k <= max(n, 0):
        raise ValueError(f"need 0 <= k <= n, got k = {k!r}, n = {n!r}")
    if n == 0:
        return math.nan, math.nan, math.nan
    z = _z(ci)
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z / (1 + z * z / n) * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    # rounding may leave the score interval a hair past p at k = 0 or n: it must hold p
    return p, min(p, max(0.0, centre - half)), max(p, min(1.0, centre + half))


def share_difference(k1: int, n1: int, k2: int, n2: int,
                     ci: float = 0.95) -> tuple[float, float, float]:
    """(p1 − p2, lo, hi): the difference of two independent shares with Newcombe's hybrid
    score interval; NaNs when either n is 0."""
    p1, l1, u1 = wilson(k1, n1, ci)
    p2, l2, u2 = wilson(k2, n2, ci)
    if math.isnan(p1) or math.isnan(p2):
        return math.nan, math.nan, math.nan
    d = p1 - p2
    return (d, d - math.sqrt((p1 - l1) ** 2 + (u2 - p2) ** 2),
            d + math.sqrt((u1 - p1) ** 2 + (p2 - l2) ** 2))
