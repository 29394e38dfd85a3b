"""The trajectory checker can fail: each test corrupts one event of a real recorded run the
way a wrong kernel would, and the checker must flag it (the unperturbed run passes)."""

import dataclasses
import math

import numpy as np
import pytest

from bbb import Numerics, Params, simulate
from bbb.ensemble import initial_state
from tests.bbb.trajectory_check import (
    CONTACT_LIFT,
    STOP,
    Floor,
    Report,
    _contact_rates,
    _contact_state,
    _rest_loads,
    _slip,
    check_particle,
    check_run,
    start_event,
)

P = Params.preset("klages2004", f=60.0)
J = 40  # the corrupted event: a collision that ends a flight from a collision


@pytest.fixture(scope="module")
def events() -> np.ndarray:
    run = simulate(P, 1, 1.0, seed=3, initial="launched", record_collisions=120, record_liftoffs=True)
    ev = run.collisions_dense[0, : run.n_recorded[0]].copy()
    assert ev[J, 6] == 0.0 and ev[J - 1, 6] == 0.0 and ev[J - 1, 3] != 0.0
    return ev


def failed(ev: np.ndarray) -> set[str]:
    rep = check_particle(P, ev)
    return {k for k, v in rep.failures.items() if v}


def outgoing(vx_in: float, vy_in: float, x: float, phase: float, sign: float = -1.0,
             t_sign: float = 1.0) -> tuple[float, float]:
    """Eqs. (5)-(6) in the floor frame (sign = -1, t_sign = 1 is the paper's rule)."""
    vf = -P.A * P.omega * math.cos(2 * math.pi * phase)
    d = x - math.floor(x / P.S + 0.5) * P.S
    nx, ny = d / P.R, math.sqrt(P.R**2 - d * d) / P.R
    un, ut = vx_in * nx + (vy_in - vf) * ny, vx_in * ny - (vy_in - vf) * nx
    un, ut = sign * P.alpha * un, t_sign * P.beta * ut
    return un * nx + ut * ny, vf + un * ny - ut * nx


def test_the_recorded_run_passes(events):
    assert failed(events) == set()


def test_a_collision_time_off_by_a_nanosecond_is_flagged(events):
    ev = events.copy()
    ev[J, 0] += 1e-9
    assert "clock" in failed(ev)


def test_a_collision_a_nanosecond_late_on_a_consistent_clock_is_flagged(events):
    ev = events.copy()
    ev[J, 0] += 1e-9
    ev[J, 5] += 1e-9 * P.f
    assert {"off_parabola", "off_surface"} <= failed(ev)


@pytest.mark.parametrize("early", [1e-9, 1e-11])
def test_a_collision_declared_too_early_on_the_parabola_is_flagged(events, early):
    """The event is moved back along the incoming parabola (t, phase, x, y consistent) and
    given the outgoing velocity Eqs. (5)-(6) would give there: only its height above the
    surface (|G'|·early, ≥ 10 tol_t·|G'|) betrays it."""
    ev = events.copy()
    a = ev[J - 1]
    tau = ev[J, 0] - a[0] - early
    x = a[1] + a[3] * tau
    ev[J, :3] = a[0] + tau, x, a[2] + a[4] * tau - 0.5 * P.g * tau * tau
    ev[J, 5] = (a[5] + tau * P.f) % 1.0
    ev[J, 3:5] = outgoing(a[3], a[4] - P.g * tau, x, ev[J, 5])
    assert "off_surface" in failed(ev)


@pytest.mark.parametrize("sign,t_sign", [(1.0, 1.0), (-1.0, -1.0)], ids=["normal", "tangential"])
def test_a_wrong_sign_in_the_velocity_rule_is_flagged(events, sign, t_sign):
    ev = events.copy()
    a = ev[J - 1]
    tau = ev[J, 0] - a[0]
    ev[J, 3:5] = outgoing(a[3], a[4] - P.g * tau, ev[J, 1], ev[J, 5], sign, t_sign)
    assert "velocity" in failed(ev)


def test_the_paper_rule_rebuilt_here_passes(events):
    # the control for the two tests above: the same rebuild with the right signs passes
    ev = events.copy()
    a = ev[J - 1]
    tau = ev[J, 0] - a[0]
    ev[J, 3:5] = outgoing(a[3], a[4] - P.g * tau, ev[J, 1], ev[J, 5])
    assert failed(ev) == set()


def test_a_missed_collision_is_flagged(events):
    # drop one collision: the flight before it now passes through the surface
    ev = np.delete(events, J, axis=0)
    assert "below" in failed(ev)


@pytest.fixture(scope="module")
def sticky() -> tuple[Params, np.ndarray, int]:
    """A creeping run (f = 56 Hz from rest) and the index of a lift-off after a stuck collision."""
    p = Params.preset("klages2004", f=56.0)
    run = simulate(p, 1, 0.5, seed=1, initial="rest", record_collisions=400, record_liftoffs=True)
    ev = run.collisions_dense[0, : run.n_recorded[0]].copy()
    k = int(np.nonzero(ev[1:, 6] == 1.0)[0][0]) + 1
    assert check_particle(p, ev).ok
    return p, ev, k


