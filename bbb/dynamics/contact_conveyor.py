"""Where a particle touches the conveyor's floor: the collision rule (Eqs. 5-6 relative to the
moving floor) and, under the ``slide`` and ``coulomb`` contact models, sustained contact.

Frame and symbols as in :mod:`bbb.dynamics.bounds_conveyor`: floor coordinates, gravity (−gx, −gy), floor
displacement (Ax, Ay)(−sin ωt).  In the floor's frame a particle in contact feels the
effective gravity −(Gx, Gy) with Gx = gx + Ax ω² sin ωs, Gy = gy + Ay ω² sin ωs (mm/s²).  On
its arc, at angle θ from the top (normal n = (sin θ, cos θ), tangent (cos θ, −sin θ)):

    R θ̈ = Gy sin θ − Gx cos θ − μ N sgn(v),     N = Gx sin θ + Gy cos θ − v²/R

(flat floor: d̈ = −Gx − μ Gy sgn(v), N = Gy).  :func:`bbb.dynamics.slide.slide` integrates it with
its certified event location, given the frame.  At rest, friction holds the particle
while |F_t| ≤ μN with F_t = Gy sin θ − Gx cos θ.  In a cusp (within CUSP_REACH of it, where the
floor lets go only when both arcs do) it slides up a wall only where that wall presses, N > 0,
and pulls it up the wall by more than μN; a wall with N ≤ 0 does not touch it (before
2026-11-25 that case counted too: a 'slip' up a wall that had let go, then at once a lift-off
off it while the other wall still pressed — the checker's contact_start flags of the conveyor
hypothesis test).  F_t and N are affine in u = sin ωs, so where static friction holds is an
interval of u on one arc and the complement of two intervals in a cusp;
:func:`slip_wait_c` finds when the floor's phase first leaves it.
"""

from __future__ import annotations

import math

from numba import njit

from .bounds import cusp_side
from .collide import collide, floor_velocity_at
from .events import EV_COLLISION, EV_CONTACT, EV_CONTACT_LIFT, EV_CUSP, EV_STOP, put_row, wrap_period
from .floors import is_flat, normal
from .floors.arc import arc_normal
from .motion import on_arc_velocity, surface_y
from .options import Contact, Tally
from .slide import BUDGET, CUSP, END, LIFT, normal_force, slide, tangential_force

# a contact step's verdicts for bbb.dynamics.evolve's loop (contact_c, bbb.dynamics.contact_level)
NEXT = 0  # the state changed: loop again
DONE = 1  # t_max reached while sliding
HELD = 2  # held at rest until lift-off: the stuck branch (bbb.dynamics.evolve) takes over
STALLED = 3  # bbb.dynamics.slide's step budget ran out: the particle stops (bbb.simulate raises)
TWO_PI = 2.0 * math.pi


@njit(cache=True, inline="always")
def forces_at_rest(nx, ny, frame, w):
    """(F_t, dF_t/du, N, dN/du) (mm/s²) at rest where the normal is (nx, ny), u = sin ωs."""
    gx, gy, Ax, Ay = frame
    w2 = w * w
    return gy * nx - gx * ny, (Ay * nx - Ax * ny) * w2, gx * nx + gy * ny, (Ax * nx + Ay * ny) * w2


@njit(cache=True, inline="always")
def cut(lo, hi, c, k):
    # intersect [lo, hi] with {u : c + k u ≤ 0}
    if k > 0.0:
        return lo, min(hi, -c / k)
    if k < 0.0:
        return max(lo, -c / k), hi
    if c > 0.0:
        return math.inf, -math.inf
    return lo, hi


@njit(cache=True)
def hold_interval(d, fl, frame, mu):
    """The interval [lo, hi] of u = sin ωs in which static friction holds a particle at rest
    on one arc at offset d, |F_t| ≤ μN (empty: lo > hi; N ≥ |F_t|/μ ≥ 0 there)."""
    nx, ny = arc_normal(d, fl.R)
    ft, ftu, n, nu = forces_at_rest(nx, ny, frame, fl.w)
    lo, hi = cut(-math.inf, math.inf, ft - mu * n, ftu - mu * nu)
    return cut(lo, hi, -ft - mu * n, -ftu - mu * nu)


