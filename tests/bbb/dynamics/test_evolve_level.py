"""The collision map against analytic results, invariants and brute force."""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from bbb import Numerics, Params, simulate
from bbb.ensemble import InitialState, initial_state
from tests.bbb.flight_check import gap_along_flights, on_surface_tolerance
from tests.bbb.no_miss import assert_no_miss
from tests.bbb.trajectory_check import check_particle, start_event

ALPHA = 0.7
# Period-1 orbit of a ball on a flat sinusoidal plate (restitution α): it exists for
# Γ ≥ Γ1 = π(1-α)/(1+α) and is linearly stable for Γ < Γ2 = sqrt(Γ1² + [2(1+α²)/(1+α)²]²)
# (Holmes 1982; Tufillaro, Abbott & Reilly 1992, ch. 3); its launch speed is g/(2f).
GAMMA1 = math.pi * (1 - ALPHA) / (1 + ALPHA)
GAMMA2 = math.hypot(GAMMA1, 2 * (1 + ALPHA**2) / (1 + ALPHA) ** 2)


def period_one_run(gamma: float, R: float, periods: int = 3000):
    """Start 1 % off the period-1 orbit of a flat-floor ball; return the last post-collision
    vertical speeds in units of g/(2f) and flight times in floor periods."""
    A, g = 0.1, 9800.0
    w = math.sqrt(gamma * g / A)
    f = w / (2 * math.pi)
    p = Params(g=g, A=A, f=f, R=R, S=2.0, alpha=ALPHA, beta=0.99)
    V = g / (2 * f)
    # launch phase of the orbit: floor velocity -Aw cos θ = V(1-α)/(1+α), θ in (π, 3π/2)
    theta = math.pi + math.acos(min(GAMMA1 / gamma, 1.0))
    one = np.ones(1)
    state = InitialState(np.zeros(1, np.int64), 0.0 * one, -A * math.sin(theta) * one, 0.0 * one,
                         1.01 * V * one, theta / w * one, np.zeros(1, bool), np.ones(1, bool))
    run = simulate(p, 1, periods / f, seed=0, initial=state, record_collisions=3 * periods)
    rows = run.collisions_dense[0, : run.n_recorded[0]]
    return rows[-6:, 4] / V, np.diff(rows[-6:, 0]) * f, run.n_recorded[0]


@pytest.mark.parametrize("R", [math.inf, 1e8])
@pytest.mark.parametrize("gamma", [1.1 * GAMMA1, 0.5 * (GAMMA1 + GAMMA2), 0.97 * GAMMA2])
def test_flat_floor_period_one_orbit_is_stable_inside_the_analytic_window(gamma, R):
    v, flights, _ = period_one_run(gamma, R)
    assert np.allclose(v, 1.0, atol=1e-6)
    assert np.allclose(flights, 1.0, atol=1e-6)


@pytest.mark.parametrize("R", [math.inf, 1e8])
def test_flat_floor_period_one_orbit_is_unstable_just_above_the_window(R):
    v, _, _ = period_one_run(1.03 * GAMMA2, R)
    assert np.max(np.abs(v - 1.0)) > 0.05


@pytest.mark.parametrize("R", [math.inf, 1e8])
def test_flat_floor_period_one_orbit_does_not_exist_below_the_window(R):
    # below Γ1 the particle cannot keep launching at g/(2f): it chatters down and sticks
    v, _, n = period_one_run(0.95 * GAMMA1, R)
    assert n < 1000 and np.max(np.abs(v - 1.0)) > 0.5