def liftoff_at(p: Params, ev: np.ndarray, k: int, dt: float) -> np.ndarray:
    """Event k (a lift-off) moved by dt s, the floor's state there (on the surface, its velocity)."""
    ev = ev.copy()
    ph = (ev[k, 5] + dt * p.f) % 1.0
    d = ev[k, 1] - math.floor(ev[k, 1] / p.S + 0.5) * p.S
    ev[k, 0] += dt
    ev[k, 2] = -p.A * math.sin(2 * math.pi * ph) - d * d / (p.R + math.sqrt(p.R**2 - d * d))
    ev[k, 4] = -p.A * p.omega * math.cos(2 * math.pi * ph)
    ev[k, 5] = ph
    return ev


@pytest.mark.parametrize("dt_periods", [-1e-6, 1.0], ids=["early", "a period late"])
def test_a_liftoff_before_the_floor_lets_go_or_after_a_skipped_window_is_flagged(sticky, dt_periods):
    p, ev, k = sticky
    rep = check_particle(p, liftoff_at(p, ev, k, dt_periods / p.f))
    assert rep.failures["liftoff_time"] == 1


def test_a_stuck_particle_that_moves_is_flagged(sticky):
    p, ev, k = sticky
    ev = ev.copy()
    ev[k, 1] += 1e-9
    assert check_particle(p, ev).failures["carried"] == 1


@pytest.fixture(scope="module")
def conveyor() -> tuple[Params, list[np.ndarray]]:
    """Runs on arcs tilted by −30° and thrown at 60° (Γ ≈ 5.8): long flights across many
    moving cusps, landing near-grazing."""
    p = Params.preset("klages2004", f=60.0, A=0.4, tilt=-30.0, throw=60.0)
    run = simulate(p, 6, 2.0, seed=5, initial="launched", record_collisions=200, record_liftoffs=True)
    return p, [run.collisions_dense[i, : run.n_recorded[i]].copy() for i in range(6)]


def test_every_flight_on_tilted_thrown_arcs_is_certified(conveyor):
    # the range bounds alone leave several of these flights 'uncertified'
    p, runs = conveyor
    reps = [check_particle(p, ev) for ev in runs]
    assert sum(r.flights for r in reps) > 50
    assert all(r.ok for r in reps), [r.messages for r in reps]


def test_a_missed_collision_on_tilted_thrown_arcs_is_flagged(conveyor):
    p, runs = conveyor
    ev = max(runs, key=len)
    k = int(np.nonzero((ev[1:-1, 6] == 0.0) & (ev[:-2, 6] == 0.0))[0][5]) + 1
    rep = check_particle(p, np.delete(ev, k, axis=0))
    assert rep.failures["below"] > 0


# ---- sliding and Coulomb contact on the conveyor (tilted / thrown floor)

#: the four kinds of conveyor contact runs (preset klages2004: R = 15, S = 2, A = 0.1, from rest)
CONVEYOR_CONTACT = {
    "coulomb 3/60 at 55 Hz": dict(f=55.0, contact="coulomb", mu=0.3, tilt=3.0, throw=60.0),
    "slide 3/60 at 55 Hz": dict(f=55.0, contact="slide", tilt=3.0, throw=60.0),
    "coulomb 10/90 at 40 Hz": dict(f=40.0, contact="coulomb", mu=0.3, tilt=10.0, throw=90.0),
    "coulomb 0/60 at 40 Hz": dict(f=40.0, contact="coulomb", mu=0.3, tilt=0.0, throw=60.0),
}


def conveyor_contact_run(kind: str, n: int = 3, t: float = 1.0) -> tuple[Params, list[np.ndarray]]:
    """n particles from rest for t s, each record led by its initial state (a start at rest)."""
    p = Params.preset("klages2004", **CONVEYOR_CONTACT[kind])
    st = initial_state(p, n, np.random.SeedSequence(1), "rest")
    run = simulate(p, n, t, seed=1, initial=st, record_collisions=4000, record_liftoffs=True)
    assert np.all(run.n_recorded < 4000)
    return p, [np.vstack([start_event(p, st.cell[i], st.d[i], st.y[i], st.vx[i], st.vy[i], st.s[i],
                                      st.stuck[i]), run.collisions_dense[i, : run.n_recorded[i]]])
               for i in range(n)]


@pytest.fixture(scope="module", params=list(CONVEYOR_CONTACT))
def conveyor_contact(request):
    return conveyor_contact_run(request.param)


@pytest.fixture(scope="module")
def coulomb_conveyor():
    return conveyor_contact_run("coulomb 3/60 at 55 Hz")


