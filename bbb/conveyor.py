"""The jitted map on a conveyor: a floor tilted by φ whose vibration is thrown at ψ to its plane.

Used by :func:`bbb.simulate` only for a scene with ``tilt`` ≠ 0 or ``throw`` ≠ 90°; the
paper's floor (φ = 0, ψ = 90°) runs the unchanged :mod:`bbb.kernel`, so default scenes keep
their code, speed and bits.  docs/physics.md, "Transport", derives what follows.

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

The collision search over this gap lives in :mod:`bbb.conveyor_search`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .conveyor_contact import DONE, HELD, STALLED, collide_c, contact_c, enter_contact_c
from .conveyor_search import cusp_side, next_collision_c, round_half_away
from .kernel import EV_CONTACT, EVENT_WINDOW, STOP_STEPS, count_event, wrap_period
from .search import NO_COLLISION, STACK_DEPTH
from .surface import arc_depth, arc_normal

__all__ = ["evolve_ensemble_c"]


@njit(cache=True, inline="always")
def normal_load(nx, ny, gx, gy, Ax, Ay, w):
    # the normal force per unit mass that carries a particle with the floor, n·(a_floor +
    # (gx, gy)) = k sin ωs + gn (mm/s²): returns (k, gn)
    return (nx * Ax + ny * Ay) * w * w, nx * gx + ny * gy


@njit(cache=True)
def letgo_delay(th, k, gn, w):
    """Time (s) from the phase th (rad) until k sin θ + gn next turns negative (a downward
    crossing, 0 if at th); inf if it never is negative, −1 if it is at all but isolated θ."""
    if k == 0.0:
        return -1.0 if gn < 0.0 else math.inf
    c = -gn / abs(k)
    if c <= -1.0:
        return math.inf
    if c >= 1.0:
        return -1.0
    if k < 0.0:
        th += math.pi
    th = th % (2.0 * math.pi)
    th_l = math.pi - math.asin(c)
    if th <= th_l:
        return (th_l - th) / w
    return (th_l + 2.0 * math.pi - th) / w


@njit(cache=True)
def liftoff_wait_c(s, d, gx, gy, Ax, Ay, w, R, S, retry):
    """Time (s) until a particle carried by the floor at offset d lifts off: the normal
    contact force per unit mass, n·(a_floor + (gx, gy)) = An ω² sin ωs + gn, turns negative
    (An, gn: the floor amplitude and gravity along the arc's normal n).  inf if never.
    In a cusp (bbb.conveyor_search.cusp_side) both arcs must let go."""
    side = cusp_side(d, R, S)
    if side != 0:
        return liftoff_wait_cusp(s, d, side, gx, gy, Ax, Ay, w, R, S, retry)
    nx, ny = arc_normal(d, R)
    k, gn = normal_load(nx, ny, gx, gy, Ax, Ay, w)
    T = 2.0 * math.pi / w
    if k == 0.0:
        if gn < 0.0:
            return T if retry else 0.0
        return math.inf
    c = -gn / abs(k)
    if c <= -1.0:
        return math.inf
    sn = math.sin(w * s) if k > 0.0 else -math.sin(w * s)
    if not retry and sn < c:
        return 0.0
    if c >= 1.0:
        return T * 0.25  # lifting everywhere but at one phase: after a failed try, move on
    th = w * s if k > 0.0 else w * s + math.pi
    if th >= 2.0 * math.pi:
        th -= 2.0 * math.pi
    th_l = math.pi - math.asin(c)
    if th < th_l:
        return (th_l - th) / w
    return (th_l + 2.0 * math.pi - th) / w


@njit(cache=True)
def liftoff_wait_cusp(s, d, side, gx, gy, Ax, Ay, w, R, S, retry):
    """liftoff_wait_c in a cusp: the first time both arcs' normal loads are negative (the
    particle's free motion relative to the floor then leaves both), inf if never.  A vertical
    cusp (R = S/2: horizontal normals) lets go only of a load with no sideways part."""
    T = 2.0 * math.pi / w
    n1x, n1y = arc_normal(d, R)
    n2x, n2y = arc_normal(d - side * S, R)
    k1, g1 = normal_load(n1x, n1y, gx, gy, Ax, Ay, w)
    k2, g2 = normal_load(n2x, n2y, gx, gy, Ax, Ay, w)
    if n1y == 0.0 or n2y == 0.0:
        if Ax != 0.0 or gx != 0.0:
            return math.inf  # pressed on one wall at all but isolated phases: held for good
        k1, g1 = Ay * w * w, gy
        k2, g2 = k1, g1
    th = w * s
    if not retry and k1 * math.sin(th) + g1 < 0.0 and k2 * math.sin(th) + g2 < 0.0:
        return 0.0
    e1 = letgo_delay(th, k1, g1, w)
    e2 = letgo_delay(th, k2, g2, w)
    if e1 == math.inf or e2 == math.inf:
        return math.inf
    if e1 < 0.0 and e2 < 0.0:
        return T * 0.25  # both let go at all but isolated phases, a try failed: move on
    best = math.inf
    for i in range(2):
        e, kb, gb, eb = (e1, k2, g2, e2) if i == 0 else (e2, k1, g1, e1)
        if e < 0.0:
            continue  # never turns negative: it is; the other's turn is the candidate
        if e == 0.0 and retry:
            e = T
        ok = eb < 0.0
        if not ok:
            # the other arc's load at this turn: negative, or turning at the same phase
            thc = th + w * e
            fb = kb * math.sin(thc) + gb
            tol = 64.0 * 2.220446049250313e-16 * (abs(kb) + abs(gb))
            ok = fb < -tol or (fb <= tol and kb * math.cos(thc) < 0.0)
        if ok:
            best = min(best, e)
    return best


@njit(cache=True, inline="always")
def wall_met(cell, d, vx, vy, s, Ax, Ay, w, R, S):
    """(cell, d, met) of the wall a collision at offset d meets: at a cusp (within CUSP_REACH)
    the one the particle approaches, relative normal speed < 0 — the nearest arc by rounding
    may be the one it leaves (a rattle down a steep cusp: Eq. (5) took |u⊥| on the wrong
    wall); met is False where it leaves both walls there: the root found was the gap's
    rounding at the cusp point (a bounce 4e-16 mm short of it 'hit' the neighbour 2e-16 s later,
    again and again), not a collision."""
    side = cusp_side(d, R, S)
    if side == 0:
        return cell, d, True
    cw = w * math.cos(w * s)
    ux = vx + Ax * cw
    uy = vy + Ay * cw
    nx, ny = arc_normal(d, R)
    mx, my = arc_normal(d - side * S, R)
    own = ux * nx + uy * ny
    other = ux * mx + uy * my
    if own >= 0.0 and other < 0.0:
        return cell + side, d - side * S, True
    return cell, d, own < 0.0 or other < 0.0


@njit(cache=True)
def evolve_c(cell, d, y, vx, vy, s, stuck, from_surface, g, A, w, R, S, alpha, beta, tilt,
             throw, t_max, sample_times, pos, rec_from, rec, tol_t, v_stick, h_max_periods,
             stack, counters, friction, times, status):
    """bbb.kernel.evolve on the conveyor (angles ``tilt``, ``throw`` in degrees).  Positions
    and recorded x are the lab's, along the floor's plane: cell·S + d + X_f.  ``friction``:
    None (stick) or μ (slide: 0, coulomb), compile-time specialised as in bbb.kernel.evolve;
    sustained contact is bbb.conveyor_contact's.  ``times`` receives the time (s) held at
    rest relative to the floor and the time sliding, ``status`` the guards' verdict, as
    bbb.kernel.evolve's."""
    gx = g * math.sin(math.radians(tilt))
    gy = g * math.cos(math.radians(tilt))
    # from ψ − 90° so that ψ → 180° − ψ flips Ax's sign bit-exactly and ψ = 90 gives Ay = A
    dev = math.radians(throw - 90.0)
    Ax = -A * math.sin(dev)
    Ay = A * math.cos(dev)
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
    sliding = False
    q = 0.0
    vt = 0.0
    t_held = 0.0
    t_slid = 0.0
    if stuck:
        vx = -Ax * w * math.cos(w * s)
        vy = -Ay * w * math.cos(w * s)
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
        if friction is not None and (stuck or sliding):
            was_held = stuck
            # held at rest until the lift-off the stuck branch below would take (in a cusp:
            # both arcs let go), unless static friction lets go first
            t_n = liftoff_wait_c(s, d, gx, gy, Ax, Ay, w, R, S, retry) if stuck else 0.0
            verdict, cell, d, y, vx, vy, s, tp, isamp, stuck, sliding, q, vt, kicked, n_rec, \
                dc, ds, dl, el, worst = contact_c(cell, d, s, tp, s0, T, isamp, stuck, t_n, q, vt,
                                                  gx, gy, Ax, Ay, w, R, S, alpha, beta, friction,
                                                  flat, t_max, sample_times, pos, rec_from, rec,
                                                  n_rec, tol_t, v_stick)
            status[1] = max(status[1], worst)
            n_coll += dc
            n_stick += ds
            n_lift += dl
            # the call moved the clock by el of sliding, after a hold until friction let go
            # if it began held (a call that began sliding holds nothing: no rounding residue)
            t_slid += el
            if was_held:
                t_held += min(tp * T + (s - s0), t_max) - t_now - el
            if verdict == DONE:
                break
            if verdict == STALLED:
                status[0] = STOP_STEPS
                status[3] = tp * T + (s - s0)
                break
            if verdict != HELD:
                from_surface = True
                lifting = False
                continue
        if stuck:
            wait = liftoff_wait_c(s, d, gx, gy, Ax, Ay, w, R, S, retry)
            t_lift = t_now + wait
            t_held += min(wait, t_max - t_now)
            base = cell * S + d
            while isamp < ns and sample_times[isamp] < t_lift:
                pos[isamp] = base - Ax * math.sin(w * (s + (sample_times[isamp] - t_now)))
                isamp += 1
            if t_lift >= t_max:
                break
            s, tp = wrap_period(s + wait, tp, T)
            y = -Ay * math.sin(w * s) - arc_depth(d, R)
            vx = -Ax * w * math.cos(w * s)
            vy = -Ay * w * math.cos(w * s)
            stuck = False
            lifting = True
            from_surface = True
            n_lift += 1
            continue
        tau = next_collision_c(y, vy, vx, d, s, from_surface, lifting, gx, gy, Ax, Ay, w, R, S,
                               t_max - t_now, tol_t, h_max, stack)
        x0 = cell * S + d - Ax * math.sin(w * s)
        if tau == NO_COLLISION:
            while isamp < ns:
                dt = sample_times[isamp] - t_now
                pos[isamp] = x0 + vx * dt - 0.5 * gx * dt * dt
                isamp += 1
            break
        if lifting and tau == 0.0:
            stuck = True
            retry = True
            n_lift -= 1
            continue
        retry = False
        if lifting and rec.shape[1] > 6 and t_now >= rec_from and n_rec < nrec_max:
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
            dt = sample_times[isamp] - t_now
            pos[isamp] = x0 + vx * dt - 0.5 * gx * dt * dt
            isamp += 1
        # the flight (module doc): offset relative to the floor, then the nearest arc
        d = d + vx * tau - 0.5 * gx * tau * tau + Ax * (math.sin(w * (s + tau)) - math.sin(w * s))
        k = round_half_away(d / S)
        d -= k * S
        cell += int(k)
        d = min(max(d, -0.5 * S), 0.5 * S)
        vx = vx - gx * tau
        vy = vy - gy * tau
        s, tp = wrap_period(s + tau, tp, T)
        cell, d, met = wall_met(cell, d, vx, vy, s, Ax, Ay, w, R, S)
        y = -Ay * math.sin(w * s) - arc_depth(d, R)
        if not met:
            # leaving both walls of a cusp: no collision, the flight goes on from here
            from_surface = True
            lifting = False
            continue
        vx, vy, un_out, kicked = collide_c(vx, vy, d, s, gx, gy, Ax, Ay, w, R, alpha, beta,
                                           v_stick, not kicked)
        n_coll += 1
        if not (math.isfinite(vx) and math.isfinite(vy)):
            n_anom += 1
            vx = 0.0
            un_out = 0.0
        if un_out < v_stick:
            stuck = True
            if friction is not None:
                # sustained contact: slide with the tangential speed, or held
                vt, q, sliding = enter_contact_c(vx, vy, d, s, gx, gy, Ax, Ay, w, R, S, friction,
                                                 flat, v_stick)
                stuck = not sliding
            if stuck:
                # 'stick': carried with the floor (x fixed relative to it), whatever the tilt
                vx = -Ax * w * math.cos(w * s)
                vy = -Ay * w * math.cos(w * s)
                n_stick += 1
            else:
                nx, ny = arc_normal(d, R)
                vx = -Ax * w * math.cos(w * s) + vt * ny
                vy = -Ay * w * math.cos(w * s) - vt * nx
        t_c = tp * T + (s - s0)
        if t_c >= rec_from and n_rec < nrec_max and t_c < t_max:
            rec[n_rec, 0] = t_c
            rec[n_rec, 1] = cell * S + d - Ax * math.sin(w * s)
            rec[n_rec, 2] = y
            rec[n_rec, 3] = vx
            rec[n_rec, 4] = vy
            rec[n_rec, 5] = s / T
            if rec.shape[1] > 6:
                rec[n_rec, 6] = EV_CONTACT if sliding else 0.0
            n_rec += 1
        from_surface = True
        lifting = False
    base = cell * S + d
    t_now = tp * T + (s - s0)
    while isamp < ns:
        # stuck to the end: carried with the floor
        pos[isamp] = base - Ax * math.sin(w * (s + (sample_times[isamp] - t_now)))
        isamp += 1
    counters[0] = n_coll
    counters[1] = n_stick
    counters[2] = n_lift
    counters[3] = n_rec
    counters[4] = n_anom
    times[0] = t_held
    times[1] = t_slid


@njit(cache=True)
def evolve_ensemble_c(cell, d, y, vx, vy, s, stuck, from_surface, g, A, w, R, S, alpha, beta,
                      tilt, throw, t_max, sample_times, pos, rec_from, rec, tol_t, v_stick,
                      h_max_periods, counters, friction, times, status):
    """Run every particle of an ensemble independently on the conveyor; ``friction``,
    ``times`` and ``status`` (one row per particle) as in :func:`evolve_c`."""
    stack = np.empty(STACK_DEPTH)
    for i in range(cell.shape[0]):
        evolve_c(cell[i], d[i], y[i], vx[i], vy[i], s[i], stuck[i], from_surface[i], g, A, w,
                 R, S, alpha, beta, tilt, throw, t_max, sample_times, pos[i], rec_from, rec[i],
                 tol_t, v_stick, h_max_periods, stack, counters[i], friction, times[i], status[i])


