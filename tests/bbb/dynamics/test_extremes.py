"""Numerical stability at the edges of every parameter (issue 5), table-driven.

Each row of ``CASES`` is one extreme (alpha → 0 or 1, beta = 0 or 1, R = S/2 or ∞, A = 0 or
Γ ≫ 1, f tiny or huge, grazing, cusps, starts on the surface, 10⁶ floor periods) with the
*physical* claim that must hold there.  Every row is also held to the invariants that hold
everywhere: every recorded value is finite, no velocity needed repair, the independent
trajectory checker (tests/bbb/trajectory_check.py) passes every recorded flight and lift-off
(each collision where the previous flight's parabola meets the moving surface, Eqs. (5)-(6),
the gap ≥ 0 in between, lift-off at the first moment the floor lets go), and a brute-force
fine-grid search finds no point of any recorded flight below the surface.
``benchmarks/checks/soak.py`` drives the same table to ≥ 10⁹ collisions, so a row must make sense for
any number of particles and any seed.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import pytest

from bbb import Params, SimRun, simulate
from bbb.dynamics.evolve import evolve_ensemble
from bbb.dynamics.options import Floor as KernelFloor
from bbb.dynamics.options import Run
from bbb.ensemble import InitialState, initial_state
from bbb.numerics import Numerics
from bbb.record import COLLISION_FIELDS, COUNTER_NAMES
from bbb.surface import cell_of, depth, surface_normal
from tests.bbb.flight_check import gap_along_flights, on_surface_tolerance
from tests.bbb.trajectory_check import Floor, Report, _rest_loads, check_particle, start_event

G = 9800.0
BASE = dict(g=G, A=0.1, f=60.0, R=15.0, S=2.0, alpha=0.7, beta=0.99)
#: brute force checks at most this many flights per particle (the 10⁶-period run has ~10⁶)
MAX_FLIGHTS_CHECKED = 3000
#: Γ = 3 at 1000 Hz: A = 3 g / (2π f)²
A_1000HZ = 3.0 * G / (2 * math.pi * 1000.0) ** 2


def params(**changes: float | str) -> Params:
    return Params(**{**BASE, **changes})


# ---- what a case is -------------------------------------------------------------------------


Builder = Callable[[Params, int, np.random.Generator], InitialState]
Claim = Callable[[Params, InitialState, SimRun], None]


@dataclass(frozen=True)
class Case:
    """One extreme: parameters, how particles start, how long they run, the claim, and what
    its run exercises (``exercises``).

    ``initial`` is a family name of ``bbb.ensemble`` (with ``family_kw``) or a builder
    ``(params, n, rng) -> InitialState``; a builder may use ``rng`` only for what the claim
    does not depend on, so that the soak can run many different particles through it."""

    name: str
    params: Params
    initial: str | Builder
    claim: Claim
    n: int = 6
    t_max: float = 2.0
    record: int = 2000
    family_kw: dict = field(default_factory=dict)
    per_period: int = 200
    xfail: str | None = None
    #: what the case's run exercises, each checked by the invariants only where it happened:
    #: "flights", "carried" (stuck stretches and their lift-offs), "contacts" (sliding
    #: stretches); a case that declares one must have at least one of it (no vacuous pass)
    exercises: tuple[str, ...] = ("flights",)


def start(case: Case, n: int, seed: int) -> InitialState:
    """The initial states of ``n`` particles of ``case`` drawn from ``seed``."""
    if isinstance(case.initial, str):
        return initial_state(case.params, n, np.random.SeedSequence(seed), case.initial, **case.family_kw)
    return case.initial(case.params, n, np.random.default_rng(seed))


def run_case(case: Case, n: int, t_max: float, seed: int, record: int, record_from: float = 0.0,
             n_samples: int = 101) -> tuple[InitialState, SimRun]:
    st = start(case, n, seed)
    run = simulate(case.params, n, t_max, seed=seed, initial=st, record_collisions=record,
                   record_from=record_from, sample_times=np.linspace(0.0, t_max, n_samples),
                   record_liftoffs=True)
    return st, run


def events_of(run: SimRun, i: int) -> np.ndarray:
    """Particle i's recorded rows: collisions and (if recorded) lift-offs, in time order."""
    return run.collisions_dense[i, : run.n_recorded[i]]


def rows_of(run: SimRun, i: int) -> np.ndarray:
    """Particle i's recorded post-collision rows (t, x, y, vx, vy, phase), lift-offs left out."""
    ev = events_of(run, i)
    return ev[ev[:, 6] == 0.0, :6] if run.liftoffs else ev


def surface_at(p: Params, x: np.ndarray, phase: np.ndarray) -> np.ndarray:
    """Surface height (mm) under x (mm) at floor phase ``phase`` (periods)."""
    _, d = cell_of(x, p.S)
    return -p.A * np.sin(2 * np.pi * phase) - depth(d, p.R)


def floor_velocity(p: Params, phase: np.ndarray) -> np.ndarray:
    return -p.A * p.omega * np.cos(2 * np.pi * phase)


def is_stuck(p: Params, rows: np.ndarray) -> np.ndarray:
    """Rows that ended in sticking: at rest relative to the floor (the kernel's rule)."""
    return (rows[:, 3] == 0.0) & (np.abs(rows[:, 4] - floor_velocity(p, rows[:, 5])) < 1e-9)


def energy(p: Params, rows: np.ndarray) -> np.ndarray:
    return 0.5 * (rows[:, 3] ** 2 + rows[:, 4] ** 2) + p.g * rows[:, 2]


def impacts(p: Params, rows: np.ndarray) -> dict[str, np.ndarray]:
    """For each recorded collision after the first: the velocity relative to the floor in
    the arc's normal/tangential frame just before (``un_in``, ``ut_in``, from the previous
    row's flight) and just after (``un_out``, ``ut_out``); ``from_flight`` is False where
    the previous row ended stuck (that flight starts at an unrecorded lift-off);
    ``weight`` is the normal component of gravity in the floor's frame, (g + a_floor) n_y."""
    before, after = rows[:-1], rows[1:]
    vf = floor_velocity(p, after[:, 5])
    nx, ny = surface_normal(p, after[:, 1])
    ux_in, uy_in = before[:, 3], before[:, 4] - p.g * np.diff(rows[:, 0]) - vf
    ux_out, uy_out = after[:, 3], after[:, 4] - vf
    floor_a = p.A * p.omega**2 * np.sin(2 * np.pi * after[:, 5])
    return dict(from_flight=~is_stuck(p, before), stuck=is_stuck(p, after),
                speed_in=np.hypot(ux_in, uy_in), weight=(p.g + floor_a) * ny,
                un_in=ux_in * nx + uy_in * ny, ut_in=ux_in * ny - uy_in * nx,
                un_out=ux_out * nx + uy_out * ny, ut_out=ux_out * ny - uy_out * nx)


