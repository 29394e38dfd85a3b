"""Bootstraps over independent units (mirror pairs) instead of particles: bbb.analysis.stats.unit_means
and the ``units`` keyword of bootstrap_mean / bootstrap_D / bbb.analysis.stationarity."""

from __future__ import annotations

import numpy as np
import pytest

from bbb.analysis.stationarity import stationarity
from bbb.analysis.stats import bootstrap_D, bootstrap_mean, unit_means

T = np.arange(101) * 0.5  # the scenes' sampling: 50 s at 0.5 s


def test_unit_means_average_each_unit_and_keep_the_mean():
    v = np.array([1.0, 2.0, 3.0, 5.0, 7.0, 11.0])
    u = np.array([2, 0, 1, 2, 0, 1])
    assert unit_means(v, u).tolist() == [4.5, 7.0, 3.0]
    assert unit_means(v, u).mean() == pytest.approx(v.mean(), rel=1e-15)
    with pytest.raises(ValueError, match="unequal size"):
        unit_means(v, [0, 0, 0, 1, 1, 2])


def test_units_of_one_particle_change_nothing():
    x = np.cumsum(np.random.default_rng(1).normal(size=(40, T.size)), axis=1)
    assert bootstrap_D(x, T, n_resamples=300, seed=4, units=np.arange(40)) == \
        bootstrap_D(x, T, n_resamples=300, seed=4)


def test_a_particle_and_its_copy_as_one_unit_give_the_particles_own_CIs():
    # every particle twice, paired: resampling the pairs is resampling the particles, bit for
    # bit (fails if the units were ignored: the copies would halve the apparent variance)
    rng = np.random.default_rng(2)
    x = np.cumsum(rng.normal(size=(30, T.size)), axis=1)
    dup, units = np.concatenate([x, x]), np.tile(np.arange(30), 2)
    assert bootstrap_D(dup, T, n_resamples=300, seed=5, units=units) == \
        bootstrap_D(x, T, n_resamples=300, seed=5)
    a = stationarity(dup, T, n_resamples=300, seed=6, units=units)
    b = stationarity(x, T, n_resamples=300, seed=6)
    assert (a.dD_lo, a.dD_hi) == (b.dD_lo, b.dD_hi)
    assert bootstrap_D(dup, T, n_resamples=300, seed=5).hi < \
        bootstrap_D(x, T, n_resamples=300, seed=5).hi  # the too-narrow CI of ignoring them


def test_correlated_partners_need_the_unit_bootstrap_for_95_percent_coverage():
    # 64 pairs of identical values N(0, 1): the particle bootstrap counts 128 independent
    # values and covers the true mean 0 only ~83 % of the time; the pairs cover ~95 %
    rng = np.random.default_rng(3)
    units = np.tile(np.arange(64), 2)
    cover = {"units": 0, "particles": 0}
    reps = 400
    for r in range(reps):
        v = np.tile(rng.normal(size=64), 2)
        for k, u in (("units", units), ("particles", None)):
            _, lo, hi = bootstrap_mean(v, n_resamples=500, seed=r, units=u)
            cover[k] += lo <= 0.0 <= hi
    assert cover["units"] / reps >= 0.91, cover  # 95 % less a bootstrap's small-n shortfall
    assert cover["particles"] / reps <= 0.88, cover