def test_conveyor_contact_runs_pass_the_checker(conveyor_contact):
    p, runs = conveyor_contact
    reps = [check_particle(p, ev) for ev in runs]
    assert sum(r.contacts for r in reps) >= 30
    assert all(r.ok for r in reps), [(r.failures, r.messages) for r in reps if not r.ok]


def test_conveyor_contact_runs_hold_stretches_from_rest_and_cusps(conveyor_contact):
    # what the test above covers: slides that start from rest (no row where they slip) and,
    # except on the flat-tilted run, cusps reached while sliding
    p, runs = conveyor_contact
    ev = np.vstack(runs)
    from_rest = np.isin(ev[:-1, 6], (0.0, 3.0, 6.0)) & np.isin(ev[1:, 6], (5.0, 6.0, 7.0))
    assert np.count_nonzero(from_rest) >= 3
    assert np.count_nonzero(ev[:, 6] == 7.0) >= 1


def slide_rebuilt(p: Params, a: np.ndarray, th0: float, d_arc: float, v0: float, tau: float,
                  mu: float, lift: bool, steps: int = 20_000) -> np.ndarray:
    """The end row of a sliding stretch rebuilt here: from row a's place (on the arc at offset
    d_arc, tangential speed v0 relative to the floor) at floor phase θ₀ (rad), slide for the
    rest of τ (s, from row a) under friction μ (the checker's own RK4, finer)."""
    fl = Floor(p)
    th_a = 2 * math.pi * a[5]
    h = (tau - (th0 - th_a) / fl.w) / steps
    q, v, th = math.asin(d_arc / p.R), v0, th0
    pull = v0 if v0 != 0.0 else float(_rest_loads(fl, mu, d_arc, th0)[0])  # from rest: F_t's way
    sgn = math.copysign(1.0, pull)
    for _ in range(steps):
        k1 = _contact_rates(fl, mu, q, v, th, sgn)[:2]
        k2 = _contact_rates(fl, mu, q + h / 2 * k1[0], v + h / 2 * k1[1], th + fl.w * h / 2, sgn)[:2]
        k3 = _contact_rates(fl, mu, q + h / 2 * k2[0], v + h / 2 * k2[1], th + fl.w * h / 2, sgn)[:2]
        k4 = _contact_rates(fl, mu, q + h * k3[0], v + h * k3[1], th + fl.w * h, sgn)[:2]
        q = q + h * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]) / 6
        v = v + h * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]) / 6
        th += fl.w * h
    th_e = th_a + fl.w * tau
    d = p.R * math.sin(q)
    nx, ny = d / p.R, math.sqrt(p.R**2 - d * d) / p.R
    x = (a[1] - fl.xf(th_a) - d_arc) + d + fl.xf(th_e)
    vs = Numerics().v_stick if lift else 0.0
    vx = fl.vxf(th_e) + v * ny + vs * nx
    vy = fl.v(th_e) - v * nx + vs * ny
    return np.array([a[0] + tau, x, fl.surface(x, th_e), vx, vy, (a[5] + tau * p.f) % 1.0,
                     CONTACT_LIFT if lift else STOP])


def contact_pair(p, runs, end: float, held: float = 0.0) -> tuple[np.ndarray, int]:
    """A record and the index j of its first stretch from rest (a held row: a stop or a collision
    that ended held) to a row of kind ``end``, held for more than ``held`` s before it slips."""
    fl = Floor(p)
    for ev in runs:
        for j in np.nonzero(np.isin(ev[:-1, 6], (0.0, 6.0)) & (ev[1:, 6] == end))[0] + 1:
            th_s = rest_slip(p, ev, j)[0]
            if th_s - 2 * math.pi * ev[j - 1, 5] > fl.w * held:
                return ev.copy(), int(j)
    raise AssertionError("no such stretch")


def rest_slip(p, ev, j):
    """The checker's slip phase (rad) and arc offset for the stretch from rest ev[j-1] → ev[j]."""
    fl = Floor(p)
    a = ev[j - 1]
    th_a = 2 * math.pi * a[5]
    _, _, d, _ = _contact_state(fl, a[1:2], a[3:4], a[4:5], np.array([th_a]), np.array([True]))
    cusp = abs(0.5 * p.S - abs(float(d[0]))) <= 1e-12
    th_s, arc, _ = _slip(fl, p.mu, float(d[0]), th_a, th_a + fl.w * (ev[j, 0] - a[0]), cusp, 0.0)
    return th_s, arc


def failed_on(p: Params, ev: np.ndarray) -> set[str]:
    return {k for k, v in check_particle(p, ev).failures.items() if v}