@pytest.mark.parametrize("R", [15.0, 1.0, math.inf])
def test_energy_is_conserved_on_an_elastic_motionless_floor(R):
    p = Params(g=9800.0, A=0.0, f=50.0, R=R, S=2.0, alpha=1.0, beta=1.0)
    run = simulate(p, 1, 8000.0, seed=3, initial="dropped", drop_height=(1.0, 3.0),
                   record_collisions=100_000)
    rows = run.collisions_dense[0, : run.n_recorded[0]]
    assert rows.shape[0] == 100_000
    energy = 0.5 * (rows[:, 3] ** 2 + rows[:, 4] ** 2) + p.g * rows[:, 2]
    assert np.max(np.abs(energy / energy[0] - 1.0)) <= 1e-9


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    f=st.floats(5.0, 200.0),
    A=st.floats(0.0, 1.0),
    radius=st.one_of(st.floats(1.0, 60.0), st.just(1.0), st.just(math.inf)),
    alpha=st.floats(0.05, 1.0),
    beta=st.floats(0.0, 1.0),
    family=st.sampled_from(["rest", "dropped", "launched"]),
    seed=st.integers(0, 2**32 - 1),
)
def test_no_collision_is_missed_and_no_particle_goes_below_the_surface(f, A, radius, alpha, beta,
                                                                       family, seed):
    """The independent trajectory checker passes every recorded flight, collision and
    lift-off, from the initial state on; the brute-force grid finds no point below."""
    p = Params(g=9800.0, A=A, f=f, R=radius, S=2.0, alpha=alpha, beta=beta)
    st = initial_state(p, 3, np.random.SeedSequence(seed), family, drop_height=(0.0, 1.0),
                       launch_speed=(0.0, 150.0))
    run = simulate(p, 3, 60.0 / f, seed=seed, initial=st, record_collisions=300, record_liftoffs=True)
    for i in range(3):
        rows = run.collisions_dense[i, : run.n_recorded[i]]
        assert np.all(np.isfinite(rows))
        start = start_event(p, st.cell[i], st.d[i], st.y[i], st.vx[i], st.vy[i], st.s[i], st.stuck[i])
        rep = check_particle(p, np.vstack([start, rows]))
        assert rep.ok, rep.messages
        # brute force: between two recorded collisions the particle stays above the surface
        worst, _ = gap_along_flights(p, rows, n_grid=200)
        assert worst > -on_surface_tolerance(p)
    assert run.counters["anomalies"].sum() == 0


def test_a_sticking_collision_at_a_subnormal_amplitude_passes_the_velocity_rule():
    """Found by hypothesis inside the main domain (A = 2.2e-311 mm, f = 5, R = 51, launched,
    seed 112, particle 2, event 14): the checker's fault, not the kernel's.  Its rounding bound
    on a floor velocity was relative, 16 ε Aω, which underflows to ~0 for a subnormal A, whose
    numbers have an absolute spacing (5e-324): the kernel's and the checker's floor velocities
    (3e-310 mm/s) differed by a few spacings.  The bound is now 32 spacings of Aω (Floor.vf_tol)."""
    test_no_collision_is_missed_and_no_particle_goes_below_the_surface.hypothesis.inner_test(
        f=5.0, A=2.225073858507e-311, radius=51.0, alpha=0.421875, beta=0.8125,
        family="launched", seed=112)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    f=st.floats(5.0, 200.0),
    A=st.floats(0.0, 1.0),
    radius=st.one_of(st.floats(1.05, 60.0), st.just(math.inf)),
    alpha=st.floats(0.05, 1.0),
    beta=st.floats(0.0, 1.0),
    tilt=st.one_of(st.floats(-30.0, 30.0), st.sampled_from([-30.0, 30.0])),
    throw=st.one_of(st.floats(10.0, 170.0), st.sampled_from([10.0, 90.0, 170.0])),
    family=st.sampled_from(["rest", "dropped", "launched"]),
    seed=st.integers(0, 2**32 - 1),
)
def test_no_collision_is_missed_on_a_tilted_and_thrown_floor(f, A, radius, alpha, beta, tilt,
                                                            throw, family, seed):
    """The conveyor kernel (bbb.conveyor) under the same independent checker and brute force,
    every check included: the checker certifies flights across a cusp on both whole circles,
    so no flight is left 'uncertified' (none has been since the checker's whole-circle bounds).
    The vertical cusps of R < 1.05 S/2 are refused on the conveyor (bbb.Params: flights below
    the surface there are an open fault), so R starts at 1.05."""
    p = Params(g=9800.0, A=A, f=f, R=radius, S=2.0, alpha=alpha, beta=beta, tilt=tilt,
               throw=throw)
    st = initial_state(p, 3, np.random.SeedSequence(seed), family, drop_height=(0.0, 1.0),
                       launch_speed=(0.0, 150.0))
    run = simulate(p, 3, 60.0 / f, seed=seed, initial=st, record_collisions=300,
                   record_liftoffs=True, _force_conveyor=True)
    assert_no_miss(p, st, run)


def test_a_particle_carried_at_a_cusp_of_a_thrown_floor_lifts_off_when_both_arcs_let_go():
    """The example hypothesis found (f = 53, A = 1, R = 1.5, α = 0.25, β = 0, ψ = 10°, from
    rest, seed 0): the kernel lifted off on one arc's normal while the other still held the
    particle and met it again ~1e-10 s later, hundreds of times a period (issue 14)."""
    test_no_collision_is_missed_on_a_tilted_and_thrown_floor.hypothesis.inner_test(
        f=53.0, A=1.0, radius=1.5, alpha=0.25, beta=0.0, tilt=0.0, throw=10.0, family="rest",
        seed=0)