def invariant_violations(p: Params, run: SimRun, per_period: int = 200, flights: int = MAX_FLIGHTS_CHECKED,
                         brute_force_particles: int | None = None,
                         start: InitialState | None = None) -> dict[str, float]:
    """Everything that must never happen, whatever the parameters, counted over a run:
    non-finite recorded values or positions, repaired velocities ('anomalies'), and on the
    last ``flights`` recorded events of the first ``brute_force_particles`` particles (all by
    default) the trajectory checker's failures — 'off_surface' (clock, parabola, surface),
    'rule' (Eqs. (5)-(6)), 'liftoff' (carried stretches and lift-offs), 'gap' (a flight
    below the surface or not certified above it) — and the lowest brute-force gap
    (flight_check.gap_along_flights; negative: a point of a flight below the surface).
    ``start``: the run's initial states, when it recorded from t = 0: the first flight (or
    carried stretch) is checked too.  ``below`` counts particles with any of these faults."""
    nonfinite = int(np.count_nonzero(~np.isfinite(run.positions)))
    tol = on_surface_tolerance(p)
    rows_checked = n_flights = below = 0
    worst_gap = math.inf
    total = Report()
    for i in range(run.n_particles):
        ev = events_of(run, i)
        bad = int(np.count_nonzero(~np.isfinite(ev)))
        good = ev[np.all(np.isfinite(ev), axis=1)]
        if start is not None and good.shape[0] <= flights:
            good = np.vstack([start_event(p, start.cell[i], start.d[i], start.y[i], start.vx[i], start.vy[i],
                                          start.s[i], start.stuck[i]), good])
        good = good[-flights - 1:]
        gap = math.inf
        rep = Report()
        if brute_force_particles is None or i < brute_force_particles:
            gap, checked = gap_along_flights(p, good, per_period=per_period)
            n_flights += checked
            rep = check_particle(p, good, per_period=per_period)
            total.add(rep)
        nonfinite += bad
        rows_checked += ev.shape[0]
        worst_gap = min(worst_gap, gap)
        below += bool(not rep.ok or gap <= -tol or run.counters["anomalies"][i])
    f = total.failures
    return dict(nonfinite=nonfinite, rows=rows_checked, checked=total.flights + total.carried,
                checked_flights=total.flights, carried=total.carried,
                off_surface=f["clock"] + f["off_parabola"] + f["off_surface"], rule=f["velocity"],
                liftoff=f["carried"] + f["liftoff_state"] + f["liftoff_time"] + f["stuck_flight"],
                gap=f["below"] + f["uncertified"], messages=total.messages,
                contact=f["contact_start"] + f["contact_path"] + f["contact_normal"] + f["contact_event"],
                contacts=total.contacts,
                anomalies=int(run.counters["anomalies"].sum()), flights=n_flights, worst_gap=worst_gap,
                below=below)


# ---- builders of explicit initial states ----------------------------------------------------


def state(n: int, d, y, vx, vy, s, cell=0, stuck=False, from_surface=False) -> InitialState:
    def arr(v, dtype=float):
        return np.broadcast_to(np.asarray(v, dtype=dtype), (n,)).copy()

    return InitialState(arr(cell, np.int64), arr(d), arr(y), arr(vx), arr(vy), arr(s),
                        arr(stuck, bool), arr(from_surface, bool))


def drop_above_cusp(p: Params, n: int, rng: np.random.Generator) -> InitialState:
    """At rest 0.2–2 mm above the cusp x = S/2, at a random floor phase."""
    s = rng.uniform(0.0, 1.0 / p.f, n)
    d = 0.5 * p.S
    return state(n, d, -p.A * np.sin(p.omega * s) - depth(d, p.R) + rng.uniform(0.2, 2.0, n), 0.0, 0.0, s)


def drop_sideways(p: Params, n: int, rng: np.random.Generator) -> InitialState:
    """1 mm above the surface at rest vertically, moving sideways at ±(20–80) mm/s."""
    s = rng.uniform(0.0, 1.0 / p.f, n)
    d = rng.uniform(-0.5 * p.S, 0.5 * p.S, n)
    vx = rng.choice([-1.0, 1.0], n) * rng.uniform(20.0, 80.0, n)
    return state(n, d, -p.A * np.sin(p.omega * s) - depth(d, p.R) + 1.0, vx, 0.0, s)


def graze(height: float) -> Builder:
    """On a motionless floor (A = 0), a parabola whose apex lies ``height`` mm above the top
    of arc 0 (x = 0), flown at 800–1200 mm/s: its curvature g/vx² < 1/R, so near the top it
    stays above the arc except within the apex ``height`` (if negative)."""

    def build(p: Params, n: int, rng: np.random.Generator) -> InitialState:
        assert p.A == 0.0 and G / 800.0**2 < 1.0 / p.R
        vx = rng.uniform(800.0, 1200.0, n)
        d0 = rng.uniform(-0.95, -0.5, n) * 0.5 * p.S
        t_apex = -d0 / vx
        return state(n, d0, height - 0.5 * p.g * t_apex**2, vx, p.g * t_apex, 0.0)

    return build


def tiny_launch(p: Params, n: int, rng: np.random.Generator) -> InitialState:
    """Exactly on the surface, leaving it vertically at 1e-9 mm/s relative to the floor."""
    st = initial_state(p, n, np.random.SeedSequence(int(rng.integers(2**32))), "rest")
    return state(n, st.d, st.y, 0.0, st.vy + 1e-9, st.s, from_surface=True)


# ---- the physical claims --------------------------------------------------------------------


def energy_is_conserved(p: Params, st: InitialState, run: SimRun) -> None:
    # α = β = 1 on a motionless floor: Eqs. (5)-(6) reflect the velocity, g conserves E
    e0 = 0.5 * (st.vx**2 + st.vy**2) + p.g * st.y
    for i in range(run.n_particles):
        rows = rows_of(run, i)
        assert rows.shape[0] > 100
        assert np.max(np.abs(energy(p, rows) / e0[i] - 1.0)) <= 1e-9


def every_collision_sticks_and_x_never_changes(p: Params, st: InitialState, run: SimRun) -> None:
    # α = 1e-6: the outgoing normal speed α|u_n| < v_stick at once; lift-offs are vertical
    assert np.all(run.counters["collisions"] >= 1)
    assert np.array_equal(run.counters["sticks"], run.counters["collisions"])
    assert np.all(run.positions == (st.cell * p.S + st.d)[:, None])


def vx_is_zero_after_every_collision(p: Params, st: InitialState, run: SimRun) -> None:
    # β = 0 on a flat floor: the tangential velocity (= vx) is lost at the first impact,
    # so x moves only during the first flight
    for i in range(run.n_particles):
        rows = rows_of(run, i)
        assert rows.shape[0] > 2 and np.all(rows[:, 3] == 0.0)
        x0 = st.cell[i] * p.S + st.d[i]
        assert rows[0, 1] == pytest.approx(x0 + st.vx[i] * rows[0, 0], abs=1e-12)
        assert np.all(rows[:, 1] == rows[0, 1]) and run.positions[i, -1] == rows[0, 1]


