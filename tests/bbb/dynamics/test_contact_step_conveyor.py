"""Sliding and Coulomb contact on the conveyor (bbb.dynamics.contact_step with a Frame) against
analytic mechanics, the mirror symmetry, and the independent checker on random inputs."""

import math
from datetime import timedelta

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from bbb import Params, simulate
from bbb.ensemble import InitialState, initial_state
from tests.bbb.dynamics.test_conveyor_mechanics import mirrored_runs
from tests.bbb.no_miss import assert_no_miss

G = 9800.0
STOP, CONTACT_LIFT, CUSP = 6.0, 5.0, 7.0  # bbb.record.EVENT_CODES


def one(value, dtype=float):
    return np.full(1, value, dtype=dtype)


def at_rest(d: float, y: float = 0.0) -> InitialState:
    """One particle at rest on the floor at offset d (cell 0), floor time 0."""
    return InitialState(one(0, np.int64), one(d), one(y), one(0.0), one(0.0), one(0.0),
                        one(True, bool), one(True, bool))


def tilted(phi: float, mu: float, R: float = math.inf) -> Params:
    """A motionless floor (A = 0) tilted by φ (degrees) under slide (μ = 0) or Coulomb μ."""
    return Params(g=G, A=0.0, f=50.0, R=R, S=2.0, alpha=0.5, beta=0.9, tilt=phi,
                  contact="slide" if mu == 0.0 else "coulomb", mu=mu)


@pytest.mark.parametrize(("phi", "mu"), [(10.0, 0.0), (10.0, 0.1), (-25.0, 0.3), (30.0, 0.5)])
def test_on_a_motionless_tilted_flat_floor_a_particle_slides_at_g_sin_phi_minus_mu_cos_phi(phi, mu):
    # tan φ > μ: x(t) = x₀ − sgn(φ) g (sin|φ| − μ cos φ) t²/2, downhill (towards −x for φ > 0)
    a = G * (math.sin(math.radians(abs(phi))) - mu * math.cos(math.radians(phi)))
    assert a > 0
    times = np.linspace(0.0, 0.6, 61)
    run = simulate(tilted(phi, mu), 1, 0.6, seed=0, initial=at_rest(0.3), sample_times=times)
    x = run.positions[0]
    travel = 0.5 * a * times**2
    expected = 0.3 - math.copysign(1.0, phi) * travel
    # 1e-9 relative to the distance from the origin x = 0 along the way
    assert np.all(np.abs(x - expected) <= 1e-9 * (0.3 + travel))


@pytest.mark.parametrize(("phi", "mu"), [(10.0, 0.2), (-25.0, 0.5), (0.5, 0.01)])
def test_on_a_motionless_tilted_flat_floor_static_friction_holds_where_tan_phi_is_below_mu(phi, mu):
    assert math.tan(math.radians(abs(phi))) < mu
    times = np.linspace(0.0, 1.0, 11)
    run = simulate(tilted(phi, mu), 1, 1.0, seed=0, initial=at_rest(0.3), sample_times=times)
    assert np.all(run.positions[0] == 0.3)


@pytest.mark.parametrize("phi", [8.0, -15.0])
def test_a_frictionless_particle_leaves_a_tilted_arc_where_the_classic_two_thirds_rule_says(phi):
    # A = 0: on an arc the particle is a point on a circle under gravity g at φ to the arc's
    # axis; from rest at θ₀ it keeps E (v² = 2gR (cos(θ₀−φ) − cos(θ−φ))) and leaves where
    # N = g cos(θ−φ) − v²/R = 0, i.e. cos(θ−φ) = (2/3) cos(θ₀−φ)
    R = 1.05
    ph = math.radians(phi)
    th0 = ph + math.copysign(0.05, phi)
    p = tilted(phi, 0.0, R)
    run = simulate(p, 1, 0.2, seed=0, initial=at_rest(R * math.sin(th0), -R * (1 - math.cos(th0))),
                   record_collisions=4, record_liftoffs=True)
    rows = run.collisions_dense[0, : run.n_recorded[0]]
    assert rows[0, 6] == CONTACT_LIFT
    t, x, y, vx, vy = rows[0, :5]
    th = math.asin(x / R)
    th_pred = ph + math.copysign(math.acos(2.0 / 3.0 * math.cos(th0 - ph)), phi)
    assert abs(th - th_pred) <= 1e-7
    # the speed it leaves with (less the kick v_stick along the normal) from energy
    nx, ny = math.sin(th), math.cos(th)
    v2 = (vx - run.numerics.v_stick * nx) ** 2 + (vy - run.numerics.v_stick * ny) ** 2
    v2_pred = 2.0 * G * R * (math.cos(th0 - ph) - math.cos(th - ph))
    assert abs(v2 - v2_pred) <= 1e-9 * 2.0 * G * R


