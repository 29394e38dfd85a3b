"""The certified collision search, one driver for both floors (Eqs. 2-4): the first time τ
(s) at which a particle in flight meets the floor, never missing one.

The gap G(τ) = y_particle − y_surface along a flight is only declared positive on an
interval when a rigorous lower bound is positive there; a root is refined by Newton
safeguarded by bisection to ``tol_t``.  The gap and its certificates are
:mod:`bbb.dynamics.bounds`'s; ``frame`` (None: the paper's floor) selects each floor's variant
at compile time.  The paper's floor splits a flight at the
cusps it crosses (one arc per piece); the conveyor's bounds hold across them.  On the level
floor ``R`` is any floor shape (bbb.dynamics.floors: the arc's radius or a shape's record),
whose cells the search crosses one at a time; the conveyor's is the arc's radius.
"""

from __future__ import annotations

import math
from collections import namedtuple

from ..jit import inlined, jitted
from .bounds import curvature_cap, gap, lower_bound, reach, start_step
from .floors import is_flat, valley_depth

NO_COLLISION = -1.0
#: what a search returns instead of τ when its step budget ran out (bbb.dynamics.events)
SEARCH_SPENT = -2.0
STACK_DEPTH = 96


#: a flight as the search sees it: height y (mm), velocity (vx, vy) (mm/s), offset d0 (mm)
#: from the centre of the cell searched, floor time s (s) at τ = 0, sin ωs and the bound Dx
#: (mm/s²) of |d''| (the conveyor's; 0 on the paper's floor), whether it starts at a lift-off
Flight = namedtuple("Flight", "y vy vx d0 s sin_s Dx lifting")


@inlined
def newton_ok(G1, frame):
    # a Newton step from slope G1 is taken (the conveyor's G' is infinite at a vertical wall)
    if frame is None:
        return G1 != 0.0
    return G1 != 0.0 and math.isfinite(G1)


@inlined
def slope_cap(a, b, ea, eb, fli, fl, frame):
    # an upper bound of G'' on [a, b] (ea, eb: gap there): G' < 0 throughout if
    # G'(a) + max(M, 0) (b − a) < 0
    return curvature_cap(ea, eb, reach(b - a, ea, eb, fli, fl, frame), fli, fl, frame)


@jitted
def refine_root(a, b, Ga, Gb, fli, fl, frame, tol_t):
    """Newton safeguarded by bisection on a bracket with G(a) > 0 ≥ G(b)."""
    t = b - Gb * (b - a) / (Gb - Ga) if Ga != Gb else 0.5 * (a + b)
    if not (a < t < b):
        t = 0.5 * (a + b)
    for _ in range(200):
        e = gap(t, fli, fl, frame)
        G, G1 = e.G, e.G1
        if G > 0.0:
            a = t
            Ga = G
        else:
            b = t
            Gb = G
        tn = t
        if newton_ok(G1, frame):
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


@jitted
def search_piece(pa, pb, fli, from_surface, fl, frame, srch, left):
    """(first root of G in [pa, pb] of the Flight ``fli``, or NO_COLLISION if none, and
    ``left`` less the bracketing steps taken); SEARCH_SPENT once ``left`` runs out.
    ``from_surface``: the flight starts on the surface at pa; srch = (tol_t, h_max, stack)."""
    tol_t, h_max, stack = srch
    a = pa
    ea = gap(a, fli, fl, frame)
    if from_surface:
        if pb <= pa:
            # zero-length piece (a cusp at τ = 0): only an approach into this arc counts
            return (a if ea.G1 < 0.0 else NO_COLLISION), left
        sigma = start_step(min(h_max, pb - pa), ea, fli, fl, frame)
        if sigma <= 0.0:
            return a, left
        a = a + sigma
        if a >= pb:
            return NO_COLLISION, left
        ea = gap(a, fli, fl, frame)
        if ea.G <= 0.0:
            # separation below rounding: the particle is back on the surface at a > 0
            return a, left
    elif ea.G <= 0.0:
        return a, left
    n = 0
    h = h_max
    b = min(a + h, pb)
    while True:
        eb = gap(b, fli, fl, frame)
        width = b - a
        if eb.G <= 0.0:
            # unique root when G' < 0 on all of [a, b]: G'(a) + M⁺(b-a) < 0
            M = slope_cap(a, b, ea, eb, fli, fl, frame)
            if ea.G1 + max(M, 0.0) * width < 0.0 or width <= tol_t:
                return refine_root(a, b, ea.G, eb.G, fli, fl, frame, tol_t), left
        else:
            lb = lower_bound(a, b, ea, eb, fli, fl, frame)
            # below tol_t a dip is at most M tol_t²/8 deep: far below rounding of y
            if lb > 0.0 or width <= tol_t:
                a = b
                ea = eb
                if n > 0:
                    n -= 1
                    b = stack[n]
                else:
                    if a >= pb:
                        return NO_COLLISION, left
                    # the step budget pays for each fresh step and each halving (a pop
                    # retraces a halving): integer compares, so that nothing loops here
                    # without end, e.g. on a NaN bracket that halves for ever
                    left -= 1
                    if left < 0:
                        return SEARCH_SPENT, left
                    h = min(2.0 * width, h_max)
                    b = min(a + h, pb)
                continue
        if n < stack.shape[0]:
            stack[n] = b
            n += 1
        left -= 1
        if left < 0:
            return SEARCH_SPENT, left
        b = 0.5 * (a + b)


