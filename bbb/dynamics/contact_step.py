"""Sustained contact (``slide``, ``coulomb``), one contact step of the map for both floors: a
particle held at rest until static friction lets go (bbb.dynamics.static_friction) or the
floor does (the caller's lift-off), a stretch of sliding (bbb.dynamics.slide) and what its
event leads to — a lift-off, a cusp (the neighbouring arc's wall, Eqs. 5-6), or a stop.
Also the contact start after a collision that ends a bouncing cascade (enter_contact).

``frame`` None is the paper's floor, pruned at compile time as in the rest of the kernel: a
particle at rest there stays at rest or slides from rest at once (holding depends on where it
rests only), positions are cell·S + d and the floor moves along y only; on the conveyor (a
Frame) it is carried with the floor until static friction lets go of it, and the lab's x
adds the floor's displacement.  Each floor keeps the expressions its bits were made with.
"""

from __future__ import annotations

import math

from ..jit import inlined, jitted
from .bounds import cusp_side
from .collide import collide, floor_velocity_at
from .events import EV_COLLISION, EV_CONTACT, EV_CONTACT_LIFT, EV_CUSP, EV_STOP, Row, put_row, wrap_period
from .floors import is_flat, normal
from .floors.arc import arc_normal
from .liftoff import liftoff_wait
from .motion import fill_carried, lab_x, on_arc_velocity, surface_y
from .options import Contact, Tally
from .slide import BUDGET, CUSP, END, LIFT, Stretch, g_eff, normal_force, slide, tangential_force
from .static_friction import held_at_rest, holds_at_rest, in_cusp, slip_wait

__all__ = ["DONE", "HELD", "NEXT", "STALLED", "contact_step", "enter_contact"]

# a contact step's verdicts for bbb.dynamics.evolve's loop
NEXT = 0  # the state changed: loop again
DONE = 1  # t_max reached while sliding
HELD = 2  # held at rest until lift-off: the stuck branch (bbb.dynamics.evolve) takes over
STALLED = 3  # bbb.dynamics.slide's step budget ran out: the particle stops (bbb.simulate raises)


@jitted
def enter_contact(vx, vy, d, s, fl, frame, mu, v_stick):
    """After a collision that ended a bouncing cascade (outgoing normal speed < v_stick), on
    the floor ``frame`` selects (None: the paper's): the tangential speed v (mm/s) relative to
    the floor, the contact angle θ (d on a flat floor), and whether the particle slides (else
    it is held at rest: N ≤ 0, i.e. it can only leave when the floor lets go, or at rest
    where static friction holds it).  In a cusp a tangential speed below v_stick (mm/s) is
    rest there, held by both walls, whichever wall the collision met: the exact model
    rattles up a wall between the two walls, ever closer to the cusp (an inelastic collapse,
    ~1e-14 mm, ~1e-9 s: below what x resolves); its limit is rest in the cusp, as after a
    cusp event (on the conveyor the cusp's rule, static_friction.slip_wait, then decides
    which wall it may slide up — not the arc it last hit)."""
    R = fl.R
    flat = is_flat(R)
    nx, ny = normal(R, d)
    vfx, vfy = floor_velocity_at(s, fl.w, fl, frame)
    v = (vx - vfx) * ny - (vy - vfy) * nx
    q = d if flat else math.asin(nx)
    if normal_force(q, v, s, fl, frame) <= 0.0:
        return v, q, False
    if not flat and abs(v) < v_stick and in_cusp(d, R, fl.S, frame):
        return 0.0, q, False
    if v == 0.0 and held_at_rest(d, s, fl, frame, mu, flat):
        return v, q, False
    return v, q, True


@inlined
def stretch_end(q, vt, s, ev, fl, frame, flat):
    # the state at the end of a slide (bbb.dynamics.slide: angle q, tangential speed vt, at
    # floor time s, event ev) on the floor ``frame`` selects: (d, (nx, ny), y, (vx, vy)), the
    # offset d (mm; the cusp point at a CUSP event), the normal, the height (mm) and the
    # velocity (mm/s), carried along the floor's motion
    R = fl.R
    if ev == CUSP:
        d = math.copysign(0.5 * fl.S, q)
    else:
        d = q if flat else R * math.sin(q)
    nx, ny = normal(R, d)
    vfx, vfy = floor_velocity_at(s, fl.w, fl, frame)
    return d, (nx, ny), surface_y(s, d, fl.A, fl.w, R, frame), on_arc_velocity(vt, nx, ny, vfx,
                                                                                 vfy, frame)


@inlined
def kick_kept(kicked, frame):
    # whether the last collision's kick still counts after a contact step: kept on the paper's
    # floor, forgotten on the conveyor (each floor as its bits were made)
    if frame is None:
        return kicked
    return False