def mirror_pair(R: float, contact: str, mu: float):
    """(φ, ψ) and (−φ, 180° − ψ) from mirrored states (d, vₓ → −d, −vₓ) at low Γ (22 Hz)."""
    p = Params.preset("klages2004", f=22.0, R=R, tilt=3.0, throw=60.0, contact=contact, mu=mu)
    return mirrored_runs(p, seed=7, y=(0.05, 0.3), v=30.0, record=400)


@pytest.mark.parametrize(("contact", "mu"), [("slide", 0.0), ("coulomb", 0.3)])
# R = 15: shallow cusps (θ_c = 3.8°, near φ = 3°) that particles leave from rest
@pytest.mark.parametrize("R", [1.5, 15.0, math.inf])
def test_mirrored_conveyor_and_state_give_the_mirrored_sliding_trajectory_bit_exactly(R, contact, mu):
    a, b = mirror_pair(R, contact, mu)
    events = a.collisions_dense[..., 6]
    assert np.all(np.any(events >= 4, axis=1))  # every particle slides
    assert np.array_equal(a.positions, -b.positions)
    assert np.array_equal(a.n_recorded, b.n_recorded)
    sign = np.array([1, -1, 1, -1, 1, 1, 1])
    assert np.array_equal(a.collisions_dense * sign, b.collisions_dense, equal_nan=True)


def test_a_coulomb_particle_slipping_from_rest_near_a_shallow_cusp_reaches_it_when_scipy_says():
    # klages2004 (R = 15, θ_c = 3.8°) tilted 3°, thrown 60°, 40 Hz: held by static friction
    # 7e-9 mm from a cusp, it slips where |F_t| = μN and slides into the cusp.  It starts from
    # v = v̇ = 0: the kernel once crawled out in steps of tol_t whose position increments
    # rounded away (v h/R < ulp θ) and arrived 2.4 % late (3.7575e-5 s instead of 3.6677e-5)
    from scipy.integrate import solve_ivp
    from scipy.optimize import brentq

    mu = 0.3
    p = Params.preset("klages2004", f=40.0, tilt=3.0, throw=60.0, contact="coulomb", mu=mu)
    gx, gy = p.g * math.sin(math.radians(3.0)), p.g * math.cos(math.radians(3.0))
    ax, ay = p.A * math.cos(math.radians(60.0)), p.A * math.sin(math.radians(60.0))
    w, R = p.omega, p.R
    q0 = 0.066716147927911709
    d0 = R * math.sin(q0)
    s0 = 0.014  # floor time (s), inside the interval where friction holds it

    def forces(t, q, v=0.0):
        u = math.sin(w * t)
        Gx, Gy = gx + ax * w * w * u, gy + ay * w * w * u
        return Gy * math.sin(q) - Gx * math.cos(q), Gx * math.sin(q) + Gy * math.cos(q) - v * v / R

    def grip(t):  # > 0 while static friction holds it
        ft, n = forces(t, q0)
        return mu * n - abs(ft)

    assert grip(s0) > 0
    ts = np.linspace(s0, s0 + 0.5 / p.f, 2001)
    first = int(np.nonzero([grip(t) <= 0 for t in ts])[0][0])
    t_slip = brentq(grip, ts[first - 1], ts[first], xtol=1e-16, rtol=4 * np.finfo(float).eps)
    sgn = math.copysign(1.0, forces(t_slip, q0)[0] + forces(t_slip + 1e-9, q0)[0])

    def rhs(t, y):
        ft, n = forces(t, y[0], y[1])
        return [y[1] / R, ft - mu * n * sgn]

    def cusp(t, y):
        return abs(y[0]) - math.asin(0.5 * p.S / R)

    cusp.terminal = True
    sol = solve_ivp(rhs, [t_slip, t_slip + 1e-3], [q0, 0.0], method="DOP853", rtol=1e-13,
                    atol=1e-20, events=cusp)
    t_cusp = sol.t_events[0][0]
    y0 = -ay * math.sin(w * s0) - (R - math.sqrt(R * R - d0 * d0))
    state = InitialState(one(0, np.int64), one(d0), one(y0),
                         one(-ax * w * math.cos(w * s0)), one(-ay * w * math.cos(w * s0)), one(s0),
                         one(True, bool), one(True, bool))
    run = simulate(p, 1, 0.004, seed=0, initial=state, record_collisions=4, record_liftoffs=True)
    rows = run.collisions_dense[0, : run.n_recorded[0]]
    assert rows[0, 6] == CUSP
    assert abs(rows[0, 0] - (t_cusp - s0)) <= 1e-10


