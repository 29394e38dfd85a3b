"""bbb.analysis.transport on synthetic drifting Brownian walks with known v (mm/s) and D (mm²/s)."""

import numpy as np
import pytest

from bbb.analysis.stats.synthetic import brownian
from bbb.analysis.transport import drift_velocity, per_particle_drift, transport

DT, N_SAMPLES, N = 0.1, 501, 400  # 50 s sampled every 0.1 s, 400 particles
TIMES = np.arange(N_SAMPLES) * DT


def _walks(v: float, D: float, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    x = brownian(rng, np.full(N, D), N_SAMPLES, DT)
    return x + v * TIMES[None, :] + rng.uniform(-5, 5, (N, 1))  # spread starting points


@pytest.mark.parametrize("v,D", [(3.0, 2.0), (-0.7, 0.5), (25.0, 10.0)])
def test_drifting_walks_recover_v_and_D_within_their_CIs(v, D):
    # 95 % CIs: over 40 independent ensembles each should cover the truth ~38 times; the
    # threshold 32 (80 %) fails with probability < 1e-3 for a correct 95 % interval
    # (binomial), while a biased estimator (e.g. D without subtracting v t) covers 0 times.
    hits_v = hits_d = 0
    for rep in range(40):
        est = transport(_walks(v, D, rep)[:200], TIMES, 2.0, n_resamples=500, seed=rep)
        hits_v += est.v_lo <= v <= est.v_hi
        hits_d += est.D_lo <= D <= est.D_hi
        assert est.Pe == pytest.approx(est.v * 2.0 / est.D)
    assert hits_v >= 32 and hits_d >= 32, (hits_v, hits_d)


def test_zero_drift_walks_give_a_drift_CI_containing_zero():
    v, lo, hi = drift_velocity(_walks(0.0, 3.0, 2), TIMES, n_resamples=2000, seed=3)
    assert lo < 0.0 < hi
    assert hi - lo < 0.5  # and it is informative: ~4 sqrt(2 D / (N T)) wide


def test_a_pure_drift_gives_every_particle_exactly_that_drift():
    x = 1.5 * TIMES[None, :] + np.arange(3.0)[:, None]  # no noise: m_i(L) = v L dt exactly
    assert np.allclose(per_particle_drift(x, TIMES), 1.5, rtol=1e-12)


def test_a_constant_drift_is_steady_and_an_accelerating_ensemble_is_not():
    est = transport(_walks(3.0, 2.0, 5), TIMES, 2.0, n_resamples=1000, seed=1)
    assert est.steady and est.dv_lo <= 0.0 <= est.dv_hi
    # running away downhill at a = 50 mm/s²: the halves' drifts differ by a T/2 ≈ 1100 mm/s
    x = _walks(0.0, 2.0, 6) - 25.0 * TIMES[None, :] ** 2
    acc = transport(x, TIMES, 2.0, n_resamples=1000, seed=1)
    assert not acc.steady
    assert acc.dv == pytest.approx(-50.0 * 22.5, rel=0.02)


def test_zero_drift_walks_are_steady_although_their_dv_is_all_noise():
    est = transport(_walks(0.0, 3.0, 8), TIMES, 2.0, n_resamples=1000, seed=2)
    assert est.steady  # the tolerance 5 % of |v| ~ 0 is far inside the noise of dv


# -- mirror pairs --------------------------------------------------------------------------
def test_with_mirror_symmetry_v_and_dv_are_zero_exactly_and_D_is_the_particles_own():
    from bbb.analysis.stats import bootstrap_D
    from bbb.analysis.transport import SYMMETRY

    x = _walks(0.4, 2.0, 11)[:100]  # a drift the images cancel: the estimate never sees it
    est = transport(x, TIMES, 2.0, n_resamples=500, seed=3, pairing=SYMMETRY)
    assert (est.v, est.v_lo, est.v_hi, est.dv, est.dv_lo, est.dv_hi) == (0.0,) * 6
    assert est.steady and est.v_by == SYMMETRY and est.Pe == 0.0
    s_d = np.random.SeedSequence(3).spawn(4)[1]  # the D bootstrap's child seed
    assert (est.D, est.D_lo, est.D_hi) == tuple(bootstrap_D(x, TIMES, n_resamples=500, seed=s_d))


def _antithetic(rep: int, n_pairs: int = 100, v: float = 2.0):
    # each particle runs at its own speed s_i (spread 5 mm/s) plus noise; its partner at -s_i:
    # the pair mean cancels the spread that dominates Var(v_i)
    rng = np.random.default_rng(rep)
    s = rng.normal(0.0, 5.0, n_pairs)
    walk = brownian(rng, np.full(2 * n_pairs, 0.5), N_SAMPLES, DT)
    x = walk + (v + np.concatenate([s, -s]))[:, None] * TIMES[None, :]
    return x, np.tile(np.arange(n_pairs), 2)


def test_mirror_pairs_resampled_as_pairs_cover_v_with_a_much_narrower_CI():
    from bbb.analysis.transport import PAIRS

    hits, width_pairs, width_indep = 0, [], []
    for rep in range(40):
        x, units = _antithetic(rep)
        p = transport(x, TIMES, 2.0, n_resamples=500, seed=rep, pairing=PAIRS, units=units)
        q = transport(x, TIMES, 2.0, n_resamples=500, seed=rep)
        hits += p.v_lo <= 2.0 <= p.v_hi
        width_pairs.append(p.v_hi - p.v_lo)
        width_indep.append(q.v_hi - q.v_lo)
    assert hits >= 32, hits  # 95 % CIs: fails with probability < 1e-3 (binomial)
    assert np.median(width_pairs) < 0.3 * np.median(width_indep)


def test_pair_labels_go_with_pairs_only():
    from bbb.analysis.transport import PAIRS

    x, units = _antithetic(0, 10)
    with pytest.raises(ValueError, match="units"):
        transport(x, TIMES, 2.0, n_resamples=50, seed=0, pairing=PAIRS)
    with pytest.raises(ValueError, match="units"):
        transport(x, TIMES, 2.0, n_resamples=50, seed=0, units=units)


# -- the calibrated checks (benchmarks/calibrations/transport_rules.py, bbb/analysis/transport_rules.json) --
SCENE_TIMES = np.arange(101) * 0.5  # the transport scenes: 50 s every 0.5 s
SCENE_FIT = dict(fit_from=2.25, fit_to=11.25, discard=0.1)


def _steady_flags(make, reps: int) -> float:
    flags = []
    for rep in range(reps):
        x = make(np.random.default_rng(rep))
        flags.append(not transport(x, SCENE_TIMES, 2.0, n_resamples=400, seed=rep,
                                   **SCENE_FIT).steady)
    return float(np.mean(flags))


def test_steady_drifts_near_zero_are_not_flagged_by_their_noise():
    # 128 walks of heterogeneous D (Gamma, CV 1), no drift: calibrated false flags ≤ 1 %; a
    # bare 95 % test of dv (the tolerance 5 % |v| + 1e-6 mm/s alone, k = 0) flags ~5 %
    from bbb.analysis.stats.synthetic import gamma_D

    def make(rng):
        return brownian(rng, gamma_D(rng, 128, 2.0, 1.0), SCENE_TIMES.size, 0.5)
    assert _steady_flags(make, 300) <= 0.025


def test_a_drift_that_changes_by_many_standard_errors_is_flagged():
    # a t²/2 on 128 walks (D = 2, v = 3): dv ≈ a · 22.5 s ≈ 1.1 mm/s, ~40 SE(v) of ~0.03 mm/s
    def make(rng):
        return brownian(rng, np.full(128, 2.0), SCENE_TIMES.size, 0.5) + \
            3.0 * SCENE_TIMES + 0.025 * SCENE_TIMES**2
    assert _steady_flags(make, 50) >= 0.9


def _stuck_runners(rng, n=256, p_stuck=0.07):
    stuck = rng.random(n) < p_stuck
    v = np.where(stuck, 0.0, rng.normal(-300.0, 40.0, n))
    return brownian(rng, np.where(stuck, 1e-3, 100.0), SCENE_TIMES.size, 0.5) + v[:, None] * SCENE_TIMES


def test_stuck_and_running_particles_are_ballistic_not_diffusive():
    # tilt 2°, 58 Hz: 7 % stuck, the rest running at -300 ± 40 mm/s; MSD about the drift ~ Δ²
    est = transport(_stuck_runners(np.random.default_rng(1)), SCENE_TIMES, 2.0, n_resamples=400,
                    seed=1, **SCENE_FIT)
    assert est.diffusive is False and est.curvature_lo > 1.7
    walks = brownian(np.random.default_rng(2), np.full(256, 50.0), SCENE_TIMES.size, 0.5)
    ok = transport(walks - 280.0 * SCENE_TIMES, SCENE_TIMES, 2.0, n_resamples=400, seed=1,
                   **SCENE_FIT)
    assert ok.diffusive is True and ok.curvature_lo < 1.0 < ok.curvature_hi


def test_a_persistent_walk_with_its_negative_intercept_is_diffusive():
    # MSD ≈ 2 D (Δ − τ), τ = 1 s: the log-log exponent over the fit lags is ~1.24 (a check on
    # it would flag this walk), the slope ratio ~1
    from bbb.analysis.stats import tamsd
    from bbb.analysis.stats.synthetic import persistent

    x = persistent(np.random.default_rng(3), np.full(256, 50.0), SCENE_TIMES.size, 0.5, tau=1.0)
    lags = np.arange(5, 23)
    assert np.polyfit(np.log(lags), np.log(tamsd(x[:, 10:], lags).mean(0)), 1)[0] > 1.2
    est = transport(x, SCENE_TIMES, 2.0, n_resamples=400, seed=2, **SCENE_FIT)
    assert est.diffusive is True and est.curvature_lo < 1.0 < est.curvature_hi


def test_an_ensemble_at_rest_has_no_exponent_and_is_not_judged():
    est = transport(np.zeros((10, SCENE_TIMES.size)), SCENE_TIMES, 2.0, n_resamples=50, seed=0,
                    **SCENE_FIT)
    assert np.isnan(est.curvature) and est.diffusive is None


# -- estimator failure ---------------------------------------------------------------------
def _oscillating(period: float) -> np.ndarray:
    """Particles oscillating about fixed points (amplitude ~1 mm, random phases): the MSD about
    the drift rises to a lag of half the period, then falls."""
    rng = np.random.default_rng(1)
    phase, amp = rng.uniform(0, 2 * np.pi, (200, 1)), rng.uniform(0.5, 1.5, (200, 1))
    return amp * np.sin(2 * np.pi * TIMES[None, :] / period + phase)


def test_a_d_about_the_drift_significantly_below_zero_is_no_value_but_a_failure():
    # period 10 s: the fit lags (2.3-11.2 s) straddle the falling half of the MSD
    est = transport(_oscillating(10.0), TIMES, 2.0, n_resamples=300, seed=1)
    assert np.isnan([est.D, est.D_lo, est.D_hi, est.Pe]).all()
    assert est.D_status.startswith("estimator failed: fit D = -")
    # period 20 s: the MSD still rises over the fit lags -- a (small) D with its CI
    ok = transport(_oscillating(20.0), TIMES, 2.0, n_resamples=300, seed=1)
    assert ok.D_status == "ok" and 0.0 < ok.D_lo < ok.D < ok.D_hi


# -- what v means: v_status ---------------------------------------------------------------------
def test_an_ensemble_moving_by_rounding_only_has_no_mover_and_no_drift_d_or_pe():
    # particles held on a conveyor below lift-off: x changes by 1e-13 mm at most
    rng = np.random.default_rng(4)
    x = rng.uniform(-50, 50, (32, 1)) + 1e-13 * rng.standard_normal((32, N_SAMPLES))
    est = transport(x, TIMES, 2.0, n_resamples=200, seed=0)
    assert est.n_moving == 0 and est.v_status == "no mover" and est.steady is None
    assert all(np.isnan([est.v_lo, est.v_hi, est.D, est.D_lo, est.D_hi, est.Pe]))
    assert est.D_status.startswith("no mover among 32")


def test_a_uniform_acceleration_is_recovered_exactly_and_v_is_the_velocity_mid_run():
    # x = x0 + u t + a t²/2 without noise: a = 2 dv / T_a exactly; v = u + a t_mid
    a_true, u = -7.0, 3.0
    x = np.arange(4.0)[:, None] + u * TIMES + 0.5 * a_true * TIMES**2
    est = transport(x, TIMES, 2.0, n_resamples=50, seed=0)
    assert est.a == pytest.approx(a_true, rel=1e-9)
    t_a = 0.1 * TIMES[-1]  # the discarded 10 %
    assert est.v == pytest.approx(u + a_true * (t_a + TIMES[-1]) / 2, rel=1e-9)


def test_an_accelerating_ensemble_reports_its_acceleration_not_v_with_a_ci():
    x = _walks(0.0, 2.0, 6) - 25.0 * TIMES[None, :] ** 2  # a = -50 mm/s²
    est = transport(x[:100], TIMES, 2.0, n_resamples=500, seed=1)
    assert est.v_status == "accelerating" and est.steady is False
    assert np.isnan(est.v_lo) and np.isnan(est.v_hi) and np.isnan(est.Pe)
    assert est.a_lo <= -50.0 <= est.a_hi and est.a_hi - est.a_lo < 1.0


def test_a_steady_drift_is_ok_and_mirror_symmetry_is_by_construction():
    from bbb.analysis.transport import SYMMETRY

    x = _walks(3.0, 2.0, 5)[:100]
    assert transport(x, TIMES, 2.0, n_resamples=300, seed=1).v_status == "ok"
    assert transport(x, TIMES, 2.0, n_resamples=300, seed=1,
                     pairing=SYMMETRY).v_status == "by construction"
