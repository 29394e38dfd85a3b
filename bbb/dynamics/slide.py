"""Sustained contact with an arc under the `slide` and `coulomb` models: the jitted
integrator of the contact phase and its certified event location, for both floors.

In the floor's frame (which accelerates with ÿ_f) a particle in contact is a point on the
circle of radius R of its arc, at angle θ from the arc's top (offset d = R sin θ), with
tangential speed v = R θ̇ (positive towards +x).  With g_eff(t) = g + ÿ_f(t) (mm/s²):

    R θ̈ = g_eff sin θ − μ N sgn(v),       N = g_eff cos θ − v²/R  (normal force per mass)

(``slide``: μ = 0).  A flat floor (R = ∞) has θ ≡ 0: the state is the offset d itself,
ḋ = v, v̇ = −μ g_eff sgn(v), N = g_eff.  Contact ends at an event:

- LIFT: N ≤ 0 (the floor no longer pushes): free flight with the current velocity;
- CUSP: |θ| reaches θ_c = asin(S/2R): the particle meets the neighbouring arc;
- STOP (μ > 0): v reaches 0; static friction holds it if |tan θ| ≤ μ;
- END: the run's t_max (or the caller's limit) is reached.

Integration: classic RK4 with step h ≤ T/256, ≤ 2π√(R/(g + Aω²))/2048 (the arc's pendulum
period) and ≤ 0.02 R/|v| (≤ 0.02 rad per step); local error O((ωh)⁵) ≈ 1e-10 relative per
step.  The particle is on its arc by construction (the
state is an angle), so it is never below the surface.

Certified event location: a step [a, b] with no event at b is accepted only when a bound
on the exact solution excludes a crossing inside: N ≥ (N_a + N_b)/2 − L_N h/2 > 0 with
L_N ≥ sup |Ṅ| on the step; ±θ ≤ ±θ_a ± θ̇_a τ + a_max τ²/(2R) < θ_c; for Coulomb
sgn(v)·v ≥ sgn(v)(v_a + v̇_a τ) − J τ²/2 > 0 (a_max, J bound |v̇|, |v̈|); otherwise the step
is halved.  A step with an event at b is halved (a
bisection from a) until it is ≤ tol_t: the event is located to tol_t (s).  On a conveyor a
particle may start from rest where v = v̇ = 0 (a slip at the edge of static friction, or out
of a cusp): there the cusp may also be excluded by the cubic bound ±θ ≤ ±θ_a ± (v_a τ +
v̇_a τ²/2)/R + J τ³/(6R), and the step grows back (doubling) up to the earliest event met,
so that it leaves in a few dozen steps instead of ~10⁸ steps of tol_t.  What can be
missed: an excursion of the event function shallower than L·tol_t/2 (e.g. N below 0 by
≤ L_N tol_t/2 ≈ 1e-5 mm/s² at f = 60), or one smaller than the integration error.
"""

from __future__ import annotations

import math
from collections import namedtuple

from ..jit import inlined, jitted
from .floors import is_flat
from .options import heave

#: a contact stretch's state (slide's argument and result): the angle θ from the arc's top (rad;
#: the offset d in mm on a flat floor) q, the tangential speed v (mm/s) relative to the floor,
#: floor time s (s) in its period count tp, the cell, the next position sample isamp
Stretch = namedtuple("Stretch", "q v s tp cell isamp")

LIFT = 1
CUSP = 2
STOP = 3
END = 4
BUDGET = 5  # more than STRETCH_BUDGET steps without progress: the caller stops (bbb.simulate raises)
#: RK4 steps per floor period at most
STEPS_PER_PERIOD = 256.0
#: RK4 steps per pendulum period 2π√(R/g_max) at most (the timing error of a stretch grows
#: as (h/√(R/g))⁴: 256 steps left 3e-7 relative at R = 1, f = 5 Hz; 2048 steps, ≤ 1e-10)
STEPS_PER_SWING = 2048.0
#: largest angle (rad) a step may sweep
MAX_ANGLE_STEP = 0.02
#: the step budget of a contact stretch (slide): its debt, tried steps less PAYBACK for each
#: nominal step's worth of time covered, may not exceed STRETCH_BUDGET (margins measured by
#: benchmarks/calibrations/guards.py)
PAYBACK = 64.0
STRETCH_BUDGET = 2.0**24