@pytest.mark.parametrize("side", [1.0, -1.0])
def test_a_bounce_exactly_at_a_cusp_leaving_both_arcs_flies(side):
    # a contact model's cusp event leaves the particle at d = ±S/2 exactly; a bounce there
    # that leaves both arcs (here: up and sideways relative to the floor) must fly, not meet the
    # neighbouring arc at τ = 0 (before 2026-11-23: r = 0 in start_step_c, so τ = 0 and a
    # collision applied with an arc the particle leaves, a chain of them at one instant)
    from bbb.dynamics.options import Floor, Frame
    from bbb.dynamics.search import STACK_DEPTH, next_collision

    p = Params.preset("klages2004", f=55.0, contact="slide", tilt=3.0, throw=60.0)
    gx, gy, Ax, Ay = p.floor_frame()
    w, s, d0 = p.omega, 0.3 / p.f, side * 0.5 * p.S
    y = -Ay * math.sin(w * s) - (p.R - math.sqrt(p.R**2 - d0 * d0))
    # relative velocity (3, 5) mm/s: the walls' slopes are ±1/15, so it leaves both
    vx, vy = -Ax * w * math.cos(w * s) + 3.0, -Ay * w * math.cos(w * s) + 5.0
    fl = Floor(0.0, 0.0, w, p.R, p.S, p.alpha, p.beta)
    tau, _, _ = next_collision((y, vy, vx, d0, s), True, False, fl, Frame(gx, gy, Ax, Ay), 1.0,
                               (1e-12, 1.0 / p.f, np.empty(STACK_DEPTH)), 2**24)
    assert tau > 1e-4


@pytest.mark.parametrize(("phi", "mu", "held"), [(10.0, 0.3, True), (10.0, 0.1, False), (-25.0, 0.0, False)])
def test_on_a_motionless_tilted_flat_floor_contact_time_is_all_held_or_all_sliding(phi, mu, held):
    # tan φ < μ: held at rest the whole run; tan φ > μ: sliding the whole run (never flies)
    assert (math.tan(math.radians(abs(phi))) < mu) == held
    run = simulate(tilted(phi, mu), 1, 0.6, seed=0, initial=at_rest(0.3))
    got = (run.contact_time["held"][0], run.contact_time["sliding"][0])
    assert got == pytest.approx((0.6, 0.0) if held else (0.0, 0.6), abs=1e-12)


def flight_time(p: Params, ev: np.ndarray, t_max: float) -> float:
    """Seconds in flight by the record alone (every event from t = 0 of a particle that starts
    at rest): each collision (event 0 or 4) ends a flight from the event before it; the run
    ends in flight after a lift-off (1, 5) or a collision that left the particle moving
    relative to the floor (a lift-off has a row only if its flight ends in a collision)."""
    ends = np.isin(ev[1:, 6], (0.0, 4.0))
    t = float(np.sum(ev[1:, 0][ends] - ev[:-1, 0][ends]))
    last = ev[-1]
    th = 2 * math.pi * last[5]
    dev = math.radians(p.throw - 90.0)
    vf = (p.A * math.sin(dev) * p.omega * math.cos(th), -p.A * math.cos(dev) * p.omega * math.cos(th))
    moving = abs(last[3] - vf[0]) + abs(last[4] - vf[1]) > 1e-9
    flying = last[6] in (1.0, 5.0) or (last[6] == 0.0 and moving)
    return t + (t_max - last[0] if flying else 0.0)


@pytest.mark.parametrize("kw", [dict(contact="coulomb", mu=0.3, throw=30.0, f=50.0),
                                dict(contact="slide", tilt=3.0, throw=60.0, f=55.0),
                                dict(contact="coulomb", mu=0.3, tilt=3.0, throw=60.0, f=55.0),
                                dict(contact="stick", tilt=3.0, throw=60.0, f=55.0)],
                         ids=["coulomb 0/30 50 Hz", "slide 3/60 55 Hz", "coulomb 3/60 55 Hz",
                              "stick 3/60 55 Hz"])
