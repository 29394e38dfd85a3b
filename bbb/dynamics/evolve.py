"""The jitted bouncing-ball-billiard map, one for both floors: free flight, collision rule
(Eqs. 5-6), sticking, lift-off and the contact phase, around the certified collision search.

State of a particle between events: cell index ``cell`` and offset ``d`` (mm, |d| ≤ S/2)
so that x = cell·S + d (on the conveyor d is relative to the moving floor); height ``y``
(mm); velocity ``vx, vy`` (mm/s); floor time ``s`` (s) within the current period [0, 1/f)
and the number of whole periods ``tp``.  Options come as the records of
:mod:`bbb.dynamics.options`; ``frame`` (None: the paper's floor) and ``friction`` (None: the
stick model) are compile-time choices, each pruned by numba where it is None.  Everything
is flat functions over scalars, compiled as bbb.jit says (nopython, cached, no fastmath).

The collision search (bbb.dynamics.search) never misses a collision.
"""

from __future__ import annotations

import math

import numpy as np

from ..jit import allocating, jitted
from .collide import collide, wall_met
from .contact_step import DONE, HELD, STALLED, contact_step, enter_contact
from .events import (
    EV_COLLISION,
    EV_CONTACT,
    EV_LIFTOFF,
    EVENT_WINDOW,
    SEARCH_BURST,
    SEARCH_RATE,
    STOP_SEARCH,
    STOP_STEPS,
    Row,
    count_event,
    row_due,
    wrap_period,
    write_counters,
    write_row,
)
from .floors import normal
from .liftoff import liftoff_wait
from .motion import fill_carried, fill_flight, floor_velocity, fly, lab_x, on_arc_velocity, surface_y
from .options import Contact
from .search import SEARCH_SPENT, STACK_DEPTH, next_collision

__all__ = ["evolve", "evolve_ensemble"]


