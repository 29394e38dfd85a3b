"""Claims about bbb.analysis.approx: the flat-floor spiral, paper Eqs. (8)–(9), and k = 2 v f / g (Eq. 7).

Hand arithmetic uses A = 0.1 mm, g = 9800 mm/s², alpha = 0.7, so
alpha g / 2 = 3430 mm/s² and A 2π f (1 + alpha) = 0.17 · 2π f mm/s.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from bbb.analysis.approx import floor_t0, locking_ratio, spiral, spiral_of
from bbb.params import Params

A, G, ALPHA = 0.1, 9800.0, 0.7


@pytest.mark.parametrize("f", [30.0, 54.0, 60.0, 97.3])
def test_floor_t0_is_the_time_of_maximal_upward_floor_velocity(f):
    # y_f = -A sin(2π f t)  =>  v_f = -2π f A cos(2π f t); search one period on a fine grid.
    t = np.linspace(0.0, 1.0 / f, 200_001, endpoint=False)
    v_f = -2 * math.pi * f * A * np.cos(2 * math.pi * f * t)
    assert floor_t0(f) == pytest.approx(t[np.argmax(v_f)], abs=1.0 / f / 100_000)
    assert 0.0 <= floor_t0(f) < 1.0 / f


def test_spiral_at_zero_flight_time_f60():
    # t0 = 1/120 s, t1 = t0: 2π·60·(1/120) = π, sin π = 0, cos π = -1.
    # y = 0;  v = 0 - 0.17 · 120π · (-1) = 20.4π ≈ 64.088 mm/s.
    y, v = spiral(A, 60.0, G, ALPHA, 0.0)
    assert y == pytest.approx(0.0, abs=1e-12)
    assert v == pytest.approx(20.4 * math.pi, rel=1e-12)


def test_spiral_at_quarter_period_flight_f60():
    # t_c = 1/240 s: t1 = 1/120 + 1/240 = 1/80, phase 2π·60/80 = 3π/2, sin = -1, cos = 0.
    # y = -0.1 · (-1) = 0.1 mm;  v = 3430 / 240 = 14.291666... mm/s.
    y, v = spiral(A, 60.0, G, ALPHA, 1.0 / 240.0)
    assert y == pytest.approx(0.1, rel=1e-12)
    assert v == pytest.approx(3430.0 / 240.0, rel=1e-12)


def test_spiral_at_half_period_flight_f60():
    # t_c = 1/120 s: t1 = 1/60, phase 2π, sin = 0, cos = 1.
    # v = 3430/120 - 20.4π = 28.58333 - 64.08849 = -35.50516 mm/s.
    y, v = spiral(A, 60.0, G, ALPHA, 1.0 / 120.0)
    assert y == pytest.approx(0.0, abs=1e-12)
    assert v == pytest.approx(3430.0 / 120.0 - 20.4 * math.pi, rel=1e-12)


def test_spiral_at_f50_after_a_30_ms_flight():
    # t0 = 1/100 = 0.01 s, t_c = 0.03 s: t1 = 0.04 s, phase 2π·50·0.04 = 4π, sin = 0, cos = 1.
    # v = 3430 · 0.03 - 0.17 · 100π = 102.9 - 17π ≈ 49.4929 mm/s.
    y, v = spiral(A, 50.0, G, ALPHA, np.array([0.03]))
    np.testing.assert_allclose(y, [0.0], atol=1e-12)
    np.testing.assert_allclose(v, [102.9 - 17.0 * math.pi], rtol=1e-12)


def test_spiral_of_reads_A_f_g_alpha_from_params():
    # klages2004 preset: A = 0.1, g = 9800, alpha = 0.7 — the same hand value as at f = 60.
    p = Params.preset("klages2004", f=60.0)
    _, v = spiral_of(p, 0.0)
    assert v == pytest.approx(20.4 * math.pi, rel=1e-12)
    # g enters only after a flight: at t_c = 1/240 s, v = alpha g / 2 · t_c (hand value above);
    # with g halved and A doubled, v = 0.7 · 4900 / 2 / 240 and y = 0.2 mm
    y, v = spiral_of(Params.preset("klages2004", f=60.0, g=4900.0, A=0.2), 1.0 / 240.0)
    assert v == pytest.approx(0.7 * 4900.0 / 2 / 240.0, rel=1e-12)
    assert y == pytest.approx(0.2, rel=1e-12)


def test_spiral_refuses_negative_flight_times():
    with pytest.raises(ValueError, match="t_c"):
        spiral(A, 60.0, G, ALPHA, [0.01, -0.001])


def test_locking_ratio_of_100_mm_per_s_at_49_hz_is_one():
    # k = 2 · 100 · 49 / 9800 = 9800 / 9800 = 1: flight time 2v/g = 1/49 s = one floor period.
    assert locking_ratio(100, 49, 9800) == 1.0