@njit(cache=True, inline="always")
def above(lo, hi, c, k):
    # intersect (lo, hi) with {u : c + k u > 0}
    if k > 0.0:
        return max(lo, -c / k), hi
    if k < 0.0:
        return lo, min(hi, -c / k)
    if c > 0.0:
        return lo, hi
    return math.inf, -math.inf


@njit(cache=True)
def wall_slip(nx, ny, up, frame, w, mu):
    """The open interval (lo, hi) of u = sin ωs in which a particle at rest in a cusp slides
    up the wall of normal (nx, ny) (``up`` = ±1: the x direction up that wall, away from the
    cusp): the wall presses, N > 0, and the pull up it beats friction, up·F_t > μN.  A wall
    with N ≤ 0 does not touch the particle: it cannot slide on it."""
    ft, ftu, n, nu = forces_at_rest(nx, ny, frame, w)
    lo, hi = above(-math.inf, math.inf, n, nu)
    return above(lo, hi, up * ft - mu * n, up * ftu - mu * nu)


@njit(cache=True)
def exit_wait(s, w, lo, hi):
    """Time (s) until u = sin ω(s+τ) first leaves [lo, hi]: 0 if outside now, inf if never."""
    u0 = math.sin(w * s)
    if not (lo <= u0 <= hi):
        return 0.0
    ph0 = w * s
    best = math.inf
    if hi < 1.0:  # sin rises through hi at asin(hi)
        r = (math.asin(hi) - ph0) % TWO_PI
        best = min(best, 0.0 if r > TWO_PI - 1e-9 else r / w)
    if lo > -1.0:  # and falls through lo at π − asin(lo)
        r = (math.pi - math.asin(lo) - ph0) % TWO_PI
        best = min(best, 0.0 if r > TWO_PI - 1e-9 else r / w)
    return best


@njit(cache=True)
def enter_wait(s, w, lo, hi):
    """Time (s) until u = sin ω(s+τ) first lies in the open (lo, hi): 0 if it does now, inf
    if never.  An interval narrower than 16 ε is empty: its ends are one boundary rounded two
    ways (throw = 90° − tilt: the effective gravity and with it every load of both walls
    vanishes at one phase, and a wall's N and pull change sign together)."""
    if not hi - lo > 16.0 * 2.220446049250313e-16 or lo >= 1.0 or hi <= -1.0:
        return math.inf
    u0 = math.sin(w * s)
    if lo < u0 < hi:
        return 0.0
    ph0 = w * s
    best = math.inf
    if lo >= -1.0:  # sin rises through lo at asin(lo)
        r = (math.asin(lo) - ph0) % TWO_PI
        best = min(best, 0.0 if r > TWO_PI - 1e-9 else r / w)
    if hi <= 1.0:  # and falls through hi at π − asin(hi)
        r = (math.pi - math.asin(hi) - ph0) % TWO_PI
        best = min(best, 0.0 if r > TWO_PI - 1e-9 else r / w)
    return best


@njit(cache=True)
def slip_wait_c(d, s, fl, frame, mu, flat):
    """(time in s until static friction lets go of a particle at rest at offset d from floor
    time s, the wall it then slides on: 0 its own arc, ±1 the neighbour on that side).

    On one arc: until |F_t| > μN (which includes N turning ≤ 0: the caller compares with the
    floor's letting go).  In a cusp (within CUSP_REACH, bbb.dynamics.bounds_conveyor.cusp_side: where
    the floor lets go only when both arcs do) it slides up the wall whose pull beats friction
    while that wall presses (wall_slip); the two cannot hold at once (up both walls the pull
    would have to point into both, N < 0 on each)."""
    w, R, S = fl.w, fl.R, fl.S
    side = 0 if flat else cusp_side(d, R, S)
    if side == 0:
        lo, hi = hold_interval(d, fl, frame, mu)
        return exit_wait(s, w, lo, hi), 0
    # up this arc is away from the cusp (−side), up the neighbour's is +side
    nx, ny = arc_normal(d, R)
    lo, hi = wall_slip(nx, ny, -float(side), frame, w, mu)
    t_own = enter_wait(s, w, lo, hi)
    nx, ny = arc_normal(d - side * S, R)
    lo, hi = wall_slip(nx, ny, float(side), frame, w, mu)
    t_other = enter_wait(s, w, lo, hi)
    if t_other < t_own:
        return t_other, side
    return t_own, 0