def rebuilt(p, ev, j, dt_end=0.0, dt_slip=0.0, mu=None):
    """Stretch ev[j-1] (at rest) → ev[j] rebuilt here, its slip moved by dt_slip s and its end
    by dt_end s along the path, under friction μ (the record's by default); the record ends
    there (the flight after it is the kernel's, from the kernel's end state)."""
    fl = Floor(p)
    a = ev[j - 1]
    th_s, arc = rest_slip(p, ev, j)
    ev = ev.copy()
    lift = ev[j, 6] == CONTACT_LIFT
    ev[j] = slide_rebuilt(p, a, th_s + fl.w * dt_slip, arc, 0.0, ev[j, 0] - a[0] + dt_end,
                          p.mu if mu is None else mu, lift=lift)
    if not lift:  # a stop: at rest relative to the floor
        ev[j, 3], ev[j, 4] = fl.vxf(2 * math.pi * ev[j, 5]), fl.v(2 * math.pi * ev[j, 5])
    return ev[: j + 1]


@pytest.mark.parametrize("end", [CONTACT_LIFT, STOP], ids=["lift-off", "stop"])
def test_a_coulomb_stretch_from_rest_rebuilt_here_passes(coulomb_conveyor, end):
    # the control for the perturbations below: the same rebuild, unperturbed, passes
    p, runs = coulomb_conveyor
    ev, j = contact_pair(p, runs, end, held=2e-4)
    assert failed_on(p, rebuilt(p, ev, j)) == set()


@pytest.mark.parametrize("dt,check", [(1e-4, "contact_normal"), (-1e-4, "contact_event")],
                         ids=["late", "early"])
def test_a_contact_lift_off_moved_along_its_path_is_flagged(coulomb_conveyor, dt, check):
    # the end state is the exact one at the moved time: only the event (N = 0) betrays it
    p, runs = coulomb_conveyor
    ev, j = contact_pair(p, runs, CONTACT_LIFT)
    assert check in failed_on(p, rebuilt(p, ev, j, dt_end=dt))


def test_friction_along_the_motion_is_flagged(coulomb_conveyor):
    # friction's sign flipped (μ → −μ) in the rebuilt stretch
    p, runs = coulomb_conveyor
    ev, j = contact_pair(p, runs, CONTACT_LIFT)
    assert "contact_path" in failed_on(p, rebuilt(p, ev, j, mu=-p.mu))


@pytest.mark.parametrize("dt", [-1e-4, 1e-4], ids=["early", "late"])
def test_a_slip_from_rest_at_the_wrong_time_is_flagged(coulomb_conveyor, dt):
    # held > 2e-4 s: slipping 1e-4 s early is still slipping while static friction holds
    p, runs = coulomb_conveyor
    ev, j = contact_pair(p, runs, STOP, held=2e-4)
    assert "contact_path" in failed_on(p, rebuilt(p, ev, j, dt_slip=dt))


def held_to_liftoff(p, ev, j) -> np.ndarray:
    """Rows j-1 (held at rest, off any cusp) and a lift-off from there where the floor first
    lets go after it (normal load at rest 0, bisected): a kernel that never let it slip."""
    fl = Floor(p)
    a = ev[j - 1]
    th_a = 2 * math.pi * a[5]
    d = float(fl.offset(a[1], th_a))
    th = np.linspace(th_a, th_a + 2 * math.pi, 8193)
    k = int(np.argmax(_rest_loads(fl, p.mu, d, th)[1] <= 0.0))
    assert k > 0
    lo, hi = th[k - 1], th[k]
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if _rest_loads(fl, p.mu, d, mid)[1] <= 0.0 else (mid, hi)
    tau = (hi - th_a) / fl.w
    x = a[1] - fl.xf(th_a) + fl.xf(hi)
    lift = [a[0] + tau, x, fl.surface(x, hi), fl.vxf(hi), fl.v(hi), (a[5] + tau * p.f) % 1.0, 1.0]
    return np.vstack([a, lift])


def test_a_held_particle_lifting_off_after_friction_let_go_is_flagged(coulomb_conveyor):
    # held past its slip (it should have slid, the checker's slip search says when), until
    # the floor lets go.  Under a sideways load any finite μ lets go just before the floor does
    # (|F_t| > μN as N → 0: 0.34 ms before it at μ = 10 here); with μ = 1e12 that is ~1e-15 s
    # before, below tol_t, and the same pair passes
    p, runs = coulomb_conveyor
    ev, j = contact_pair(p, runs, STOP, held=2e-4)
    assert abs(abs(Floor(p).offset(ev[j - 1, 1], 2 * math.pi * ev[j - 1, 5])) - 0.5 * p.S) > 1e-6
    pair = held_to_liftoff(p, ev, j)
    assert failed_on(dataclasses.replace(p, mu=1e12), pair) == set()
    assert failed_on(p, pair) == {"liftoff_time"}


# ---- flights from a cusp on the conveyor (the soak's 'gap not certified', 2026-11-23)