def test_no_collision_is_missed_at_high_frequency_with_many_floor_periods_per_flight():
    # Γ ≈ 8: the floor completes several periods during one flight
    p = Params(g=9800.0, A=0.05, f=200.0, R=15.0, S=2.0, alpha=0.7, beta=0.99)
    run = simulate(p, 4, 2.0, seed=11, initial="launched", launch_speed=(50.0, 200.0),
                   record_collisions=400)
    flights_in_periods = []
    for i in range(4):
        rows = run.collisions_dense[i, : run.n_recorded[i]]
        worst, checked = gap_along_flights(p, rows, per_period=400)
        assert worst > -1e-9 and checked > 50
        flights_in_periods.append(np.max(np.diff(rows[:, 0])) * p.f)
    assert max(flights_in_periods) > 3


def test_mean_displacement_vanishes_on_the_symmetric_floor():
    p = Params.preset("klages2004", f=70.0)
    run = simulate(p, 400, 10.0, seed=5, initial="launched", sample_times=np.array([0.0, 10.0]))
    dx = run.positions[:, -1] - run.positions[:, 0]
    stderr = dx.std(ddof=1) / math.sqrt(dx.size)
    assert stderr > 0
    assert abs(dx.mean()) < 3.5 * stderr


def test_particle_at_rest_never_lifts_off_below_gamma_one():
    p = Params.preset("klages2004", f=48.0)
    assert p.gamma < 1
    run = simulate(p, 50, 5.0, seed=2, initial="rest", sample_times=np.linspace(0, 5, 11))
    assert run.counters["liftoffs"].sum() == 0 and run.counters["collisions"].sum() == 0
    assert np.all(run.positions == run.positions[:, :1])


def test_particle_at_rest_lifts_off_above_gamma_one():
    run = simulate(Params.preset("klages2004", f=52.0), 20, 0.5, seed=2, initial="rest")
    assert np.all(run.counters["liftoffs"] >= 1)


@pytest.mark.parametrize("family", ["rest", "dropped", "launched"])
def test_same_seed_gives_bit_identical_output(family):
    kw = dict(seed=np.random.SeedSequence(9, spawn_key=(60000, 1)), initial=family,
              sample_times=np.linspace(0, 2, 21), record_collisions=50)
    p = Params.preset("klages2004", f=60.0)
    a = simulate(p, 30, 2.0, **kw)
    b = simulate(p, 30, 2.0, **kw)
    assert np.array_equal(a.positions, b.positions)
    assert np.array_equal(a.collisions_dense, b.collisions_dense, equal_nan=True)


def test_different_seeds_give_different_trajectories():
    p = Params.preset("klages2004", f=60.0)
    times = np.linspace(0, 2, 5)
    a = simulate(p, 10, 2.0, seed=1, initial="launched", sample_times=times)
    b = simulate(p, 10, 2.0, seed=2, initial="launched", sample_times=times)
    assert not np.array_equal(a.positions, b.positions)


def test_sticking_threshold_ends_creeping_cascades():
    # at f = 54 particles from rest creep: long cascades cut by sticking episodes
    p = Params.preset("klages2004", f=54.0)
    run = simulate(p, 20, 1.0, seed=4, initial="rest", numerics=Numerics(v_stick=1e-2))
    assert run.counters["sticks"].sum() > 0
    assert np.all(run.counters["liftoffs"] >= run.counters["sticks"] - 1)


def test_soft_impacts_in_a_vertical_cusp_end_in_sticking_not_an_endless_zeno_sequence():
    # found by hypothesis: R = S/2, alpha = 0.05, beta = 1, Γ ≈ 10.  A soft impact on a wall
    # whose arc falls away may fly off with v_stick, but the facing wall of the cusp sends the
    # particle straight back; kicking again every time never ended.
    p = Params(g=9800.0, A=1.0, f=50.09734740894464, R=1.0, S=2.0, alpha=0.05, beta=1.0)
    run = simulate(p, 3, 1.2, seed=0, initial="dropped", drop_height=(0.0, 1.0), record_collisions=300)
    assert np.all(run.counters["collisions"] < 1000)
    assert np.all(run.counters["sticks"] >= 1)