@njit(cache=True)
def holds_at_rest(d, R, S, mu, flat):
    """Whether a particle at rest at offset d stays at rest while g_eff > 0: on a flat
    floor, in a cusp (held by both walls), at an arc's top, or where static friction
    holds it, |g_eff sin θ| ≤ μ N = μ g_eff cos θ, i.e. |tan θ| ≤ μ."""
    if flat or d == 0.0 or abs(d) >= 0.5 * S:
        return True
    nx, ny = arc_normal(d, R)
    return abs(nx) <= mu * ny


@njit(cache=True, inline="always")
def held_at_rest(d, s, fl, frame, mu, flat):
    # whether a particle at rest relative to the floor at offset d stays at rest now: on the
    # paper's floor holds_at_rest, on the conveyor until static friction lets go (slip_wait_c)
    if frame is None:
        return holds_at_rest(d, fl.R, fl.S, mu, flat)
    return slip_wait_c(d, s, fl, frame, mu, flat)[0] > 0.0


@njit(cache=True, inline="always")
def in_cusp(d, R, S, frame):
    # at a cusp, where both walls hold a particle: exactly there on the paper's floor,
    # within CUSP_REACH on the conveyor (bbb.dynamics.bounds_conveyor.cusp_side)
    if frame is None:
        return abs(d) >= 0.5 * S
    return cusp_side(d, R, S) != 0


@njit(cache=True)
def enter_contact(vx, vy, d, s, fl, frame, mu, v_stick):
    """After a collision that ended a bouncing cascade (outgoing normal speed < v_stick), on
    the floor ``frame`` selects (None: the paper's): the tangential speed v (mm/s) relative to
    the floor, the contact angle θ (d on a flat floor), and whether the particle slides (else
    it is held at rest: N ≤ 0, i.e. it can only leave when the floor lets go, or at rest
    where static friction holds it).  In a cusp a tangential speed below v_stick (mm/s) is
    rest there, held by both walls, whichever wall the collision met: the exact model
    rattles up a wall between the two walls, ever closer to the cusp (an inelastic collapse,
    ~1e-14 mm, ~1e-9 s: below what x resolves); its limit is rest in the cusp, as after a
    cusp event (on the conveyor the cusp's rule, slip_wait_c, then decides which wall it may
    slide up — not the arc it last hit)."""
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


@njit(cache=True, inline="always")
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


