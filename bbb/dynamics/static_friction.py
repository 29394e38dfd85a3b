"""When static friction holds a particle at rest relative to the floor, on either floor
(``slide`` has μ = 0, ``coulomb`` μ > 0).

On the paper's floor (``frame`` None) that depends on where it rests only: at an arc's top,
in a cusp (held by both walls), on a flat floor, or where |tan θ| ≤ μ.  On the conveyor
(frame and symbols as in :mod:`bbb.dynamics.bounds`: floor coordinates, gravity
(−gx, −gy), floor displacement (Ax, Ay)(−sin ωt)) a particle in contact feels the effective
gravity −(Gx, Gy), Gx = gx + Ax ω² sin ωs, Gy = gy + Ay ω² sin ωs (mm/s²); at rest on its arc,
at angle θ from the top (normal n = (sin θ, cos θ)), friction holds it while |F_t| ≤ μN with
F_t = Gy sin θ − Gx cos θ and N = Gx sin θ + Gy cos θ (the motion itself:
:mod:`bbb.dynamics.slide`).  In a cusp (within CUSP_REACH of it, where the floor lets go only
when both arcs do) it slides up a wall only where that wall presses, N > 0, and pulls it up
the wall by more than μN; a wall with N ≤ 0 does not touch it (before 2026-11-25 that case
counted too: a 'slip' up a wall that had let go, then at once a lift-off off it while the
other wall still pressed — the checker's contact_start flags of the conveyor hypothesis
test).  F_t and N are affine in u = sin ωs, so where static friction holds is an interval of
u on one arc and the complement of two intervals in a cusp; :func:`slip_wait` finds when the
floor's phase first leaves it.
"""

from __future__ import annotations

import math

from ..jit import inlined, jitted
from .bounds import cusp_side
from .floors.arc import arc_normal

TWO_PI = 2.0 * math.pi


@inlined
def forces_at_rest(nx, ny, frame, w):
    """(F_t, dF_t/du, N, dN/du) (mm/s²) at rest where the normal is (nx, ny), u = sin ωs."""
    gx, gy, Ax, Ay = frame
    w2 = w * w
    return gy * nx - gx * ny, (Ay * nx - Ax * ny) * w2, gx * nx + gy * ny, (Ax * nx + Ay * ny) * w2


@inlined
def cut(lo, hi, c, k):
    # intersect [lo, hi] with {u : c + k u ≤ 0}
    if k > 0.0:
        return lo, min(hi, -c / k)
    if k < 0.0:
        return max(lo, -c / k), hi
    if c > 0.0:
        return math.inf, -math.inf
    return lo, hi


@jitted
def hold_interval(d, fl, frame, mu):
    """The interval [lo, hi] of u = sin ωs in which static friction holds a particle at rest
    on one arc at offset d, |F_t| ≤ μN (empty: lo > hi; N ≥ |F_t|/μ ≥ 0 there)."""
    nx, ny = arc_normal(d, fl.R)
    ft, ftu, n, nu = forces_at_rest(nx, ny, frame, fl.w)
    lo, hi = cut(-math.inf, math.inf, ft - mu * n, ftu - mu * nu)
    return cut(lo, hi, -ft - mu * n, -ftu - mu * nu)


@inlined
def above(lo, hi, c, k):
    # intersect (lo, hi) with {u : c + k u > 0}
    if k > 0.0:
        return max(lo, -c / k), hi
    if k < 0.0:
        return lo, min(hi, -c / k)
    if c > 0.0:
        return lo, hi
    return math.inf, -math.inf


@jitted
def wall_slip(nx, ny, up, frame, w, mu):
    """The open interval (lo, hi) of u = sin ωs in which a particle at rest in a cusp slides
    up the wall of normal (nx, ny) (``up`` = ±1: the x direction up that wall, away from the
    cusp): the wall presses, N > 0, and the pull up it beats friction, up·F_t > μN.  A wall
    with N ≤ 0 does not touch the particle: it cannot slide on it."""
    ft, ftu, n, nu = forces_at_rest(nx, ny, frame, w)
    lo, hi = above(-math.inf, math.inf, n, nu)
    return above(lo, hi, up * ft - mu * n, up * ftu - mu * nu)