@inlined
def g_eff(s, g, A, w):
    # g + ÿ_f with y_f = -A sin(ωs) (Sec. 2): the floor frame's gravity
    return g + A * w * w * math.sin(w * s)


@inlined
def normal_force(q, v, s, fl, frame):
    """N (mm/s²) per unit mass on the floor fl (bbb.dynamics.options.Floor): g_eff cos θ − v²/R
    (g_eff on a flat floor); on a conveyor (``frame`` a Frame, module doc) gx_eff sin θ +
    g_eff cos θ − v²/R."""
    g, A = heave(fl, frame)
    w, R = fl.w, fl.R
    flat = is_flat(R)
    if frame is None:
        if flat:
            return g_eff(s, g, A, w)
        return g_eff(s, g, A, w) * math.cos(q) - v * v / R
    if flat:
        return g_eff(s, g, A, w)
    return g_eff(s, frame.gx, frame.Ax, w) * math.sin(q) + g_eff(s, g, A, w) * math.cos(q) \
        - v * v / R


@inlined
def rates(q, v, s, fl, frame, mu, sgn):
    # contact equation R θ̈ = g_eff sin θ − μ N sgn(v) (docs/physics.md, "Contact models");
    # on a conveyor R θ̈ = g_eff sin θ − gx_eff cos θ − μ N sgn(v) ("Transport")
    g, A = heave(fl, frame)
    w, R = fl.w, fl.R
    flat = is_flat(R)
    ge = g_eff(s, g, A, w)
    if frame is None:
        if flat:
            return v, -mu * ge * sgn
        n = ge * math.cos(q) - v * v / R
        return v / R, ge * math.sin(q) - mu * n * sgn
    gxe = g_eff(s, frame.gx, frame.Ax, w)
    if flat:
        return v, -gxe - mu * ge * sgn
    sq = math.sin(q)
    cq = math.cos(q)
    n = gxe * sq + ge * cq - v * v / R
    return v / R, ge * sq - gxe * cq - mu * n * sgn


@inlined
def tangential_force(q, s, fl, frame):
    """The tangential force per unit mass at rest (mm/s², positive towards +x), friction
    aside: g_eff sin θ − gx_eff cos θ (−gx_eff on a flat floor)."""
    g, A = heave(fl, frame)
    w = fl.w
    flat = is_flat(fl.R)
    if frame is None:
        return 0.0 if flat else g_eff(s, g, A, w) * math.sin(q)
    gxe = g_eff(s, frame.gx, frame.Ax, w)
    if flat:
        return -gxe
    return g_eff(s, g, A, w) * math.sin(q) - gxe * math.cos(q)


@jitted
def rk4(q, v, s, h, fl, frame, mu, sgn):
    """One classic RK4 step of length h (s) from floor time s; returns the increments (δq, δv)
    (the caller adds them: q + δq is the same rounding as before the split)."""
    k1q, k1v = rates(q, v, s, fl, frame, mu, sgn)
    k2q, k2v = rates(q + 0.5 * h * k1q, v + 0.5 * h * k1v, s + 0.5 * h, fl, frame, mu, sgn)
    k3q, k3v = rates(q + 0.5 * h * k2q, v + 0.5 * h * k2v, s + 0.5 * h, fl, frame, mu, sgn)
    k4q, k4v = rates(q + h * k3q, v + h * k3v, s + h, fl, frame, mu, sgn)
    return h * (k1q + 2.0 * k2q + 2.0 * k3q + k4q) / 6.0, h * (k1v + 2.0 * k2v + 2.0 * k3v + k4v) / 6.0


