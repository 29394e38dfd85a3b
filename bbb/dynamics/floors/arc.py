"""The paper's floor shape: circular arcs of radius R (mm) centred at the cell centres, cusps
at the cell edges (Fig. 1); R = inf is the flat floor.  The kernel carries the arc as its
radius, a float, so that the paper's floor compiles to exactly the expressions it always had
(bbb.surface's arc_* functions).  Offsets d (mm) are from the arc's centre, |d| ≤ S/2."""

from __future__ import annotations

import math

from numba import njit

from ...surface import arc_curvature, arc_depth, arc_normal, arc_slope

#: the record type of an arc: its radius R (mm), a float (``sh`` below)
RECORD = float


@njit(cache=True, inline="always")
def depth(sh, d):
    return arc_depth(d, sh)


@njit(cache=True, inline="always")
def slope(sh, d):
    return arc_slope(d, sh)


@njit(cache=True, inline="always")
def curvature(sh, d):
    return arc_curvature(d, sh)


@njit(cache=True, inline="always")
def normal(sh, d):
    return arc_normal(d, sh)


@njit(cache=True, inline="always")
def curvature_max(sh, da, db):
    # c'' grows with |d| within a cell
    return arc_curvature(max(abs(da), abs(db)), sh)


@njit(cache=True, inline="always")
def concavity(sh):
    # c'' ≥ 0 everywhere: never concave
    return 0.0


@njit(cache=True, inline="always")
def depth_min(sh, da, db, ca, cb):
    # c grows with |d| within a cell: 0 over an interval holding the top, else at an end
    return 0.0 if da * db <= 0.0 else min(ca, cb)


@njit(cache=True, inline="always")
def valley_depth(sh, S):
    return arc_depth(0.5 * S, sh)


@njit(cache=True, inline="always")
def is_flat(sh):
    return math.isinf(sh)
