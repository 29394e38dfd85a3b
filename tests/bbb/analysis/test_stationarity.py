"""bbb.analysis.stationarity: D of the two halves of the run, the paired CI and the flag, on walks whose
answer is known (constant diffusivity, diffusivity growing in time)."""

from __future__ import annotations

import numpy as np
import pytest

from bbb.analysis.stationarity import TOLERANCE, half_run_diffusion, stationarity
from bbb.analysis.stats import diffusion_coefficient

T = np.arange(0.0, 50.0001, 0.5)  # the Fig. 2 scene's sampling: 50 s at 0.5 s


def _walk(rng, n, growth=0.0, D=100.0):
    """Gaussian walks whose diffusivity is D (1 + growth t / t_end), mm²/s."""
    Dt = D * (1.0 + growth * T[1:] / T[-1])
    steps = rng.normal(size=(n, T.size - 1)) * np.sqrt(2.0 * Dt * 0.5)
    return np.concatenate([np.zeros((n, 1)), np.cumsum(steps, axis=1)], axis=1)


def _flag_rate(growth, n, reps, seed):
    rng = np.random.default_rng(seed)
    flags = [not stationarity(_walk(rng, n, growth), T, n_resamples=300, seed=r).stationary
             for r in range(reps)]
    return float(np.mean(flags))


def test_each_half_is_fitted_like_a_whole_run_of_that_length():
    x = _walk(np.random.default_rng(0), 50)
    d1, d2, T_h, _ = half_run_diffusion(x, T)
    start = 10  # discard 10 % of 50 s = 5 s = 10 samples
    half = (T.size - start) // 2
    for d, a in ((d1, start), (d2, start + half)):
        sl = slice(a, a + half)
        assert d.mean() == pytest.approx(diffusion_coefficient(x[:, sl], T[sl], discard=0.0).D,
                                         rel=1e-12)
    assert T_h == pytest.approx((half - 1) * 0.5)


def test_the_halves_recover_a_known_change_of_diffusivity():
    # D(t) = 100 (1 + t/50): mean over 5-27 s is 132, over 27.5-50 s is 177.5 (approx.)
    x = _walk(np.random.default_rng(1), 4000, growth=1.0)
    s = stationarity(x, T, n_resamples=200, seed=1)
    assert s.D_half1 == pytest.approx(132.0, rel=0.05)
    assert s.D_half2 == pytest.approx(177.5, rel=0.05)
    assert s.dD_lo < s.dD < s.dD_hi and not s.stationary


def test_the_paired_ci_covers_the_true_difference_about_95_percent_of_the_time():
    rng = np.random.default_rng(2)
    cover = [(lambda s: s.dD_lo <= 0.0 <= s.dD_hi)(
        stationarity(_walk(rng, 128), T, n_resamples=300, seed=r, tolerance=0.0)) for r in range(200)]
    assert 0.90 <= np.mean(cover) <= 0.985  # 95 % CI; binomial sd over 200 runs ~1.5 %


def test_stationary_walks_are_rarely_flagged():
    # calibration (module docstring): <= 3 % at 64 particles, <= 1 % from 256 on
    assert _flag_rate(0.0, 64, 200, seed=3) <= 0.05
    assert _flag_rate(0.0, 256, 100, seed=4) <= 0.03


def test_a_walk_whose_diffusivity_doubles_over_the_run_is_flagged():
    assert _flag_rate(1.0, 256, 60, seed=5) >= 0.85


def test_the_tolerance_is_relative_to_d():
    x = _walk(np.random.default_rng(6), 400)
    s = stationarity(x, T, n_resamples=100, seed=6)
    assert s.tolerance == pytest.approx(TOLERANCE * abs(s.D_half1 + s.D_half2) / 2 + 1e-6)
    still = stationarity(np.zeros((10, T.size)), T, n_resamples=50, seed=0)
    assert still.D_half1 == still.D_half2 == 0.0 and still.stationary


def test_a_run_too_short_for_two_fit_lags_is_refused():
    with pytest.raises(ValueError, match="fit lag"):
        stationarity(np.zeros((4, 12)), np.arange(12.0), n_resamples=10, seed=0)


def test_an_ensemble_that_never_moves_gets_no_interval_of_the_change_not_a_zero_width_one():
    # particles held still: every D_i is 0 in both halves; [0, 0] would claim certainty
    x = np.tile(np.arange(16.0)[:, None], (1, 101))
    s = stationarity(x, np.arange(101) * 0.5, n_resamples=200, seed=0)
    assert s.dD == 0.0 and np.isnan(s.dD_lo) and np.isnan(s.dD_hi)
    assert s.stationary  # nothing to flag