#: a grazing bounce off a cusp recorded by the 1e8 soak of the conveyor contact rows (row
#: contact=slide, tilt=3, throw=60, f=55; event 7, the cusp reached while sliding left, the
#: collision with the next arc at the same instant, the next collision): the flight starts
#: exactly on the cusp (offset −S/2), so the offset's range holds the cusp on every
#: sub-interval, and bounds on one arc never applied (30 such flights, one repeating orbit)
CUSP_BOUNCE = np.array([
    [2.8862616718376916e+01, -1.1430408719220070e+03, -1.0416269842329010e-01, -5.0951599501216990e+01,
     1.3169477942221956e+01, 3.4769670059847702e-01, 7.0],
    [2.8862616718376916e+01, -1.1430408719220070e+03, -1.0416269842329010e-01, -4.9427635045373421e+01,
     2.6903440831942074e+01, 3.4769670059847702e-01, 0.0],
    [2.8863254607815094e+01, -1.1430725056370620e+03, -8.8992369582086089e-02, -4.8532060054440073e+01,
     2.9977279250955561e+01, 3.8278061969826749e-01, 0.0],
])
P_CUSP = Params.preset("klages2004", f=55.0, contact="slide", tilt=3.0, throw=60.0)


def test_a_grazing_flight_from_a_cusp_on_the_conveyor_is_certified():
    fl = Floor(P_CUSP)
    assert float(fl.offset(CUSP_BOUNCE[1, 1], 2 * math.pi * CUSP_BOUNCE[1, 5])) == -0.5 * P_CUSP.S
    rep = check_particle(P_CUSP, CUSP_BOUNCE)
    # two flights: the zero-time one from the cusp event to the bounce, and the grazing one
    assert rep.flights == 2 and rep.ok, (rep.failures, rep.messages)


def dip_from_cusp(p: Params, side: float, v_n: float, tau: float, phase: float = 0.75) -> np.ndarray:
    """A flight from a cusp onto the arc on ``side`` (+1 the arc to the right): 10 mm/s along
    that arc, v_n mm/s into it, at a phase where the floor falls faster than g (G'' > 0), so the
    particle dips below the arc briefly and rises again; the record ends τ s later on the
    parabola (that row is not a collision: only 'below' matters here)."""
    fl = Floor(p)
    th0 = 2 * math.pi * phase
    d = -side * 0.5 * p.S  # the cusp, seen from the arc the particle moves onto
    x0 = fl.xf(th0) + 3 * p.S + d
    q = math.sqrt(p.R**2 - d * d)
    vx = side * 10.0 * q / p.R - v_n * d / p.R + fl.vxf(th0)
    vy = -side * 10.0 * d / p.R - v_n * q / p.R + fl.v(th0)
    y0 = float(fl.surface(x0, th0))
    x1, y1 = x0 + vx * tau - 0.5 * fl.gx * tau**2, y0 + vy * tau - 0.5 * fl.gy * tau**2
    return np.array([[0.0, x0, y0, vx, vy, phase, 0.0],
                     [tau, x1, y1, vx - fl.gx * tau, vy - fl.gy * tau, (phase + tau * p.f) % 1.0, 0.0]])


@pytest.mark.parametrize("side", [1.0, -1.0], ids=["onto the right arc", "onto the left arc"])
def test_a_dip_below_the_arc_beside_a_cusp_between_samples_is_flagged(side):
    # the dip (≈ 2e-10 mm deep, ~3e-6 s long) ends before the checker's first dense sample
    # (τ/128): only the bisection with a sound lower bound finds it; a Taylor bound on the
    # other arc's circle alone (the one the particle leaves) would certify this flight
    p = Params.preset("klages2004", f=55.0, tilt=3.0, throw=60.0)
    fl = Floor(p)
    ev = dip_from_cusp(p, side, v_n=3e-4, tau=1e-3)
    s = np.linspace(0.0, 1e-3, 100_001)
    x = ev[0, 1] + ev[0, 3] * s - 0.5 * fl.gx * s * s
    gap = ev[0, 2] + ev[0, 4] * s - 0.5 * fl.gy * s * s - fl.surface(x, 2 * math.pi * ev[0, 5] + fl.w * s)
    below = s[gap < -1e-12]
    assert below.size and below.max() < 1e-3 / 128 and gap[-1] > 0
    assert check_particle(p, ev).failures["below"] == 1


def skim_over_an_arc(p: Params, s_top: float, tau: float, u: float = 2000.0,
                     delta: float = 1e-9) -> np.ndarray:
    """A fast flight (u mm/s sideways relative to the floor) over the arcs around arc 3 that
    passes δ mm below arc 3's top at s_top s, when the floor falls faster than g (phase 0.75):
    G is convex there and the dip lasts ~2e-7 s.  The end row is the parabola's point at τ."""
    fl = Floor(p)
    th = 1.5 * math.pi  # the phase at the dip
    vx, vy = u + float(fl.vxf(th)) + fl.gx * s_top, float(fl.v(th)) + fl.gy * s_top
    x0 = float(fl.xf(th)) + 3 * p.S - vx * s_top + 0.5 * fl.gx * s_top**2
    y0 = float(fl.y(th)) - delta - vy * s_top + 0.5 * fl.gy * s_top**2
    ph0 = 0.75 - p.f * s_top
    return np.array([[0.0, x0, y0, vx, vy, ph0, 0.0],
                     [tau, x0 + vx * tau - 0.5 * fl.gx * tau**2, y0 + vy * tau - 0.5 * fl.gy * tau**2,
                      vx - fl.gx * tau, vy - fl.gy * tau, (ph0 + tau * p.f) % 1.0, 0.0]])


