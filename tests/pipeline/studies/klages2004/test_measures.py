"""Measures of Klages, Barna & Mátyás (2004) claims: what claim 17 says about the spread of the
per-particle D."""

from __future__ import annotations

import math

import pandas as pd

from pipeline.studies.klages2004.measures import _spread_text


def test_the_spread_bound_text_names_the_frequencies_without_a_bound():
    # a CV² upper bound ≤ 0 gives no CV bound (NaN): said so, not counted as "0 %"
    sel = pd.DataFrame({"f": [58.0, 59.0, 60.0], "CV_D_upper": [0.19, math.nan, 0.08]})
    text = _spread_text(sel)
    assert "above CV 8 %–19 % (95 % upper bound; weakest at 58 Hz)" in text
    assert "no bound at 59 Hz" in text
    none = _spread_text(sel.assign(CV_D_upper=math.nan))
    assert none.startswith("; no bound at 58, 59, 60 Hz") and "exclude" not in none
