"""Claims about bbb.analysis.locking: creeping band, maximal v_y+, dominant peak, flight times, k."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bbb.analysis.locking import (
    creep_speed,
    dominant_peak,
    flight_time_max,
    flight_times,
    locking_estimate,
    spiral_vmax,
)

A, G = 0.1, 9800.0


def _creeping(rng, f, n):
    """Post-collision v_y+ of creeping particles: about the floor velocity, |v| <= A 2 pi f."""
    return -A * 2 * math.pi * f * np.cos(rng.uniform(0, 2 * math.pi, n))


def test_creep_speed_is_the_floor_peak_speed_plus_ten_percent():
    assert creep_speed(0.1, 60.0) == pytest.approx(1.1 * 0.1 * 2 * math.pi * 60.0)
    assert creep_speed(0.1, 60.0, margin=0.0) == pytest.approx(0.1 * 2 * math.pi * 60.0)


def test_maximal_v_is_the_99_percent_quantile_above_the_creeping_band():
    rng = np.random.default_rng(0)
    bouncing = rng.normal(120.0, 5.0, 200_000)
    v = np.concatenate([_creeping(rng, 60.0, 400_000), bouncing])
    # 0.99 quantile of N(120, 5): 120 + 2.3263 * 5
    assert spiral_vmax(v, creep_speed(A, 60.0)) == pytest.approx(120 + 2.3263 * 5, abs=0.2)


def test_the_creeping_band_does_not_move_the_maximal_v():
    rng = np.random.default_rng(1)
    bouncing = rng.normal(120.0, 5.0, 50_000)
    vc = creep_speed(A, 60.0)
    few = spiral_vmax(np.concatenate([_creeping(rng, 60.0, 1000), bouncing]), vc)
    many = spiral_vmax(np.concatenate([_creeping(rng, 60.0, 10**6), bouncing]), vc)
    assert few == pytest.approx(many, abs=0.3)


def test_dominant_peak_is_the_denser_of_two_bouncing_modes():
    rng = np.random.default_rng(2)
    v = np.concatenate([_creeping(rng, 60.0, 300_000), rng.normal(70.0, 4.0, 70_000),
                        rng.normal(120.0, 6.0, 30_000)])
    assert dominant_peak(v, creep_speed(A, 60.0)) == pytest.approx(70.0, abs=1.0)


def test_dominant_peak_ignores_even_a_huge_creeping_band():
    rng = np.random.default_rng(3)
    v = np.concatenate([_creeping(rng, 54.0, 10**6), rng.normal(95.0, 3.0, 5_000)])
    assert dominant_peak(v, creep_speed(A, 54.0)) == pytest.approx(95.0, abs=1.0)


def test_a_1_1_locking_spot_gives_k_one():
    # T_p = 2 v / g = 1/f  <=>  v = g / (2 f) = 90.74 mm/s at 54 Hz
    rng = np.random.default_rng(4)
    v = np.concatenate([_creeping(rng, 54.0, 20_000), rng.normal(G / 108.0, 2.0, 20_000)])
    est = locking_estimate(v, A, 54.0, G)
    assert est.k_peak == pytest.approx(1.0, abs=0.02)
    assert est.frac_creep == pytest.approx(0.5, abs=0.01)


def test_too_few_points_above_the_band_give_nan():
    v = np.concatenate([np.zeros(1000), [100.0] * 5])
    assert math.isnan(spiral_vmax(v, 40.0))
    assert math.isnan(dominant_peak(v, 40.0))
    assert math.isnan(locking_estimate(v, A, 60.0, G).k_max)


def _bounces(T, t_start=0.0):
    """Collisions of a particle bouncing on a still flat floor at y = 0 with flight times T."""
    t = t_start + np.concatenate([[0.0], np.cumsum(T)])
    vy = np.append(G * np.asarray(T) / 2.0, np.nan)  # leaves each collision to land after T
    vy[-1] = vy[-2]
    return t, np.zeros_like(t), vy


def test_flight_times_of_ballistic_bounces_are_recovered():
    T = np.array([0.010, 0.020, 0.015, 0.030])
    t, y, vy = _bounces(T, t_start=123.0)
    np.testing.assert_allclose(flight_times(t, y, vy, G), T, rtol=1e-9)


def test_an_interval_spent_stuck_on_the_floor_is_not_a_flight():
    T = np.array([0.010, 0.020, 0.015])
    t, y, vy = _bounces(T)
    vy[1] = 0.0  # after collision 1 the particle is carried with the floor, then hit again
    np.testing.assert_allclose(flight_times(t, y, vy, G), [0.010, 0.015], rtol=1e-9)


def test_flight_times_stay_within_each_particle_and_skip_nan_padding():
    t1, y1, v1 = _bounces([0.01, 0.02])
    t2, y2, v2 = _bounces([0.03])
    pad = lambda a: np.append(a, [np.nan] * (len(t1) - len(a)))  # noqa: E731
    t = np.stack([t1, pad(t2)])
    y, vy = np.stack([y1, pad(y2)]), np.stack([v1, pad(v2)])
    np.testing.assert_allclose(np.sort(flight_times(t, y, vy, G)), [0.01, 0.02, 0.03], rtol=1e-9)


def test_t_max_is_the_99_percent_quantile_of_the_flight_times():
    T = np.linspace(0.0, 0.04, 10_001)
    assert flight_time_max(T) == pytest.approx(0.99 * 0.04, rel=1e-9)
    assert math.isnan(flight_time_max(T[:5]))


def test_the_bootstrap_ci_of_the_peak_and_the_maximum_covers_the_truth():
    # 40 particles, each 300 states above the band, v ~ N(120, 5) mm/s: the dominant peak is
    # 120 and the 0.99 quantile 120 + 2.326 * 5; the CIs must hold them and be narrow
    from bbb.analysis.locking import bootstrap_locking, locking_estimate

    rng = np.random.default_rng(3)
    v = rng.normal(120.0, 5.0, size=(40, 300))
    ci = bootstrap_locking(v, 0.1, 60.0, 9800.0, n_resamples=300, seed=1)
    est = locking_estimate(v, 0.1, 60.0, 9800.0)
    assert ci.v_peak_lo <= est.v_peak <= ci.v_peak_hi
    assert ci.v_peak_lo <= 120.0 <= ci.v_peak_hi and ci.v_peak_hi - ci.v_peak_lo < 3.0
    assert ci.v_max_lo <= 120.0 + 2.326 * 5.0 <= ci.v_max_hi
    assert ci.k_max_lo == pytest.approx(2 * ci.v_max_lo * 60.0 / 9800.0)


def test_the_bootstrap_ci_resamples_particles_not_collisions():
    # particles at two speeds (half at 100, half at 140 mm/s, 1 mm/s noise): the peak of a
    # resample flips between them, so its CI must span both; a collision bootstrap would not
    from bbb.analysis.locking import bootstrap_locking

    rng = np.random.default_rng(4)
    v = np.where(np.arange(20)[:, None] < 10, 100.0, 140.0) + rng.normal(0, 1.0, (20, 200))
    ci = bootstrap_locking(v, 0.1, 60.0, 9800.0, n_resamples=400, seed=2)
    assert ci.v_peak_lo < 105.0 and ci.v_peak_hi > 135.0


def test_a_creeping_ensemble_has_no_locking_ci():
    from bbb.analysis.locking import bootstrap_locking

    v = np.full((8, 100), 10.0)  # all in the creeping band at 60 Hz (edge 41.5 mm/s)
    ci = bootstrap_locking(v, 0.1, 60.0, 9800.0, n_resamples=50, seed=0)
    assert math.isnan(ci.k_max_lo) and math.isnan(ci.v_peak_hi)