def test_a_dip_below_the_middle_of_three_arcs_is_flagged():
    # the dip lies off the dense samples and off the bisection's points; a sub-interval whose
    # offset reaches three arcs gets no Taylor bound: with one from the two outer circles
    # (~0.13 mm below the middle arc's top) this flight is certified (s_top, τ found so)
    p = Params.preset("klages2004", f=55.0, tilt=3.0, throw=60.0)
    fl = Floor(p)
    ev = skim_over_an_arc(p, s_top=0.9e-3, tau=2.5e-3)
    s = np.linspace(0.0, ev[1, 0], 250_001)
    x = ev[0, 1] + ev[0, 3] * s - 0.5 * fl.gx * s * s
    gap = ev[0, 2] + ev[0, 4] * s - 0.5 * fl.gy * s * s - fl.surface(x, 2 * math.pi * ev[0, 5] + fl.w * s)
    below = s[gap < 0]
    assert below.size and abs(below.mean() - 0.9e-3) < 1e-7 and np.ptp(below) < 1e-6
    assert check_particle(p, ev).failures["below"] == 1


# ---- the checker's own tolerances -----------------------------------------------------------


def test_a_run_made_at_a_coarser_root_tolerance_fails_the_checker():
    """The checker asks event times to its own TOL_T (1e-12 s), whatever the run's Numerics:
    the same Coulomb conveyor run at tol_t = 1e-9 s has its sliding events 1e-9 s off and is
    flagged (when the checker read tol_t from the run, it passed)."""
    p = Params.preset("klages2004", f=55.0, contact="coulomb", mu=0.3, tilt=3.0, throw=60.0)

    def flags(tol_t: float) -> set[str]:
        run = simulate(p, 4, 1.0, seed=3, initial="rest", record_collisions=3000,
                       record_liftoffs=True, numerics=Numerics(tol_t=tol_t))
        return {k for i in range(4)
                for k, v in check_particle(p, run.collisions_dense[i, : run.n_recorded[i]]).failures.items()
                if v}

    assert flags(1e-12) == set()
    assert "contact_path" in flags(1e-9)


@pytest.mark.parametrize("A", [0.1, 1e-200, 2.225073858507e-311, 0.0])
def test_the_floor_velocity_rounding_bound_does_not_underflow(A):
    # 16 ε Aω relative to Aω where A is a normal number, at least 32 subnormal spacings where
    # Aω is subnormal (the relative bound 16 ε Aω was 0 at A = 2.2e-311: fails this)
    fl = Floor(Params(g=9800.0, A=A, f=5.0, R=51.0, S=2.0, alpha=0.5, beta=0.8))
    aw = A * fl.w
    assert fl.vf_tol >= 16.0 * np.finfo(float).eps * aw
    assert fl.vf_tol >= 32.0 * 5e-324
    assert fl.vf_tol <= 64.0 * np.finfo(float).eps * aw + 32.0 * 5e-324


def fly_off(g2: float) -> np.ndarray:
    """Two events of the paper's floor (P): a flight of 1e-6 s ending in a soft touch
    (α|u⊥| = v_stick/2) at d = 0.5 mm whose tangential speed makes the kick's G'' =
    −g − Aω² sin θ + (β u∥)²/√(R² − d²) equal ``g2`` (mm/s²), and the kernel's fly-off from it
    (u⊥⁺ = v_stick, u∥⁺ = β u∥)."""
    tc = Floor(P)
    d, th, tau, vs = 0.5, 3.6, 1e-6, 1e-3
    q = math.sqrt(P.R**2 - d * d)
    g_eff = P.g + P.A * P.omega**2 * math.sin(th)
    ut = math.sqrt((g_eff + g2) * q) / P.beta
    nx, ny = d / P.R, q / P.R
    un = -0.5 * vs / P.alpha
    vf = float(tc.v(th))
    vx_in, vy_in = un * nx + ut * ny, vf + un * ny - ut * nx
    vx_out = vs * nx + P.beta * ut * ny
    vy_out = vf + vs * ny - P.beta * ut * nx
    y_b = float(tc.surface(np.array(d), th))
    t_b, ph_b = 0.01, th / (2 * math.pi)
    a = [t_b - tau, d - vx_in * tau, y_b - vy_in * tau - 0.5 * P.g * tau**2, vx_in, vy_in + P.g * tau,
         ph_b - tau * P.f, 0.0]
    return np.array([a, [t_b, d, y_b, vx_out, vy_out, ph_b, 0.0]])


