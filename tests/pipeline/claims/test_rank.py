import math

import numpy as np
import pytest

from pipeline.claims.rank import rank_trend, spearman


def test_spearman_of_a_monotonic_curve_is_one_and_of_its_reverse_minus_one():
    x = np.arange(10.0)
    assert spearman(x, np.exp(x)) == pytest.approx(1.0)
    assert spearman(x, -x**3) == pytest.approx(-1.0)


def test_spearman_agrees_with_scipy_with_ties():
    stats = pytest.importorskip("scipy.stats")
    rng = np.random.default_rng(3)
    x, y = rng.integers(0, 5, 15).astype(float), rng.normal(size=15)
    assert spearman(x, y) == pytest.approx(stats.spearmanr(x, y).statistic)


def test_the_exact_p_of_a_perfect_order_of_five_is_two_in_120():
    rho, p, n = rank_trend([1, 2, 3, 4, 5], [10, 20, 30, 40, 50])
    assert (rho, n) == (pytest.approx(1.0), 5)
    assert p == pytest.approx(2 / 120)  # the order and its reverse


def test_a_trend_in_noise_is_found_and_pure_noise_rarely():
    rng = np.random.default_rng(11)
    x = np.linspace(0.4, 0.95, 12)
    found = [rank_trend(x, 60 - 10 * x + rng.normal(0, 0.8, 12))[1] <= 0.05 for _ in range(40)]
    assert np.mean(found) >= 0.9
    false = [rank_trend(x, rng.normal(0, 1, 12))[1] <= 0.05 for _ in range(200)]
    assert np.mean(false) <= 0.09  # 5 % nominal; 200 draws: 3 standard errors


def test_the_p_value_is_the_same_on_every_call():
    x, y = np.arange(12.0), np.sin(np.arange(12.0))
    assert rank_trend(x, y) == rank_trend(x, y)


def test_fewer_than_three_points_give_no_trend():
    rho, p, n = rank_trend([1.0, 2.0, math.nan], [3.0, 1.0, 2.0])
    assert math.isnan(rho) and math.isnan(p) and n == 2