def tangential_relative_velocity_vanishes(p: Params, st: InitialState, run: SimRun) -> None:
    # β = 0, Eq. (6): v⁺_∥ = v_f∥ after every collision, on curved arcs too
    n_rows = 0
    for i in range(run.n_particles):
        rows = rows_of(run, i)
        nx, ny = surface_normal(p, rows[:, 1])
        ux, uy = rows[:, 3], rows[:, 4] - floor_velocity(p, rows[:, 5])
        assert np.all(np.abs(ux * ny - uy * nx) <= 1e-9 * (1.0 + np.hypot(ux, uy)))
        n_rows += int(np.count_nonzero(rows[:, 3]))
    assert n_rows > 100  # the arcs did turn vertical impacts into sideways motion


def restitution_holds_at_every_collision(p: Params, st: InitialState, run: SimRun) -> None:
    """Eqs. (5)-(6) at each collision that ends a recorded flight: in the floor frame the
    normal speed is reversed and scaled by α, the tangential one scaled by β; an outgoing
    normal speed below v_stick would end in riding with the floor (checked where it occurs:
    at Γ = 29 no recorded collision does, the trajectory checker covers that rule elsewhere).
    At Γ ≫ 1 the floor moves at Aω ≈ 750 mm/s: no collision may gain speed from rounding."""
    v_stick = Numerics().v_stick
    n_checked = 0
    for i in range(run.n_particles):
        rows = rows_of(run, i)
        if rows.shape[0] < 2:
            continue
        m = impacts(p, rows)
        tol = 1e-9 * (1.0 + m["speed_in"])
        bounce = m["from_flight"] & (p.alpha * np.abs(m["un_in"]) >= 2 * v_stick)
        assert np.all(np.abs(m["un_out"] + p.alpha * m["un_in"])[bounce] <= tol[bounce])
        assert np.all(np.abs(m["ut_out"] - p.beta * m["ut_in"])[bounce] <= tol[bounce])
        stick = m["from_flight"] & (p.alpha * np.abs(m["un_in"]) < 0.5 * v_stick)
        assert np.all(m["stuck"][stick])
        n_checked += int(np.count_nonzero(bounce))
    assert n_checked > 100


def x_never_changes(p: Params, st: InitialState, run: SimRun) -> None:
    # R = ∞: the normal is vertical, nothing ever pushes a vx = 0 particle sideways
    x0 = (st.cell * p.S + st.d)[:, None]
    assert np.all(run.counters["collisions"] > 10)
    assert np.all(run.positions == x0)
    for i in range(run.n_particles):
        assert np.all(rows_of(run, i)[:, 1] == x0[i])


def x_drifts_less_than_a_nanometre_per_second(p: Params, st: InitialState, run: SimRun) -> None:
    # R = 10¹² mm: normals tilt by |d|/R ≤ 1e-12, a vx ~ 1e-10 mm/s kick per collision
    x0 = (st.cell * p.S + st.d)[:, None]
    assert np.all(run.counters["collisions"] > 10)
    assert np.max(np.abs(run.positions - x0)) < 1e-6 * run.t_max


def every_particle_comes_to_rest(p: Params, st: InitialState, run: SimRun) -> None:
    # A = 0: nothing feeds energy in, the bounce cascade ends in sticking (and the floor
    # never lifts anything off again), so positions freeze and D → 0
    assert np.all(run.counters["sticks"] == 1) and np.all(run.counters["liftoffs"] == 0)
    half = run.positions.shape[1] // 2
    assert np.all(run.positions[:, half:] == run.positions[:, -1:])
    for i in range(run.n_particles):
        assert is_stuck(p, rows_of(run, i)[-1:])[0]


def cascade_ends_when_a_motionless_floors_would(p: Params, st: InitialState, run: SimRun) -> None:
    """f = 0.5 Hz: the floor moves at ≤ Aω ≈ 0.3 mm/s against impacts of ~100 mm/s, so the
    cascade from rest at height h lasts as on a motionless floor, sqrt(2h/g)(1+α)/(1-α),
    within 0.2 %; Γ ≈ 1e-4, so it is never lifted off again."""
    h = st.y - surface_at(p, st.cell * p.S + st.d, st.s * p.f)
    expected = np.sqrt(2 * h / p.g) * (1 + p.alpha) / (1 - p.alpha)
    assert np.all(run.counters["sticks"] == 1) and np.all(run.counters["liftoffs"] == 0)
    t_rest = np.array([rows_of(run, i)[-1, 0] for i in range(run.n_particles)])
    assert np.allclose(t_rest, expected, rtol=2e-3)


def many_floor_periods_pass_during_a_flight(p: Params, st: InitialState, run: SimRun) -> None:
    # f = 1000 Hz: the invariants' brute force (400 points per period) covers these flights
    longest = max(np.max(np.diff(rows_of(run, i)[:, 0])) for i in range(run.n_particles))
    assert longest * p.f > 10


def flight_over_the_top_lands_on_the_next_arc(p: Params, st: InitialState, run: SimRun) -> None:
    """An apex 1e-8 mm above the arc top is not a collision: the particle lands where the
    parabola meets arc 1 (found here by bisection on the exact gap)."""
    for i in range(run.n_particles):
        x0, vx, vy, y0 = st.d[i], st.vx[i], st.vy[i], st.y[i]

        def gap(t, x0=x0, vx=vx, vy=vy, y0=y0):
            return y0 + vy * t - 0.5 * p.g * t * t + float(depth(x0 + vx * t - p.S, p.R))

        lo, hi = (0.5 * p.S - x0) / vx, (p.S - x0) / vx  # from the cusp to the top of arc 1
        assert gap(lo) > 0 > gap(hi)
        for _ in range(100):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if gap(mid) > 0 else (lo, mid)
        first = rows_of(run, i)[0]
        assert first[0] == pytest.approx(lo, abs=1e-11)
        assert first[1] == pytest.approx(x0 + vx * lo, abs=1e-8)


def dip_into_the_top_is_a_collision_there(p: Params, st: InitialState, run: SimRun) -> None:
    """An apex 1e-8 mm inside the arc top is a collision within the dip, |x| ≤ sqrt(2e-8 /
    (1/R - g/vx²)), obeying Eq. (6): the tangential speed is kept (times β)."""
    for i in range(run.n_particles):
        first = rows_of(run, i)[0]
        half_width = math.sqrt(2e-8 / (1 / p.R - p.g / st.vx[i] ** 2))
        assert abs(first[1]) <= half_width
        assert first[3] == pytest.approx(p.beta * st.vx[i], rel=1e-6)


