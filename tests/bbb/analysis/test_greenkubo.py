"""The Taylor–Green–Kubo expansion against AR(1) sequences (analytic C(k) = σ²ρ^k) and
against the MSD-based D of real runs.

Tolerances: particles are independent, so the bootstrap over particles estimates the
sampling error of every D_n; 4 standard errors (se = CI half-width / 1.96) make a false
failure less likely than 1e-4 per compared value.  The sequences are seeded, so each test
is deterministic.
"""

import math

import numpy as np
import pytest

from bbb import Params, simulate
from bbb.analysis.greenkubo import cell_jumps, collision_jumps, expansion, period_jumps
from bbb.analysis.stats import bootstrap_D

STEP = 1.0 / 60.0  # s
SIGMA = 0.3  # mm: stationary standard deviation of a jump


def ar1(rho: float, n_particles: int = 256, n_steps: int = 4000, seed: int = 7) -> np.ndarray:
    """Stationary AR(1) jumps x_{n+1} = ρ x_n + √(1−ρ²) σ ε_n (x_0 ~ N(0, σ²))."""
    rng = np.random.default_rng(seed)
    eps = rng.standard_normal((n_particles, n_steps)) * SIGMA * math.sqrt(1 - rho * rho)
    x = np.empty((n_particles, n_steps))
    x[:, 0] = rng.standard_normal(n_particles) * SIGMA
    for n in range(1, n_steps):
        x[:, n] = rho * x[:, n - 1] + eps[:, n]
    return x


def ar1_partial_sum(rho: float, n: np.ndarray) -> np.ndarray:
    """D_n = σ²/(2T) [1 + 2 Σ_{k=1..n} ρ^k] = σ²/(2T) [1 + 2ρ(1 − ρⁿ)/(1 − ρ)]."""
    return SIGMA**2 / (2 * STEP) * (1 + 2 * rho * (1 - rho**n) / (1 - rho))


def se_of(gk, n):
    return (gk.D_hi[n] - gk.D_lo[n]) / (2 * 1.96)


@pytest.mark.parametrize("rho", [0.6, -0.5])
def test_ar1_partial_sums_equal_the_analytic_truncations(rho):
    gk = expansion(ar1(rho), STEP, max_lag=30, seed=1)
    n = np.arange(31)
    se = se_of(gk, n)
    exact = ar1_partial_sum(rho, n)
    # the tolerance is tight enough to mean something: below 2 % of D_∞
    assert np.all(se < 0.02 * SIGMA**2 * (1 + rho) / (1 - rho) / (2 * STEP))
    assert np.all(np.abs(gk.D_n - exact) <= 4 * se)


@pytest.mark.parametrize("rho", [0.6, -0.5])
def test_ar1_converged_sum_equals_sigma2_1_plus_rho_over_1_minus_rho(rho):
    gk = expansion(ar1(rho), STEP, max_lag=100, seed=1)
    exact = SIGMA**2 * (1 + rho) / (1 - rho) / (2 * STEP)
    se = (gk.D_inf_hi - gk.D_inf_lo) / (2 * 1.96)
    # the rule stops at K, where |C| reaches ~2 se of one C(k): its bias is the analytic tail
    # Σ_{k≥K} 2ρ^k σ²/(2T), of the order of the statistical error of D_∞ (measured ≤ 1.1 se)
    tail = abs(exact - ar1_partial_sum(rho, gk.lag - 1))
    assert gk.converged and 2 <= gk.lag <= 30
    assert tail < 2 * se
    assert abs(gk.D_inf - exact) <= 4 * se + tail


def test_iid_jumps_give_d_n_equal_to_d0_for_every_n():
    n_p, n_steps = 256, 4000
    gk = expansion(ar1(0.0, n_p, n_steps), STEP, max_lag=50, seed=1)
    # D_n − D_0 = (1/T) Σ_{k=1..n} C(k): for i.i.d. jumps each C(k) has variance σ⁴/(n_p n_steps)
    se_diff = np.sqrt(np.arange(51)) * SIGMA**2 / math.sqrt(n_p * n_steps) / STEP
    assert np.all(np.abs(gk.D_n - gk.D_n[0]) <= 4 * se_diff + 1e-12)
    # the rule may stop at K > 1 on a noise excursion (calibrated: K = 1 in 78 % of i.i.d.
    # sequences at noise_z = 2), but then D_∞ = D_{K−1} is D_0 within noise
    assert gk.converged and gk.lag <= 10
    assert abs(gk.D_inf - gk.D_n[0]) <= 4 * se_diff[gk.lag - 1] + 1e-12


@pytest.fixture(scope="module", params=[60.0, 72.0, 80.0])
def real_run(request):
    """256 particles × 50 s from rest, x sampled every floor period (≈ 1 s each)."""
    f = request.param
    p = Params.preset("klages2004", f=f)
    times = np.arange(int(round(50 * f)) + 1) / f
    run = simulate(p, 256, float(times[-1]), seed=11, sample_times=times)
    return f, times, run.positions