@jitted
def evolve(init, fl, run, frame, friction, sample_times, out, stack):
    """Run one particle from its initial state ``init`` = (cell, d, y, vx, vy, s, stuck,
    from_surface) (module doc) to run.t_max (s, from its own start).

    ``out`` = (pos, rec, counters, times, status).  Writes x at ``sample_times`` into ``pos``
    (the lab's x along the floor's plane on the conveyor, cell·S + d + X_f) and
    post-collision (t, x, y, vx, vy, floor phase) at t ≥ ``run.rec_from`` into ``rec`` (rows
    until full).  A ``rec`` with a 7th column also gets a row per lift-off that starts a
    flight ending in a collision (the state leaving the floor), column 6 = 1 for a lift-off,
    0 for a collision; under the contact models also the contact events
    (bbb.record.EVENT_CODES).  ``counters`` receives collisions, sticking episodes,
    lift-offs, recorded rows, anomalies; ``times`` the time (s) held at rest relative to the
    floor and the time sliding; ``status`` the guards' verdict (bbb.dynamics.events; a 5th
    column, if there is one, gets the deepest draw on the search budget).
    ``friction`` is None for the stick model, else μ (0 for slide); ``frame`` None for the
    paper's floor, else the conveyor's Frame; ``fl.R`` is the floor's shape
    (bbb.dynamics.floors: the arc's radius, or a sine's or sawtooth's record, level floor and
    stick model only): their types select the compiled kernel."""
    cell, d, y, vx, vy, s, stuck, from_surface = init
    pos, rec, counters, times, status = out
    g, A, w, R, S, alpha, beta = fl
    t_max, rec_from, tol_t, v_stick, h_max_periods = run
    T = 2.0 * math.pi / w
    h_max = h_max_periods * T
    s0 = s
    tp = 0
    isamp = 0
    n_coll = 0
    n_stick = 0
    n_lift = 0
    n_rec = 0
    n_anom = 0
    lifting = False
    retry = False
    kicked = False
    t_held = 0.0
    t_slid = 0.0
    sliding = False
    q = 0.0
    vt = 0.0
    if frame is not None:
        if stuck:
            vx, vy = floor_velocity(s, A, w, frame)
    win = EVENT_WINDOW * T
    t_mark = -math.inf
    n_win = 0
    # the search budget (bbb.dynamics.events): integers, topped up once per floor period
    credit = SEARCH_BURST
    low = SEARCH_BURST
    tp_paid = 0
    while True:
        t_now = tp * T + (s - s0)
        if t_now >= t_max:
            break
        t_mark, n_win, spent = count_event(t_now, t_mark, n_win, win, status)
        if spent:
            break
        if friction is not None:
            if stuck or sliding:
                was_held = stuck
                verdict, st, tally = contact_step(
                    Contact(cell, d, y, vx, vy, s, tp, isamp, stuck, sliding, q, vt, kicked, n_rec),
                    s0, fl, run, frame, friction, retry, (sample_times, pos, rec))
                cell, d, y, vx, vy, s, tp, isamp, stuck, sliding, q, vt, kicked, n_rec = st
                dc, ds, dl, el, worst = tally
                status[1] = max(status[1], worst)
                n_coll += dc
                n_stick += ds
                n_lift += dl
                t_slid += el
                if frame is not None:
                    # the call moved the clock by el of sliding, after a hold until friction
                    # let go if it began held
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
            wait = liftoff_wait(s, d, fl, frame, retry)
            t_lift = t_now + wait
            t_held += min(wait, t_max - t_now)
            isamp = fill_carried((sample_times, pos), isamp, t_lift, cell * S + d, s, t_now, w,
                                 frame)
            if t_lift >= t_max:
                break
            s, tp = wrap_period(s + wait, tp, T)
            y = surface_y(s, d, A, w, R, frame)
            vx, vy = floor_velocity(s, A, w, frame)
            stuck = False
            lifting = True
            from_surface = True
            n_lift += 1
            continue
        if tp > tp_paid:
            if tp - tp_paid >= SEARCH_BURST // SEARCH_RATE:
                credit = SEARCH_BURST
            else:
                credit = min(SEARCH_BURST, credit + SEARCH_RATE * (tp - tp_paid))
            tp_paid = tp
        tau, j, credit = next_collision((y, vy, vx, d, s), from_surface, lifting, fl, frame,
                                        t_max - t_now, (tol_t, h_max, stack), credit)
        low = min(low, credit)
        x0 = lab_x(cell, d, s, S, w, frame)
        if tau < 0.0:
            # NO_COLLISION (the flight outlasts the run) or SEARCH_SPENT (the budget ran out)
            if tau == SEARCH_SPENT:
                status[0] = STOP_SEARCH
                status[3] = t_now
                break
            isamp = fill_flight((sample_times, pos), isamp, math.inf, x0, vx, t_now, frame)
            break
        if lifting and tau == 0.0:
            # the floor did not let go after all (rounding at the edge of the window)
            stuck = True
            retry = True
            n_lift -= 1
            continue
        retry = False
        if lifting and row_due(rec, n_rec, rec_from, t_now, t_max, True):
            # a 7-column record also keeps lift-offs (event 1): the state the flight starts from
            n_rec = write_row(rec, n_rec, Row(t_now, x0, y, vx, vy, s / T), EV_LIFTOFF)
        isamp = fill_flight((sample_times, pos), isamp, t_now + tau, x0, vx, t_now, frame)
        # free flight, Eqs. (1)-(4)
        cell, d, vx, vy = fly((cell, d, vx, vy, s), tau, j, fl, frame)
        s, tp = wrap_period(s + tau, tp, T)
        met = True
        if frame is not None:
            cell, d, met = wall_met(cell, d, vx, vy, s, fl, frame)
        # on the surface exactly: the root is known to tol_t, the height to rounding
        y = surface_y(s, d, A, w, R, frame)
        if not met:
            # leaving both walls of a cusp: no collision, the flight goes on from here
            from_surface = True
            lifting = False
            continue
        vx, vy, un_out, kicked = collide(vx, vy, d, s, fl, frame, v_stick, not kicked)
        n_coll += 1
        if not (math.isfinite(vx) and math.isfinite(vy)):
            n_anom += 1
            vx = 0.0
            un_out = 0.0
        code = EV_COLLISION
        if un_out < v_stick:
            # the cascade ends: held with the floor (stick), or sustained contact
            stuck = True
            if friction is not None:
                vt, q, sliding = enter_contact(vx, vy, d, s, fl, frame, friction, v_stick)
                stuck = not sliding
            vfx, vfy = floor_velocity(s, A, w, frame)
            if stuck:
                vx = vfx
                vy = vfy
                n_stick += 1
            else:
                nx, ny = normal(R, d)
                vx, vy = on_arc_velocity(vt, nx, ny, vfx, vfy, frame)
                code = EV_CONTACT
        t_c = tp * T + (s - s0)
        if row_due(rec, n_rec, rec_from, t_c, t_max, False):
            n_rec = write_row(rec, n_rec, Row(t_c, lab_x(cell, d, s, S, w, frame), y, vx, vy, s / T),
                              code)
        from_surface = True
        lifting = False
    if status.shape[0] > 4:
        status[4] = SEARCH_BURST - low
    fill_carried((sample_times, pos), isamp, math.inf, cell * S + d, s, tp * T + (s - s0), w,
                 frame)
    write_counters(counters, times, (n_coll, n_stick, n_lift, n_rec, n_anom), (t_held, t_slid))


@allocating
def evolve_ensemble(init, fl, run, frame, friction, sample_times, out):
    """Run every particle of an ensemble independently: ``init`` = arrays (cell, d, y, vx, vy,
    s, stuck, from_surface) of initial states, ``out`` = (pos, rec, counters, times, status)
    with one row per particle, see :func:`evolve`."""
    cell, d, y, vx, vy, s, stuck, from_surface = init
    pos, rec, counters, times, status = out
    stack = np.empty(STACK_DEPTH)
    for i in range(cell.shape[0]):
        evolve((cell[i], d[i], y[i], vx[i], vy[i], s[i], stuck[i], from_surface[i]), fl, run, frame,
               friction, sample_times, (pos[i], rec[i], counters[i], times[i], status[i]), stack)