def tangent_touch_keeps_the_tangential_speed(p: Params, st: InitialState, run: SimRun) -> None:
    """An apex exactly at the arc top touches it tangentially: whether or not that counts as
    a collision, Eq. (6) keeps the tangential speed (times β), so |vx| stays > 0.9 vx0."""
    for i in range(run.n_particles):
        first = rows_of(run, i)[0]
        assert abs(first[3]) > 0.9 * st.vx[i]


def collision_at_the_cusp_reflects_off_one_arc(p: Params, st: InitialState, run: SimRun) -> None:
    """A vertical drop onto x = S/2 hits exactly the cusp; the outgoing velocity is Eqs.
    (5)-(6) with the normal of one of the two arcs meeting there (either is physical)."""
    for i in range(run.n_particles):
        first = rows_of(run, i)[0]
        assert first[1] == 0.5 * p.S
        vf = float(floor_velocity(p, first[5]))
        vy_in = -math.sqrt(2 * p.g * (st.y[i] - first[2]))
        options = []
        for side in (1.0, -1.0):
            nx = side * 0.5 * p.S / p.R
            ny = math.sqrt(1 - nx * nx)
            un, ut = (vy_in - vf) * ny, -(vy_in - vf) * nx
            un_out, ut_out = -p.alpha * un, p.beta * ut
            options.append((un_out * nx + ut_out * ny, vf + un_out * ny - ut_out * nx))
        assert any(first[3:5] == pytest.approx(o, rel=1e-6) for o in options)


def particle_stays_in_the_cusp(p: Params, st: InitialState, run: SimRun) -> None:
    # R = S/2: the normal at the cusp is horizontal, a vertical impact has no normal speed
    # and sticks; lift-off is vertical, so the particle lands in the same cusp for ever
    assert np.all(run.counters["collisions"] > 10)
    assert np.array_equal(run.counters["sticks"], run.counters["collisions"])
    assert np.all(run.positions == 0.5 * p.S)


def vertical_cusps_trap_every_particle(p: Params, st: InitialState, run: SimRun) -> None:
    # R = S/2: near a cusp the normal is nearly horizontal, impacts there stick, and vertical
    # lift-offs land in place: every particle ends in a cusp (x ≡ S/2 mod S) and D → 0
    x_end = run.positions[:, -1]
    assert np.all(np.abs(np.abs(np.mod(x_end, p.S) - 0.5 * p.S)) < 1e-6)
    assert np.all(run.positions[:, -10:] == x_end[:, None])
    assert np.any(x_end != st.cell * p.S + st.d)


def falls_back_at_once_and_sticks(p: Params, st: InitialState, run: SimRun) -> None:
    # Γ < 1: the floor decelerates slower than g, so a particle leaving at 1e-9 mm/s is
    # caught at once and stays stuck for ever at its x
    assert np.all(run.counters["collisions"] == 1) and np.all(run.counters["sticks"] == 1)
    assert np.all(run.positions == (st.cell * p.S + st.d)[:, None])


def first_collision_comes_after_the_start(p: Params, st: InitialState, run: SimRun) -> None:
    # ... never before it, and it is recorded (record_from = 0).  The exact flight lasts
    # 2e-9/(g - Aω²) ≈ 6e-13 s, but its gap never exceeds ~1e-22 mm, far below the rounding
    # of y (~1e-17 mm): in double precision the landing is only defined to where the true
    # gap reaches that rounding, τ ~ sqrt(2·1e-16 mm/(g - Aω²)) ≈ 2.4e-10 s.
    assert np.array_equal(run.n_recorded, run.counters["collisions"])
    t_first = run.collisions_dense[:, 0, 0]
    rounding_time = math.sqrt(2e-16 / (p.g - p.A * p.omega**2))
    assert np.all((t_first >= 0.0) & (t_first < 4 * rounding_time))


def moves_as_if_started_at_rest(p: Params, st: InitialState, run: SimRun) -> None:
    """Γ > 1: 1e-9 mm/s off the floor's velocity is no different from resting on it — the
    particle is caught at once (or, where the floor falls faster than g, flies off with it)
    and lifts off when a resting one would: its next collisions are the rest family's."""
    rest = state(run.n_particles, st.d, st.y, 0.0, floor_velocity(p, st.s * p.f), st.s, cell=st.cell,
                 stuck=True, from_surface=True)
    ref = simulate(p, run.n_particles, run.t_max, seed=0, initial=rest, record_collisions=4)
    for i in range(run.n_particles):
        rows = rows_of(run, i)
        rows = rows[rows[:, 0] > 1e-6][:3]  # drop the catch at t ≈ 0
        assert rows.shape[0] == 3
        assert np.allclose(rows, rows_of(ref, i)[:3], rtol=0.0, atol=1e-6)


def phase_follows_the_clock(p: Params, st: InitialState, run: SimRun) -> None:
    """10⁶ floor periods: the recorded floor phase is the clock's, frac(f (s0 + t)), to 1e-9
    period — the kernel reduces the floor time every period and counts periods apart, so
    neither drifts.  t is known to ulp(t) ≈ 4e-12 s here, i.e. 2e-10 period."""
    T = 1.0 / p.f
    for i in range(run.n_particles):
        rows = rows_of(run, i)
        assert rows[-1, 0] > 0.99 * run.t_max
        whole = np.floor((st.s[i] + rows[:, 0]) / T)
        clock = (st.s[i] + rows[:, 0] - whole * T) / T
        err = np.abs(clock - rows[:, 5])
        assert np.max(np.minimum(err, 1.0 - err)) < 1e-9


def held_only_where_the_model_can_hold(p: Params, st: InitialState, run: SimRun) -> None:
    """Contact models: a particle is held at rest (a collision row or a stop at rest whose
    next event is at the same x, i.e. it did not slide on) only where the model can hold it:
    an arc top, a cusp, or (Coulomb) |tan θ| ≤ μ; and some particle slid (the case exercises
    the contact phase, unless μ exceeds the steepest slope, tan θ at the cusp).  A stop where
    static friction cannot hold slides back: not held."""
    if p.mu * math.sqrt(p.R**2 - p.S**2 / 4) < p.S / 2:
        assert np.sum(run.contact_time["sliding"]) > 0
    n_held = 0
    for i in range(run.n_particles):
        ev = events_of(run, i)
        stays = np.append(ev[1:, 1] == ev[:-1, 1], True)
        held = ((ev[:, 6] == 0.0) | (ev[:, 6] == 6.0)) & is_stuck(p, ev) & stays
        _, d = cell_of(ev[held, 1], p.S)
        ad = np.abs(d)
        q = np.sqrt(np.maximum(p.R**2 - d * d, 0.0))
        ok = (ad == 0.0) | (np.abs(ad - 0.5 * p.S) <= 1e-12) | (ad <= p.mu * q * (1 + 1e-12))
        assert np.all(ok), d[~ok]
        n_held += int(np.count_nonzero(held))
    assert n_held >= 1  # the claim's premise: some particle was held