@jitted
def exit_wait(s, w, lo, hi):
    """Time (s) until u = sin ω(s+τ) first leaves [lo, hi]: 0 if outside now, inf if never."""
    u0 = math.sin(w * s)
    if not (lo <= u0 <= hi):
        return 0.0
    ph0 = w * s
    best = math.inf
    if hi < 1.0:  # sin rises through hi at asin(hi)
        r = (math.asin(hi) - ph0) % TWO_PI
        best = min(best, 0.0 if r > TWO_PI - 1e-9 else r / w)
    if lo > -1.0:  # and falls through lo at π − asin(lo)
        r = (math.pi - math.asin(lo) - ph0) % TWO_PI
        best = min(best, 0.0 if r > TWO_PI - 1e-9 else r / w)
    return best


@jitted
def enter_wait(s, w, lo, hi):
    """Time (s) until u = sin ω(s+τ) first lies in the open (lo, hi): 0 if it does now, inf
    if never.  An interval narrower than 16 ε is empty: its ends are one boundary rounded two
    ways (throw = 90° − tilt: the effective gravity and with it every load of both walls
    vanishes at one phase, and a wall's N and pull change sign together)."""
    if not hi - lo > 16.0 * 2.220446049250313e-16 or lo >= 1.0 or hi <= -1.0:
        return math.inf
    u0 = math.sin(w * s)
    if lo < u0 < hi:
        return 0.0
    ph0 = w * s
    best = math.inf
    if lo >= -1.0:  # sin rises through lo at asin(lo)
        r = (math.asin(lo) - ph0) % TWO_PI
        best = min(best, 0.0 if r > TWO_PI - 1e-9 else r / w)
    if hi <= 1.0:  # and falls through hi at π − asin(hi)
        r = (math.pi - math.asin(hi) - ph0) % TWO_PI
        best = min(best, 0.0 if r > TWO_PI - 1e-9 else r / w)
    return best


@jitted
def slip_wait(d, s, fl, frame, mu, flat):
    """(time in s until static friction lets go of a particle at rest at offset d from floor
    time s, the wall it then slides on: 0 its own arc, ±1 the neighbour on that side).

    On one arc: until |F_t| > μN (which includes N turning ≤ 0: the caller compares with the
    floor's letting go).  In a cusp (within CUSP_REACH, bbb.dynamics.bounds.cusp_side: where
    the floor lets go only when both arcs do) it slides up the wall whose pull beats friction
    while that wall presses (wall_slip); the two cannot hold at once (up both walls the pull
    would have to point into both, N < 0 on each)."""
    w, R, S = fl.w, fl.R, fl.S
    side = 0 if flat else cusp_side(d, R, S)
    if side == 0:
        lo, hi = hold_interval(d, fl, frame, mu)
        return exit_wait(s, w, lo, hi), 0
    # up this arc is away from the cusp (−side), up the neighbour's is +side
    nx, ny = arc_normal(d, R)
    lo, hi = wall_slip(nx, ny, -float(side), frame, w, mu)
    t_own = enter_wait(s, w, lo, hi)
    nx, ny = arc_normal(d - side * S, R)
    lo, hi = wall_slip(nx, ny, float(side), frame, w, mu)
    t_other = enter_wait(s, w, lo, hi)
    if t_other < t_own:
        return t_other, side
    return t_own, 0


@jitted
def holds_at_rest(d, R, S, mu, flat):
    """Whether a particle at rest at offset d stays at rest while g_eff > 0: on a flat
    floor, in a cusp (held by both walls), at an arc's top, or where static friction
    holds it, |g_eff sin θ| ≤ μ N = μ g_eff cos θ, i.e. |tan θ| ≤ μ."""
    if flat or d == 0.0 or abs(d) >= 0.5 * S:
        return True
    nx, ny = arc_normal(d, R)
    return abs(nx) <= mu * ny


@inlined
def held_at_rest(d, s, fl, frame, mu, flat):
    # whether a particle at rest relative to the floor at offset d stays at rest now: on the
    # paper's floor holds_at_rest, on the conveyor until static friction lets go (slip_wait)
    if frame is None:
        return holds_at_rest(d, fl.R, fl.S, mu, flat)
    return slip_wait(d, s, fl, frame, mu, flat)[0] > 0.0


@inlined
def in_cusp(d, R, S, frame):
    # at a cusp, where both walls hold a particle: exactly there on the paper's floor,
    # within CUSP_REACH on the conveyor (bbb.dynamics.bounds.cusp_side)
    if frame is None:
        return abs(d) >= 0.5 * S
    return cusp_side(d, R, S) != 0
