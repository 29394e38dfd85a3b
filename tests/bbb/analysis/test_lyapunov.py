"""The largest Lyapunov exponent against the analytic Floquet multiplier of the flat floor's
period-1 orbit, the exact tangent map, and mirror symmetry."""

import math

import numpy as np
import pytest

from bbb import Params, simulate
from bbb.analysis.lyapunov import flat_floor_jacobian, flat_floor_tangent_exponent, lyapunov
from bbb.ensemble import InitialState

ALPHA = 0.7
A, G = 0.1, 9800.0
GAMMA1 = math.pi * (1 - ALPHA) / (1 + ALPHA)
GAMMA2 = math.hypot(GAMMA1, 2 * (1 + ALPHA**2) / (1 + ALPHA) ** 2)
VERTICAL = (0.0, 1.0, 0.0, 1.0)


def flat(gamma: float, alpha: float = ALPHA) -> Params:
    f = math.sqrt(gamma * G / A) / (2 * math.pi)
    return Params(g=G, A=A, f=f, R=math.inf, S=2.0, alpha=alpha, beta=0.99)


def floquet_multiplier(gamma: float) -> float:
    """Largest |μ| of the period-1 fixed point of the exact flat-floor map (t, v) → (t', v').

    At the fixed point τ = T, v = V = gT/2, v⁻ = −V, u = V(1−α)/(1+α) and the impact
    acceleration a = −g √(Γ² − Γ1²) (phase in (π, 3π/2)); the implicit-function Jacobian
    (see bbb.analysis.lyapunov.flat_floor_tangent_exponent) there has det = α² and
    trace = 1 + α² + (1+α)² a/g, so μ² − trace μ + α² = 0."""
    tr = 1 + ALPHA**2 - (1 + ALPHA) ** 2 * math.sqrt(gamma**2 - GAMMA1**2)
    disc = tr * tr - 4 * ALPHA**2
    if disc <= 0:
        return ALPHA  # complex pair, |μ|² = det
    return (abs(tr) + math.sqrt(disc)) / 2


def period_one_state(p: Params, n: int = 1) -> InitialState:
    """On the period-1 orbit at its apex (half a period after launch), vₓ = 0."""
    w, T = p.omega, 1.0 / p.f
    gamma = p.gamma
    theta = math.pi + math.acos(GAMMA1 / gamma)  # launch phase (tests/bbb/dynamics/test_evolve_level.py)
    V = p.g * T / 2
    y = -p.A * math.sin(theta) + V * T / 2 - p.g * T * T / 8
    s = (theta / w + T / 2) % T
    one = np.ones(n)
    return InitialState(np.zeros(n, np.int64), 0.0 * one, y * one, 0.0 * one, 0.0 * one,
                        s * one, np.zeros(n, bool), np.zeros(n, bool))


@pytest.mark.parametrize(("gamma", "rel"), [(0.8, 3e-3), (0.99 * GAMMA2, 1e-4)])
def test_flat_floor_period_one_orbit_gives_log_of_the_floquet_multiplier_per_period(gamma, rel):
    # Γ = 0.8: complex multipliers, |μ| = α, and |δ| oscillates within the period of their
    # rotation: a bounded term O(1)/(1800 periods) remains (measured 0.2 %);
    # 0.99 Γ2: a real multiplier μ ≈ −0.92, the separation aligns with its eigenvector
    p = flat(gamma)
    res = lyapunov(p, 1, 2000 / p.f, 0, period_one_state(p), direction=VERTICAL, n_resamples=10)
    exact = math.log(floquet_multiplier(gamma)) * p.f
    assert res.n_collapsed == 0
    assert res.lam_i[0] == pytest.approx(exact, rel=rel)
    # one collision per period: per collision it is ln|μ|
    assert res.per_coll_i[0] == pytest.approx(exact / p.f, rel=rel)


