"""Claims about bbb.analysis.extrema: significant extrema of a noisy curve with confidence intervals."""

from __future__ import annotations

from itertools import pairwise

import numpy as np
import pytest

from bbb.analysis.extrema import critical_z, find_extrema, nearest

F = np.arange(50.0, 99.2001, 0.4)  # the Fig. 2 grid: 124 points


def _curve(f):
    """Known extrema: max near 60, min near 66, max near 80 (exact positions found numerically)."""
    return (1000 + 800 * np.exp(-((f - 60) ** 2) / 8) - 500 * np.exp(-((f - 66) ** 2) / 8)
            + 1500 * np.exp(-((f - 80) ** 2) / 32))


def _true_extrema():
    x = np.linspace(50, 99.2, 200_001)
    y = _curve(x)
    d = np.diff(np.sign(np.diff(y)))
    return [("max" if s < 0 else "min", x[i + 1]) for i, s in zip(np.flatnonzero(d), d[d != 0], strict=True)]


def _noisy(seed, sigma_rel=0.05, sigma_abs=40.0):
    rng = np.random.default_rng(seed)
    true = _curve(F)
    s = sigma_abs + sigma_rel * true
    D = true + rng.normal(size=F.size) * s
    return D, D - 1.96 * s, D + 1.96 * s


def test_the_synthetic_curve_has_the_extrema_the_tests_assume():
    kinds = [k for k, _ in _true_extrema()]
    assert kinds == ["max", "min", "max"]


@pytest.mark.parametrize("seed", range(8))
def test_finds_exactly_the_known_extrema_of_a_noisy_curve_within_a_hertz(seed):
    found = find_extrema(F, *_noisy(seed))
    truth = _true_extrema()
    assert [e.kind for e in found] == [k for k, _ in truth]
    for e, (_, f_true) in zip(found, truth, strict=True):
        assert abs(e.f - f_true) <= 1.2


def test_the_reported_position_range_contains_the_true_extremum_in_most_curves():
    hits = total = 0
    for seed in range(40):
        found = find_extrema(F, *_noisy(seed))
        for e, (_, f_true) in zip(found, _true_extrema(), strict=False):
            total += 1
            hits += e.f_lo - 0.2 <= f_true <= e.f_hi + 0.2  # half a grid step of slack
    assert total >= 100 and hits / total >= 0.9


def test_pure_noise_yields_an_extremum_in_at_most_alpha_of_the_curves():
    rng = np.random.default_rng(0)
    spurious = 0
    for _ in range(200):
        D = 1000 + 40 * rng.normal(size=F.size)
        spurious += bool(find_extrema(F, D, D - 1.96 * 40, D + 1.96 * 40))
    assert spurious / 200 <= 0.08  # alpha = 0.05, plus sampling slack


def test_a_monotone_noisy_curve_has_no_extremum():
    rng = np.random.default_rng(3)
    D = 20 * F + 10 * rng.normal(size=F.size)
    assert find_extrema(F, D, D - 20, D + 20) == []


def test_a_peak_at_the_end_of_the_range_is_not_reported():
    D = np.exp(F / 10)  # rises to the last point, zero-width intervals
    assert find_extrema(F, D, D, D) == []


def test_maxima_and_minima_alternate():
    rng = np.random.default_rng(5)
    D = 1000 + 600 * np.sin(F / 2) + 20 * rng.normal(size=F.size)
    kinds = [e.kind for e in find_extrema(F, D, D - 40, D + 40)]
    assert len(kinds) >= 6
    assert all(a != b for a, b in pairwise(kinds))


def test_rows_with_nan_are_ignored():
    D, lo, hi = _noisy(1)
    D2, lo2, hi2 = D.copy(), lo.copy(), hi.copy()
    D2[[3, 50, 90]] = np.nan
    a = [(e.kind, e.f) for e in find_extrema(F, D, lo, hi)]
    b = [(e.kind, e.f) for e in find_extrema(F, D2, lo2, hi2)]
    assert [k for k, _ in a] == [k for k, _ in b] == [k for k, _ in _true_extrema()]
    # the extrema stay where they were (no NaN row sits at one of them)
    assert all(abs(fa - fb) <= 0.4 for (_, fa), (_, fb) in zip(a, b, strict=True))


def test_min_depth_suppresses_small_but_statistically_sharp_differences():
    D = np.array([0.0, 1e-6, 0.0, 1e-6, 0.0])  # exact values, zero-width intervals
    assert [e.kind for e in find_extrema(np.arange(5.0), D, D, D)] == ["max", "min", "max"]
    assert find_extrema(np.arange(5.0), D, D, D, min_depth=1.0) == []


def test_an_interval_that_does_not_contain_its_value_is_refused():
    with pytest.raises(ValueError, match="lo ≤ D ≤ hi"):
        find_extrema([1.0, 2.0, 3.0], [1.0, 2.0, 1.0], [1.5, 1.5, 0.5], [2.0, 2.5, 1.5])


def test_critical_z_is_bonferroni_over_pairs():
    # n = 124: 7626 pairs, alpha = 0.05 -> one-sided level 6.56e-6 -> z = 4.36
    assert critical_z(124) == pytest.approx(4.36, abs=0.01)
    assert critical_z(2, alpha=0.05) == pytest.approx(1.645, abs=1e-3)


def test_nearest_picks_the_extremum_of_that_kind_within_the_window():
    found = find_extrema(F, *_noisy(0))
    # the minimum near 66 Hz is closer to 63.5 Hz than the maximum near 60 Hz: kind decides
    assert abs(nearest(found, "max", 63.5, window=5.0).f - 60) < 1.5
    assert nearest(found, "min", 90.0, window=2.0) is None
    assert nearest(found, "max", 79.0, window=2.0).f > 75