@inlined
def slide_from_rest(st, q, frame):
    # st (a Contact) set sliding from rest at angle q
    return Contact(st.cell, st.d, st.y, st.vx, st.vy, st.s, st.tp, st.isamp, False, True, q, 0.0,
                   kick_kept(st.kicked, frame), st.n_rec)


@jitted
def leave_rest(st, s0, fl, run, frame, mu, retry, samples):
    """A particle held at rest (st: a Contact, stuck): (whether it slides before the floor lets
    go of it, the Contact it slides from, the direction it starts in: ±1, or 0 for the pull's
    sign).  On the paper's floor it slides at once unless it is held (static_friction's
    holds_at_rest) or the floor is about to let go (g_eff ≤ 0: lift-off first).  On the
    conveyor it is carried with the floor (its positions written into samples = (sample_times,
    pos)) until static friction lets go, unless the floor lets go first (retry: a let-go was
    just tried and failed, bbb.dynamics.liftoff.liftoff_wait) or the run ends."""
    cell, d, s, tp, isamp = st.cell, st.d, st.s, st.tp, st.isamp
    R, S = fl.R, fl.S
    flat = is_flat(R)
    if frame is None:
        if holds_at_rest(d, R, S, mu, flat) or not g_eff(s, fl.g, fl.A, fl.w) > 0.0:
            return False, st, 0.0
        return True, slide_from_rest(st, d if flat else math.asin(max(-1.0, min(1.0, d / R))),
                                     frame), 0.0
    sample_times, pos = samples
    w = fl.w
    T = 2.0 * math.pi / w
    t_now = tp * T + (s - s0)
    # held at rest until the lift-off the stuck branch would take (in a cusp: both arcs let
    # go), unless static friction lets go first
    t_n = liftoff_wait(s, d, fl, frame, retry)
    t_f, wall = slip_wait(d, s, fl, frame, mu, flat)
    # at least tol_t held: a particle sent straight back into a cusp (at a slip's edge)
    # must not loop without time passing; a slip within tol_t of the floor's letting go
    # is the lift-off (where the effective gravity vanishes, throw = 90° − tilt, every
    # load reaches 0 at once and the two waits differ by rounding)
    t_f = max(t_f, run.tol_t)
    if not t_f < t_n - run.tol_t or t_f >= run.t_max - t_now:
        return False, st, 0.0
    # carried with the floor until static friction lets go
    isamp = fill_carried((sample_times, pos), isamp, t_now + t_f, cell * S + d, s, t_now, w, frame)
    s, tp = wrap_period(s + t_f, tp, T)
    start_dir = 0.0
    side = 0 if flat else cusp_side(d, R, S)
    if side != 0:
        # in a cusp it rests at the cusp point (CUSP_REACH): it slides from there, up its
        # own arc or the neighbour's (moving x by ≤ CUSP_REACH·S; from where it lay, up the
        # neighbour's wall would start on that circle beyond its arc, under the floor),
        # towards that arc's centre
        d = side * 0.5 * S
        if wall != 0:
            cell += wall
            d -= wall * S
        start_dir = -1.0 if d > 0.0 else 1.0
    q = d if flat else math.asin(max(-1.0, min(1.0, d / R)))
    if side == 0:
        # the way the pull points just after the slip: at it |F_t| = μN, ~0 for a tiny μN,
        # where rounding would pick the sign (T·2⁻²⁰ on, the pull's sign is its own)
        ft = tangential_force(q, s + T * 2.0**-20, fl, frame)
        start_dir = 1.0 if ft > 0.0 else -1.0
    return True, Contact(cell, d, st.y, st.vx, st.vy, s, tp, isamp, False, True, q, 0.0, False,
                         st.n_rec), start_dir