def test_converged_sum_equals_the_msd_diffusion_coefficient_on_real_runs(real_run):
    f, times, x = real_run
    # the MSD fit drops the first 10 % of the run as transient: drop the same periods here
    discard = math.ceil(0.1 * (times.size - 1))
    gk = expansion(period_jumps(x, discard), 1.0 / f, seed=2)
    msd = bootstrap_D(x, times, n_resamples=1000, seed=3)
    assert gk.converged
    # CIs overlap: |difference| within the root-sum-square of the half-widths
    half_gk = 0.5 * (gk.D_inf_hi - gk.D_inf_lo)
    half_msd = 0.5 * (msd.hi - msd.lo)
    assert abs(gk.D_inf - msd.D) <= math.hypot(half_gk, half_msd)


def test_per_collision_expansions_equal_the_msd_diffusion_coefficient_at_80_hz():
    f = 80.0
    p = Params.preset("klages2004", f=f)
    times = np.arange(int(round(50 * f)) + 1) / f
    run = simulate(p, 256, float(times[-1]), seed=11, sample_times=times,
                   record_collisions=6000, record_from=5.0)
    msd = bootstrap_D(run.positions, times, n_resamples=1000, seed=3)
    cj = cell_jumps(run.collisions_dense, run.n_recorded, p.S)
    gk = expansion(cj.jumps * p.S, cj.tau, seed=2)
    assert cj.n_excluded <= 5 and cj.jumps.shape[1] > 1000
    # in mm, each particle with its own τ̄ (the pipeline's per-collision expansion)
    dx, dt = collision_jumps(run.collisions_dense, run.n_recorded)
    n = int(np.isfinite(dx).sum(axis=1).min())
    gx = expansion(dx[:, :n], dt[:, :n].sum(axis=1) / n, seed=2)
    assert n > 1000
    for g in (gk, gx):
        assert g.converged
        half = math.hypot(0.5 * (g.D_inf_hi - g.D_inf_lo), 0.5 * (msd.hi - msd.lo))
        assert abs(g.D_inf - msd.D) <= half


def test_collision_jumps_are_the_differences_of_the_recorded_rows_and_nan_beyond():
    rows = np.full((2, 4, 6), np.nan)
    rows[0, :3, :2] = [[0.0, 1.0], [0.5, 3.0], [0.75, 2.5]]
    rows[1, :4, :2] = [[0.0, 0.0], [0.1, -1.0], [0.3, -1.5], [0.6, 0.5]]
    dx, dt = collision_jumps(rows, np.array([3, 4]))
    np.testing.assert_array_equal(dx, [[2.0, -0.5, np.nan], [-1.0, -0.5, 2.0]])
    np.testing.assert_allclose(dt, [[0.5, 0.25, np.nan], [0.1, 0.2, 0.3]], rtol=1e-12)


def test_per_particle_steps_divide_by_their_mean_in_the_estimate_and_in_every_resample():
    x = ar1(0.6, n_particles=64, n_steps=1000)
    steps = np.where(np.arange(64) < 32, STEP, 3 * STEP)
    g = expansion(x, steps, max_lag=20, n_resamples=200, seed=4)
    c0 = np.mean(x * x, axis=1)  # each particle's C(0)
    assert g.step == pytest.approx(2 * STEP, rel=1e-12)
    assert g.D_n[0] == pytest.approx(c0.mean() / (2 * 2 * STEP), rel=1e-12)
    # a resample's D_0 is its particles' mean C(0) over twice their mean step: the replicates
    # spread more than with one common step (the step varies with the drawn particles)
    same = expansion(x, 2 * STEP, max_lag=20, n_resamples=200, seed=4)
    assert same.D_n[0] == pytest.approx(g.D_n[0], rel=1e-12)
    assert np.std(g.D0_boot) > 1.5 * np.std(same.D0_boot)
    # equal steps given per particle: the same numbers as one step
    one = expansion(x, np.full(64, STEP), max_lag=20, n_resamples=200, seed=4)
    ref = expansion(x, STEP, max_lag=20, n_resamples=200, seed=4)
    np.testing.assert_allclose(one.D_n, ref.D_n, rtol=1e-12)
    np.testing.assert_allclose(one.D0_boot, ref.D0_boot, rtol=1e-12)


def test_kept_replicates_are_the_ones_behind_the_cis():
    g = expansion(ar1(0.6, n_particles=64, n_steps=1000), STEP, max_lag=40, n_resamples=300,
                  seed=5)
    assert g.D0_boot.shape == g.D_inf_boot.shape == (300,)
    np.testing.assert_allclose(np.quantile(g.D0_boot, [0.025, 0.975]), [g.D_lo[0], g.D_hi[0]],
                               rtol=1e-12)
    np.testing.assert_allclose(np.quantile(g.D_inf_boot, [0.025, 0.975]),
                               [g.D_inf_lo, g.D_inf_hi], rtol=1e-12)