def held_where_it_rests_and_never_slides(p: Params, st: InitialState, run: SimRun) -> None:
    """Coulomb with μ above the steepest slope, tan θc (μ = 2 against 0.067): static friction
    holds a particle at rest anywhere, so each particle from rest is carried from its start
    until the floor first lets go, sin ωt < −1/Γ — its first recorded event is that lift-off
    at its start x — and it never slides (at Γ = 29 it never comes to rest again, so the start
    is where the claim is exercised; μ = 0.05 fails it: particles off the tops slide away)."""
    assert p.mu * math.sqrt(p.R**2 - p.S**2 / 4) > p.S / 2  # μ > tan θc: the premise
    assert np.all(run.contact_time["sliding"] == 0.0)
    waits = []
    for i in range(run.n_particles):
        first = events_of(run, i)[0]
        assert first[6] == 1.0 and first[1] == st.cell[i] * p.S + st.d[i]
        th = p.omega * st.s[i]
        inside = math.sin(th) < -1.0 / p.gamma  # the floor lets go at once
        wait = 0.0 if inside else (math.pi + math.asin(1.0 / p.gamma) - th) % (2 * math.pi) / p.omega
        assert first[0] == pytest.approx(wait, abs=1e-12)
        assert run.contact_time["held"][i] == pytest.approx(wait, abs=1e-12)
        waits.append(wait)
    assert max(waits) > 0.0  # some particle was held before it lifted off


FLAT = math.inf
CASES: list[Case] = [
    # no slide/coulomb at R = S/2: Params refuses them there (vertical cusp walls make sliding
    # a Zeno ping-pong; tests/bbb/dynamics/test_contact_step_level.py, test_sliding_contact_is_refused_...)
    # 50 Hz: at 54 Hz no particle was ever held in a cusp (the claim passed on nothing)
    Case("slide at 50 Hz from rest: held only at tops and cusps", params(f=50.0, contact="slide"),
         "rest", held_only_where_the_model_can_hold, t_max=2.0,
         exercises=("flights", "carried", "contacts")),
    Case("coulomb mu=0.05 at 54 Hz from rest: held only where static friction can",
         params(f=54.0, contact="coulomb", mu=0.05), "rest", held_only_where_the_model_can_hold,
         t_max=2.0,
         exercises=("flights", "carried", "contacts")),
    Case("coulomb mu=2 Gamma=29 (A=2) from rest: held where it rests, never slides",
         params(A=2.0, contact="coulomb", mu=2.0), "rest", held_where_it_rests_and_never_slides,
         t_max=5.0,
         exercises=("flights", "carried")),
    Case("alpha=1 flat motionless floor: energy conserved", params(A=0.0, R=FLAT, alpha=1.0, beta=1.0),
         "dropped", energy_is_conserved, n=3, t_max=10.0, family_kw=dict(drop_height=(1.0, 3.0))),
    Case("alpha=1e-6 (plastic): every collision sticks, x never changes", params(alpha=1e-6),
         "dropped", every_collision_sticks_and_x_never_changes,
         exercises=("flights", "carried")),
    Case("beta=0 flat floor: vx=0 after every collision", params(R=FLAT, beta=0.0),
         drop_sideways, vx_is_zero_after_every_collision,
         exercises=("flights", "carried")),
    Case("beta=0 arcs: tangential relative velocity vanishes", params(beta=0.0),
         "launched", tangential_relative_velocity_vanishes, family_kw=dict(launch_speed=(50.0, 200.0)),
         exercises=("flights", "carried")),
    Case("beta=1 alpha=1 motionless arcs: energy conserved", params(A=0.0, alpha=1.0, beta=1.0),
         "dropped", energy_is_conserved, n=3, t_max=10.0, family_kw=dict(drop_height=(1.0, 3.0))),
    Case("R=S/2 drop onto the cusp: stays in the cusp", params(R=1.0), drop_above_cusp,
         particle_stays_in_the_cusp,
         exercises=("flights", "carried")),
    Case("R=S/2 driven: vertical cusps trap every particle", params(R=1.0), "launched",
         vertical_cusps_trap_every_particle, t_max=20.0, record=5000,
         exercises=("flights", "carried")),
    Case("R=inf launched vertically: x never changes", params(R=FLAT), "launched", x_never_changes,
         exercises=("flights", "carried")),
    Case("R=1e12: x drifts < 1e-6 mm/s", params(R=1e12), "launched",
         x_drifts_less_than_a_nanometre_per_second,
         exercises=("flights", "carried")),
    Case("A=0: every particle comes to rest", params(A=0.0), "dropped", every_particle_comes_to_rest,
         family_kw=dict(drop_height=(0.5, 2.0))),
    Case("Gamma=29 (A=2): restitution Eqs. (5)-(6) hold at every collision", params(A=2.0), "rest",
         restitution_holds_at_every_collision, t_max=20.0,
         exercises=("flights", "carried")),
    Case("f=0.5 Hz: bounce cascade ends as on a motionless floor", params(f=0.5, R=FLAT), "dropped",
         cascade_ends_when_a_motionless_floors_would, n=8, t_max=4.0,
         family_kw=dict(drop_height=(1.0, 3.0))),
    Case("f=1000 Hz Gamma=3: many periods per flight, none missed", params(f=1000.0, A=A_1000HZ),
         "launched", many_floor_periods_pass_during_a_flight, n=4, t_max=1.0, record=800,
         family_kw=dict(launch_speed=(50.0, 200.0)), per_period=400,
         exercises=("flights", "carried")),
    Case("graze 1e-8 mm above an arc top: no collision there", params(A=0.0), graze(1e-8),
         flight_over_the_top_lands_on_the_next_arc, t_max=0.2),
    Case("dip 1e-8 mm into an arc top: collision there", params(A=0.0), graze(-1e-8),
         dip_into_the_top_is_a_collision_there, t_max=0.2),
    Case("tangent touch of an arc top: tangential speed kept", params(A=0.0), graze(0.0),
         tangent_touch_keeps_the_tangential_speed, t_max=0.2),
    Case("drop onto the cusp (R=15): reflected by one arc", params(), drop_above_cusp,
         collision_at_the_cusp_reflects_off_one_arc,
         exercises=("flights", "carried")),
    Case("on the surface at 1e-9 mm/s (Gamma<1): falls back and sticks", params(f=40.0), tiny_launch,
         falls_back_at_once_and_sticks, n=16, t_max=1.0),
    Case("on the surface at 1e-9 mm/s (Gamma<1): first collision after the start", params(f=40.0),
         tiny_launch, first_collision_comes_after_the_start, n=16, t_max=1.0),
    Case("on the surface at 1e-9 mm/s (Gamma>1): moves as if started at rest", params(), tiny_launch,
         moves_as_if_started_at_rest,
         exercises=("flights", "carried")),
    Case("1e6 floor periods at 60 Hz: phase follows the clock", params(), "launched",
         phase_follows_the_clock, n=1, t_max=1e6 / 60.0, record=1_500_000,
         exercises=("flights", "carried")),
]

