"""The conveyor's gap and its certificates (a floor tilted by φ, thrown at ψ), for the
collision search of :mod:`bbb.dynamics.search`: the first time τ (s) at which a flight meets
the moving arcs, never missing one.

Coordinates are the floor's: x along its mean plane, y normal to it.  Gravity is
(−gx, −gy) = (−g sin φ, −g cos φ) (mm/s²); the floor moves rigidly by
A·(cos ψ, sin ψ)·(−sin 2πft) = (X_f, Y_f) with amplitudes (Ax, Ay) (mm).  The particle's
state is its cell and its offset ``d`` *relative to the floor* (lab x = cell·S + d + X_f),
height y, lab velocity (vx, vy), floor time s in [0, T).

A flight is a parabola in x and y; its offset relative to the moving floor is
d(τ) = d₀ + vx τ − gx τ²/2 + Ax (sin ω(s+τ) − sin ωs), and the gap to the nearest arc is
G(τ) = y₀ + vy τ − gy τ²/2 + Ay sin ω(s+τ) + c(d(τ) − kS), k the nearest centre.  The search
stays certified without splitting the flight at cusps: the depth of the nearest arc has only
concave kinks at cusps, so chord bounds that need an upper bound on G'' stay valid across
them, and the bounds that need a lower bound are used only on intervals that cannot reach a
cusp (|d''| ≤ Dx = |gx| + |Ax| ω² bounds where d can go).

The paper floor's are :mod:`bbb.dynamics.bounds_level`'s; docs/physics.md,
"Transport", derives the rest.
"""

from __future__ import annotations

import math

from numba import njit

from .bounds_level import quartic_step
from .floors.arc import arc_curvature, arc_depth, arc_slope

#: a carried particle within CUSP_REACH·S of a cusp rests in it: both arcs hold it, and it
#: lifts off only when both let go (docs/physics.md, "Transport"); 1e-9 S is far above the
#: ~|u|·tol_t ≲ 1e-9 mm to which a collision's place is known and far below any scale of
#: the motion
CUSP_REACH = 1e-9


@njit(cache=True, inline="always")
def round_half_away(u):
    # nearest integer, ties away from 0: odd in u bit for bit, so a mirrored run (x → −x)
    # takes mirrored decisions everywhere
    return math.floor(u + 0.5) if u >= 0.0 else -math.floor(0.5 - u)


@njit(cache=True, inline="always")
def nearest(d, S):
    # offset from the nearest arc centre
    return d - round_half_away(d / S) * S


@njit(cache=True, inline="always")
def gap_c(tau, y, vy, s, d0, vx, sin_s, gx, gy, Ax, Ay, w, R, S):
    # G, dG/dτ, the unwrapped floor-relative offset d and d' at flight time τ (module doc)
    ph = w * (s + tau)
    sp = math.sin(ph)
    cp = math.cos(ph)
    d = d0 + vx * tau - 0.5 * gx * tau * tau + Ax * (sp - sin_s)
    d1 = vx - gx * tau + Ax * w * cp
    dn = nearest(d, S)
    G = y + vy * tau - 0.5 * gy * tau * tau + Ay * sp + arc_depth(dn, R)
    G1 = vy - gy * tau + Ay * w * cp
    if d1 != 0.0:
        G1 += arc_slope(dn, R) * d1
    return G, G1, d, d1


@njit(cache=True, inline="always")
def offset_range(da, db, h, Dx, S):
    # |nearest offset| over [a, b]: (max, min, cusp inside?) from d ∈ chord ± Dx h²/8
    e = Dx * h * h * 0.125
    lo = min(da, db) - e
    hi = max(da, db) + e
    # a cusp lies in [lo, hi] iff the nearest centres differ; a centre iff an integer lies in
    # [lo/S, hi/S] (both tests odd under lo, hi → −hi, −lo)
    cusp = round_half_away(lo / S) != round_half_away(hi / S)
    centre = math.ceil(lo / S) <= math.floor(hi / S)
    nl = abs(nearest(lo, S))
    nh = abs(nearest(hi, S))
    amax = 0.5 * S if cusp else max(nl, nh)
    amin = 0.0 if centre else min(nl, nh)
    return min(amax, 0.5 * S), amin, cusp


@njit(cache=True, inline="always")
def times_or_zero(a, b):
    # a·b with 0·inf = 0: a bound term that vanishes with its factor
    return 0.0 if a == 0.0 or b == 0.0 else a * b


@njit(cache=True)
def upper_curvature(amax, D1, Dx, gy, Ay, w, R):
    """Upper bound (mm/s²) of G'' = −gy − Ay ω² sin + c''(d) d'² + c'(d) d'' where |d| ≤ amax,
    |d'| ≤ D1, |d''| ≤ Dx."""
    m = -gy + abs(Ay) * w * w
    m += times_or_zero(arc_curvature(amax, R), D1 * D1)
    m += times_or_zero(arc_slope(amax, R), Dx)
    return m


