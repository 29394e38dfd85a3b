"""The gap between a flight and the floor, and the certificates the collision search of
:mod:`bbb.dynamics.search` proves with (Eqs. 2-4), each rule written once for both floors.

The gap G(τ) = y_particle − y_surface along a flight is only declared positive on an
interval when a rigorous lower bound (chord minus curvature bound, Taylor bound, or
monotone-depth bound) is positive there.  ``frame`` None is the paper's level floor, a
compile-time-pruned variant: the search splits its flights at the cells' edges, so its
bounds hold in one cell of any floor shape ``fl.R`` (bbb.dynamics.floors, whose certificates
they are built from).  A :class:`~bbb.dynamics.options.Frame` is the conveyor: a floor of
arcs tilted by φ, thrown at ψ.

Conveyor coordinates are the floor's: x along its mean plane, y normal to it.  Gravity is
(−gx, −gy) = (−g sin φ, −g cos φ) (mm/s²); the floor moves rigidly by
A·(cos ψ, sin ψ)·(−sin 2πft) = (X_f, Y_f) with amplitudes (Ax, Ay) (mm).  The particle's
state is its cell and its offset ``d`` *relative to the floor* (lab x = cell·S + d + X_f),
height y, lab velocity (vx, vy), floor time s in [0, T).  A flight's offset relative to the
moving floor is d(τ) = d₀ + vx τ − gx τ²/2 + Ax (sin ω(s+τ) − sin ωs), and the gap is taken
to the nearest arc.  Those bounds hold without splitting the flight at cusps: the depth of
the nearest arc has only concave kinks at cusps, so chord bounds that need an upper bound on
G'' stay valid across them, and the bounds that need a lower bound are used only on
intervals that cannot reach a cusp (|d''| ≤ Dx = |gx| + |Ax| ω² bounds where d can go).
docs/physics.md, "Transport", derives the rest.

The flight ``fli`` is bbb.dynamics.search's Flight record, the floor ``fl`` a
:class:`~bbb.dynamics.options.Floor`; ``ea``, ``eb`` are :func:`gap`'s :data:`Probe` at an
interval's ends.
"""

from __future__ import annotations

import math
from collections import namedtuple

from ..jit import inlined
from .floors import concavity, curvature, curvature_max, depth, depth_min, slope
from .options import heave

#: the gap at one flight time (:func:`gap`): G (mm) and G' (mm/s), the offset d (mm) and d'
#: (mm/s) they were taken at, and the floor's depth c (mm) there, which the bounds reuse
Probe = namedtuple("Probe", "G G1 d d1 c")

#: a carried particle within CUSP_REACH·S of a cusp rests in it: both arcs hold it, and it
#: lifts off only when both let go (docs/physics.md, "Transport"); 1e-9 S is far above the
#: ~|u|·tol_t ≲ 1e-9 mm to which a collision's place is known and far below any scale of
#: the motion
CUSP_REACH = 1e-9


@inlined
def round_half_away(u):
    # nearest integer, ties away from 0: odd in u bit for bit, so a mirrored run (x → −x)
    # takes mirrored decisions everywhere
    return math.floor(u + 0.5) if u >= 0.0 else -math.floor(0.5 - u)


@inlined
def nearest(d, S):
    # offset from the nearest arc centre
    return d - round_half_away(d / S) * S


@inlined
def times_or_zero(a, b):
    # a·b with 0·inf = 0: a bound term that vanishes with its factor
    return 0.0 if a == 0.0 or b == 0.0 else a * b


@inlined
def cusp_side(d, R, S):
    """±1 when the offset d (mm, |d| ≤ S/2) lies within CUSP_REACH·S of the cusp on that
    side (a carried particle there rests in the cusp, held by both arcs), else 0."""
    if math.isinf(R) or 0.5 * S - abs(d) > CUSP_REACH * S:
        return 0
    return 1 if d > 0.0 else -1


