"""The sign rules of the drift claims (pipeline/claims/signs.py) on synthetic
v(f) curves with known answers, fixed before any transport store was reduced."""

from __future__ import annotations

import numpy as np
import pytest

from pipeline.claims.signs import (
    reversal_intervals,
    reversals,
    significant_signs,
    steady_rows,
)

F = np.arange(50.0, 100.1, 2.0)  # the transport map's 26 frequencies
SE = 0.5  # mm/s: standard error of each v


def _noisy(v_true: np.ndarray, rng) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    v = v_true + SE * rng.standard_normal(v_true.size)
    return v, v - 1.96 * SE, v + 1.96 * SE


def test_a_current_free_curve_shows_a_significant_v_in_at_most_5_percent_of_curves():
    rng = np.random.default_rng(1)
    hits = sum(bool(significant_signs(*_noisy(np.zeros(F.size), rng)).any()) for _ in range(2000))
    # Bonferroni over 26 points: family-wise 1 − (1 − α/26)^26 ≈ 4.9 %; 7 % is 4 binomial SDs
    # above that, while unadjusted 95 % CIs would flag 1 − 0.95^26 ≈ 74 % of curves.
    assert hits / 2000 <= 0.07, hits


def test_a_current_free_curve_almost_never_shows_a_reversal():
    rng = np.random.default_rng(2)
    n = sum(bool(reversals(F, significant_signs(*_noisy(np.zeros(F.size), rng))))
            for _ in range(2000))
    assert n / 2000 <= 0.01, n


def test_a_current_that_changes_sign_is_found_as_one_reversal_near_its_zero():
    rng = np.random.default_rng(3)
    found = []
    for _ in range(200):  # v = 3 SE ... -3 SE ... crossing zero at 75 Hz, 8 SE at the ends
        r = reversals(F, significant_signs(*_noisy(-8 * SE * np.tanh((F - 75.0) / 8.0), rng)))
        found.append(len(r) == 1 and abs(r[0] - 75.0) <= 6.0)
    assert np.mean(found) >= 0.9


def test_pure_one_sign_drift_has_no_reversal():
    s = significant_signs(np.full(F.size, -3.0), np.full(F.size, -3.5), np.full(F.size, -2.5))
    assert (s == -1).all() and reversals(F, s) == []


def test_rounding_level_currents_of_particles_at_rest_are_not_significant():
    v = np.full(F.size, -6e-16)  # a CI of rounding size that excludes 0
    assert not significant_signs(v, v - 1e-16, v + 1e-16).any()


def test_a_reversal_is_located_between_the_last_point_of_one_sign_and_the_first_of_the_other():
    x = np.array([90.0, 75.0, 60.0, 45.0, 30.0])  # a cut along the throw
    s = np.array([-1, 0, 0, 1, 1])
    assert reversal_intervals(x, s) == [(90.0, 45.0, 1)]
    assert reversals(x, s) == [67.5]
    s2 = np.array([1, 1, -1, 0, 1])  # two changes, the second across a non-significant point
    assert reversal_intervals(F[:5], s2) == [(52.0, 54.0, -1), (54.0, 58.0, 1)]
    assert reversal_intervals(F[:5], np.array([1, 0, 1, 0, 1])) == []


def test_steady_rows_leave_out_the_unsteady_frequencies_and_say_which():
    import pandas as pd

    t = pd.DataFrame({"f": F[::-1], "v": 1.0, "v_lo": 0.5, "v_hi": 1.5, "steady": F[::-1] < 60})
    out = steady_rows(t)
    assert list(out["f"]) == [50.0, 52.0, 54.0, 56.0, 58.0]
    assert out.attrs["unsteady"] == list(F[5:])
    assert steady_rows(t.drop(columns="v")) is None and steady_rows(None) is None


def test_a_sums_interval_adds_each_sides_standard_errors_in_quadrature():
    from pipeline.claims.signs import sum_interval

    s, lo, hi = sum_interval([1.0], [0.7], [1.4], [-1.0], [-1.4], [-0.6])
    assert s[0] == 0.0
    assert lo[0] == pytest.approx(-np.hypot(0.3, 0.4)) and hi[0] == pytest.approx(np.hypot(0.4, 0.4))
    assert np.isnan(sum_interval([1.0], [np.nan], [1.2], [0.0], [0.0], [0.0])[1][0])