# ---- the conveyor (issue 14): tilt φ up to ±30°, throw ψ from 10° to 90° --------------------
# Kinematics from the independent checker's Floor (x along the floor's plane, y normal to it;
# gravity (−g sin φ, −g cos φ); the floor displaced by A (cos ψ, sin ψ)(−sin 2πft)).


def start_x(p: Params, st: InitialState) -> np.ndarray:
    """Initial lab x (mm): d is the offset relative to the moving floor."""
    fl = Floor(p)
    return st.cell * p.S + st.d + fl.xf(fl.w * st.s)


def energy_is_kept_on_the_tilted_floor(p: Params, st: InitialState, run: SimRun) -> None:
    """α = β = 1 on a motionless tilted floor: E = |v|²/2 + g sin φ x + g cos φ y is kept
    (mm²/s²), while the particle speeds up downhill to ~g sin φ t."""
    fl = Floor(p)
    e0 = 0.5 * (st.vx**2 + st.vy**2) + fl.gx * start_x(p, st) + fl.gy * st.y
    for i in range(run.n_particles):
        rows = rows_of(run, i)
        assert rows.shape[0] > 10
        kinetic = 0.5 * (rows[:, 3] ** 2 + rows[:, 4] ** 2)
        e = kinetic + fl.gx * rows[:, 1] + fl.gy * rows[:, 2]
        scale = abs(e0[i]) + kinetic + np.abs(fl.gx * rows[:, 1])
        assert np.all(np.abs(e - e0[i]) <= 1e-9 * scale)
        assert kinetic[-1] > 10.0 * kinetic[0]  # the tilt did drive it


def vx_is_the_floors_along_plane_velocity(p: Params, st: InitialState, run: SimRun) -> None:
    """β = 0 on a flat thrown floor: Eq. (6) on the velocity relative to the floor leaves
    vₓ = the floor's along-plane velocity −A cos ψ ω cos 2πft after every collision, whatever
    gravity's along-plane pull did in flight."""
    fl = Floor(p)
    n_rows = 0
    for i in range(run.n_particles):
        rows = rows_of(run, i)
        vxf = fl.vxf(2 * np.pi * rows[:, 5])
        assert np.all(np.abs(rows[:, 3] - vxf) <= 1e-9 * (1.0 + np.hypot(rows[:, 3], rows[:, 4])))
        n_rows += int(np.count_nonzero(np.abs(vxf) > 1.0))
    assert n_rows > 100  # the floor was moving sideways at those collisions


def rides_with_the_floor_once_stuck(p: Params, st: InitialState, run: SimRun) -> None:
    """A sin ψ ω² < g cos φ (and on the arcs the normal contact force stays positive): the
    bounce cascade ends in sticking and the floor never lets go; a stuck particle keeps its
    place relative to the floor, so x(t) − X_f(t) is constant, X_f = −A cos ψ sin 2πft."""
    assert np.all(run.counters["sticks"] == 1) and np.all(run.counters["liftoffs"] == 0)
    carried_after(p, st, run, max(rows_of(run, i)[-1, 0] for i in range(run.n_particles)))


def relative_to_floor(p: Params, st: InitialState, run: SimRun) -> np.ndarray:
    """x − X_f (mm) at the run's sample times: the place relative to the moving floor."""
    fl = Floor(p)
    t = np.linspace(0.0, run.t_max, run.positions.shape[1])
    return run.positions - fl.xf(fl.w * (st.s[:, None] + t[None, :]))


def carried_after(p: Params, st: InitialState, run: SimRun, t_last: float) -> None:
    """After t_last (s) every particle keeps its place relative to the floor (x − X_f constant
    at more than 10 sample times) while the floor carries it sideways by more than Aₓ."""
    t = np.linspace(0.0, run.t_max, run.positions.shape[1])
    rel = relative_to_floor(p, st, run)
    late = t > t_last
    assert np.count_nonzero(late) > 10
    assert np.all(np.abs(rel[:, late] - rel[:, -1:]) <= 1e-9)
    assert np.ptp(run.positions[:, late], axis=1).min() > Floor(p).Ax  # it did move with the floor


def every_particle_goes_downhill(p: Params, st: InitialState, run: SimRun) -> None:
    """φ = −30° against arcs no steeper than asin(S/2R) ≈ 4°, thrown at ψ ≤ 90°: gravity's
    along-plane pull g sin|φ| and the throw's along-plane push (cos ψ ≥ 0) both point to +x,
    so every particle ends more than 10 S downhill of where it started.  (Thrown forward
    against an uphill pull, particles may be conveyed uphill instead: not claimed here.)"""
    assert p.tilt < 0 and p.throw <= 90
    assert np.all(run.positions[:, -1] - start_x(p, st) > 10 * p.S)


def drifts_downhill_on_average(p: Params, st: InitialState, run: SimRun) -> None:
    """R = 1.05 S/2 (near-vertical cusp walls) tilted by −30°: a particle that comes to rest
    in a cusp stays there (one wall presses at every phase: docs/physics.md, "A carried
    particle in a cusp"), but those that move go downhill, so the mean displacement does."""
    assert p.tilt < 0
    assert np.mean(run.positions[:, -1] - start_x(p, st)) > 10 * p.S


def static_friction_holds_everywhere(p: Params, st: InitialState, run: SimRun) -> None:
    """Coulomb at Γ < 1 with μ above the largest |F_t|/N of a particle at rest anywhere on the
    tilted, thrown arcs at any phase (the checker's own loads, N > 0 throughout): once the
    bounce cascade of a dropped particle has brought it to rest, it never slips or lifts off
    again, so it keeps its place relative to the floor, x − X_f constant, while the floor
    carries it sideways."""
    fl = Floor(p)
    d = np.linspace(-0.5 * p.S, 0.5 * p.S, 401)[:, None]
    ft, n = _rest_loads(fl, p.mu, d, np.linspace(0.0, 2 * math.pi, 721)[None, :])
    assert n.min() > 0 and np.max(np.abs(ft) / n) < 0.5 * p.mu  # the premise, with margin
    assert np.all(run.counters["liftoffs"] == 0)
    carried_after(p, st, run, max(events_of(run, i)[-1, 0] for i in range(run.n_particles)))