@inlined
def heave_bound(fl, frame):
    # (gravity, |amplitude|) normal to the floor's plane, as the bounds read them: the floor's
    # pull on G'' lies within −gn ± |an| ω²
    if frame is None:
        return fl.g, fl.A
    return frame.gy, abs(frame.Ay)


@inlined
def gap(t, fli, fl, frame):
    # Eq. (2): the Probe at flight time t (the level floor's d from the centre of the cell
    # searched, the conveyor's unwrapped and relative to the moving floor)
    w = fl.w
    ph = w * (fli.s + t)
    sp = math.sin(ph)
    cp = math.cos(ph)
    if frame is None:
        # the cell's own profile: its depth is read within the cell
        d = fli.d0 + fli.vx * t
        d1 = fli.vx
        dn = min(max(d, -0.5 * fl.S), 0.5 * fl.S)
    else:
        d = fli.d0 + fli.vx * t - 0.5 * frame.gx * t * t + frame.Ax * (sp - fli.sin_s)
        d1 = fli.vx - frame.gx * t + frame.Ax * w * cp
        dn = nearest(d, fl.S)
    gn, an = heave(fl, frame)
    # depth and slope side by side, outside the branch below: a shape whose two share their
    # work (the sine's half angle) computes it once
    c = depth(fl.R, dn)
    c1 = slope(fl.R, dn)
    G = fli.y + fli.vy * t - 0.5 * gn * t * t + an * sp + c
    G1 = fli.vy - gn * t + an * w * cp
    if d1 != 0.0:
        G1 += c1 * d1
    return Probe(G, G1, d, d1, c)


@inlined
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


@inlined
def reach(h, ea, eb, fli, fl, frame):
    # where the conveyor's offset goes on [a, a+h]: (max and min |nearest offset|, a cusp
    # inside?, a bound of |d'|); the level floor's bounds read the ends' offsets instead
    if frame is None:
        return 0.0, 0.0, False, 0.0
    amax, amin, cusp = offset_range(ea.d, eb.d, h, fli.Dx, fl.S)
    return amax, amin, cusp, max(abs(ea.d1), abs(eb.d1)) + 0.5 * fli.Dx * h


@inlined
def curvature_cap(ea, eb, rg, fli, fl, frame):
    # M ≥ G'' = −gn − an ω² sin + c''(d) d'² + c'(d) d'' on [a, b] (rg: reach there)
    gn, an = heave_bound(fl, frame)
    m = -gn + an * fl.w * fl.w
    if frame is None:
        # d' = vx, d'' = 0, d within one cell
        if fli.vx != 0.0:
            m += fli.vx * fli.vx * curvature_max(fl.R, ea.d, eb.d, ea.c, eb.c)
        return m
    amax, _amin, _cusp, D1 = rg
    m += times_or_zero(curvature(fl.R, amax), D1 * D1)
    m += times_or_zero(slope(fl.R, amax), fli.Dx)
    return m


@inlined
def pull_cap(G1a, rg, fli, fl, frame):
    # K with G'' ≥ −K on [a, b], where the Taylor bound from a applies; NaN where it does not
    # (the conveyor across a cusp's concave kink, or from a vertical wall)
    gn, an = heave_bound(fl, frame)
    k = gn + an * fl.w * fl.w
    if frame is None:
        # more where the shape curves the other way (c'' ≥ −κ)
        kappa = concavity(fl.R)
        if kappa != 0.0:
            k += fli.vx * fli.vx * kappa
        return k
    amax, _amin, cusp, _D1 = rg
    if cusp or not math.isfinite(G1a):
        return math.nan
    # c'' d'² ≥ 0 on arcs; c' d'' ≥ −c'(amax) Dx
    return k + times_or_zero(slope(fl.R, amax), fli.Dx)


@inlined
def least_depth(ea, eb, rg, fli, fl, frame):
    # a lower bound of the floor's depth c on [a, b], whose kinks the depth bound carries (the
    # ends' depths are the gap's: G − c there is the flight over the floor's tops)
    if frame is None:
        return depth_min(fl.R, ea.d, eb.d, ea.c, eb.c)
    return depth(fl.R, rg[1])


