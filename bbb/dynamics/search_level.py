"""The certified collision search of the paper's floor (Eqs. 2-4): the first time τ (s) at
which a particle in flight meets the vibrating arcs, never missing one.

The gap G(τ) = y_particle − y_surface along a flight is only declared positive on an
interval when a rigorous lower bound (chord minus curvature bound, Taylor bound, or
monotone-depth bound) is positive there; a root is refined by bisection to ``tol_t``.
Used by :mod:`bbb.dynamics.evolve` on the paper's floor; the conveyor's bounds are
:mod:`bbb.dynamics.search_conveyor`'s.
"""

from __future__ import annotations

import math

from numba import njit

from ..surface import arc_curvature, arc_depth, arc_slope, floor_a

NO_COLLISION = -1.0
STACK_DEPTH = 96


@njit(cache=True, inline="always")
def gap(tau, y, vy, s, dj, vx, g, A, w, R, half_s):
    # Eq. (2) against the floor of Sec. 2: G and dG/dτ at flight time τ in the cell dj refers to
    dd = min(max(dj + vx * tau, -half_s), half_s)
    ph = w * (s + tau)
    G = y + vy * tau - 0.5 * g * tau * tau + A * math.sin(ph) + arc_depth(dd, R)
    G1 = vy - g * tau + A * w * math.cos(ph)
    if vx != 0.0:
        G1 += arc_slope(dd, R) * vx
    return G, G1


@njit(cache=True, inline="always")
def curvature_bound(da, db, vx, g, A, w, R):
    # upper bound of G'' = -g + Aw² sin + vx² c''(d) on a sub-interval of one cell
    m = -g + A * w * w
    if vx != 0.0:
        m += vx * vx * arc_curvature(max(abs(da), abs(db)), R)
    return m


@njit(cache=True)
def lower_bound(h, Ga, G1a, Gb, da, db, vx, g, A, w, R):
    """Rigorous lower bound of G on [a, a+h] inside one cell (no cusp crossed)."""
    # chord minus curvature: G ≥ min(Ga, Gb) - M⁺h²/8
    M = curvature_bound(da, db, vx, g, A, w, R)
    lb = min(Ga, Gb) - max(M, 0.0) * h * h * 0.125
    # Taylor from a with G'' ≥ -g - Aw² (c'' ≥ 0): a concave quadratic, minimal at the ends
    q = Ga + G1a * h - 0.5 * (g + A * w * w) * h * h
    lb = max(lb, min(Ga, q))
    # depth bounded below by its minimum over [da, db]; the rest has bounded curvature.
    # Handles the vertical cusps of R = S/2, where the curvature bound is infinite.
    if vx != 0.0:
        ca = arc_depth(da, R)
        cb = arc_depth(db, R)
        cmin = 0.0 if da * db <= 0.0 else min(ca, cb)
        mf = max(-g + A * w * w, 0.0)
        lb = max(lb, min(Ga - ca, Gb - cb) - mf * h * h * 0.125 + cmin)
    return lb


@njit(cache=True)
def refine_root(a, b, Ga, Gb, y, vy, s, dj, vx, g, A, w, R, half_s, tol_t):
    """Newton safeguarded by bisection on a bracket with G(a) > 0 ≥ G(b)."""
    t = b - Gb * (b - a) / (Gb - Ga) if Ga != Gb else 0.5 * (a + b)
    if not (a < t < b):
        t = 0.5 * (a + b)
    for _ in range(200):
        G, G1 = gap(t, y, vy, s, dj, vx, g, A, w, R, half_s)
        if G > 0.0:
            a = t
            Ga = G
        else:
            b = t
            Gb = G
        if G1 != 0.0:
            tn = t - G / G1
            # a converged Newton step is accurate to O(step²): stop only on those
            if a <= tn <= b and abs(tn - t) <= tol_t:
                return tn
        if b - a <= tol_t:
            break
        if not (G1 != 0.0 and a < tn < b):
            tn = 0.5 * (a + b)
        t = tn
    # bracket below tol_t without a Newton step inside it: secant, O(width²) accurate
    t = b - Gb * (b - a) / (Gb - Ga) if Ga != Gb else b
    return min(max(t, a), b)


@njit(cache=True)
def start_step(h_max, G1, vx, s, g, A, w, lifting):
    """A flight step σ > 0 on which G > 0, for a flight that starts on the surface (G(0) = 0).

    Returns 0 when no positive step is certified (the particle does not separate)."""
    sigma = 0.0
    if G1 > 0.0:
        # G ≥ G1 σ - (g + Aw²) σ²/2 > 0 for σ < 2 G1/(g + Aw²); take half of that
        sigma = G1 / (g + A * w * w)
    if vx == 0.0 and G1 >= 0.0:
        # vertical flight over a fixed point: Taylor to 4th order with |y_f''''| ≤ Aw⁴
        G2 = -g - floor_a(s, A, w)
        if lifting:
            # lift-off is timed where G'' ≥ 0; drop rounding below it (sinks ≤ ε T²/2 with ε
            # the rounding of G'', ≲ 1e-14 mm: docs/physics.md, "Why the lift-off step may clamp")
            G2 = max(G2, 0.0)
        if G2 >= 0.0:
            G3 = -A * w * w * w * math.cos(w * s)
            K = A * w * w * w * w
            tr = h_max
            for _ in range(80):
                if 0.5 * G2 + G3 * tr / 6.0 - K * tr * tr / 24.0 > 0.0:
                    sigma = max(sigma, tr)
                    break
                tr *= 0.5
    return min(sigma, h_max)