def slides_downhill_without_equilibrium(p: Params, st: InitialState, run: SimRun) -> None:
    """Frictionless, tilted by φ < 0 beyond the arcs' steepest slope even when the floor's
    normal acceleration adds to gravity, tan|φ| > (1 + Γ) tan θc with Γ = Aω²/g: no place on
    the floor holds a particle at any phase, so every particle from rest ends far downhill."""
    th_c = math.asin(0.5 * p.S / p.R)
    assert math.tan(abs(math.radians(p.tilt))) > (1 + p.A * p.omega**2 / p.g) * math.tan(th_c)
    every_particle_goes_downhill(p, st, run)


def bounces_off_cusps(p: Params, st: InitialState, run: SimRun) -> None:
    """Sliding particles reach cusps, and there (the model's rule, docs/physics.md) meet the
    neighbouring arc at the same instant: every cusp event is followed by a collision at the
    same t and x, which leaves the floor or starts contact on that arc; some particle did it."""
    bounces = 0
    for i in range(run.n_particles):
        ev = events_of(run, i)
        k = np.nonzero(ev[:-1, 6] == 7.0)[0]
        assert np.all(np.isin(ev[k + 1, 6], (0.0, 4.0)))
        assert np.all(ev[k + 1, 0] == ev[k, 0]) and np.all(ev[k + 1, 1] == ev[k, 1])
        bounces += k.size
    assert bounces >= 10


def never_lets_go_below_liftoff(p: Params, st: InitialState, run: SimRun) -> None:
    """Below the lift-off frequency (bbb.analysis.liftoff_onset: no particle at rest anywhere can lift off)
    and with sliding speeds far below those whose centripetal v²/R would eat the normal
    load's margin, particles from rest slide (Coulomb lets go) but the floor never lets go
    of them: no lift-off from rest, no lift-off from sliding.  They fly only where sliding
    brings them into a cusp and the other wall bounces them (Eqs. (5)-(6)): every run of
    collisions in the record starts at a cusp event."""
    from bbb.analysis.liftoff_onset import liftoff_frequency

    assert p.f < 0.8 * liftoff_frequency(p)  # margin ≥ 1 − 0.8² = 36 % of the normal load
    rel = relative_to_floor(p, st, run)
    assert np.max(np.abs(rel - rel[:, :1])) > 1e-3  # friction did let go: some particle slid
    assert np.all(run.counters["liftoffs"] == 0)
    bounces = 0
    for i in range(run.n_particles):
        kinds = events_of(run, i)[:, 6]
        assert not np.any(np.isin(kinds, (1.0, 5.0))), np.unique(kinds)
        # the last event before each collision that is not itself a collision
        last = np.maximum.accumulate(np.where(kinds != 0.0, np.arange(kinds.size), -1))
        opened = last[1:][kinds[1:] == 0.0]
        assert np.all(opened >= 0) and np.all(kinds[opened] == 7.0)
        bounces += int(np.count_nonzero(kinds == 7.0))
    assert bounces >= 1


CASES += [
    Case("tilt=30 A=0 alpha=beta=1 flat: energy kept, speeds up downhill",
         params(A=0.0, R=FLAT, alpha=1.0, beta=1.0, tilt=30.0), "dropped",
         energy_is_kept_on_the_tilted_floor,
         n=3, t_max=5.0, family_kw=dict(drop_height=(1.0, 3.0))),
    Case("tilt=-30 A=0 alpha=beta=1 arcs: energy kept, speeds up downhill",
         params(A=0.0, alpha=1.0, beta=1.0, tilt=-30.0), "dropped", energy_is_kept_on_the_tilted_floor,
         n=3, t_max=2.0, family_kw=dict(drop_height=(1.0, 3.0))),
    Case("throw=10 tilt=30 Gamma=29 flat beta=0: vx = floor's after every collision",
         params(A=2.0, R=FLAT, beta=0.0, tilt=30.0, throw=10.0), "launched",
         vx_is_the_floors_along_plane_velocity,
         exercises=("flights", "carried")),
    Case("throw=10 tilt=-30 Gamma=1.4 flat: stuck particles ride with the floor",
         params(R=FLAT, tilt=-30.0, throw=10.0), "dropped", rides_with_the_floor_once_stuck,
         family_kw=dict(drop_height=(0.1, 1.0))),
    Case("throw=45 tilt=-30 Gamma=1.4 flat: every particle goes downhill",
         params(R=FLAT, tilt=-30.0, throw=45.0), "launched", every_particle_goes_downhill,
         exercises=("flights", "carried")),
    Case("throw=10 tilt=-30 Gamma=29 (A=2) arcs: every particle goes downhill",
         params(A=2.0, tilt=-30.0, throw=10.0), "launched", every_particle_goes_downhill),
    Case("throw=60 tilt=-30 Gamma=5.8 (A=0.4) arcs: every particle goes downhill",
         params(A=0.4, tilt=-30.0, throw=60.0), "launched", every_particle_goes_downhill),
    Case("throw=90 tilt=-30 R=1.05 S/2 driven: the mean drift is downhill",
         params(R=1.05, tilt=-30.0), "launched", drifts_downhill_on_average,
         exercises=("flights", "carried")),
    # contact models on the conveyor (issue 13 item 4; near-vertical cusps are refused)
    Case("coulomb mu=2 Gamma=0.64 (40 Hz) tilt=3 throw=60 dropped: once at rest never slips",
         params(f=40.0, contact="coulomb", mu=2.0, tilt=3.0, throw=60.0), "dropped",
         static_friction_holds_everywhere, family_kw=dict(drop_height=(0.1, 1.0)),
         exercises=("flights", "contacts")),
    Case("coulomb mu=0.3 throw=30 at 50 Hz (lift-off 66.7 Hz) from rest: slides, never lifts off",
         params(f=50.0, contact="coulomb", mu=0.3, throw=30.0), "rest", never_lets_go_below_liftoff,
         exercises=("flights", "contacts")),
    Case("slide tilt=-10 Gamma=0.64 (40 Hz): no equilibrium, every particle goes downhill",
         params(f=40.0, contact="slide", tilt=-10.0), "rest", slides_downhill_without_equilibrium,
         exercises=("flights", "contacts")),
    Case("slide tilt=3 throw=60 at 55 Hz launched: bounces off cusps (the soak's row)",
         params(f=55.0, contact="slide", tilt=3.0, throw=60.0), "launched", bounces_off_cusps,
         exercises=("flights", "contacts")),
    Case("f=1000 Hz Gamma=3 throw=30 tilt=15: many periods per flight, none missed",
         params(f=1000.0, A=A_1000HZ, tilt=15.0, throw=30.0), "launched",
         many_floor_periods_pass_during_a_flight,
         n=4, t_max=1.0, record=800, family_kw=dict(launch_speed=(50.0, 200.0)), per_period=400),
]
IDS = [c.name for c in CASES]
assert len(set(IDS)) == len(IDS)


@functools.cache
def result(name: str) -> tuple[InitialState, SimRun]:
    """Each case runs once per session (seed fixed), shared by its tests."""
    case = CASES[IDS.index(name)]
    return run_case(case, case.n, case.t_max, seed=20261122, record=case.record)


