"""The conveyor (tilt φ, throw ψ) against analytic mechanics and its mirror symmetry."""

import math

import numpy as np
import pytest

from bbb import Params, simulate
from bbb.ensemble import InitialState

ALPHA = 0.7
# the flat-floor period-1 window of tests/bbb/dynamics/test_evolve_level.py (Holmes 1982), in Γ_y = A_y ω²/g
GAMMA1 = math.pi * (1 - ALPHA) / (1 + ALPHA)
GAMMA2 = math.hypot(GAMMA1, 2 * (1 + ALPHA**2) / (1 + ALPHA) ** 2)


def one(value, dtype=float):
    return np.full(1, value, dtype=dtype)


def conveyor_drift(psi: float, R: float, beta: float = 0.9, periods: int = 600):
    """Launch a flat-floor ball near its period-1 orbit on a floor thrown at ψ; return bbb's
    drift (mm/s) over the last 100 periods, the analytic drift and the orbit's launch phase."""
    A, g = 0.1, 9800.0
    ay = A * math.sin(math.radians(psi))
    gamma = 0.5 * (GAMMA1 + GAMMA2)  # Γ_y mid-window: period 1 stable
    w = math.sqrt(gamma * g / ay)
    f = w / (2 * math.pi)
    p = Params(g=g, A=A, f=f, R=R, S=2.0, alpha=ALPHA, beta=beta, throw=psi)
    # vertical motion: the textbook ball of amplitude A_y; launch speed g/(2f), and the
    # floor's normal velocity at impact −A_y ω cos θ = (g/2f)(1−α)/(1+α), θ in (π, 3π/2)
    theta = math.pi + math.acos(GAMMA1 / gamma)
    V = g / (2 * f)
    # locked: u⁺ = u⁻ (no force along the floor) and u⁺ − V_x = β(u⁻ − V_x) ⇒ u = V_x(θ):
    # v = −A cos ψ ω cos θ = cot ψ · g (1−α) / (2 f (1+α))
    v_pred = g * (1 - ALPHA) / (2 * f * (1 + ALPHA)) / math.tan(math.radians(psi))
    s0 = theta / w
    state = InitialState(one(0, np.int64), one(0.1), one(-ay * math.sin(theta)),
                         one(v_pred + 20.0), one(1.01 * V), one(s0), one(False, bool),
                         one(True, bool))
    T = 1.0 / f
    times = np.array([(periods - 101) * T, (periods - 1) * T])
    run = simulate(p, 1, periods * T, seed=0, initial=state, sample_times=times,
                   record_collisions=2 * periods)
    x = run.positions[0]
    rows = run.collisions_dense[0, : run.n_recorded[0]]
    return (x[1] - x[0]) / (times[1] - times[0]), v_pred, rows


@pytest.mark.parametrize("R", [math.inf, 1e8])
@pytest.mark.parametrize("psi", [60.0, 30.0, 135.0])
def test_locked_period_one_conveyor_drifts_at_the_floors_along_plane_velocity(psi, R):
    v, v_pred, rows = conveyor_drift(psi, R)
    # the vertical motion is the period-1 orbit (one collision per period)
    assert np.allclose(np.diff(rows[-20:, 0]) * rows.shape[0] / rows[-1, 0], 1.0, atol=0.05)
    assert abs(v - v_pred) <= 1e-6 * abs(v_pred)


