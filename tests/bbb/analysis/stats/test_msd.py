"""Claims about bbb.analysis.stats.msd: the time-averaged MSD of single trajectories and ensembles."""

from __future__ import annotations

import numpy as np
import pytest

from bbb.analysis.stats import (
    msd_time_averaged,
    tamsd,
)

from .walks import DT, brownian, times

# few lags -> direct sums; all lags -> FFT path: every claim about δ² holds for both
LAG_SETS = {"few_lags": np.array([0, 1, 7, 50, 99]), "all_lags": np.arange(100)}


# --- time-averaged MSD ------------------------------------------------------------------


@pytest.mark.parametrize("lags", LAG_SETS.values(), ids=LAG_SETS.keys())
def test_tamsd_of_straight_line_is_v_squared_lag_squared(lags):
    # x = x0 + v t  =>  every window gives (v L dt)², so δ²(L) = v² (L dt)² exactly.
    v = np.array([[3.0], [-0.5], [120.0]])  # mm/s
    x = 250.0 + v * times(100)[None, :]
    expected = v**2 * (lags * DT)[None, :] ** 2
    np.testing.assert_allclose(tamsd(x, lags), expected, rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("lags", LAG_SETS.values(), ids=LAG_SETS.keys())
def test_tamsd_of_constant_trajectory_is_zero(lags):
    x = np.full((4, 100), 1234.5)
    np.testing.assert_allclose(tamsd(x, lags), 0.0, atol=1e-12)


@pytest.mark.parametrize("lags", LAG_SETS.values(), ids=LAG_SETS.keys())
def test_tamsd_is_the_mean_over_all_sliding_windows(lags):
    rng = np.random.default_rng(1)
    x = brownian(rng, 5, 100, D=2.0) + 500.0
    naive = np.array(
        [
            [np.mean([(xp[i + L] - xp[i]) ** 2 for i in range(100 - L)]) for L in lags]
            for xp in x
        ]
    )
    np.testing.assert_allclose(tamsd(x, lags), naive, rtol=1e-8, atol=1e-12)


def test_ensemble_msd_of_brownian_motion_is_two_D_lag():
    rng = np.random.default_rng(2)
    D = 0.8
    x = brownian(rng, 2000, 200, D)
    lags_s, msd = msd_time_averaged(x, DT, [1, 10, 40])
    np.testing.assert_allclose(lags_s, [0.01, 0.10, 0.40])
    # relative SE at the largest lag ≈ sqrt(4/3 · 40/160 / 2000) ≈ 1.3 %
    np.testing.assert_allclose(msd / (2 * lags_s), D, rtol=0.05)


def test_time_averaged_msd_scatters_much_less_than_single_origin_msd():
    # 300 independent ensembles of 20 particles; compare the spread of the two MSD
    # estimators at the same lag Δ = 0.1 T.  Theory: std ratio ≈ sqrt(4/3 · 0.1 / 2) ≈ 0.26.
    rng = np.random.default_rng(3)
    n_rep, n_part, n_samples, lag = 300, 20, 401, 40
    x = brownian(rng, n_rep * n_part, n_samples, D=1.0)
    ta = tamsd(x, [lag])[:, 0].reshape(n_rep, n_part).mean(axis=1)
    single = ((x[:, lag] - x[:, 0]) ** 2).reshape(n_rep, n_part).mean(axis=1)
    assert ta.std() < 0.5 * single.std()
