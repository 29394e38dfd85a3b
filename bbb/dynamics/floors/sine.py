"""A sinusoidally undulating floor: c(d) = a (1 − cos kd) below its tops, a (mm) the sine's
amplitude (top to valley 2a), k = 2π/S (1/mm) its wavenumber, S its wavelength; tops at the
cell centres, valleys at the cell edges.  Its curvature a k² cos kd changes sign: convex tops,
concave valleys, so the collision search bounds G'' from below by a k² (``concavity``).

Depth and slope are both taken from the half angle kd/2: c = 2a sin²(kd/2),
c' = 2ak sin(kd/2) cos(kd/2), so that the gap, which needs both, costs one sine and cosine of
one argument (computed together); the curvature bound reads the depth, c'' = k² (a − c).

Offsets d (mm) are from the cell centre, |d| ≤ S/2: c grows with |d| and c'' falls with
|d| there, which the bounds use."""

from __future__ import annotations

import math
from collections import namedtuple

from ...jit import inlined

#: the kernel's record of a sine floor: amplitude a (mm) and wavenumber k = 2π/S (1/mm)
Sine = namedtuple("Sine", "a k")
RECORD = Sine


def record(depth: float, S: float) -> Sine:
    """The record of a sine floor ``depth`` (mm) from top to valley, wavelength S (mm)."""
    return Sine(0.5 * depth, 2.0 * math.pi / S)


@inlined
def depth(sh, d):
    # a (1 − cos kd) as 2a sin²(kd/2): free of cancellation at the tops
    h = math.sin(0.5 * sh.k * d)
    return 2.0 * sh.a * h * h


@inlined
def slope(sh, d):
    # a k sin kd as 2 a k sin(kd/2) cos(kd/2): the half angle the depth takes
    x = 0.5 * sh.k * d
    return 2.0 * sh.a * sh.k * math.sin(x) * math.cos(x)


@inlined
def curvature(sh, d):
    return sh.a * sh.k * sh.k * math.cos(sh.k * d)


@inlined
def normal(sh, d):
    # outward unit normal of y = −c(d): (c', 1)/√(1 + c'²)
    c1 = slope(sh, d)
    r = math.sqrt(1.0 + c1 * c1)
    return c1 / r, 1.0 / r


@inlined
def curvature_max(sh, da, db, ca, cb):
    # c'' = a k² cos kd = k² (a − c) falls with |d| within a cell, where c grows: largest at
    # the end of smaller depth
    if da * db <= 0.0:
        return sh.a * sh.k * sh.k
    return sh.k * sh.k * (sh.a - min(ca, cb))


@inlined
def concavity(sh):
    # c'' ≥ −a k² everywhere
    return sh.a * sh.k * sh.k


@inlined
def depth_min(sh, da, db, ca, cb):
    # c grows with |d| within a cell: 0 over an interval holding the top, else at an end
    return 0.0 if da * db <= 0.0 else min(ca, cb)


@inlined
def valley_depth(sh, S):
    return 2.0 * sh.a


@inlined
def is_flat(sh):
    return False
