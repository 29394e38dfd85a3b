"""What both floors' maps share: event codes, the event guard, the floor clock, recorded
rows, position samples and the counters a run hands back."""

from __future__ import annotations

import math
from collections import namedtuple

from ..jit import inlined

#: one recorded row: time t (s), position x (mm, the lab's), height y (mm), velocity (vx, vy)
#: (mm/s) and the floor's phase (in periods); its event code travels beside it
Row = namedtuple("Row", "t x y vx vy phase")

# event codes of a 7-column record (bbb.record.EVENT_CODES)
EV_COLLISION = 0.0
EV_LIFTOFF = 1.0
EV_CONTACT = 4.0
EV_CONTACT_LIFT = 5.0
EV_STOP = 6.0
EV_CUSP = 7.0

#: the event guard (no input loops without end): more than EVENT_BUDGET events of a particle
#: within EVENT_WINDOW floor periods stop it, and bbb.simulate raises (margins measured by
#: benchmarks/calibrations/guards.py).  A particle's status row: why it stopped (STOP_*), the peak step
#: debt of its contact stretches, the most events in one window, the time (s) it stopped
EVENT_WINDOW = 1.0 / 1024.0
EVENT_BUDGET = 2**20
STOP_OK, STOP_STEPS, STOP_EVENTS, STOP_SEARCH = 0.0, 1.0, 2.0, 3.0
#: the search budget (no input loops without end, not even within one collision search): a
#: particle holds at most SEARCH_BURST search steps (fresh bracketing steps, halvings, arcs crossed;
#: bbb.dynamics.search), earns SEARCH_RATE more per floor period of its simulated time, and
#: pays one per step; a particle that runs out stops, and bbb.simulate raises.  So a call
#: takes at most SEARCH_BURST + SEARCH_RATE · f·t_max search steps per particle, and a search
#: that makes no progress in time stops after SEARCH_BURST steps (~0.5 s).  Status column
#: 4 holds the deepest a particle drew on it (margins measured by benchmarks/calibrations/guards.py)
SEARCH_BURST = 2**22
SEARCH_RATE = 2**16


@inlined
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


@inlined
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


@inlined
def row_due(rec, n_rec, rec_from, t, t_max, event_only):
    # whether a row at time t is recorded; contact events (``event_only``) only in a 7-column
    # record.  The hot path asks first, so that a row's ingredients are computed only when due
    return (t >= rec_from and n_rec < rec.shape[0] and t < t_max
            and (rec.shape[1] > 6 or not event_only))


@inlined
def write_row(rec, n_rec, row, code):
    # one recorded row (a Row; the event code in a 7-column record); returns the rows now written
    if rec.shape[1] > 6:
        rec[n_rec, 6] = code
    rec[n_rec, 0] = row.t
    rec[n_rec, 1] = row.x
    rec[n_rec, 2] = row.y
    rec[n_rec, 3] = row.vx
    rec[n_rec, 4] = row.vy
    rec[n_rec, 5] = row.phase
    return n_rec + 1


@inlined
def put_row(rec, n_rec, run, row, code, event_only):
    # one recorded row (a Row) if it is due (row_due; run: bbb.dynamics.options.Run)
    if row_due(rec, n_rec, run.rec_from, row.t, run.t_max, event_only):
        return write_row(rec, n_rec, row, code)
    return n_rec


@inlined
def write_counters(counters, times, counts, held_slid):
    # a particle's counters (bbb.record.COUNTER_NAMES: counts = (collisions, sticking episodes,
    # lift-offs, recorded rows, anomalies)) and contact times (CONTACT_TIME_NAMES: held_slid =
    # (time held at rest, time sliding), s)
    n_coll, n_stick, n_lift, n_rec, n_anom = counts
    counters[0] = n_coll
    counters[1] = n_stick
    counters[2] = n_lift
    counters[3] = n_rec
    counters[4] = n_anom
    times[0] = held_slid[0]
    times[1] = held_slid[1]
