"""The onset theory's linear maps against the kernel's own map: finite-difference Jacobians of
bbb.simulate over one and two bounces (period-1, period-2 at the sine's valley), one
chattering cycle's horizontal multiplier, the cusp wedge's kick, and the end of the
chattering cycle from rest on the flat floor (docs/physics.md, "Why motion starts")."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bbb import Params, simulate
from bbb.analysis import onset_theory as ot
from bbb.ensemble import InitialState
from bbb.surface import floor_depth

G, A = 9800.0, 0.1


def _state(p, xs, us, s, vy, stuck=False):
    """States at x = S/2 + ξ (the valley or cusp between cells 0 and 1) on the surface at
    floor time s, horizontal speed u, vertical speed vy."""
    xs, us = np.atleast_1d(xs).astype(float), np.atleast_1d(us).astype(float)
    x = 0.5 * p.S + xs
    cell = np.floor(x / p.S + 0.5).astype(np.int64)
    d = x - cell * p.S
    y = -p.A * np.sin(p.omega * s) - floor_depth(p, d)
    n = xs.size
    return InitialState(cell, d, y, us, np.full(n, vy), np.full(n, s), np.full(n, stuck),
                        np.ones(n, bool))


def _after(p, st, bounces):
    """(ξ, vx) after the ``bounces``-th collision of each particle."""
    run = simulate(p, st.cell.size, (bounces + 0.5) / p.f, 0, st, record_collisions=bounces)
    rec = run.collisions_dense[:, bounces - 1]
    return rec[:, 1] - 0.5 * p.S, rec[:, 3]


def _fd_jacobian(p, s, vy, bounces, eps=1e-6, du=1e-4):
    st = _state(p, [eps, -eps, 0.0, 0.0], [0.0, 0.0, du, -du], s, vy)
    xi, u = _after(p, st, bounces)
    return np.array([[(xi[0] - xi[1]) / (2 * eps), (xi[2] - xi[3]) / (2 * du)],
                     [(u[0] - u[1]) / (2 * eps), (u[2] - u[3]) / (2 * du)]])


def _sine(f, alpha, depth=0.3):
    return Params.preset("klages2004", f=f, alpha=alpha, floor="sine", depth=depth)


def test_the_bounce_matrix_of_the_1_1_orbit_at_the_sine_valley_is_the_kernels_jacobian():
    f, a = 52.0, 0.7
    p = _sine(f, a)
    U, tau = ot.period1(f, a, G)
    vf = G * tau * (1 - a) / (2 * (1 + a))  # the floor's velocity at the orbit's impacts
    s = (2 * math.pi - math.acos(-vf / (p.A * p.omega))) / p.omega
    J = _fd_jacobian(p, s, vf + a * U, 1)
    M = ot.bounce_matrix(ot.sine_curvature(0.3, p.S), U, tau, a, p.beta)
    assert np.allclose(J, M, rtol=2e-3, atol=2e-3 * np.abs(M).max())


def test_the_period_2_orbit_and_its_two_bounce_matrix_are_the_kernels():
    f, a = 56.0, 0.7
    p = _sine(f, a)
    orbit = ot.period2(p.A * p.omega**2 / G, f, a, G)
    assert orbit is not None
    (U1, t1), (U2, t2) = orbit["legs"]
    assert abs(t1 + t2 - 2 / f) < 1e-9 and abs(t1 - t2) > 0.1 / f  # two unequal flights
    s = orbit["phase"] / p.omega
    vy = -p.A * p.omega * math.cos(orbit["phase"]) + orbit["u"]
    J = _fd_jacobian(p, s, vy, 2)
    M = ot.cycle_matrix(ot.sine_curvature(0.3, p.S), orbit["legs"], a, p.beta)
    assert np.allclose(J, M, rtol=5e-3, atol=5e-3 * np.abs(M).max())


def test_one_chattering_cycle_at_the_sine_valley_scales_the_offset_by_lambda():
    f, a = 55.0, 0.7
    p = _sine(f, a)
    gam = p.A * p.omega**2 / G
    cyc = ot.chatter_cycle(gam, f, a, G)
    lam = ot.chatter_lambda(ot.sine_curvature(0.3, p.S), cyc, a, p.beta)
    # held at rest at ±ξ a little before the lift-off window; one period later it is held again
    s = cyc["t0"] - 0.05 / f
    eps = 1e-6
    st = _state(p, [eps, -eps], [0.0, 0.0], s, -p.A * p.omega * math.cos(p.omega * s),
                stuck=True)
    run = simulate(p, 2, 0.9 / f, 0, st, sample_times=np.array([0.9 / f]))
    xi = run.positions[:, 0] - 0.5 * p.S
    assert run.counters["sticks"].tolist() == [1, 1]
    assert abs((xi[0] - xi[1]) / (2 * eps) - lam) < 1e-6  # measured: 1e-10
    assert abs(lam) < 1.0  # the rest point is horizontally stable under chattering here


@pytest.mark.parametrize("R", [1.05, 2.5, 15.0])
def test_at_the_cusp_a_vertical_impact_is_kicked_toward_it_however_small_the_offset(R):
    f, a = 52.0, 0.7
    p = Params.preset("klages2004", f=f, alpha=a, R=R)
    U, tau = ot.period1(f, a, G)
    vf = G * tau * (1 - a) / (2 * (1 + a))
    s = (2 * math.pi - math.acos(-vf / (p.A * p.omega))) / p.omega
    K = ot.wedge_kick(U, a, p.beta, R, p.S)
    for eps in (1e-5, 1e-8):
        _, u = _after(p, _state(p, [eps, -eps], [0.0, 0.0], s, vf + a * U), 1)
        assert np.allclose(u, [-K, K], rtol=2e-3)  # the kick does not shrink with the offset


def test_the_chattering_cycle_ends_within_its_period_below_f_c_and_not_above():
    a = 0.7
    fc = ot.chatter_limit(a, A=A, g=G, tol=0.01)
    assert 50.0 < fc < 65.0
    per_period = []
    for f in (fc - 0.1, fc + 0.1):
        p = Params.preset("klages2004", f=f, alpha=a, R=math.inf)
        # sticks over periods 50-100 (whole periods; the first 50 a transient)
        r1, r2 = simulate(p, 2, 50.25 / f, 1, "rest"), simulate(p, 2, 100.25 / f, 1, "rest")
        per_period.append((r2.counters["sticks"] - r1.counters["sticks"]) / 50.0)
    assert np.all(per_period[0] == 1.0)  # one stick a period: the chattering cycle
    assert np.all(per_period[1] < 0.5)  # the kernel leaves it, as the theory says


def test_the_1_1_orbit_at_a_smooth_minimum_flips_where_the_bounce_matrix_trace_reaches_minus_1_minus_beta():
    a, b, k = 0.7, 0.99, ot.sine_curvature(0.3, 2.0)
    c = 2 * (1 + b) * (1 + a) / ((a + b) * k * G)  # 1/f² at the flip, solved by hand
    f_flip = 1 / math.sqrt(c)
    for f, want in ((f_flip * 0.999, False), (f_flip * 1.001, True)):
        U, tau = ot.period1(f, a, G)
        assert ot.stable(ot.bounce_matrix(k, U, tau, a, b)) is want
    assert abs(np.linalg.det(ot.bounce_matrix(k, 100.0, 0.02, a, b)) - b) < 1e-12