@functools.cache
def violations(name: str) -> dict[str, float]:
    case = CASES[IDS.index(name)]
    st, run = result(name)
    return invariant_violations(case.params, run, per_period=case.per_period, start=st)


def exercising(kind: str) -> list[Case]:
    """The cases whose run exercises ``kind`` (Case.exercises): the invariant about it is
    claimed there, and there it must have happened at least once."""
    return [c for c in CASES if kind in c.exercises]


def names(cases: list[Case]) -> list[str]:
    return [c.name for c in cases]


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_every_recorded_value_is_finite_and_no_velocity_needed_repair(case):
    v = violations(case.name)
    assert v["rows"] > 0 and v["nonfinite"] == 0 and v["anomalies"] == 0


@pytest.mark.parametrize("case", exercising("flights"), ids=names(exercising("flights")))
def test_every_recorded_collision_lies_where_the_previous_flight_meets_the_surface(case):
    v = violations(case.name)
    assert v["checked_flights"] > 0 and v["off_surface"] == 0, v["messages"]


@pytest.mark.parametrize("case", exercising("flights"), ids=names(exercising("flights")))
def test_every_outgoing_velocity_follows_eqs_5_6_from_the_incoming_one(case):
    v = violations(case.name)
    assert v["checked_flights"] > 0 and v["rule"] == 0, v["messages"]


@pytest.mark.parametrize("case", exercising("carried"), ids=names(exercising("carried")))
def test_every_stuck_particle_is_carried_and_lifts_off_when_the_floor_first_lets_go(case):
    v = violations(case.name)
    assert v["carried"] > 0 and v["liftoff"] == 0, v["messages"]


@pytest.mark.parametrize("case", exercising("flights"), ids=names(exercising("flights")))
def test_every_flight_is_certified_above_the_surface(case):
    v = violations(case.name)
    assert v["checked_flights"] > 0 and v["gap"] == 0, v["messages"]


@pytest.mark.parametrize("case", exercising("contacts"), ids=names(exercising("contacts")))
def test_every_sliding_stretch_follows_the_contact_equations(case):
    v = violations(case.name)
    assert v["contacts"] > 0 and v["contact"] == 0, v["messages"]


@pytest.mark.parametrize("case", exercising("flights"), ids=names(exercising("flights")))
def test_brute_force_finds_no_flight_below_the_surface(case):
    v = violations(case.name)
    assert v["flights"] > 0 and v["worst_gap"] > -on_surface_tolerance(case.params)


def test_no_case_fails_an_invariant_outside_what_it_exercises():
    """The checker runs on every recorded event of every case: a lift-off or a sliding stretch
    in a case that does not claim to exercise it must still pass (it just may not occur)."""
    for case in CASES:
        v = violations(case.name)
        assert v["liftoff"] == 0 and v["contact"] == 0, (case.name, v["messages"])


@pytest.mark.parametrize("case", [
    pytest.param(c, marks=pytest.mark.xfail(strict=True, reason=c.xfail)) if c.xfail else c
    for c in CASES], ids=IDS)
def test_the_physical_claim_of_the_extreme_holds(case):
    st, run = result(case.name)
    case.claim(case.params, st, run)


# ---- the 10⁶-period run, continued with a differently reduced clock -------------------------


def test_long_run_restarted_from_a_late_state_with_a_fresh_clock_continues_identically():
    """The state after 10⁶ periods, handed over with the clock reset to 0 (floor time =
    phase/f, x split into cell and offset again), reproduces the next collisions of the long
    run: its floor time and position carry no hidden drift.  Chaos amplifies the rounding
    of the hand-over (≤ ulp of x), so only a few collisions are compared."""
    case = CASES[IDS.index("1e6 floor periods at 60 Hz: phase follows the clock")]
    p = case.params
    _, run = result(case.name)
    rows = rows_of(run, 0)
    k = next(k for k in range(rows.shape[0] - 50, 0, -1) if not is_stuck(p, rows[k: k + 9]).any())
    t_k, x_k, y_k, vx_k, vy_k, ph_k = rows[k]
    cell = int(np.floor(x_k / p.S + 0.5))
    st = state(1, x_k - cell * p.S, y_k, vx_k, vy_k, ph_k / p.f, cell=cell, from_surface=True)
    again = simulate(p, 1, rows[k + 8, 0] - t_k + 1e-3, seed=0, initial=st, record_collisions=8)
    expected = rows[k + 1: k + 9].copy()
    expected[:, 0] -= t_k
    got = rows_of(again, 0)
    assert got.shape == expected.shape
    assert np.allclose(got, expected, rtol=0.0, atol=1e-6)
    assert t_k * p.f > 0.99e6


def test_clock_started_a_million_periods_later_gives_the_same_first_collision():
    """evolve_ensemble given the floor time s0 + 10⁶ T instead of s0 (the same floor phase)
    reduces it to one period at the first collision and finds the same collision: the
    unreduced clock costs only its rounding, ulp(10⁶ T) ≈ 4e-12 s, i.e. Aω² × 4e-12 ≈ 1e-7 mm/s
    of floor velocity.  (Later collisions then part as chaos amplifies that difference.)"""
    p = params()
    n = 8
    st = initial_state(p, n, np.random.SeedSequence(7), "launched", launch_speed=(50.0, 200.0))
    T = 2 * math.pi / p.omega

    def run(s):
        rec = np.full((n, 3, len(COLLISION_FIELDS)), np.nan)
        counters = np.zeros((n, len(COUNTER_NAMES)), np.int64)
        floor = KernelFloor(p.g, p.A, p.omega, p.R, p.S, p.alpha, p.beta)
        evolve_ensemble((st.cell, st.d, st.y, st.vx, st.vy, s, st.stuck, st.from_surface), floor,
                        Run(1.0, 0.0, 1e-12, 1e-3, 0.25), None, None, np.zeros(0),
                        (np.zeros((n, 0)), rec, counters, np.zeros((n, 2)), np.zeros((n, 4))))
        return rec

    a, b = run(st.s), run(st.s + 1_000_000 * T)
    assert np.all(np.isfinite(b)) and np.all((b[:, :, 5] >= 0.0) & (b[:, :, 5] < 1.0))
    first_a, first_b = a[:, 0], b[:, 0]
    assert np.allclose(first_a[:, 0], first_b[:, 0], rtol=0.0, atol=1e-10)  # t (s)
    assert np.allclose(first_a[:, 1:3], first_b[:, 1:3], rtol=0.0, atol=1e-9)  # x, y (mm)
    assert np.allclose(first_a[:, 3:5], first_b[:, 3:5], rtol=0.0, atol=1e-5)  # v (mm/s)
    assert np.allclose(first_a[:, 5], first_b[:, 5], rtol=0.0, atol=1e-9)  # phase
