"""bbb.transport on synthetic drifting Brownian walks with known v (mm/s) and D (mm²/s)."""

import numpy as np
import pytest

from bbb.stats.synthetic import brownian
from bbb.transport import drift_velocity, per_particle_drift, transport

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