@pytest.mark.parametrize("g2", [1e-3, 0.0])
def test_a_fly_off_where_the_arc_falls_away_passes(g2):
    assert failed(fly_off(g2)) == set()


def test_a_fly_off_where_the_forces_still_press_is_flagged():
    # G'' = −1e-3 mm/s²: the floor still holds the particle; the kernel must not kick
    assert failed(fly_off(-1e-3)) == {"velocity"}


def test_the_fly_off_bound_is_what_accepts_a_kick_at_the_edge(monkeypatch):
    """G'' = −1e-5 mm/s² lies within the derived bound (~5e-5 here, dominated by u∥ known to
    the velocity check's own 2e-6 mm/s): accepted; with the bound removed it is flagged."""
    import tests.bbb.trajectory_check as tc

    ev = fly_off(-1e-5)
    assert failed(ev) == set()
    monkeypatch.setattr(tc, "_kick_tolerance", lambda *a, **k: 0.0)
    assert failed(ev) == {"velocity"}


def test_contact_rtol_is_the_calibrated_need_times_its_stated_margin():
    # read from tests/bbb/data/checker_calibration.json (benchmarks/calibrations/checker_calibration.py):
    # the least rtol every calibration stretch passes at, times a margin fixed beforehand
    cal = tc_module().CALIBRATION
    assert cal["contact_rtol_needed"] > 0 and cal["stretches"] > 10_000
    assert 2.0 <= cal["margin"] <= 100.0
    assert tc_module().CONTACT_RTOL == cal["contact_rtol_needed"] * cal["margin"]


def tc_module():
    import tests.bbb.trajectory_check as tc

    return tc


def calibration_input(k: int):
    """The k-th random input of benchmarks/calibrations/checker_calibration.py (stick draws skipped)."""
    from benchmarks.calibrations.guards import random_params

    rng = np.random.default_rng(20261126)
    j = 0
    while True:
        p, family, t_max = random_params(rng)
        if p.contact == "stick":
            continue
        if j == k:
            return p, family, t_max
        j += 1


def test_the_calibrations_worst_input_passes_at_the_tolerance_and_fails_below_its_need(monkeypatch):
    """The input that set CONTACT_RTOL still needs what the calibration recorded (a worse
    kernel integration would need more); it passes at CONTACT_RTOL and fails at half its need,
    so the bound is set by a real discrepancy, not by a margin on nothing."""
    tc = tc_module()
    k = int(tc.CALIBRATION["where"].split("#")[1].split()[0])
    p, family, t_max = calibration_input(k)
    st = initial_state(p, 3, np.random.SeedSequence(k), family, drop_height=(0.0, 1.0),
                       launch_speed=(0.0, 150.0))
    run = simulate(p, 3, t_max, seed=k, initial=st, record_collisions=4000, record_liftoffs=True,
                   _force_conveyor=True)

    def check():
        rep = tc.Report()
        for i in range(3):
            start = start_event(p, st.cell[i], st.d[i], st.y[i], st.vx[i], st.vy[i], st.s[i], st.stuck[i])
            rep.add(check_particle(p, np.vstack([start, run.collisions_dense[i, : run.n_recorded[i]]])))
        return rep

    rep = check()
    assert rep.ok and rep.contact_need == pytest.approx(tc.CALIBRATION["contact_rtol_needed"], rel=1e-6)
    monkeypatch.setattr(tc, "CONTACT_RTOL", 0.5 * rep.contact_need)
    assert check().failures["contact_path"] >= 1


# ---- the sine and the sawtooth (level, vertically vibrated, stick: where the kernel runs them)
#: the scenes the checker runs over, a user's depths and a steep case of each (flanks near 60°
#: and 80°, the sine's curvature to ±5 /mm)
SHAPES = {
    "sine": dict(floor="sine", depth=0.3),
    "sine_steep": dict(floor="sine", depth=1.0, A=0.1),
    "sawtooth": dict(floor="sawtooth", depth=0.3, peak=0.3),
    "sawtooth_steep": dict(floor="sawtooth", depth=1.0, peak=0.1, A=0.1),
}
_SHAPE_RUNS: dict = {}


def shape_run(name: str):
    """A 60 Hz ensemble of 12 launched particles over 1 s on scene ``name`` (cached)."""
    if name not in _SHAPE_RUNS:
        p = Params.preset("klages2004", f=60.0, **SHAPES[name])
        _SHAPE_RUNS[name] = simulate(p, 12, 1.0, seed=5, initial="launched", record_collisions=200,
                                     record_liftoffs=True)
    return _SHAPE_RUNS[name]