@jitted
def step_bounds(va, vb, h, fl, frame, mu, sin_c):
    """Bounds on a step of length h (s) from speeds va to vb: (a_max ≥ sup|v̇|,
    J ≥ sup|v̈|, L_N ≥ sup|Ṅ|), all on the exact solution through the step."""
    g, A = heave(fl, frame)
    w, R = fl.w, fl.R
    flat = is_flat(R)
    gmax = g + A * w * w
    jerk = A * w * w * w
    v0 = max(abs(va), abs(vb))
    if frame is None:
        if flat:
            return mu * gmax, mu * jerk, jerk
        amax = gmax * (sin_c + mu) + mu * v0 * v0 / R
        V = v0 + h * amax
        amax = gmax * (sin_c + mu) + mu * V * V / R
        V = v0 + h * amax
        # v̈ = ġ_eff (sin θ ∓ μ cos θ) + g_eff (cos θ ± μ sin θ) θ̇ ∓ 2μ v v̇/R
        J = jerk * (1.0 + mu) + gmax * (1.0 + mu) * V / R + 2.0 * mu * V * amax / R
        # Ṅ = ġ_eff cos θ − g_eff sin θ θ̇ − 2 v v̇ / R
        L = jerk + gmax * sin_c * V / R + 2.0 * V * amax / R
        return amax, J, L
    # conveyor: g, A are then the normal parts gy, Ay; |gx_eff| ≤ gxm, |ġx_eff| ≤ jx
    gxm = abs(frame.gx) + abs(frame.Ax) * w * w
    jx = abs(frame.Ax) * w * w * w
    gmax = abs(g) + abs(A) * w * w
    jerk = abs(A) * w * w * w
    if flat:
        # v̇ = −gx_eff − μ g_eff sgn v, N = g_eff
        return gxm + mu * gmax, jx + mu * jerk, jerk
    # |v̇| ≤ |gx_eff| (1 + μ) + |g_eff| (sin θ_c + μ) + μ v²/R
    amax = gmax * (sin_c + mu) + gxm * (1.0 + mu) + mu * v0 * v0 / R
    V = v0 + h * amax
    amax = gmax * (sin_c + mu) + gxm * (1.0 + mu) + mu * V * V / R
    V = v0 + h * amax
    # v̈ = d/dt(g_eff sin θ − gx_eff cos θ) ∓ μ Ṅ; each derivative ≤ (jerks) + (forces) θ̇
    J = (jerk + jx) * (1.0 + mu) + (gmax + gxm) * (1.0 + mu) * V / R + 2.0 * mu * V * amax / R
    # Ṅ = ġx_eff sin θ + ġ_eff cos θ + (gx_eff cos θ − g_eff sin θ) θ̇ − 2 v v̇ / R
    L = jerk + jx + (gmax * sin_c + gxm) * V / R + 2.0 * V * amax / R
    return amax, J, L


@inlined
def clear_of_cusp(q, v, dv, h, J, R, q_c):
    """Whether θ does not reach θ_c from below in (0, h] (s), by the cubic bound R θ(τ) ≤
    R θ_a + v_a τ + v̇_a τ²/2 + J τ³/6 (J ≥ sup|v̈| on the step) from θ_a = q (rad): θ(τ) < θ_c
    throughout, or, from θ_a ≥ θ_c (a slip up a neighbour's wall from within CUSP_REACH of the
    cusp starts just beyond its arc's end), θ(τ) < θ_a throughout (moving back in)."""
    # θ(τ) − θ_a ≤ τ k(τ)/R with k(τ) = v_a + v̇_a τ/2 + J τ²/6 convex: k ≤ max(k(0), k(h))
    kh = v + 0.5 * dv * h + J * h * h / 6.0
    m = max(v, kh)
    if m > 0.0:
        return q + h * m / R < q_c
    # k ≤ 0 on [0, h] and < 0 on (0, h] when k(h) < 0: θ stays below θ_a
    return q < q_c or kh < 0.0