def test_conveyor_contact_time_is_the_time_not_in_flight_by_the_record(kw):
    # held + sliding = t_max − the flights' time read off the record (independent of the
    # kernel's clocks); stick never slides, and the contact models do slide here
    p = Params.preset("klages2004", **kw)
    run = simulate(p, 4, 1.0, seed=2, initial="rest", record_collisions=20_000, record_liftoffs=True)
    assert np.all(run.n_recorded < 20_000)
    held, sliding = run.contact_time["held"], run.contact_time["sliding"]
    complete = 0
    for i in range(4):
        ev = run.collisions_dense[i, : run.n_recorded[i]]
        contact = 1.0 - flight_time(p, ev, 1.0)
        # a lift-off whose flight is still in the air at t_max has no row (bbb.record): the
        # record then counts that last flight as contact
        if run.counters["liftoffs"][i] == np.count_nonzero(np.isin(ev[:, 6], (1.0, 5.0))):
            assert held[i] + sliding[i] == pytest.approx(contact, abs=1e-9)
            complete += 1
        else:
            assert held[i] + sliding[i] < contact
    assert complete >= 2
    assert (np.sum(sliding) == 0.0) == (p.contact == "stick")
    assert np.all(held >= 0.0) and np.all(sliding >= 0.0)


# ---- random inputs: tilt × throw × contact model, through the checker and brute force -------

#: simulated time per example at most (s, 3 particles): 60 floor periods, but no more than
#: this, so that no example runs long (a 5 Hz floor would otherwise run 36 particle-seconds)
T_CAP = 1.0


@pytest.fixture(scope="module", autouse=True)
def compiled():
    """Compile (or load) the conveyor kernel of each contact model before hypothesis times
    its examples."""
    for contact, mu in (("stick", 0.0), ("slide", 0.0), ("coulomb", 0.5)):
        p = Params.preset("klages2004", f=60.0, tilt=1.0, throw=80.0, contact=contact, mu=mu)
        simulate(p, 1, 0.01, seed=0, record_collisions=4, record_liftoffs=True)


@settings(max_examples=60, deadline=timedelta(seconds=10),
          suppress_health_check=[HealthCheck.too_slow])
@given(
    f=st.floats(5.0, 200.0),
    A=st.floats(0.0, 1.0),
    radius=st.one_of(st.floats(1.05, 60.0), st.floats(1.05, 2.0), st.just(math.inf)),
    alpha=st.floats(0.05, 1.0),
    beta=st.floats(0.0, 1.0),
    tilt=st.one_of(st.floats(-30.0, 30.0), st.sampled_from([-30.0, 0.0, 30.0])),
    throw=st.one_of(st.floats(10.0, 170.0), st.sampled_from([10.0, 90.0, 170.0])),
    model=st.one_of(st.just(("stick", 0.0)), st.just(("slide", 0.0)),
                    st.tuples(st.just("coulomb"), st.floats(0.0, 3.0))),
    family=st.sampled_from(["rest", "dropped", "launched"]),
    seed=st.integers(0, 2**32 - 1),
)
# found by this test or the random search behind it, each a fault fixed (kernel or checker)
@example(f=10.0, A=1.0, radius=1.125, alpha=1.0, beta=0.0, tilt=0.0, throw=10.0,
         model=("slide", 0.0), family="rest", seed=0)  # zero-time ping-pong at a cusp (checker)
@example(f=16.0, A=1.0, radius=1.125, alpha=0.5, beta=0.0, tilt=0.0, throw=60.0,
         model=("slide", 0.0), family="dropped", seed=0)  # rest in a cusp after a cascade
@example(f=16.0, A=1.0, radius=1.5, alpha=1.0, beta=0.0, tilt=26.0, throw=64.0,
         model=("slide", 0.0), family="rest", seed=0)  # slip and lift-off at once
@example(f=16.0, A=1.0, radius=1.125, alpha=0.5, beta=0.0, tilt=28.0, throw=62.0,
         model=("slide", 0.0), family="rest", seed=0)  # a one-ulp slip interval
@example(f=16.0, A=1.0, radius=1.125, alpha=0.5, beta=0.0, tilt=30.0, throw=60.0,
         model=("slide", 0.0), family="rest", seed=0)  # the wall at a vanishing gravity
@example(f=19.0, A=1.0, radius=1.25, alpha=0.5, beta=0.0, tilt=0.0, throw=10.0,
         model=("coulomb", 9.665576467554072e-63), family="rest", seed=0)  # a slip with μN ≈ 0
@example(f=5.0, A=1.0, radius=1.0625, alpha=0.125, beta=1.0, tilt=0.0, throw=10.0,
         model=("slide", 0.0), family="rest", seed=0)  # the wall met in a steep cusp
@example(f=34.338035417555375, A=0.8930488166285763, radius=1.0654771972056567,
         alpha=0.3979875734303109, beta=0.17191560720598842, tilt=-21.83309838835644,
         throw=106.23038599435573, model=("coulomb", 1.2594203117868616), family="launched",
         seed=2775301032)  # a slip up the neighbour's wall from within CUSP_REACH (crawled)
