import math

import numpy as np
import pytest

from bbb.analysis.stats.proportion import share_difference, wilson


def test_wilson_matches_the_textbook_value():
    # 81 of 263 (Newcombe 1998, Table I example): 0.3080 [0.2553, 0.3662]
    p, lo, hi = wilson(81, 263)
    assert (p, lo, hi) == pytest.approx((0.30798, 0.25531, 0.36617), abs=1e-4)


def test_wilson_never_has_zero_width_at_the_edges():
    for k, n in ((0, 10), (10, 10), (0, 1)):
        p, lo, hi = wilson(k, n)
        assert lo <= p <= hi and hi - lo > 0.1
        assert 0.0 <= lo and hi <= 1.0


def test_wilson_covers_its_level_on_simulated_binomials():
    rng = np.random.default_rng(7)
    n, share = 40, 0.15
    ks = rng.binomial(n, share, size=4000)
    cover = np.mean([lo <= share <= hi for _, lo, hi in (wilson(int(k), n) for k in ks)])
    assert 0.93 <= cover <= 0.97


def test_the_difference_interval_is_newcombes_method_10():
    # Newcombe 1998, Table II (e): 56/70 - 48/80 = 0.2000 [0.0524, 0.3339]
    d, lo, hi = share_difference(56, 70, 48, 80)
    assert (d, lo, hi) == pytest.approx((0.2, 0.0524, 0.3339), abs=1e-4)


def test_no_trials_give_no_interval():
    assert all(math.isnan(x) for x in wilson(0, 0))
    assert all(math.isnan(x) for x in share_difference(1, 2, 0, 0))


def test_an_impossible_count_is_refused():
    with pytest.raises(ValueError):
        wilson(5, 4)
