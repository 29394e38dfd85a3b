"""The analyses' former module paths (bbb.stats, bbb.transport, ... before bbb/analysis/) still
give the very same objects, for one release: pipeline imports them until it moves over."""

from __future__ import annotations

import importlib

import pytest

OLD = ("stationarity", "transport", "greenkubo", "gk_contrast", "locking", "extrema", "approx",
       "liftoff", "lyapunov", "stats", "stats.bootstrap", "stats.ergodicity", "stats.interval")


@pytest.mark.parametrize("name", OLD)
def test_an_old_analysis_path_still_exports_every_public_name(name):
    old = importlib.import_module(f"bbb.{name}")
    new = importlib.import_module(f"bbb.analysis.{name}")
    assert new.__all__
    assert [n for n in new.__all__ if getattr(old, n, None) is not getattr(new, n)] == []


def test_the_old_names_of_the_shared_helpers_are_the_new_ones():
    import bbb.stats
    import bbb.stats.bootstrap
    from bbb.analysis.stats import bootstrap, fit

    assert bbb.stats._regime is fit.fit_regime
    assert bbb.stats._per_particle_fit is fit.per_particle_fit
    assert bbb.stats.bootstrap._bootstrap_mean is bootstrap.bootstrap_mean_unchecked