@example(f=80.0, A=0.5, radius=1.1640625, alpha=0.125, beta=1.0, tilt=2.7552364056913973e-14,
         throw=90.0, model=("slide", 0.0), family="rest", seed=0)  # leaving both walls of a cusp
@example(f=159.17797533443758, A=0.9358020402058362, radius=51.84506391172527,
         alpha=0.32812351320659694, beta=0.9958783676717431, tilt=0.0, throw=17.246952467194383,
         model=("coulomb", 1.5392620528858287), family="dropped",
         seed=2646913958)  # x's rounding over a flight of many periods (checker)
def test_no_contact_model_on_a_tilted_and_thrown_floor_breaks_the_checker(
        f, A, radius, alpha, beta, tilt, throw, model, family, seed):
    """The conveyor kernel under every contact model (stick, slide, Coulomb with μ up to 3)
    on tilted and thrown floors: every flight, carried stretch, lift-off, slip and sliding
    stretch passes the independent checker (tests/bbb/trajectory_check.py, nothing tolerated),
    the brute-force grid finds no flight point below the surface, nothing is non-finite, and
    the kernel's guards never stop a particle (simulate would raise).  R ≥ 1.05 S/2 (bbb.Params
    refuses sliding on steeper cusp walls); 3 particles for 60 periods, at most T_CAP s."""
    contact, mu = model
    p = Params(g=9800.0, A=A, f=f, R=radius, S=2.0, alpha=alpha, beta=beta, tilt=tilt,
               throw=throw, contact=contact, mu=mu)
    st_ = initial_state(p, 3, np.random.SeedSequence(seed), family, drop_height=(0.0, 1.0),
                        launch_speed=(0.0, 150.0))
    run = simulate(p, 3, min(60.0 / f, T_CAP), seed=seed, initial=st_, record_collisions=400,
                   record_liftoffs=True, _force_conveyor=True)
    assert_no_miss(p, st_, run)


def pinned(**kw):
    return test_no_contact_model_on_a_tilted_and_thrown_floor_breaks_the_checker.hypothesis.inner_test(**kw)


def test_a_coulomb_particle_held_in_a_cusp_does_not_slide_up_a_wall_that_has_let_go():
    """One of the two examples the random search found (f = 80.13, A = 0.578, R = 1.2, tilt
    0.05, throw 10, μ = 2, from rest, seed 988): a particle held in a cusp 'slipped' up the
    wall whose normal load had turned negative (N = −6731 mm/s² there, the other wall pressing
    with +15020 and holding it, its pull 29073 mm/s² short of μN) and lifted off that wall at
    once; all three particles failed the checker (contact_start, path, normal, event)."""
    pinned(f=80.13102688360905, A=0.5779023108959392, radius=1.2, alpha=0.05, beta=0.0,
           tilt=0.05, throw=10.0, model=("coulomb", 2.0), family="rest", seed=988)


def test_a_coulomb_particle_sliding_slowly_into_a_cusp_reaches_it_without_crawling():
    """The other example (f = 120.66, A = 0.0375, R = 1.05, α = 0.05, β = 0.118, tilt = throw
    = 29.6, μ = 2, dropped, seed 341): the same wrong slip, then a Coulomb stop 6e-14 mm from
    the cusp, and a slide from rest into it whose increments v h/R fell below ulp(θ)/2: the
    particle did not move while its speed grew, ~3e6 RK4 steps of ≤ tol_t per stretch (67 s
    for 1.5 particle-seconds).  It passes the checker, and no contact stretch of it runs a step
    debt (bbb.contact: tried steps beyond 64 per nominal step) within a factor 100 of the
    crawl's 3.1e6 steps (1.4e3 now)."""
    pinned(f=120.66361006138334, A=0.03752289548439736, radius=1.05, alpha=0.05,
           beta=0.1182055142536225, tilt=29.60906544749591, throw=29.60906544749591,
           model=("coulomb", 2.0), family="dropped", seed=341)
    p = Params(g=9800.0, A=0.03752289548439736, f=120.66361006138334, R=1.05, S=2.0, alpha=0.05,
               beta=0.1182055142536225, tilt=29.60906544749591, throw=29.60906544749591,
               contact="coulomb", mu=2.0)
    guards = np.zeros((3, 5))
    simulate(p, 3, 60.0 / p.f, seed=341, initial=initial_state(
        p, 3, np.random.SeedSequence(341), "dropped", drop_height=(0.0, 1.0)), _guards=guards)
    assert np.max(guards[:, 1]) < 3.1e6 / 100