@njit(cache=True)
def search_piece(pa, pb, dj, y, vy, s, vx, g, A, w, R, half_s, from_surface, lifting,
                 tol_t, h_max, stack):
    """First root of G in [pa, pb], one cell (offset dj at τ=0); NO_COLLISION if none."""
    a = pa
    Ga, G1a = gap(a, y, vy, s, dj, vx, g, A, w, R, half_s)
    if from_surface:
        if pb <= pa:
            # zero-length piece (a cusp at τ = 0): only an approach into this arc counts
            return a if G1a < 0.0 else NO_COLLISION
        sigma = start_step(min(h_max, pb - pa), G1a, vx, s, g, A, w, lifting)
        if sigma <= 0.0:
            return a
        a = a + sigma
        if a >= pb:
            return NO_COLLISION
        Ga, G1a = gap(a, y, vy, s, dj, vx, g, A, w, R, half_s)
        if Ga <= 0.0:
            # separation below rounding: the particle is back on the surface at a > 0
            return a
    elif Ga <= 0.0:
        return a
    n = 0
    h = h_max
    b = min(a + h, pb)
    while True:
        Gb, G1b = gap(b, y, vy, s, dj, vx, g, A, w, R, half_s)
        width = b - a
        if Gb <= 0.0:
            # unique root when G' < 0 on all of [a, b]: G'(a) + M⁺(b-a) < 0
            M = curvature_bound(dj + vx * a, dj + vx * b, vx, g, A, w, R)
            if G1a + max(M, 0.0) * width < 0.0 or width <= tol_t:
                return refine_root(a, b, Ga, Gb, y, vy, s, dj, vx, g, A, w, R, half_s, tol_t)
        else:
            lb = lower_bound(width, Ga, G1a, Gb, dj + vx * a, dj + vx * b, vx, g, A, w, R)
            # below tol_t a dip is at most M tol_t²/8 deep: far below rounding of y
            if lb > 0.0 or width <= tol_t:
                a = b
                Ga = Gb
                G1a = G1b
                if n > 0:
                    n -= 1
                    b = stack[n]
                else:
                    if a >= pb:
                        return NO_COLLISION
                    h = min(2.0 * width, h_max)
                    b = min(a + h, pb)
                continue
        if n < stack.shape[0]:
            stack[n] = b
            n += 1
        b = 0.5 * (a + b)


@njit(cache=True)
def next_collision(y, vy, vx, d, s, from_surface, lifting, g, A, w, R, S, tau_limit,
                   tol_t, h_max, stack):
    """Time τ (s) of the first collision after the current state, and the cell offset j
    (relative to the current cell) of the arc hit.  τ = NO_COLLISION if none before
    ``tau_limit``."""
    half_s = 0.5 * S
    cmax = arc_depth(half_s, R)
    top = A
    bottom = -A - cmax
    # below the lowest point of the surface the particle must already have collided
    yb = bottom - 1e-9 * (1.0 + abs(bottom))
    tau_b = (vy + math.sqrt(vy * vy + 2.0 * g * max(y - yb, 0.0))) / g
    # above the highest point of the surface no collision is possible: skip that arc
    w0a = 0.0
    w0b = tau_b
    w1a = 0.0
    w1b = -1.0
    if y > top:
        w0a = (vy + math.sqrt(vy * vy + 2.0 * g * (y - top))) / g
    else:
        disc = vy * vy - 2.0 * g * (top - y)
        if vy > 0.0 and disc > 0.0:
            sq = math.sqrt(disc)
            w0b = 2.0 * (top - y) / (vy + sq)
            w1a = (vy + sq) / g
            w1b = tau_b
    flat = math.isinf(R)
    for win in range(2):
        wa = w0a if win == 0 else w1a
        wb = min(w0b if win == 0 else w1b, tau_limit)
        if wb < wa or (wb == wa and not (wa == 0.0 and from_surface)):
            continue
        if flat:
            tau = search_piece(wa, wb, d, y, vy, s, 0.0, g, A, w, R, half_s,
                               from_surface and wa == 0.0, lifting, tol_t, h_max, stack)
            if tau != NO_COLLISION:
                return tau, 0
            continue
        xr = d + vx * wa
        if vx > 0.0:
            j = math.floor(xr / S + 0.5)
        elif vx < 0.0:
            j = math.ceil(xr / S - 0.5)
        else:
            # a vertical flight stays over its own arc (|d| ≤ S/2): at a cusp, d = ±S/2 keeps
            # the arc it is on, so mirrored states hit mirrored arcs (floor(d/S + ½) would not)
            j = 0
        pa = wa
        while True:
            if vx > 0.0:
                tc = ((j + 0.5) * S - d) / vx
            elif vx < 0.0:
                tc = ((j - 0.5) * S - d) / vx
            else:
                tc = math.inf
            pb = min(tc, wb)
            start = from_surface and pa == 0.0
            if pb > pa or (start and pb == pa):
                tau = search_piece(pa, max(pb, pa), d - j * S, y, vy, s, vx, g, A, w, R,
                                   half_s, start, lifting, tol_t, h_max, stack)
                if tau != NO_COLLISION:
                    return tau, int(j)
            if tc >= wb:
                break
            pa = max(pa, tc)
            j += 1 if vx > 0.0 else -1
    return NO_COLLISION, 0