def test_benettin_agrees_with_the_exact_tangent_map_on_a_chaotic_flat_floor():
    # α = 0.9, Γ = 2: chaotic bouncing with no sticking (checked), where both methods apply
    p = flat(2.0, alpha=0.9)
    n, periods = 32, 2000
    run = simulate(p, n, periods / p.f, 5, "dropped", record_collisions=4000,
                   drop_height=(0.5, 3.0))
    assert np.all(run.counters["sticks"] == 0)
    # skip the first 10 % of collisions, as the Benettin run skips 10 % of its periods
    tangent = np.array([
        flat_floor_tangent_exponent(run.collisions_dense[i, m // 10 : m], p)[0]
        for i, m in enumerate(run.n_recorded)
    ])
    ben = lyapunov(p, n, periods / p.f, 5, "dropped", direction=VERTICAL)
    assert ben.n_collapsed == 0
    se = math.hypot(tangent.std(ddof=1), ben.lam_i.std(ddof=1)) / math.sqrt(n)
    assert tangent.mean() > 20  # chaotic: a positive exponent, not a stable orbit
    assert abs(tangent.mean() - ben.lam) <= 3 * se


def exact_flat_map(t0: float, v0: float, p: Params) -> tuple[float, float]:
    """Next impact time and launch velocity of the flat-floor map, by scanning the flight
    gap on a fine grid and bisecting its first sign change (independent of the kernel)."""
    w, A, g = p.omega, p.A, p.g

    def gap(tau):
        return -A * math.sin(w * t0) + v0 * tau - 0.5 * g * tau * tau + A * np.sin(w * (t0 + tau))

    taus = np.linspace(1e-6, 2 * (v0 + A * w) / g + 1e-3, 200001)
    k = int(np.argmax(gap(taus) <= 0))
    a, b = taus[k - 1], taus[k]
    for _ in range(200):
        m = 0.5 * (a + b)
        a, b = (m, b) if gap(m) > 0 else (a, m)
    tau = 0.5 * (a + b)
    u1 = -A * w * math.cos(w * (t0 + tau))
    return t0 + tau, (1 + p.alpha) * u1 - p.alpha * (v0 - g * tau)


@pytest.mark.parametrize(("t0", "v0"), [(0.003, 150.0), (0.011, 90.0), (0.017, 300.0)])
def test_flat_floor_jacobian_equals_finite_differences_of_the_exact_map(t0, v0):
    p = flat(2.0, alpha=0.8)
    t1, v1 = exact_flat_map(t0, v0, p)
    J = flat_floor_jacobian(t1 - t0, v0, t0, t1, p)
    ht, hv = 1e-7, 1e-4
    fd = np.empty((2, 2))
    fd[:, 0] = (np.subtract(exact_flat_map(t0 + ht, v0, p), exact_flat_map(t0 - ht, v0, p))) / (2 * ht)
    fd[:, 1] = (np.subtract(exact_flat_map(t0, v0 + hv, p), exact_flat_map(t0, v0 - hv, p))) / (2 * hv)
    np.testing.assert_allclose(J, fd, rtol=1e-5, atol=1e-9)


def test_flat_floor_tangent_map_conserves_area_when_elastic_on_a_motionless_floor():
    # α = β = 1, A = 0: a Hamiltonian bounce; det J = 1 per collision in (t, v)
    p = Params(g=G, A=0.0, f=50.0, R=math.inf, S=2.0, alpha=1.0, beta=1.0)
    st = InitialState(np.zeros(3, np.int64), np.zeros(3), np.array([0.5, 1.0, 3.0]), np.zeros(3),
                      np.array([0.0, 40.0, -20.0]), np.array([0.0, 0.005, 0.013]),
                      np.zeros(3, bool), np.zeros(3, bool))
    run = simulate(p, 3, 2.0, 0, st, record_collisions=100)
    for i in range(3):
        rows = run.collisions_dense[i, : run.n_recorded[i]]
        dets = [np.linalg.det(flat_floor_jacobian(rows[n + 1, 0] - rows[n, 0], rows[n, 4],
                                                  rows[n, 5] / p.f, rows[n + 1, 5] / p.f, p))
                for n in range(rows.shape[0] - 1)]
        assert len(dets) > 10
        np.testing.assert_allclose(dets, 1.0, atol=1e-10)


def mirrored(st: InitialState) -> InitialState:
    return InitialState(-st.cell, -st.d, st.y, -st.vx, st.vy, st.s, st.stuck, st.from_surface)


def test_a_trajectory_and_its_mirror_image_give_the_same_exponent():
    from bbb.ensemble import initial_state

    p = Params.preset("klages2004", f=80.0)
    st = initial_state(p, 16, np.random.SeedSequence(4), "launched")
    u = (0.3, 0.5, 0.6, 0.4)
    a = lyapunov(p, 16, 5.0, 0, st, direction=u, n_resamples=10)
    b = lyapunov(p, 16, 5.0, 0, mirrored(st), direction=(-u[0], u[1], -u[2], u[3]),
                 n_resamples=10)
    assert a.n_collapsed == b.n_collapsed == 0
    assert np.all(a.lam_i > 0)
    # the kernel treats d and −d alike to the last bit (|d|, copysign, symmetric cell
    # rounding), so the mirror ensemble is the same computation: equal exactly, measured
    np.testing.assert_array_equal(b.lam_i, a.lam_i)


def test_a_separation_that_sticking_collapses_to_zero_is_counted_and_left_out():
    # flat floor, Γ = 0.4 < Γ1: a dropped ball chatters down and sticks for good; a vertical
    # separation dies with it (both copies stuck at the same x), so λ = −inf for each
    p = flat(0.4)
    res = lyapunov(p, 4, 200 / p.f, 2, "dropped", direction=VERTICAL, n_resamples=10)
    assert res.n_collapsed == 4
    assert np.all(res.lam_i == -np.inf)
    assert math.isnan(res.lam)


def test_x_range_is_how_far_the_primary_moved_after_the_transient():
    # flat floor, β = 1: vₓ survives every collision, so on the period-1 orbit (no sticking)
    # x = x0 + vₓ t exactly; over the window after the transient (20 of 200 periods) it spans
    # vₓ × 180 periods
    p = flat(0.8).with_(beta=1.0)
    st = period_one_state(p, 2)
    st = InitialState(st.cell, st.d, st.y, np.array([5.0, -2.0]), st.vy, st.s, st.stuck,
                      st.from_surface)
    res = lyapunov(p, 2, 200 / p.f, 0, st, direction=VERTICAL, discard=0.1, n_resamples=10)
    np.testing.assert_allclose(res.x_range, np.array([5.0, 2.0]) * 180 / p.f, rtol=1e-9)
