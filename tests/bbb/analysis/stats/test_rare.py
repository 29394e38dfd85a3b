"""The rare-mover rule (bbb/analysis/stats/rare.py): D's CI when a few particles carry D."""

from __future__ import annotations

import numpy as np
import pytest

from bbb.analysis.stats import bootstrap_D
from bbb.analysis.stats.rare import effective_movers, gamma_quantile, rare_mover_interval
from bbb.analysis.stats.synthetic import rare_movers

TIMES = np.arange(101) * 0.5  # the scenes' sampling: 50 s at 0.5 s


@pytest.mark.parametrize(("k", "lo", "hi"), [(1, 0.0253, 5.5716), (3, 0.6187, 8.7673),
                                             (10, 4.7954, 18.3904)])
def test_equal_movers_give_garwoods_exact_poisson_interval(k, lo, hi):
    # k movers of size 1 among 10⁶ particles: Fay-Feuer reduces to Garwood's exact 95 %
    # interval for a Poisson count k (tabulated values), divided by N; the upper end is that
    # of k + 1 movers' shape with one mover's size, i.e. Garwood's (k + 1)-shape quantile.
    d = np.zeros(1_000_000)
    d[:k] = 1.0
    got = np.array(rare_mover_interval(d, 0.95)) * 1_000_000
    assert got == pytest.approx([lo, hi], abs=2e-4)


def test_gamma_quantile_inverts_the_exponential_law():
    # Gamma(1) is the unit exponential: quantile -log(1 - q).
    for q in (1e-6, 0.025, 0.5, 0.975):
        assert gamma_quantile(q, 1.0) == pytest.approx(-np.log1p(-q), rel=1e-9)


def test_rule_leaves_an_all_moving_population_alone():
    rng = np.random.default_rng(5)
    x = rare_movers(rng, 512, TIMES.size, 0.5, 1.0, "light")
    kw = dict(n_resamples=400, seed=1)
    assert bootstrap_D(x, TIMES, rare=True, **kw) == bootstrap_D(x, TIMES, rare=False, **kw)


def test_effective_movers_counts_equal_movers():
    assert effective_movers(np.r_[np.full(7, 2.0), np.zeros(100), -np.ones(3)]) == 7.0


def test_rule_restores_coverage_where_few_particles_move():
    # 128 particles, 5 expected light-tailed movers (n_eff ~ 2.5): benchmarks/calibrations/rare_movers.py
    # measures coverage 0.83 without the rule and 0.91 with it (200 samples).
    rng = np.random.default_rng(2026)
    hits = np.zeros(2)
    n_rep, p = 300, 5 / 128
    for i in range(n_rep):
        x = rare_movers(rng, 128, TIMES.size, 0.5, p, "light")
        truth = p + (1 - p) * 1e-6
        for j, rare in enumerate((False, True)):
            _, lo, hi = bootstrap_D(x, TIMES, n_resamples=400, seed=i, rare=rare)
            hits[j] += lo <= truth <= hi
    cov = hits / n_rep
    assert cov[0] < 0.87, cov  # the bootstrap alone is anti-conservative here ...
    assert cov[1] > 0.89, cov  # ... the rule brings it near the nominal 95 %


def test_with_no_positive_D_the_rule_bounds_nothing_above():
    # no mover seen: the Fay-Feuer interval has no mover size to scale by; it returns the
    # sample's D and no upper end (was a zero-width (shift, shift))
    d = np.r_[np.zeros(30), -2e-6, -4e-6]
    lo, hi = rare_mover_interval(d, 0.95)
    assert lo == pytest.approx(d.mean(), abs=1e-20) and np.isnan(hi)
