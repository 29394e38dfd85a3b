"""Sustained contact on the paper's floor (``slide``, ``coulomb``): when a particle at rest
stays at rest, what a collision that ends a cascade leads to, and one contact step of the
map — a stretch of sliding (bbb.dynamics.slide) and what its event leads to.  The
conveyor's counterpart is :mod:`bbb.dynamics.contact_conveyor`; both return the verdicts
defined there."""

from __future__ import annotations

import math

from numba import njit

from ..surface import floor_v
from .collide import collide
from .contact_conveyor import DONE, HELD, NEXT, STALLED, enter_contact, holds_at_rest, stretch_end
from .events import EV_COLLISION, EV_CONTACT, EV_CONTACT_LIFT, EV_CUSP, EV_STOP, put_row
from .floors import is_flat
from .floors.arc import arc_normal
from .options import Contact, Tally
from .slide import BUDGET, CUSP, END, LIFT, g_eff, slide

__all__ = ["contact_level"]


@njit(cache=True)
def contact_level(st, s0, fl, run, mu, io):
    """One contact step on the paper's floor for a particle held at rest (``stuck``) or
    sliding (angle q, tangential speed vt): a slide to its event and what that leads to.
    Returns (verdict, Contact, Tally) as bbb.dynamics.contact_conveyor.contact_c; HELD: held
    at rest, left to the lift-off.  ``st`` (a Contact), ``fl``, ``run``: bbb.dynamics.options'
    records; s0 (s) the particle's start in its floor period; io = (sample_times, pos, rec)."""
    cell, d, y, vx, vy, s, tp, isamp, stuck, sliding, q, vt, kicked, n_rec = st
    sample_times, pos, rec = io
    g, A, w, R, S = fl.g, fl.A, fl.w, fl.R, fl.S
    T = 2.0 * math.pi / w
    flat = is_flat(R)
    t_max, rec_from, v_stick = run.t_max, run.rec_from, run.v_stick
    if stuck and not holds_at_rest(d, R, S, mu, flat) and g_eff(s, g, A, w) > 0.0:
        # at rest where the contact model cannot hold it (an initial state, or held
        # by N ≤ 0): slide; with g_eff ≤ 0 the floor lets go first (lift-off)
        stuck = False
        sliding = True
        q = d if flat else math.asin(max(-1.0, min(1.0, d / R)))
        vt = 0.0
    if not sliding:
        return HELD, Contact(cell, d, y, vx, vy, s, tp, isamp, stuck, sliding, q, vt, kicked, n_rec), \
            Tally(0, 0, 0, 0.0, 0.0)
    (q, vt, s, tp, cell, isamp), ev, (el, worst) = slide((q, vt, s, tp, cell, isamp), s0, fl,
                                                         None, mu, run, (sample_times, pos))
    if ev == END or ev == BUDGET:
        d = q if flat else R * math.sin(q)
        return DONE if ev == END else STALLED, Contact(cell, d, y, vx, vy, s, tp, isamp, stuck, sliding, q,
                                                       vt, kicked, n_rec), \
            Tally(0, 0, 0, el, worst)
    d, (nx, ny), y, (vx, vy) = stretch_end(q, vt, s, ev, fl, None, flat)
    vf = floor_v(s, A, w)
    t_c = tp * T + (s - s0)
    if ev == LIFT:
        # leave with the normal speed v_stick, as a fly-off in collide(): the
        # flight's start is then certified (G' > 0); adds ≤ v_stick²/2 energy
        vx += v_stick * nx
        vy += v_stick * ny
        n_rec = put_row(rec, n_rec, rec_from, t_c, t_max, cell * S + d, y, vx, vy, s / T,
                        EV_CONTACT_LIFT, True)
        return NEXT, Contact(cell, d, y, vx, vy, s, tp, isamp, stuck, False, q, vt, False, n_rec), \
            Tally(0, 0, 1, el, worst)
    if ev == CUSP:
        return cusp_level(Contact(cell, d, y, vx, vy, s, tp, isamp, stuck, sliding, q, vt, kicked,
                                  n_rec), vf, t_c, fl, run, mu, rec, (el, worst))
    # STOP (Coulomb): v = 0; static friction holds it or it slides back
    held = holds_at_rest(d, R, S, mu, flat)
    n_rec = put_row(rec, n_rec, rec_from, t_c, t_max, cell * S + d, y, 0.0, vf, s / T, EV_STOP,
                    True)
    return NEXT, Contact(cell, d, y, 0.0, vf, s, tp, isamp, held, not held, q, vt, kicked, n_rec), \
        Tally(0, 1 if held else 0, 0, el, worst)


@njit(cache=True, inline="always")
def cusp_level(st, vf, t_c, fl, run, mu, rec, spent):
    # a slide reached a cusp (st: a Contact at it, at time t_c; vf: the floor's velocity;
    # spent: the slide's (time slid, peak step debt)): the neighbouring arc's wall,
    # Eqs. (5)-(6) with its normal
    cell, d, y, vx, vy, s, tp, isamp, stuck, sliding, q, vt, kicked, n_rec = st
    el, worst = spent
    w, R, S = fl.w, fl.R, fl.S
    T = 2.0 * math.pi / w
    t_max, rec_from, v_stick = run.t_max, run.rec_from, run.v_stick
    n_rec = put_row(rec, n_rec, rec_from, t_c, t_max, cell * S + d, y, vx, vy, s / T, EV_CUSP,
                    True)
    side = 1 if d > 0.0 else -1
    cell += side
    d -= side * S
    if el == 0.0:
        # straight back into the cusp: held there by both walls
        n_rec = put_row(rec, n_rec, rec_from, t_c, t_max, cell * S + d, y, 0.0, vf, s / T,
                        EV_COLLISION, False)
        return NEXT, Contact(cell, d, y, 0.0, vf, s, tp, isamp, True, False, q, vt, kicked, n_rec), \
            Tally(0, 1, 0, el, worst)
    vx, vy, un_out, kicked = collide(vx, vy, d, s, fl, None, v_stick, True)
    code = EV_COLLISION
    stuck = False
    sliding = False
    if un_out < v_stick:
        # at rest in the cusp below v_stick: held by both walls (enter_contact)
        vt, q, sliding = enter_contact(vx, vy, d, s, fl, None, mu, v_stick)
        stuck = not sliding
        if sliding:
            nx, ny = arc_normal(d, R)
            vx = vt * ny
            vy = vf - vt * nx
            code = EV_CONTACT
        else:
            vx = 0.0
            vy = vf
    n_rec = put_row(rec, n_rec, rec_from, t_c, t_max, cell * S + d, y, vx, vy, s / T, code,
                    False)
    return NEXT, Contact(cell, d, y, vx, vy, s, tp, isamp, stuck, sliding, q, vt, kicked, n_rec), \
        Tally(1, 1 if stuck else 0, 0, el, worst)
