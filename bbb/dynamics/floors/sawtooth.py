"""A sawtooth (ratchet) floor: straight flanks from a valley at each cell edge up to one peak
per cell, ``h`` (mm) below the peak at the valleys.  The peak sits at offset dp (mm) from the
cell centre, a fraction ``peak`` of the period S from the left valley (0.5: symmetric teeth).

c(d) = kl (dp − d) left of the peak, kr (d − dp) right of it (kl = h/(dp + S/2),
kr = h/(S/2 − dp)): curvature 0 on the flanks, a convex kink at the peak (the search treats
an interval holding it as unbounded curvature above, which only ever makes it step finer) and
a concave kink at the valleys, where the search splits a flight anyway (cell edges)."""

from __future__ import annotations

from collections import namedtuple

from ...jit import inlined

#: the kernel's record of a sawtooth: depth h (mm), peak offset dp (mm), flank slopes kl, kr
Sawtooth = namedtuple("Sawtooth", "h dp kl kr")
RECORD = Sawtooth


def record(depth: float, peak: float, S: float) -> Sawtooth:
    """The record of a sawtooth ``depth`` (mm) deep, its peak a fraction ``peak`` of the period
    S (mm) from the left valley."""
    dp = (peak - 0.5) * S
    return Sawtooth(depth, dp, depth / (dp + 0.5 * S), depth / (0.5 * S - dp))


@inlined
def depth(sh, d):
    if d < sh.dp:
        return sh.kl * (sh.dp - d)
    return sh.kr * (d - sh.dp)


@inlined
def slope(sh, d):
    # at the peak itself 0: a flight through it only turns upward there (convex kink)
    if d < sh.dp:
        return -sh.kl
    if d > sh.dp:
        return sh.kr
    return 0.0


@inlined
def curvature(sh, d):
    return 0.0


@inlined
def normal(sh, d):
    c1 = slope(sh, d)
    r = (1.0 + c1 * c1) ** 0.5
    return c1 / r, 1.0 / r


@inlined
def curvature_max(sh, da, db, ca, cb):
    # straight flanks; the peak's kink is an unbounded convex curvature
    if (da - sh.dp) * (db - sh.dp) <= 0.0:
        return float("inf")
    return 0.0


@inlined
def concavity(sh):
    # within a cell c'' ≥ 0 (the concave kinks are the cell edges)
    return 0.0


@inlined
def depth_min(sh, da, db, ca, cb):
    # c grows away from the peak: 0 over an interval holding it, else at an end
    return 0.0 if (da - sh.dp) * (db - sh.dp) <= 0.0 else min(ca, cb)


@inlined
def valley_depth(sh, S):
    return sh.h


@inlined
def is_flat(sh):
    return False
