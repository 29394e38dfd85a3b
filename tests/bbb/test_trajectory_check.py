"""The trajectory checker can fail: each test corrupts one event of a real recorded run the
way a wrong kernel would, and the checker must flag it (the unperturbed run passes)."""

import math

import numpy as np
import pytest

from bbb import Numerics, Params, simulate
from tests.bbb.trajectory_check import check_particle

P = Params.preset("klages2004", f=60.0)
J = 40  # the corrupted event: a collision that ends a flight from a collision


@pytest.fixture(scope="module")
def events() -> np.ndarray:
    run = simulate(P, 1, 1.0, seed=3, initial="launched", record_collisions=120, record_liftoffs=True)
    ev = run.collisions_dense[0, : run.n_recorded[0]].copy()
    assert ev[J, 6] == 0.0 and ev[J - 1, 6] == 0.0 and ev[J - 1, 3] != 0.0
    return ev


def failed(ev: np.ndarray) -> set[str]:
    rep = check_particle(P, Numerics(), ev)
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
    assert check_particle(p, Numerics(), ev).ok
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
    rep = check_particle(p, Numerics(), liftoff_at(p, ev, k, dt_periods / p.f))
    assert rep.failures["liftoff_time"] == 1


def test_a_stuck_particle_that_moves_is_flagged(sticky):
    p, ev, k = sticky
    ev = ev.copy()
    ev[k, 1] += 1e-9
    assert check_particle(p, Numerics(), ev).failures["carried"] == 1


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
    reps = [check_particle(p, Numerics(), ev) for ev in runs]
    assert sum(r.flights for r in reps) > 50
    assert all(r.ok for r in reps), [r.messages for r in reps]


def test_a_missed_collision_on_tilted_thrown_arcs_is_flagged(conveyor):
    p, runs = conveyor
    ev = max(runs, key=len)
    k = int(np.nonzero((ev[1:-1, 6] == 0.0) & (ev[:-2, 6] == 0.0))[0][5]) + 1
    rep = check_particle(p, Numerics(), np.delete(ev, k, axis=0))
    assert rep.failures["below"] > 0
