"""Claims about bbb.stats: MSD, D, bootstrap CIs and the ergodicity rule.

Synthetic Brownian trajectories (Gaussian increments of variance 2 D dt) have a known D,
a known time-averaged MSD 2 D Δ and a known ergodicity-breaking parameter ≈ 4/3 Δ/T.
"""

from __future__ import annotations

import numpy as np
import pytest

from bbb.stats import (
    bootstrap_D,
    diffusion_coefficient,
    eb_brownian,
    ergodic_verdict,
    ergodicity_breaking,
    fit_diffusion,
    msd_time_averaged,
    tamsd,
)

DT = 0.01  # s


def brownian(
    rng: np.random.Generator, n_particles: int, n_samples: int, D: float, dt: float = DT
) -> np.ndarray:
    """Positions (mm) of Brownian particles with diffusion coefficient D (mm²/s), x(0) = 0."""
    steps = rng.normal(scale=np.sqrt(2.0 * D * dt), size=(n_particles, n_samples - 1))
    x = np.zeros((n_particles, n_samples))
    np.cumsum(steps, axis=1, out=x[:, 1:])
    return x


def times(n_samples: int, dt: float = DT) -> np.ndarray:
    return np.arange(n_samples) * dt


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


# --- fitting D --------------------------------------------------------------------------


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


# --- bootstrap --------------------------------------------------------------------------


def test_bootstrap_95_percent_ci_covers_true_D_in_90_to_98_percent_of_repetitions():
    # Measured: 94.2 % over 2000 repetitions of this setting.
    rng = np.random.default_rng(6)
    D_true, n_rep = 0.5, 400
    t = times(100)
    hits = 0
    for r in range(n_rep):
        x = brownian(rng, 100, 100, D_true)
        _, lo, hi = bootstrap_D(x, t, n_resamples=1000, seed=r)
        hits += lo <= D_true <= hi
    assert 0.90 <= hits / n_rep <= 0.98


def test_bootstrap_is_a_deterministic_function_of_the_seed():
    rng = np.random.default_rng(7)
    x, t = brownian(rng, 50, 200, D=1.0), times(200)
    a = bootstrap_D(x, t, n_resamples=500, seed=42)
    b = bootstrap_D(x, t, n_resamples=500, seed=42)
    c = bootstrap_D(x, t, n_resamples=500, seed=43)
    assert a == b
    assert (a.lo, a.hi) != (c.lo, c.hi)


def test_bootstrap_point_estimate_is_the_D_of_diffusion_coefficient():
    rng = np.random.default_rng(8)
    x, t = brownian(rng, 50, 300, D=1.0), times(300)
    boot = bootstrap_D(x, t, n_resamples=200, seed=0, method="bca")
    assert boot.D == pytest.approx(diffusion_coefficient(x, t).D, rel=1e-12)
    assert boot.lo < boot.D < boot.hi


# --- ergodicity -------------------------------------------------------------------------


def test_eb_brownian_exact_value_at_lag_one_and_its_four_thirds_limit():
    # L = 1: δ² is a mean of W = n - 1 independent squares, Var/mean² = 2/W = 2/100.
    assert eb_brownian(1, 101) == pytest.approx(0.02, rel=1e-12)
    # 1 ≪ L ≪ W: 4/3 · L/W = 4/3 · 100/99_900.
    assert eb_brownian(100, 100_000) == pytest.approx(4 / 3 * 100 / 99_900, rel=0.01)


def test_eb_of_brownian_motion_is_close_to_four_thirds_lag_over_T():
    # 2000 particles, analysed T = 399 dt (no transient), lag 20 dt: 4/3 · 20/399 ≈ 0.067.
    # The estimator's relative SE with 2000 particles is ≈ sqrt(2/1999) ≈ 3 %.
    rng = np.random.default_rng(9)
    x = brownian(rng, 2000, 400, D=1.0)
    eb = ergodicity_breaking(x, times(400), lag=20 * DT, discard=0.0)
    assert eb == pytest.approx(4 / 3 * 20 / 399, rel=0.15)


def test_eb_of_a_mixture_of_D_and_10D_is_far_above_brownian():
    # Half D, half 10 D: EB ≥ Var(D_i)/⟨D_i⟩² = (4.5/5.5)² ≈ 0.67 vs Brownian ≈ 0.07.
    rng = np.random.default_rng(10)
    x = np.vstack([brownian(rng, 500, 400, D=0.1), brownian(rng, 500, 400, D=1.0)])
    eb = ergodicity_breaking(x, times(400), lag=20 * DT, discard=0.0)
    assert eb > 5 * eb_brownian(20, 400)


def test_verdict_on_brownian_families_with_equal_D_is_ergodic():
    rng = np.random.default_rng(11)
    families = {"rest": brownian(rng, 300, 400, D=1.0), "uniform": brownian(rng, 300, 400, 1.0)}
    verdict = ergodic_verdict(families, times(400), seed=1)
    assert verdict.ergodic, verdict.reasons


def test_verdict_on_families_mixing_D_and_10D_is_non_ergodic_by_eb():
    rng = np.random.default_rng(12)

    def mixed() -> np.ndarray:
        return np.vstack([brownian(rng, 150, 400, D=0.1), brownian(rng, 150, 400, D=1.0)])

    verdict = ergodic_verdict({"a": mixed(), "b": mixed()}, times(400), seed=1)
    assert not verdict.ergodic
    assert not verdict.eb_ok, verdict.reasons


def test_verdict_on_families_with_clearly_different_D_fails_agreement():
    # Each family is homogeneous Brownian, but D differs by 50 %: rule (a) must fail.
    rng = np.random.default_rng(13)
    families = {"slow": brownian(rng, 300, 400, D=1.0), "fast": brownian(rng, 300, 400, D=1.5)}
    verdict = ergodic_verdict(families, times(400), seed=1)
    assert not verdict.ergodic
    assert not verdict.agreement_ok, verdict.reasons


def jumps(rng: np.random.Generator, n_particles: int, n_samples: int, rate: float,
          dt: float = DT) -> np.ndarray:
    """Compound Poisson walks: N(0, 1) mm jumps at `rate` per second.  Ergodic (every
    particle has the same D = rate/2), but its increments are far from Gaussian at lags
    ~ 1/rate, so EB sits above the Brownian level and still falls like 1/T."""
    steps = rng.standard_normal((n_particles, n_samples - 1))
    steps *= rng.random((n_particles, n_samples - 1)) < rate * dt
    return np.concatenate([np.zeros((n_particles, 1)), np.cumsum(steps, axis=1)], axis=1)


def test_ergodic_motion_with_eb_above_the_brownian_level_passes_by_its_decay():
    rng = np.random.default_rng(14)
    n, rate = 4000, 0.3  # 40 s runs, 12 jumps per particle: EB ~ 3/(rate T) > 2 x Brownian
    families = {"a": jumps(rng, 1000, n, rate), "b": jumps(rng, 1000, n, rate)}
    verdict = ergodic_verdict(families, times(n), seed=1)
    assert verdict.eb["(pooled)"] > verdict.eb_threshold  # the level rule alone would fail
    assert verdict.ergodic, verdict.reasons
