"""The jitted bouncing-ball-billiard map: free flight, certified collision search,
collision rule, sticking and lift-off.

State of a particle between events: cell index ``cell`` and offset ``d`` (mm, |d| ≤ S/2)
so that x = cell·S + d; height ``y`` (mm); velocity ``vx, vy`` (mm/s); floor time
``s`` (s) within the current period [0, 1/f) and the number of whole periods ``tp``.
Everything here is flat functions over scalars; numba nopython, cache=True, no fastmath.

The collision search never misses a collision: the gap G(τ) = y_particle − y_surface
along a flight is only declared positive on an interval when a rigorous lower bound
(chord minus curvature bound, Taylor bound, or monotone-depth bound) is positive there.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .contact import CUSP, END, LIFT, enter_contact, g_eff, holds_at_rest, slide
from .surface import arc_curvature, arc_depth, arc_normal, arc_slope, floor_a, floor_v, floor_y

NO_COLLISION = -1.0
STACK_DEPTH = 96
# event codes of a 7-column record (bbb.record.EVENT_CODES)
EV_COLLISION = 0.0
EV_CONTACT = 4.0
EV_CONTACT_LIFT = 5.0
EV_STOP = 6.0
EV_CUSP = 7.0


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


@njit(cache=True)
def collide(vx, vy, d, s, g, A, w, R, alpha, beta, v_stick, allow_kick):
    """Eqs. (5)-(6): restitution in the arc's normal/tangential frame, relative to the
    floor velocity.  Returns (vx⁺, vy⁺, outgoing relative normal speed, kicked); a speed
    below ``v_stick`` means the particle sticks."""
    nx, ny = arc_normal(d, R)
    vf = floor_v(s, A, w)
    ux = vx
    uy = vy - vf
    un = ux * nx + uy * ny
    ut = ux * ny - uy * nx
    # |un|: a grazing contact rounded to un ≥ 0 still reflects outward
    un_out = alpha * abs(un)
    ut_out = beta * ut
    if un_out < v_stick:
        # A cascade of ever smaller bounces (which ends in sticking) needs the surface to
        # press on the particle: G'' ≤ 0 at G = G' = 0.  Where the arc falls away faster
        # than gravity and floor pull the particle down (vx² c'' > g + a_f, a fast
        # tangential touch), the particle flies off instead: leave with v_stick.
        # Never twice in a row: in a cusp (R = S/2) the neighbouring wall sends the particle
        # straight back, and repeated kicks would be an endless Zeno sequence.
        g2 = -g - floor_a(s, A, w) + (ut_out * ny) ** 2 * arc_curvature(d, R)
        if allow_kick and g2 > 0.0 and abs(ut_out) >= v_stick:
            return v_stick * nx + ut_out * ny, vf + v_stick * ny - ut_out * nx, v_stick, True
    return un_out * nx + ut_out * ny, vf + un_out * ny - ut_out * nx, un_out, False


@njit(cache=True)
def liftoff_wait(s, A, w, g, retry):
    """Time (s) until a particle stuck to the floor lifts off: the floor must accelerate
    downward faster than g, sin(w s) < -1/Γ.  inf when Γ ≤ 1 (it never lifts off)."""
    gam = A * w * w / g
    if gam <= 1.0:
        return math.inf
    thc = math.asin(1.0 / gam)
    th = w * s
    th_l = math.pi + thc
    if not retry and math.sin(th) < -1.0 / gam:
        return 0.0
    if th < th_l:
        return (th_l - th) / w
    return (th_l + 2.0 * math.pi - th) / w


@njit(cache=True, inline="always")
def wrap_period(s, tp, T):
    # keep the floor time within [0, T): sin of a small argument stays exact for long runs
    if s >= T:
        k = math.floor(s / T)
        s -= k * T
        tp += int(k)
        if s >= T:
            s -= T
            tp += 1
        if s < 0.0:
            s = 0.0
    return s, tp


@njit(cache=True)
def evolve(cell, d, y, vx, vy, s, stuck, from_surface, g, A, w, R, S, alpha, beta,
           t_max, sample_times, pos, rec_from, rec, tol_t, v_stick, h_max_periods,
           stack, counters, friction, times):
    """Run one particle from its initial state to t_max (s, from its own start).

    Writes x at ``sample_times`` into ``pos`` and post-collision (t, x, y, vx, vy, floor phase) at
    t ≥ ``rec_from`` into ``rec`` (rows until full).  A ``rec`` with a 7th column also gets a
    row per lift-off that starts a flight ending in a collision (the state leaving the floor),
    column 6 = 1 for a lift-off, 0 for a collision; under the contact models also the
    contact events (bbb.record.EVENT_CODES).  ``counters`` receives collisions, sticking
    episodes, lift-offs, recorded rows, anomalies; ``times`` the time (s) held at rest and
    the time sliding.  ``friction`` is None for the stick model, else μ (0 for slide): its
    type selects the compiled kernel and numba prunes the branches ``friction is None``
    decides, so the stick kernel has no contact-model code in it."""
    T = 2.0 * math.pi / w
    h_max = h_max_periods * T
    s0 = s
    tp = 0
    isamp = 0
    ns = sample_times.shape[0]
    nrec_max = rec.shape[0]
    n_coll = 0
    n_stick = 0
    n_lift = 0
    n_rec = 0
    n_anom = 0
    lifting = False
    retry = False
    kicked = False
    flat = math.isinf(R)
    t_held = 0.0
    t_slid = 0.0
    sliding = False
    q = 0.0
    vt = 0.0
    while True:
        t_now = tp * T + (s - s0)
        if t_now >= t_max:
            break
        if friction is not None:
            mu = friction
            if stuck and not holds_at_rest(d, R, S, mu, flat) and g_eff(s, g, A, w) > 0.0:
                # at rest where the contact model cannot hold it (an initial state, or held
                # by N ≤ 0): slide; with g_eff ≤ 0 the floor lets go first (lift-off below)
                stuck = False
                sliding = True
                q = d if flat else math.asin(max(-1.0, min(1.0, d / R)))
                vt = 0.0
            if sliding:
                q, vt, s, tp, cell, isamp, ev, el = slide(q, vt, s, tp, s0, T, g, A, w, R, S,
                                                          mu, flat, t_max, sample_times, pos,
                                                          isamp, cell, tol_t)
                t_slid += el
                if ev == END:
                    d = q if flat else R * math.sin(q)
                    break
                if ev == CUSP:
                    d = math.copysign(0.5 * S, q)
                else:
                    d = q if flat else R * math.sin(q)
                nx, ny = arc_normal(d, R)
                vf = floor_v(s, A, w)
                y = floor_y(s, A, w) - arc_depth(d, R)
                vx = vt * ny
                vy = vf - vt * nx
                t_c = tp * T + (s - s0)
                if ev == LIFT:
                    # leave with the normal speed v_stick, as a fly-off in collide(): the
                    # flight's start is then certified (G' > 0); adds ≤ v_stick²/2 energy
                    vx += v_stick * nx
                    vy += v_stick * ny
                    n_rec = put_row(rec, n_rec, rec_from, t_c, t_max, cell * S + d, y, vx, vy,
                                    s / T, EV_CONTACT_LIFT, True)
                    sliding = False
                    from_surface = True
                    lifting = False
                    kicked = False
                    n_lift += 1
                    continue
                if ev == CUSP:
                    n_rec = put_row(rec, n_rec, rec_from, t_c, t_max, cell * S + d, y, vx, vy,
                                    s / T, EV_CUSP, True)
                    # the neighbouring arc's wall: Eqs. (5)-(6) with its normal
                    side = 1 if d > 0.0 else -1
                    cell += side
                    d -= side * S
                    sliding = False
                    if el == 0.0:
                        # straight back into the cusp: held there by both walls
                        stuck = True
                        vx = 0.0
                        vy = vf
                        n_stick += 1
                        n_rec = put_row(rec, n_rec, rec_from, t_c, t_max, cell * S + d, y, vx,
                                        vy, s / T, EV_COLLISION, False)
                        continue
                    vx, vy, un_out, kicked = collide(vx, vy, d, s, g, A, w, R, alpha, beta,
                                                     v_stick, True)
                    n_coll += 1
                    code = EV_COLLISION
                    if un_out < v_stick:
                        vt, q, sliding = enter_contact(vx, vy, d, s, g, A, w, R, S, mu, flat)
                        if abs(vt) < v_stick:
                            sliding = False  # at rest in the cusp: held by both walls
                        if sliding:
                            nx, ny = arc_normal(d, R)
                            vx = vt * ny
                            vy = vf - vt * nx
                            code = EV_CONTACT
                        else:
                            stuck = True
                            vx = 0.0
                            vy = vf
                            n_stick += 1
                    n_rec = put_row(rec, n_rec, rec_from, t_c, t_max, cell * S + d, y, vx, vy,
                                    s / T, code, False)
                    from_surface = True
                    lifting = False
                    continue
                # STOP (Coulomb): v = 0; static friction holds it or it slides back
                vx = 0.0
                vy = vf
                if holds_at_rest(d, R, S, mu, flat):
                    sliding = False
                    stuck = True
                    n_stick += 1
                n_rec = put_row(rec, n_rec, rec_from, t_c, t_max, cell * S + d, y, vx, vy,
                                s / T, EV_STOP, True)
                continue
        if stuck:
            wait = liftoff_wait(s, A, w, g, retry)
            t_lift = t_now + wait
            t_held += min(wait, t_max - t_now)
            xpos = cell * S + d
            while isamp < ns and sample_times[isamp] < t_lift:
                pos[isamp] = xpos
                isamp += 1
            if t_lift >= t_max:
                break
            s, tp = wrap_period(s + wait, tp, T)
            y = floor_y(s, A, w) - arc_depth(d, R)
            vx = 0.0
            vy = floor_v(s, A, w)
            stuck = False
            lifting = True
            from_surface = True
            n_lift += 1
            continue
        tau, j = next_collision(y, vy, vx, d, s, from_surface, lifting, g, A, w, R, S,
                                t_max - t_now, tol_t, h_max, stack)
        if tau == NO_COLLISION:
            x0 = cell * S + d
            while isamp < ns:
                pos[isamp] = x0 + vx * (sample_times[isamp] - t_now)
                isamp += 1
            break
        if lifting and tau == 0.0:
            # the floor did not let go after all (rounding at the edge of the window)
            stuck = True
            retry = True
            n_lift -= 1
            continue
        retry = False
        x0 = cell * S + d
        if lifting and rec.shape[1] > 6 and t_now >= rec_from and n_rec < nrec_max:
            # a 7-column record also keeps lift-offs (event 1): the state the flight starts from
            rec[n_rec, 0] = t_now
            rec[n_rec, 1] = x0
            rec[n_rec, 2] = y
            rec[n_rec, 3] = vx
            rec[n_rec, 4] = vy
            rec[n_rec, 5] = s / T
            rec[n_rec, 6] = 1.0
            n_rec += 1
        t_end = t_now + tau
        while isamp < ns and sample_times[isamp] < t_end:
            pos[isamp] = x0 + vx * (sample_times[isamp] - t_now)
            isamp += 1
        # free flight, Eqs. (1)-(4)
        d = d + vx * tau - j * S
        cell += j
        if flat:
            k = math.floor(d / S + 0.5)
            d -= k * S
            cell += int(k)
        else:
            d = min(max(d, -0.5 * S), 0.5 * S)
        vy = vy - g * tau
        s, tp = wrap_period(s + tau, tp, T)
        # on the surface exactly: the root is known to tol_t, the height to rounding
        y = floor_y(s, A, w) - arc_depth(d, R)
        vx, vy, un_out, kicked = collide(vx, vy, d, s, g, A, w, R, alpha, beta, v_stick, not kicked)
        n_coll += 1
        if not (math.isfinite(vx) and math.isfinite(vy)):
            n_anom += 1
            vx = 0.0
            un_out = 0.0
        code = EV_COLLISION
        if un_out < v_stick:
            if friction is None:
                # creeping cascade cut short: the particle rides with the floor
                stuck = True
                vx = 0.0
                vy = floor_v(s, A, w)
                n_stick += 1
            else:
                # sustained contact: slide on the arc with the tangential speed (or held)
                vt, q, sliding = enter_contact(vx, vy, d, s, g, A, w, R, S, friction, flat)
                vf = floor_v(s, A, w)
                if sliding:
                    nx, ny = arc_normal(d, R)
                    vx = vt * ny
                    vy = vf - vt * nx
                    code = EV_CONTACT
                else:
                    stuck = True
                    vx = 0.0
                    vy = vf
                    n_stick += 1
        t_c = tp * T + (s - s0)
        if t_c >= rec_from and n_rec < nrec_max and t_c < t_max:
            rec[n_rec, 0] = t_c
            rec[n_rec, 1] = cell * S + d
            rec[n_rec, 2] = y
            rec[n_rec, 3] = vx
            rec[n_rec, 4] = vy
            rec[n_rec, 5] = s / T
            if rec.shape[1] > 6:
                rec[n_rec, 6] = code
            n_rec += 1
        from_surface = True
        lifting = False
    while isamp < ns:
        pos[isamp] = cell * S + d
        isamp += 1
    counters[0] = n_coll
    counters[1] = n_stick
    counters[2] = n_lift
    counters[3] = n_rec
    counters[4] = n_anom
    times[0] = t_held
    times[1] = t_slid


@njit(cache=True, inline="always")
def put_row(rec, n_rec, rec_from, t, t_max, x, y, vx, vy, phase, code, event_only):
    # one recorded row; contact events (``event_only``) only in a 7-column record
    if t >= rec_from and n_rec < rec.shape[0] and t < t_max:
        if rec.shape[1] > 6:
            rec[n_rec, 6] = code
        elif event_only:
            return n_rec
        rec[n_rec, 0] = t
        rec[n_rec, 1] = x
        rec[n_rec, 2] = y
        rec[n_rec, 3] = vx
        rec[n_rec, 4] = vy
        rec[n_rec, 5] = phase
        return n_rec + 1
    return n_rec


@njit(cache=True)
def evolve_ensemble(cell, d, y, vx, vy, s, stuck, from_surface, g, A, w, R, S, alpha, beta,
                    t_max, sample_times, pos, rec_from, rec, tol_t, v_stick, h_max_periods,
                    counters, friction, times):
    """Run every particle of an ensemble (arrays of initial states) independently;
    ``friction``: None (stick) or μ (slide: 0, coulomb), see :func:`evolve`."""
    stack = np.empty(STACK_DEPTH)
    for i in range(cell.shape[0]):
        evolve(cell[i], d[i], y[i], vx[i], vy[i], s[i], stuck[i], from_surface[i], g, A, w,
               R, S, alpha, beta, t_max, sample_times, pos[i], rec_from, rec[i], tol_t,
               v_stick, h_max_periods, stack, counters[i], friction, times[i])
