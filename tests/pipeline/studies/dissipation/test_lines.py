import math

import pytest

from pipeline.studies.dissipation.lines import (
    cut,
    first_max_above,
    first_reaching,
    judged_lines,
    listed_alphas,
    onset,
)

from .synthetic import ALPHAS, dmap, line


def test_the_judged_lines_are_the_listed_alphas_not_those_refinement_added():
    lines = judged_lines(dmap(refined=True), ALPHAS)
    assert list(lines) == pytest.approx(list(ALPHAS))
    assert all(len(t) == 55 for t in lines.values())


def test_the_listed_alphas_are_the_shipped_scenes():
    assert listed_alphas() == pytest.approx(ALPHAS)


def test_a_listed_alpha_the_map_does_not_hold_is_not_judged():
    assert list(judged_lines(dmap(), (0.5, 0.52))) == [0.5]


def test_the_onset_is_the_first_frequency_that_diffuses():
    q = onset(line(58.0, 63.0, 0.7))
    assert q.value == 58.0 and q.lo == pytest.approx(57.5) and q.hi == pytest.approx(58.5)


def test_the_first_maximum_above_the_onset_is_located():
    t = line(58.0, 63.0, 0.7)
    assert first_max_above(t, onset(t).value).value == 63.0
    assert math.isnan(first_max_above(t, math.nan).value)


def test_where_k_max_first_reaches_n():
    t = line(58.0, 63.0, 0.7).assign(k_max=lambda d: (d["f"] - 46.0) / 10.0)
    t = t.assign(k_max_lo=t["k_max"] - 0.05, k_max_hi=t["k_max"] + 0.05)
    q = first_reaching(t, "k_max", 2)
    assert q.value == 66.0 and q.lo == pytest.approx(65.5) and q.hi == pytest.approx(67.5)
    assert math.isnan(first_reaching(t, "k_max", 9).value)


def test_a_cut_is_the_rows_at_one_value():
    assert len(cut(dmap(), "alpha", 0.7)) == 55
    assert cut(dmap(), "alpha", 0.71) is None


def test_many_refined_alphas_do_not_become_judged_lines():
    """Refinement can add more α values than the scene lists, each at a few frequencies."""
    import numpy as np
    import pandas as pd

    extra = [line(60.0, 65.0, a).query("f in (60.0, 61.0, 62.0)")
             for a in np.round(np.arange(0.4125, 0.95, 0.0125), 5) if round(a, 5) not in ALPHAS]
    t = pd.concat([dmap(refined=False), *extra], ignore_index=True)
    assert len(extra) > len(ALPHAS)
    assert list(judged_lines(t, ALPHAS)) == pytest.approx(list(ALPHAS))