def shape_events(name: str) -> tuple[Params, np.ndarray, int]:
    """One particle's events on scene ``name`` and a collision J on a flank (|c'| > 0.1, after a
    flight of ≥ 1 ms from a collision, followed by a collision)."""
    run = shape_run(name)
    fl = Floor(run.params)
    for i in range(run.n_particles):
        ev = run.collisions_dense[i, : run.n_recorded[i]].copy()
        for j in range(10, ev.shape[0] - 1):
            d = fl.offset(ev[j, 1], 2 * math.pi * ev[j, 5])
            if ev[j - 1, 6] == ev[j, 6] == ev[j + 1, 6] == 0.0 and ev[j, 0] - ev[j - 1, 0] > 1e-3 \
                    and abs(float(fl.slope(d))) > 0.1:
                return run.params, ev, j
    raise AssertionError(f"no collision on a flank after a long flight on {name}")


@pytest.mark.parametrize("name", SHAPES)
def test_sine_and_sawtooth_ensembles_pass_the_checker(name):
    rep = check_run(shape_run(name))
    assert rep.flights >= 500 and rep.carried >= 1  # bounces, and carried stretches with lift-offs
    assert rep.ok, rep.messages


@pytest.mark.parametrize("name", SHAPES)
def test_a_checker_told_a_depth_a_millionth_off_flags_the_collision_points(name):
    run = shape_run(name)
    wrong = dataclasses.replace(run.params, depth=run.params.depth * (1 + 1e-6))
    rep = Report()
    for i in range(run.n_particles):
        rep.add(check_particle(wrong, run.collisions_dense[i, : run.n_recorded[i]]))
    assert rep.failures["off_surface"] > 0


def test_a_checker_told_a_sawtooth_peak_a_millionth_off_flags_the_collision_points():
    run = shape_run("sawtooth")
    wrong = dataclasses.replace(run.params, peak=run.params.peak * (1 + 1e-6))
    rep = Report()
    for i in range(run.n_particles):
        rep.add(check_particle(wrong, run.collisions_dense[i, : run.n_recorded[i]]))
    assert rep.failures["off_surface"] > 0


@pytest.mark.parametrize("name", SHAPES)
def test_a_missed_collision_on_a_sine_or_sawtooth_is_flagged(name):
    p, ev, j = shape_events(name)
    assert check_particle(p, ev).ok
    assert "below" in {k for k, v in check_particle(p, np.delete(ev, j, axis=0)).failures.items() if v}


@pytest.mark.parametrize("name", SHAPES)
def test_a_bounce_off_the_flat_floors_normal_on_a_flank_is_flagged(name):
    # Eqs. (5)-(6) with the normal (0, 1) where the floor slopes: the shape's normal is checked
    p, ev, j = shape_events(name)
    a = ev[j - 1]
    tau = ev[j, 0] - a[0]
    vf = -p.A * p.omega * math.cos(2 * math.pi * ev[j, 5])
    ux, uy = a[3], a[4] - p.g * tau - vf
    ev = ev.copy()
    ev[j, 3:5] = p.beta * ux, vf - p.alpha * uy
    assert check_particle(p, ev).failures["velocity"] >= 1


@pytest.mark.parametrize("name,top", [("sine", 0.0), ("sawtooth", -0.4)], ids=["sine crest", "sawtooth peak"])
def test_a_dip_below_a_sine_crest_or_a_sawtooth_peak_between_samples_is_flagged(name, top):
    # a fast level flight (2000 mm/s) passing 1 nm below the top of cell 3 (a sine's crest at
    # its centre, a sawtooth's peak (ξ − ½)S off it), when the floor falls faster than g: the
    # dip (~3e-8 s over the crest, ~2e-12 s at the kink) lies off the dense samples, and only
    # the bisection with the shape's bounds (a sine's least curvature, a sawtooth's peak) finds it
    p = Params.preset("klages2004", f=55.0, **SHAPES[name])
    fl = Floor(p)
    s_top, tau, u = 0.9e-3, 2.5e-3, 2000.0
    th = 1.5 * math.pi
    x0, vy = 3 * p.S + top - u * s_top, float(fl.v(th)) + p.g * s_top
    y0 = float(fl.y(th)) - 1e-9 - vy * s_top + 0.5 * p.g * s_top**2
    ph0 = 0.75 - p.f * s_top
    ev = np.array([[0.0, x0, y0, u, vy, ph0, 0.0],
                   [tau, x0 + u * tau, y0 + vy * tau - 0.5 * p.g * tau**2, u, vy - p.g * tau,
                    (ph0 + tau * p.f) % 1.0, 0.0]])
    s = np.linspace(0.0, tau, 250_001)
    gap = ev[0, 2] + vy * s - 0.5 * p.g * s * s - fl.surface(x0 + u * s, 2 * math.pi * ph0 + fl.w * s)
    assert gap[1:].min() > -1e-9 and np.all(gap[np.abs(s - s_top) > 1e-6] > 0)  # only the dip
    assert check_particle(p, ev).failures["below"] == 1