@njit(cache=True)
def lower_bound_c(h, Ga, G1a, Gb, da, db, d1a, d1b, Dx, gy, Ay, w, R, S):
    """Rigorous lower bound of G on [a, a+h] (cusps may lie inside)."""
    amax, amin, cusp = offset_range(da, db, h, Dx, S)
    D1 = max(abs(d1a), abs(d1b)) + 0.5 * Dx * h
    # chord minus curvature: needs only G'' ≤ M, which the concave kinks at cusps respect
    M = upper_curvature(amax, D1, Dx, gy, Ay, w, R)
    lb = min(Ga, Gb) - max(M, 0.0) * h * h * 0.125
    if not cusp and math.isfinite(G1a):
        # Taylor from a with G'' ≥ −gy − |Ay|ω² − c'(amax) Dx (c'' d'² ≥ 0): concave quadratic
        m = -gy - abs(Ay) * w * w - times_or_zero(arc_slope(amax, R), Dx)
        q = Ga + G1a * h + 0.5 * m * h * h
        if q == q:
            lb = max(lb, min(Ga, q))
    # depth at least its minimum over the range of d; the rest (Eq. 2 minus the floor) has
    # curvature ≤ −gy + |Ay| ω².  Carries the vertical cusps of R = S/2.
    ca = arc_depth(nearest(da, S), R)
    cb = arc_depth(nearest(db, S), R)
    mf = max(-gy + abs(Ay) * w * w, 0.0)
    lb = max(lb, min(Ga - ca, Gb - cb) - mf * h * h * 0.125 + arc_depth(amin, R))
    return lb


@njit(cache=True, inline="always")
def cusp_side(d, R, S):
    """±1 when the offset d (mm, |d| ≤ S/2) lies within CUSP_REACH·S of the cusp on that
    side (a carried particle there rests in the cusp, held by both arcs), else 0."""
    if math.isinf(R) or 0.5 * S - abs(d) > CUSP_REACH * S:
        return 0
    return 1 if d > 0.0 else -1


@njit(cache=True)
def start_step_c(h_max, G1, d0, d10, s, gx, gy, Ax, Ay, w, R, S, Dx, lifting):
    """A step σ > 0 on which G > 0 for a flight starting on the surface (G(0) = 0); 0 if none."""
    dn = nearest(d0, S)
    # a lift-off within reach of a cusp, or any flight from exactly on it (a bounce there
    # after a contact model's cusp event): the one-arc path below would have r = 0, i.e. a
    # collision at τ = 0 with whichever arc the rounding names, even one the particle leaves
    side = cusp_side(dn, R, S) if lifting or abs(dn) >= 0.5 * S else 0
    if side == 0:
        # both bounds below need G'' bounded below: stop before the nearest cusp's concave kink
        return start_step_arc(h_max, G1, dn, max(0.5 * S - abs(dn), 0.0), 0.5 * S, d10, s, gx,
                              gy, Ax, Ay, w, R, Dx, lifting)
    # a lift-off from a cusp (bbb.dynamics.liftoff.liftoff_wait: both arcs have let go; a bounce
    # there takes the path above, whose tiny steps resolve a flight across the cusp): both
    # arcs are the floor, G = min(G_own, G_other), each the gap to a whole circle
    # (smooth, convex depth), while d stays within r of the cusp: both circles defined (half
    # the way to |e| = R, where the slope is infinite) and the nearest arc one of the two
    e2 = dn - side * S
    r = min(0.5 * (R - abs(e2)), 0.5 * S)
    G1b = G1
    if d10 != 0.0:
        G1b = G1 - arc_slope(dn, R) * d10 + arc_slope(e2, R) * d10
        if not math.isfinite(G1b):
            return 0.0
    a = start_step_arc(h_max, G1, dn, r, abs(dn) + r, d10, s, gx, gy, Ax, Ay, w, R, Dx, lifting)
    b = start_step_arc(h_max, G1b, e2, r, abs(e2) + r, d10, s, gx, gy, Ax, Ay, w, R, Dx, lifting)
    return min(a, b)


@njit(cache=True)
def start_step_arc(h_max, G1, e0, r, cap, d10, s, gx, gy, Ax, Ay, w, R, Dx, lifting):
    """start_step_c on one circle: the flight starts at offset e0 (mm) from its centre, G(0) = 0,
    G'(0) = G1, and the bounds hold while |d − d0| ≤ r (mm); ``cap`` bounds |e| there."""
    sigma = 0.0
    # (|d − d0| ≤ |d'0| σ + Dx σ²/2 ≤ r)
    if not math.isinf(R) and r < math.inf:
        sq = abs(d10) + math.sqrt(d10 * d10 + 2.0 * Dx * r)
        h_max = min(h_max, 2.0 * r / sq if sq > 0.0 else h_max)
    if h_max <= 0.0:
        return 0.0
    if G1 > 0.0:
        # G ≥ G1 τ + m τ²/2 with m a lower bound of G'' on [0, σ] (|d − d0| ≤ |d'0|σ + Dxσ²/2)
        sigma = h_max
        for _ in range(60):
            amax = min(abs(e0) + abs(d10) * sigma + 0.5 * Dx * sigma * sigma, cap)
            m = -gy - abs(Ay) * w * w - times_or_zero(arc_slope(amax, R), Dx)
            if not math.isfinite(m):
                sigma *= 0.5
                continue
            if G1 + 0.5 * m * sigma > 0.0:
                break
            sigma = min(0.5 * sigma, -G1 / m)
        else:
            sigma = 0.0
    cs = arc_slope(e0, R)
    if G1 >= 0.0 and math.isfinite(cs):
        # c is convex: G ≥ H = (the flight's height) − (floor) + c(d0) + c'(d0)(d(τ) − d0), a
        # flight over a flat floor of gravity gy + c' gx and amplitude Ay + c' Ax: Taylor to
        # 4th order (the lift-off from rest, G1 = G'' = 0 at the window's edge)
        ae = Ay + cs * Ax
        G2 = -(gy + cs * gx) - ae * w * w * math.sin(w * s)
        if lifting:
            # as in bbb.dynamics.bounds_level.start_step: drop rounding below the window's edge
            G2 = max(G2, 0.0)
        if G2 >= 0.0:
            sigma = quartic_step(sigma, G2, -ae * w * w * w * math.cos(w * s),
                                 abs(ae) * w * w * w * w, h_max)
    return min(sigma, h_max)