@inlined
def lower_bound(a, b, ea, eb, fli, fl, frame):
    """Rigorous lower bound (mm) of G on [a, b] (s), from ``ea``, ``eb`` = :func:`gap` at
    its ends: the best of three.  The level floor's interval lies in one cell; the
    conveyor's may hold cusps."""
    h = b - a
    Ga, G1a = ea.G, ea.G1
    Gb = eb.G
    rg = reach(h, ea, eb, fli, fl, frame)
    # chord minus curvature: G ≥ min(Ga, Gb) − M⁺h²/8; needs only G'' ≤ M, which the concave
    # kinks at the conveyor's cusps respect
    M = curvature_cap(ea, eb, rg, fli, fl, frame)
    lb = min(Ga, Gb) - max(M, 0.0) * h * h * 0.125
    # Taylor from a with G'' ≥ −K: a concave quadratic, minimal at the ends
    K = pull_cap(G1a, rg, fli, fl, frame)
    if frame is None or K == K:
        q = Ga + G1a * h - 0.5 * K * h * h
        if frame is None or q == q:
            lb = max(lb, min(Ga, q))
    # depth at least its minimum over the range of d; the rest (Eq. 2 minus the floor) has
    # curvature ≤ −gn + |an| ω².  Carries the vertical cusps of R = S/2 and a sawtooth's
    # peak, where the curvature bound is infinite (a vertical flight over the level floor
    # needs none: its depth is constant)
    if frame is not None or fli.vx != 0.0:
        cmin = least_depth(ea, eb, rg, fli, fl, frame)
        gn, an = heave_bound(fl, frame)
        mf = max(-gn + an * fl.w * fl.w, 0.0)
        lb = max(lb, min(Ga - ea.c, Gb - eb.c) - mf * h * h * 0.125 + cmin)
    return lb


@inlined
def quartic_step(sigma, G2, G3, K, h_max):
    # a flight from G = G' = 0 with G'' = G2 >= 0, G''' = G3, |G''''| <= K: G > 0 on (0, t] where
    # G2/2 + G3 t/6 - K t^2/24 > 0 (Taylor to 4th order); the longest h_max/2^k so, if > sigma
    tr = h_max
    for _ in range(80):
        if 0.5 * G2 + G3 * tr / 6.0 - K * tr * tr / 24.0 > 0.0:
            return max(sigma, tr)
        tr *= 0.5
    return sigma


@inlined
def rest_step(sigma, gn, ae, h_max, fli, fl):
    # the step of a flight from G = G' = 0 over a flat floor of gravity gn (mm/s²) and
    # amplitude ae (mm) normal to it, which bounds G from below: Taylor to 4th order with
    # |y_f''''| ≤ |ae| ω⁴ (the lift-off from rest, G1 = G'' = 0 at the window's edge)
    w = fl.w
    s = fli.s
    G2 = -gn - ae * w * w * math.sin(w * s)
    if fli.lifting:
        # lift-off is timed where G'' ≥ 0; drop rounding below it (sinks ≤ ε T²/2 with ε
        # the rounding of G'', ≲ 1e-14 mm: docs/physics.md, "Why the lift-off step may clamp")
        G2 = max(G2, 0.0)
    if G2 >= 0.0:
        sigma = quartic_step(sigma, G2, -ae * w * w * w * math.cos(w * s), abs(ae) * w * w * w * w,
                             h_max)
    return sigma