@jitted
def contact_step(st, s0, fl, run, frame, mu, retry, io):
    """One step of sustained contact (module doc) for a particle held at rest (``stuck``) or
    sliding (angle q, tangential speed vt relative to the floor): a slip from rest, a stretch
    of sliding to its event, and what that event leads to.  Returns (verdict, Contact, Tally)
    with the verdict NEXT, DONE, HELD (the floor lets go first: not moved, left to the
    caller's lift-off) or STALLED (the step budget of bbb.dynamics.slide ran out); on the
    conveyor, for the rest of the time the call moved the clock the particle was held.
    ``st`` (a Contact), ``fl``, ``run``, ``frame``: bbb.dynamics.options' records; s0 (s) the
    particle's start in its floor period; mu the friction coefficient (0: slide); ``retry``:
    the floor's let-go at st.s was just tried and failed; io = (sample_times, pos, rec)."""
    sample_times, pos, rec = io
    w, R, S = fl.w, fl.R, fl.S
    T = 2.0 * math.pi / w
    flat = is_flat(R)
    start_dir = 0.0
    if st.stuck:
        moved, st, start_dir = leave_rest(st, s0, fl, run, frame, mu, retry, (sample_times, pos))
        if not moved:
            return HELD, Contact(st.cell, st.d, st.y, st.vx, st.vy, st.s, st.tp, st.isamp, True, False,
                                 st.q, st.vt, kick_kept(st.kicked, frame), st.n_rec), \
                Tally(0, 0, 0, 0.0, 0.0)
    cell, n_rec, kicked = st.cell, st.n_rec, kick_kept(st.kicked, frame)
    (q, vt, s, tp, cell, isamp), ev, (el, worst) = slide(Stretch(st.q, st.vt, st.s, st.tp, cell,
                                                                 st.isamp), s0, fl, frame, mu, run,
                                                         (sample_times, pos), start_dir)
    d, (nx, ny), y, (vx, vy) = stretch_end(q, vt, s, ev, fl, frame, flat)
    if ev == END or ev == BUDGET:
        return DONE if ev == END else STALLED, Contact(cell, d, y, vx, vy, s, tp, isamp, False, True, q, vt,
                                                       kicked, n_rec), \
            Tally(0, 0, 0, el, worst)
    t_c = tp * T + (s - s0)
    if ev == LIFT:
        # leave with the normal speed v_stick, as a fly-off in collide(): the flight's start
        # is then certified (G' > 0); adds ≤ v_stick²/2 energy
        vx += run.v_stick * nx
        vy += run.v_stick * ny
        n_rec = put_row(rec, n_rec, run, Row(t_c, lab_x(cell, d, s, S, w, frame), y, vx, vy, s / T),
                        EV_CONTACT_LIFT, True)
        return NEXT, Contact(cell, d, y, vx, vy, s, tp, isamp, False, False, q, vt, False, n_rec), \
            Tally(0, 0, 1, el, worst)
    if ev == CUSP:
        n_rec = put_row(rec, n_rec, run, Row(t_c, lab_x(cell, d, s, S, w, frame), y, vx, vy, s / T),
                        EV_CUSP, True)
        return cusp_met(Contact(cell, d, y, vx, vy, s, tp, isamp, False, True, q, vt, kicked, n_rec),
                        t_c, fl, run, frame, mu, rec, (el, worst))
    # STOP (Coulomb): at rest relative to the floor; static friction holds it or it slides on
    vx, vy = floor_velocity_at(s, w, fl, frame)
    held = held_at_rest(d, s, fl, frame, mu, flat)
    n_rec = put_row(rec, n_rec, run, Row(t_c, lab_x(cell, d, s, S, w, frame), y, vx, vy, s / T),
                    EV_STOP, True)
    return NEXT, Contact(cell, d, y, vx, vy, s, tp, isamp, held, not held, q, 0.0, kicked, n_rec), \
        Tally(0, 1 if held else 0, 0, el, worst)


@inlined
def cusp_met(st, t_c, fl, run, frame, mu, rec, spent):
    # a slide reached a cusp (st: a Contact at the cusp point, at time t_c; spent: the slide's
    # (time slid, peak step debt)): the neighbouring arc's wall, Eqs. (5)-(6) with its normal
    cell, d, y, vx, vy, s, tp, isamp, _, _, q, vt, kicked, n_rec = st
    el, worst = spent
    w, S = fl.w, fl.S
    T = 2.0 * math.pi / w
    v_stick = run.v_stick
    side = 1 if d > 0.0 else -1
    cell += side
    d -= side * S
    held = el == 0.0  # straight back into the cusp: held there by both walls
    n_coll = 0
    sliding = False
    if not held:
        vx, vy, un_out, kicked = collide(vx, vy, d, s, fl, frame, v_stick, True)
        n_coll = 1
        if un_out < v_stick:
            # at rest in the cusp below v_stick: held by both walls (enter_contact)
            vt, q, sliding = enter_contact(vx, vy, d, s, fl, frame, mu, v_stick)
            held = not sliding or abs(vt) < v_stick
            sliding = not held
    code = EV_COLLISION
    if sliding:
        nx, ny = arc_normal(d, fl.R)
        vfx, vfy = floor_velocity_at(s, w, fl, frame)
        vx, vy = on_arc_velocity(vt, nx, ny, vfx, vfy, frame)
        code = EV_CONTACT
    elif held:
        vx, vy = floor_velocity_at(s, w, fl, frame)
    n_rec = put_row(rec, n_rec, run, Row(t_c, lab_x(cell, d, s, S, w, frame), y, vx, vy, s / T), code,
                    False)
    return NEXT, Contact(cell, d, y, vx, vy, s, tp, isamp, held, sliding, q, vt, kicked, n_rec), \
        Tally(n_coll, 1 if held else 0, 0, el, worst)