def test_free_slide_on_a_motionless_tilted_floor_keeps_energy_books_exactly():
    # A = 0, β = 1, flat floor tilted by φ: between impacts vₓ = vₓ0 − g sin φ t, impacts keep
    # vₓ (floor at rest, normal along y) and remove (1 − α²) v_y⁻²/2 of E = v²/2 + gₓx + g_y y
    phi, alpha, g = 12.0, 0.8, 9800.0
    p = Params(g=g, A=0.0, f=50.0, R=math.inf, S=2.0, alpha=alpha, beta=1.0, tilt=phi)
    gx, gy = g * math.sin(math.radians(phi)), g * math.cos(math.radians(phi))
    state = InitialState(one(0, np.int64), one(0.3), one(3.0), one(40.0), one(0.0), one(0.0),
                         one(False, bool), one(False, bool))
    times = np.linspace(0.0, 0.5, 51)
    run = simulate(p, 1, 0.5, seed=0, initial=state, sample_times=times, record_collisions=400)
    rows = run.collisions_dense[0, : run.n_recorded[0]]
    flying = rows[rows[:, 4] != 0.0]  # before the cascade ends stuck (A = 0: for ever)
    assert flying.shape[0] > 20
    t, x, y, vx, vy = flying[:, :5].T
    assert np.allclose(vx, 40.0 - gx * t, rtol=0, atol=1e-9 * (40.0 + gx * t))
    assert np.allclose(x, 0.3 + 40.0 * t - 0.5 * gx * t * t, rtol=0, atol=1e-9)
    # energy after impact n+1 = after impact n minus the normal loss at impact n+1
    E = 0.5 * (vx**2 + vy**2) + gx * x + gy * y
    vy_in = vy[:-1] - gy * np.diff(t)
    loss = 0.5 * (1 - alpha**2) * vy_in**2
    assert np.allclose(E[1:], E[:-1] - loss, rtol=0, atol=1e-9 * np.abs(E).max())
    # positions: the same parabola in x through every impact, until the particle stops
    t_stop = rows[np.nonzero(rows[:, 4] == 0.0)[0][0], 0]
    early = times < t_stop
    xs = run.positions[0, early]
    assert np.allclose(xs, 0.3 + 40.0 * times[early] - 0.5 * gx * times[early] ** 2, atol=1e-9)


def mirrored_runs(p: Params, *, n: int = 6, seed: int = 5, y: tuple[float, float] = (0.1, 1.0),
                  v: float = 50.0, record: int = 500):
    """Two 2 s runs: p's (φ, ψ) and (−φ, 180° − ψ) from mirrored initial states (d, vₓ → −d,
    −vₓ); heights y[0] + U(0, y[1]) mm, velocities U(−v, v) mm/s, phases over one period."""
    q = p.with_(tilt=-p.tilt, throw=180.0 - p.throw)
    rng = np.random.default_rng(seed)
    d = rng.uniform(-0.9, 0.9, n)
    s = rng.uniform(0.0, 1 / p.f, n)
    h = y[0] + rng.uniform(0.0, y[1], n)
    vx = rng.uniform(-v, v, n)
    vy = rng.uniform(-v, v, n)
    zero, no = np.zeros(n, np.int64), np.zeros(n, bool)
    times = np.linspace(0.0, 2.0, 201)
    kw = dict(sample_times=times, record_collisions=record, record_liftoffs=True)
    a = simulate(p, n, 2.0, 0, InitialState(zero, d, h, vx, vy, s, no, no), **kw)
    b = simulate(q, n, 2.0, 0, InitialState(zero, -d, h, -vx, vy, s, no, no), **kw)
    return a, b


def mirror_pair(R: float):
    return mirrored_runs(Params.preset("klages2004", f=70.0, R=R, tilt=3.0, throw=60.0))


@pytest.mark.parametrize("R", [15.0, 1.05, math.inf])  # 1.05: near-vertical cusps (S/2 refused)
def test_mirrored_floor_and_initial_state_give_the_mirrored_trajectory_bit_exactly(R):
    a, b = mirror_pair(R)
    assert a.counters["collisions"].sum() > 500
    assert np.array_equal(a.positions, -b.positions)
    assert np.array_equal(a.n_recorded, b.n_recorded)
    ca, cb = a.collisions_dense, b.collisions_dense
    sign = np.array([1, -1, 1, -1, 1, 1, 1])
    assert np.array_equal(ca * sign, cb, equal_nan=True)


def test_mirrored_ensembles_drift_opposite_within_their_errors():
    # independent draws: (φ, ψ) and (−φ, 180° − ψ) from 'launched', per-particle drifts
    p = Params.preset("klages2004", f=75.0, tilt=2.0, throw=60.0)
    q = p.with_(tilt=-2.0, throw=120.0)
    t = 4.0
    drift = []
    for par, seed in ((p, 1), (q, 2)):
        run = simulate(par, 200, t, seed, "launched", sample_times=np.array([0.0, t]))
        drift.append((run.positions[:, 1] - run.positions[:, 0]) / t)
    m = [np.mean(v) for v in drift]
    se = [np.std(v, ddof=1) / math.sqrt(v.size) for v in drift]
    assert abs(m[0]) > 5 * se[0]  # a drift to mirror, not noise
    assert abs(m[0] + m[1]) <= 3.0 * math.hypot(*se)