@inlined
def start_step(h_max, ea, fli, fl, frame):
    """A flight step σ (s) > 0 on which G > 0, for a flight that starts on the surface
    (G(0) = 0; ``ea`` = :func:`gap` there), at most h_max (s).

    Returns 0 when no positive step is certified (the particle does not separate)."""
    G1 = ea.G1
    if frame is None:
        sigma = 0.0
        if G1 > 0.0:
            # G ≥ G1 σ - K σ²/2 > 0 for σ < 2 G1/K (pull_cap); take half of that
            sigma = G1 / pull_cap(G1, (0.0, 0.0, False, 0.0), fli, fl, frame)
        if fli.vx == 0.0 and G1 >= 0.0:
            # vertical flight over a fixed point
            sigma = rest_step(sigma, fl.g, fl.A, h_max, fli, fl)
        return min(sigma, h_max)
    S = fl.S
    dn = nearest(ea.d, S)
    # a lift-off within reach of a cusp, or any flight from exactly on it (a bounce there
    # after a contact model's cusp event): the one-arc path below would have r = 0, i.e. a
    # collision at τ = 0 with whichever arc the rounding names, even one the particle leaves
    side = cusp_side(dn, fl.R, S) if fli.lifting or abs(dn) >= 0.5 * S else 0
    if side == 0:
        # both bounds below need G'' bounded below: stop before the nearest cusp's concave kink
        return circle_step(h_max, G1, (dn, max(0.5 * S - abs(dn), 0.0), 0.5 * S), ea.d1, fli,
                           fl, frame)
    # a lift-off from a cusp (bbb.dynamics.liftoff.liftoff_wait: both arcs have let go; a bounce
    # there takes the path above, whose tiny steps resolve a flight across the cusp): both
    # arcs are the floor, G = min(G_own, G_other), each the gap to a whole circle
    # (smooth, convex depth), while d stays within r of the cusp: both circles defined (half
    # the way to |e| = R, where the slope is infinite) and the nearest arc one of the two
    R = fl.R
    d10 = ea.d1
    e2 = dn - side * S
    r = min(0.5 * (R - abs(e2)), 0.5 * S)
    G1b = G1
    if d10 != 0.0:
        G1b = G1 - slope(R, dn) * d10 + slope(R, e2) * d10
        if not math.isfinite(G1b):
            return 0.0
    a = circle_step(h_max, G1, (dn, r, abs(dn) + r), d10, fli, fl, frame)
    b = circle_step(h_max, G1b, (e2, r, abs(e2) + r), d10, fli, fl, frame)
    return min(a, b)


@inlined
def circle_step(h_max, G1, circle, d10, fli, fl, frame):
    """The conveyor's start_step on one circle: the flight starts at offset e0 (mm) from its
    centre, G(0) = 0, G'(0) = G1, d'(0) = d10, and the bounds hold while |d − d0| ≤ r (mm);
    ``circle`` = (e0, r, cap), ``cap`` bounding |e| there."""
    e0, r, cap = circle
    R = fl.R
    Dx = fli.Dx
    sigma = 0.0
    # (|d − d0| ≤ |d'0| σ + Dx σ²/2 ≤ r)
    if not math.isinf(R) and r < math.inf:
        sq = abs(d10) + math.sqrt(d10 * d10 + 2.0 * Dx * r)
        h_max = min(h_max, 2.0 * r / sq if sq > 0.0 else h_max)
    if h_max <= 0.0:
        return 0.0
    if G1 > 0.0:
        # G ≥ G1 τ + m τ²/2 with m a lower bound of G'' on [0, σ] (|d − d0| ≤ |d'0|σ + Dxσ²/2)
        gn, an = heave_bound(fl, frame)
        w = fl.w
        sigma = h_max
        for _ in range(60):
            amax = min(abs(e0) + abs(d10) * sigma + 0.5 * Dx * sigma * sigma, cap)
            m = -gn - an * w * w - times_or_zero(slope(R, amax), Dx)
            if not math.isfinite(m):
                sigma *= 0.5
                continue
            if G1 + 0.5 * m * sigma > 0.0:
                break
            sigma = min(0.5 * sigma, -G1 / m)
        else:
            sigma = 0.0
    cs = slope(R, e0)
    if G1 >= 0.0 and math.isfinite(cs):
        # c is convex: G ≥ H = (the flight's height) − (floor) + c(d0) + c'(d0)(d(τ) − d0), a
        # flight over a flat floor of gravity gy + c' gx and amplitude Ay + c' Ax
        sigma = rest_step(sigma, frame.gy + cs * frame.gx, frame.Ay + cs * frame.Ax, h_max, fli,
                          fl)
    return min(sigma, h_max)
