"""The jitted bouncing-ball-billiard map: free flight, collision rule (Eqs. 5-6), sticking,
lift-off and the contact phase, around the certified collision search of :mod:`bbb.search`.

State of a particle between events: cell index ``cell`` and offset ``d`` (mm, |d| ≤ S/2)
so that x = cell·S + d; height ``y`` (mm); velocity ``vx, vy`` (mm/s); floor time
``s`` (s) within the current period [0, 1/f) and the number of whole periods ``tp``.
Everything here is flat functions over scalars; numba nopython, cache=True, no fastmath.

The collision search (bbb.search) never misses a collision.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .contact import BUDGET, CUSP, END, LIFT, enter_contact, g_eff, holds_at_rest, slide
from .search import NO_COLLISION, STACK_DEPTH, next_collision
from .surface import arc_curvature, arc_depth, arc_normal, floor_a, floor_v, floor_y

# event codes of a 7-column record (bbb.record.EVENT_CODES)
EV_COLLISION = 0.0
EV_CONTACT = 4.0
EV_CONTACT_LIFT = 5.0
EV_STOP = 6.0
EV_CUSP = 7.0

#: the event guard (no input loops without end): more than EVENT_BUDGET events of a particle
#: within EVENT_WINDOW floor periods stop it, and bbb.simulate raises (margins measured by
#: benchmarks/guards.py).  A particle's status row: why it stopped (STOP_*), the peak step
#: debt of its contact stretches, the most events in one window, the time (s) it stopped
EVENT_WINDOW = 1.0 / 1024.0
EVENT_BUDGET = 2**20
STOP_OK, STOP_STEPS, STOP_EVENTS = 0.0, 1.0, 2.0


@njit(cache=True, inline="always")
def count_event(t_now, t_mark, n_win, win, status):
    # the event guard: (t_mark, n_win) of the window t_now falls in, and whether it is spent
    if t_now - t_mark >= win:
        t_mark = t_now
        n_win = 0
    n_win += 1
    if n_win > status[2]:
        status[2] = n_win
    if n_win > EVENT_BUDGET:
        status[0] = STOP_EVENTS
        status[3] = t_now
        return t_mark, n_win, True
    return t_mark, n_win, False


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
           stack, counters, friction, times, status):
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
    win = EVENT_WINDOW * T
    t_mark = -math.inf
    n_win = 0
    while True:
        t_now = tp * T + (s - s0)
        if t_now >= t_max:
            break
        t_mark, n_win, spent = count_event(t_now, t_mark, n_win, win, status)
        if spent:
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
                q, vt, s, tp, cell, isamp, ev, el, worst = slide(q, vt, s, tp, s0, T, g, A, w, R,
                                                                 S, mu, flat, t_max, sample_times,
                                                                 pos, isamp, cell, tol_t, None)
                t_slid += el
                status[1] = max(status[1], worst)
                if ev == END or ev == BUDGET:
                    d = q if flat else R * math.sin(q)
                    if ev == BUDGET:
                        status[0] = STOP_STEPS
                        status[3] = tp * T + (s - s0)
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
                    counters, friction, times, status):
    """Run every particle of an ensemble (arrays of initial states) independently;
    ``friction``: None (stick) or μ (slide: 0, coulomb), ``status`` one row of 4 per
    particle, see :func:`evolve`."""
    stack = np.empty(STACK_DEPTH)
    for i in range(cell.shape[0]):
        evolve(cell[i], d[i], y[i], vx[i], vy[i], s[i], stuck[i], from_surface[i], g, A, w,
               R, S, alpha, beta, t_max, sample_times, pos[i], rec_from, rec[i], tol_t,
               v_stick, h_max_periods, stack, counters[i], friction, times[i], status[i])