@inlined
def flight_windows(y, vy, g, top, bottom):
    # the flight's times below the surface's top, (w0a, w0b) and (w1a, w1b) (empty: w1b < 0):
    # above the top no collision is possible, below the bottom one must already have happened
    yb = bottom - 1e-9 * (1.0 + abs(bottom))
    tau_b = (vy + math.sqrt(vy * vy + 2.0 * g * max(y - yb, 0.0))) / g
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
    return w0a, w0b, w1a, w1b


@inlined
def search_cells(wa, wb, fli, from_surface, fl, srch, left):
    """The paper floor's search over [wa, wb] of the Flight ``fli`` (d0: its offset in the
    current cell), one arc at a time: (τ, cell offset j of the arc hit, the step budget left),
    NO_COLLISION if none; each arc costs a step.  fl.R is the floor's shape
    (bbb.dynamics.floors); a flat one is searched in one piece."""
    y, vy, vx, d, s = fli.y, fli.vy, fli.vx, fli.d0, fli.s
    S = fl.S
    if is_flat(fl.R):
        tau, left = search_piece(wa, wb, Flight(y, vy, 0.0, d, s, 0.0, 0.0, fli.lifting),
                                 from_surface and wa == 0.0, fl, None, srch, left)
        return tau, 0, left
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
        left -= 1
        if left < 0:
            return SEARCH_SPENT, 0, left
        if vx > 0.0:
            tc = ((j + 0.5) * S - d) / vx
        elif vx < 0.0:
            tc = ((j - 0.5) * S - d) / vx
        else:
            tc = math.inf
        pb = min(tc, wb)
        start = from_surface and pa == 0.0
        if pb > pa or (start and pb == pa):
            tau, left = search_piece(pa, max(pb, pa),
                                     Flight(y, vy, vx, d - j * S, s, 0.0, 0.0, fli.lifting), start,
                                     fl, None, srch, left)
            if tau != NO_COLLISION:
                return tau, int(j), left
        if tc >= wb:
            break
        pa = max(pa, tc)
        j += 1 if vx > 0.0 else -1
    return NO_COLLISION, 0, left


@jitted
def next_collision(state, from_surface, lifting, fl, frame, tau_limit, srch, left):
    """Time τ (s) of the first collision after the current state = (y, vy, vx, d, s) (a
    flight from the surface if ``from_surface``, from a lift-off if ``lifting``) on the floor
    fl (bbb.dynamics.options.Floor) ``frame`` selects, the cell offset j
    (relative to the current cell) of the arc hit (the conveyor's: 0, its flight's end takes
    the nearest arc) and the step budget ``left`` after the search (bbb.dynamics.events).
    τ = NO_COLLISION if none before ``tau_limit``, SEARCH_SPENT if the budget ran out.
    srch = (tol_t in s, h_max in s, stack): the root tolerance, longest step, bisection stack."""
    y, vy, vx, d, s = state
    w = fl.w
    cmax = valley_depth(fl.R, fl.S)
    if frame is None:
        gn = fl.g
        top = fl.A
        Dx = 0.0
        sin_s = 0.0
    else:
        gn = frame.gy
        top = abs(frame.Ay)
        Dx = abs(frame.gx) + abs(frame.Ax) * w * w
        sin_s = math.sin(w * s)
    fli = Flight(y, vy, vx, d, s, sin_s, Dx, lifting)
    w0a, w0b, w1a, w1b = flight_windows(y, vy, gn, top, -top - cmax)
    for win in range(2):
        wa = w0a if win == 0 else w1a
        wb = min(w0b if win == 0 else w1b, tau_limit)
        if wb < wa or (wb == wa and not (wa == 0.0 and from_surface)):
            continue
        if frame is None:
            tau, j, left = search_cells(wa, wb, fli, from_surface, fl, srch, left)
        else:
            tau, left = search_piece(wa, wb, fli, from_surface and wa == 0.0, fl, frame, srch,
                                     left)
            j = 0
        if tau != NO_COLLISION:
            return tau, j, left
    return NO_COLLISION, 0, left
