"""Claims about bbb.analysis.stats.fit: D from the MSD slope, the default regime, D_last."""

from __future__ import annotations

import numpy as np
import pytest

from bbb.analysis.stats import (
    diffusion_coefficient,
    fit_diffusion,
)

from .walks import brownian, times


def test_fit_diffusion_recovers_an_exact_line():
    lags_s = np.linspace(0.1, 2.0, 20)
    D, c = fit_diffusion(lags_s, 2 * 0.7 * lags_s + 0.3, (0.1, 2.0))
    assert D == pytest.approx(0.7, rel=1e-12)
    assert c == pytest.approx(0.3, rel=1e-12)


def test_fit_diffusion_ignores_points_outside_lag_range():
    lags_s = np.arange(10) * 0.1
    msd = 2 * 1.5 * lags_s - 0.2
    msd[:3] = 100.0  # garbage outside the range must not matter
    msd[7:] = -50.0
    D, c = fit_diffusion(lags_s, msd, (0.3, 0.6))
    assert (D, c) == (pytest.approx(1.5, rel=1e-12), pytest.approx(-0.2, rel=1e-12))


@pytest.mark.parametrize(
    ("dt", "lag_range"),
    [
        # 11 · 0.03 = 0.32999999999999996 < 0.33 (start rounds below), 12 · 0.03 = 0.36
        (0.03, (0.33, 0.36)),
        # 5 · 0.1 = 0.5 exactly (start equals lo), 6 · 0.1 = 0.6000000000000001 > 0.6
        (0.1, (0.5, 0.6)),
    ],
)
def test_fit_diffusion_lag_range_is_inclusive_at_both_ends(dt, lag_range):
    # Only the two end lags fall in range, so the fit exists only if both ends count,
    # whichever way L · dt rounds.
    lags_s = np.arange(20) * dt
    D, _ = fit_diffusion(lags_s, 2 * 0.25 * lags_s, lag_range)
    assert D == pytest.approx(0.25, rel=1e-9)


def test_fit_with_fewer_than_two_lags_is_refused_with_a_clear_error():
    with pytest.raises(ValueError, match="at least 2"):
        fit_diffusion(np.arange(10) * 0.1, np.arange(10.0), (0.31, 0.39))


def test_default_regime_drops_first_10_percent_and_fits_5_to_25_percent_of_the_rest():
    # 1001 samples, dt = 0.01 s: run 10 s, transient 1 s, analysed T = 9 s,
    # fit lags 0.05 T = 0.45 s ... 0.25 T = 2.25 s, i.e. 45 ... 225 spacings = 181 lags.
    rng = np.random.default_rng(4)
    est = diffusion_coefficient(brownian(rng, 10, 1001, D=1.0), times(1001))
    assert est.t_start == pytest.approx(1.0)
    assert (est.fit_from, est.fit_to) == (pytest.approx(0.45), pytest.approx(2.25))
    assert est.n_lags == 181


def test_fitted_D_of_brownian_motion_is_within_four_standard_errors_of_truth():
    # SE from batch means over 10 independent sub-ensembles of 100 particles each.
    rng = np.random.default_rng(5)
    D_true = 0.25
    batches = [
        diffusion_coefficient(brownian(rng, 100, 1000, D_true), times(1000)).D
        for _ in range(10)
    ]
    se = np.std(batches, ddof=1) / np.sqrt(len(batches))
    assert abs(np.mean(batches) - D_true) < 4 * se


def test_D_last_is_the_single_origin_einstein_estimate_at_the_last_time():
    # x = v t over T = 0.99 s: ⟨(x(T) - x(0))²⟩ / (2T) = v² T / 2 = 4 · 0.99 / 2 = 1.98.
    x = 2.0 * times(100)[None, :] * np.ones((3, 1))
    assert diffusion_coefficient(x, times(100)).D_last == pytest.approx(1.98, rel=1e-12)