@njit(cache=True)
def contact_c(st, s0, t_n, fl, run, frame, mu, io):
    """One step of sustained contact on the conveyor (module doc) for a particle held at rest
    (``stuck``; the floor lets go of it after t_n s, bbb.dynamics.liftoff.liftoff_wait: in a cusp
    when both arcs do) or sliding (angle q, tangential speed vt relative to the floor): a
    slip, a stretch of sliding to its event, or what that event leads to.  Returns (verdict,
    Contact, Tally) with the verdict NEXT, DONE, HELD (lift-off first: not moved) or STALLED
    (the step budget of bbb.dynamics.slide ran out); for the rest of the time the call moved
    the clock the particle was held.  ``st`` (a Contact; its y, vx, vy, sliding and kicked are
    not read), ``fl``, ``run``, ``frame``: bbb.dynamics.options' records; s0 (s) the
    particle's start in its floor period; io = (sample_times, pos, rec)."""
    cell, d, _, _, _, s, tp, isamp, stuck, _, q, vt, _, n_rec = st
    sample_times, pos, rec = io
    gx, gy, Ax, Ay = frame
    w, R, S = fl.w, fl.R, fl.S
    T = 2.0 * math.pi / w
    flat = is_flat(R)
    t_max, rec_from, tol_t, v_stick = run.t_max, run.rec_from, run.tol_t, run.v_stick
    ns = sample_times.shape[0]
    t_now = tp * T + (s - s0)
    start_dir = 0.0
    if stuck:
        t_f, wall = slip_wait_c(d, s, fl, frame, mu, flat)
        # at least tol_t held: a particle sent straight back into a cusp (at a slip's edge)
        # must not loop without time passing; a slip within tol_t of the floor's letting go
        # is the lift-off (where the effective gravity vanishes, throw = 90° − tilt, every
        # load reaches 0 at once and the two waits differ by rounding)
        t_f = max(t_f, tol_t)
        if not t_f < t_n - tol_t or t_f >= t_max - t_now:
            return HELD, Contact(cell, d, 0.0, 0.0, 0.0, s, tp, isamp, True, False, q, vt, False, n_rec), \
                Tally(0, 0, 0, 0.0, 0.0)
        # carried with the floor until static friction lets go
        base = cell * S + d
        while isamp < ns and sample_times[isamp] < t_now + t_f:
            pos[isamp] = base - Ax * math.sin(w * (s + (sample_times[isamp] - t_now)))
            isamp += 1
        s, tp = wrap_period(s + t_f, tp, T)
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
        vt = 0.0
    (q, vt, s, tp, cell, isamp), ev, (el, worst) = slide((q, vt, s, tp, cell, isamp), s0, fl,
                                                         frame, mu, run, (sample_times, pos),
                                                         start_dir)
    d, (nx, ny), y, (vx, vy) = stretch_end(q, vt, s, ev, fl, frame, flat)
    cw = w * math.cos(w * s)
    if ev == END or ev == BUDGET:
        return DONE if ev == END else STALLED, Contact(cell, d, y, vx, vy, s, tp, isamp, False, True, q, vt,
                                                       False, n_rec), \
            Tally(0, 0, 0, el, worst)
    t_c = tp * T + (s - s0)
    xl = cell * S + d - Ax * math.sin(w * s)
    if ev == LIFT:
        # leave with the normal speed v_stick, as on the paper's floor (contact_level)
        vx += v_stick * nx
        vy += v_stick * ny
        n_rec = put_row(rec, n_rec, rec_from, t_c, t_max, xl, y, vx, vy, s / T,
                        EV_CONTACT_LIFT, True)
        return NEXT, Contact(cell, d, y, vx, vy, s, tp, isamp, False, False, q, vt, False, n_rec), \
            Tally(0, 0, 1, el, worst)
    if ev == CUSP:
        n_rec = put_row(rec, n_rec, rec_from, t_c, t_max, xl, y, vx, vy, s / T, EV_CUSP, True)
        # the neighbouring arc's wall: Eqs. (5)-(6) with its normal
        side = 1 if d > 0.0 else -1
        cell += side
        d -= side * S
        held = el == 0.0  # straight back into the cusp: held there by both walls
        n_coll = 0
        kicked = False
        sliding = False
        if not held:
            vx, vy, un_out, kicked = collide(vx, vy, d, s, fl, frame, v_stick, True)
            n_coll = 1
            if un_out < v_stick:
                vt, q, sliding = enter_contact(vx, vy, d, s, fl, frame, mu, v_stick)
                held = not sliding or abs(vt) < v_stick
                sliding = not held
        code = EV_COLLISION
        if sliding:
            nx, ny = arc_normal(d, R)
            vx = -Ax * cw + vt * ny
            vy = -Ay * cw - vt * nx
            code = EV_CONTACT
        elif held:
            vx = -Ax * cw
            vy = -Ay * cw
        n_rec = put_row(rec, n_rec, rec_from, t_c, t_max, cell * S + d - Ax * math.sin(w * s), y,
                        vx, vy, s / T, code, False)
        return NEXT, Contact(cell, d, y, vx, vy, s, tp, isamp, held, sliding, q, vt, kicked, n_rec), \
            Tally(n_coll, 1 if held else 0, 0, el, worst)
    # STOP (Coulomb): at rest relative to the floor; static friction holds it or it slides on
    vx = -Ax * cw
    vy = -Ay * cw
    held = slip_wait_c(d, s, fl, frame, mu, flat)[0] > 0.0
    n_rec = put_row(rec, n_rec, rec_from, t_c, t_max, xl, y, vx, vy, s / T, EV_STOP, True)
    return NEXT, Contact(cell, d, y, vx, vy, s, tp, isamp, held, not held, q, 0.0, False, n_rec), \
        Tally(0, 1 if held else 0, 0, el, worst)
