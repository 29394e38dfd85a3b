"""The paper's floor shape: circular arcs of radius R (mm) centred at the cell centres, cusps
at the cell edges (Fig. 1); R = inf is the flat floor.  The kernel carries the arc as its
radius, a float, so that the paper's floor compiles to exactly the expressions it always had;
``arc_normal(d, R)`` is the normal in the argument order the conveyor's modules call it with.
Offsets d (mm) are from the arc's centre, |d| ≤ S/2."""

from __future__ import annotations

import math

from ...jit import inlined


@inlined
def root_r2_d2(d, R):
    # (R-|d|)(R+|d|) instead of R²-d²: exact to rounding at the cusps when R = S/2
    ad = abs(d)
    return math.sqrt(max(0.0, (R - ad) * (R + ad)))


#: the record type of an arc: its radius R (mm), a float (``sh`` below)
RECORD = float


@inlined
def depth(sh, d):
    # Fig. 1 geometry: R - sqrt(R²-d²) written as d²/(R+sqrt(R²-d²)), free of cancellation
    if math.isinf(sh):
        return 0.0
    return d * d / (sh + root_r2_d2(d, sh))


@inlined
def slope(sh, d):
    # dc/dd; infinite at a vertical cusp (R = S/2, |d| = R)
    if math.isinf(sh):
        return 0.0
    q = root_r2_d2(d, sh)
    return d / q if q != 0.0 else math.copysign(math.inf, d)


@inlined
def curvature(sh, d):
    # d²c/dd² = R²/(R²-d²)^(3/2), increasing in |d|
    if math.isinf(sh):
        return 0.0
    q = root_r2_d2(d, sh)
    return sh * sh / (q * q * q) if q != 0.0 else math.inf


@inlined
def arc_normal(d, R):
    # outward unit normal of the arc of radius R at offset d (Fig. 1's v_perp direction)
    if math.isinf(R):
        return 0.0, 1.0
    return d / R, root_r2_d2(d, R) / R


@inlined
def normal(sh, d):
    return arc_normal(d, sh)


@inlined
def curvature_max(sh, da, db, ca, cb):
    # c'' grows with |d| within a cell
    return curvature(sh, max(abs(da), abs(db)))


@inlined
def concavity(sh):
    # c'' ≥ 0 everywhere: never concave
    return 0.0


@inlined
def depth_min(sh, da, db, ca, cb):
    # c grows with |d| within a cell: 0 over an interval holding the top, else at an end
    return 0.0 if da * db <= 0.0 else min(ca, cb)


@inlined
def valley_depth(sh, S):
    return depth(sh, 0.5 * S)


@inlined
def is_flat(sh):
    return math.isinf(sh)