@jitted
def slide(st, s0, fl, frame, mu, run, io, start_dir=0.0):
    """Integrate one contact stretch from st (a :data:`Stretch`) until an event, on the floor
    fl (bbb.dynamics.options.Floor) that ``frame`` selects; s0 (s) is the particle's start in
    its floor period, ``run`` gives t_max and tol_t.  Writes x (mm) at the sample times into
    ``pos``, io = (sample_times, pos).

    ``frame`` is None on the paper's floor (the branches it decides are pruned at compile
    time, here and in the helpers it passes it to); on a conveyor (a Frame) the forces split
    into the along-plane (gx, Ax) and the normal (gy, Ay), the g, A of the helpers
    (bbb.dynamics.options.heave); q, v are relative to the moving floor and the positions
    written are the lab's, cell·S + d + X_f (bbb.dynamics.bounds).

    ``start_dir`` (±1) is the direction of a start from rest where the caller knows it (a slip
    up a cusp's wall, or where the pull is ~0 at the slip: μN ≈ 0); 0: the pull's sign then.

    Returns (Stretch, event, (elapsed time in s, the step debt's peak)).  A flat floor's q is
    the offset d, wrapped into [-S/2, S/2) with ``cell``.  The step debt counts tried steps
    less PAYBACK per nominal step's worth of time covered; above :data:`STRETCH_BUDGET` it
    ends the stretch with the event BUDGET (the caller stops the particle, bbb.simulate
    raises): no input makes a stretch crawl without end."""
    q, v, s, tp, cell, isamp = st
    sample_times, pos = io
    g, A = heave(fl, frame)
    w, R, S = fl.w, fl.R, fl.S
    T = 2.0 * math.pi / w
    flat = is_flat(R)
    t_max, tol_t = run.t_max, run.tol_t
    sgn = 1.0 if v > 0.0 else -1.0
    if v == 0.0:
        # from rest the particle moves downhill (the caller only starts a stretch at rest
        # where static friction cannot hold it)
        if frame is None:
            sgn = 1.0 if math.sin(q) > 0.0 else -1.0
        elif start_dir != 0.0:
            sgn = start_dir
        else:
            sgn = 1.0 if tangential_force(q, s, fl, frame) > 0.0 else -1.0
    sin_c = 0.0 if flat else min(0.5 * S / R, 1.0)
    q_c = math.inf if flat else math.asin(sin_c)
    # resolve the faster of the floor's period and the arc's pendulum period 2π√(R/g_max)
    h_nom = T / STEPS_PER_PERIOD
    if not flat:
        h_nom = min(h_nom, 2.0 * math.pi * math.sqrt(R / (g + A * w * w)) / STEPS_PER_SWING)
        if frame is not None:  # the swing under the whole effective gravity, |G| ≤ g + Aω²
            gm = math.hypot(g, frame.gx) + math.hypot(A, frame.Ax) * w * w
            h_nom = min(h_nom, 2.0 * math.pi * math.sqrt(R / gm) / STEPS_PER_SWING)
    t_start = tp * T + (s - s0)
    n_a = normal_force(q, v, s, fl, frame)
    if n_a <= 0.0:
        return Stretch(q, v, s, tp, cell, isamp), LIFT, (0.0, 0.0)
    if not flat and abs(q) >= q_c and q * v > 0.0:
        return Stretch(q, v, s, tp, cell, isamp), CUSP, (0.0, 0.0)
    h = h_nom  # the next step to try
    hunting = False  # an event lies within h of the current state: bisect, never grow
    t_hit = math.inf  # the earliest end (s) of a tried step that met an event
    ns = sample_times.shape[0]
    # increments of q lost to rounding whole (|δq| < ulp(q)/2: v h/R below ~1e-16 rad) add up
    # here, and the cusp test takes them into account: a slow particle near a cusp otherwise
    # never arrived while its speed grew, in steps of ≤ tol_t (~1e6 per stretch, bounded only
    # by the step budget).  The state q itself keeps its arithmetic (bits unchanged wherever
    # the test's verdict is: everywhere but within q_lost of θ_c)
    q_lost = 0.0
    # the step budget: each tried step adds 1, each accepted one pays back PAYBACK × its
    # share of the nominal step (a sample time reached pays in full); steps that average
    # below 1/PAYBACK of the nominal one run the debt up
    debt = 0.0
    worst = 0.0
    while True:
        t_now = tp * T + (s - s0)
        if t_max - t_now <= tol_t:
            return Stretch(q, v, s, tp, cell, isamp), END, (t_now - t_start, worst)
        debt += 1.0
        if debt > worst:
            worst = debt
            if debt > STRETCH_BUDGET:
                return Stretch(q, v, s, tp, cell, isamp), BUDGET, (t_now - t_start, worst)
        hs = h
        cap = h_nom
        if not flat:
            cap = min(cap, MAX_ANGLE_STEP * R / max(abs(v), 1e-300))
            hs = min(hs, cap)
        # end steps on the next sample time and on t_max: positions there are states
        t_lim = t_max
        if isamp < ns and sample_times[isamp] < t_lim:
            t_lim = sample_times[isamp]
        sampling = t_lim - t_now <= hs
        if sampling:
            hs = max(t_lim - t_now, 0.0)
        dq, dv = rk4(q, v, s, hs, fl, frame, mu, sgn)
        qb = q + dq
        vb = v + dv
        lost = q_lost + dq if qb == q else q_lost
        sb = s + hs
        nb = normal_force(qb, vb, sb, fl, frame)
        lift = nb <= 0.0
        cusp = (not flat) and abs(qb + lost) >= q_c
        if frame is not None:
            # on a conveyor a particle may leave a cusp from rest (bbb.dynamics.contact_step):
            # θ then stays at ±θ_c to rounding for a while, which is no arrival at the cusp
            cusp = cusp and qb * vb > 0.0
        stop = mu > 0.0 and sgn * vb <= 0.0
        amax, J, L = step_bounds(v, vb, hs, fl, frame, mu, sin_c)
        # N: chord minus Lipschitz, N ≥ (N_a + N_b)/2 − L h/2
        certified = n_a + nb > L * hs
        dva = 0.0
        if mu > 0.0 or frame is not None:
            dva = rates(q, v, s, fl, frame, mu, sgn)[1]
        if not flat:
            # ±θ(τ) ≤ ±θ_a ± θ̇_a τ + a_max τ²/(2R), convex: below θ_c at both ends
            # (θ_a itself may be at a cusp it is leaving) means below it in between
            reach = amax * hs * hs / (2.0 * R)
            up = q + v * hs / R + reach < q_c
            down = -q - v * hs / R + reach < q_c
            if frame is not None:
                # a particle leaving a cusp from rest (bbb.dynamics.contact_step) starts with
                # v = v̇ = 0: the quadratic bound then admits steps of only ~v/a_max and
                # it crawls out in steps of tol_t; the cubic one grows them geometrically
                up = up or clear_of_cusp(q, v, dva, hs, J, R, q_c)
                down = down or clear_of_cusp(-q, -v, -dva, hs, J, R, q_c)
            certified = certified and up and down
        if mu > 0.0:
            # sgn·v(τ) ≥ sgn·(v_a + v̇_a τ) − J τ²/2, concave: positive at τ = h and ≥ 0 at 0
            certified = certified and sgn * (v + dva * hs) - 0.5 * J * hs * hs > 0.0
        event = lift or cusp or stop
        if (event or not certified) and hs > tol_t:
            h = 0.5 * hs
            hunting = hunting or event
            if event:
                t_hit = min(t_hit, t_now + hs)
            continue
        # accept the step [t_now, t_now + hs]
        debt = max(0.0, debt - PAYBACK * (1.0 if sampling else hs / cap))
        q_lost = lost
        q = qb
        v = vb
        n_a = nb
        s = sb
        if s >= T:
            k = math.floor(s / T)
            s -= k * T
            tp += int(k)
            if s < 0.0:
                s = 0.0
        if flat:
            k = math.floor(q / S + 0.5)
            q -= k * S
            cell += int(k)
        if sampling and isamp < ns:
            x = cell * S + (q if flat else R * math.sin(q))
            if frame is not None:
                x -= frame.Ax * math.sin(w * s)
            while isamp < ns and sample_times[isamp] <= t_lim:
                pos[isamp] = x
                isamp += 1
        t_el = tp * T + (s - s0) - t_start
        if lift:
            return Stretch(q, v, s, tp, cell, isamp), LIFT, (t_el, worst)
        if cusp:
            return Stretch(math.copysign(q_c, q), v, s, tp, cell, isamp), CUSP, (t_el, worst)
        if stop:
            return Stretch(q, 0.0, s, tp, cell, isamp), STOP, (t_el, worst)
        if hs > 0.0:
            h = hs if hunting else min(h_nom, 2.0 * hs)
            if hunting and frame is not None:
                t_after = tp * T + (s - s0)
                if t_after >= t_hit:
                    # the event the bisection chased did not come (the longer step's
                    # truncation error put it there): stop hunting, grow the step again;
                    # else h stays pinned at hs for the rest of the stretch
                    hunting = False
                    t_hit = math.inf
                    h = min(h_nom, 2.0 * hs)
                else:
                    # grow back up to the event met: a step halved for its certificate (from
                    # rest at a slip, v = v̇ = 0) rather than for the event must not pin h
                    h = max(hs, min(h_nom, 2.0 * hs, t_hit - t_after))
