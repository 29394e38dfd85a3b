"""What an interval of D says (bbb/analysis/stats/interval.py): no zero-width interval, the mover-share
bound where nothing moved, estimator failures flagged, calibrated coverage where it is below
nominal."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from bbb.analysis.stats import bootstrap_D
from bbb.analysis.stats.bootstrap import bootstrap_mean_unchecked
from bbb.analysis.stats.interval import (
    CALIBRATION,
    FAILED,
    NO_MOVER,
    NO_SPREAD,
    OK,
    RARE,
    d_interval,
    rare_coverage,
)
from bbb.analysis.stats.rare import mover_share_bound
from bbb.analysis.stats.synthetic import rare_movers

TIMES = np.arange(101) * 0.5  # the scenes' sampling: 50 s at 0.5 s


def _interval(d, seed=0, ci=0.95):
    d = np.asarray(d, dtype=float)
    return d_interval(d, bootstrap_mean_unchecked(d, 400, ci, np.random.default_rng(seed), "percentile"),
                      ci)


def test_a_sample_where_nothing_moves_has_no_upper_bound_only_a_mover_share_bound():
    # 32 particles held still (the stick model below Γ = 1): D_i = 0 exactly.  The old rule
    # gave [0, 0]; the data bound the share of movers at 1 - 0.05^(1/32) = 8.9 %, not D.
    x = np.tile(np.linspace(0.0, 31.0, 32)[:, None], (1, TIMES.size))
    r = bootstrap_D(x, TIMES, n_resamples=400, seed=1, detail=True)
    assert r.status == NO_MOVER and r.D == 0.0 and r.lo == 0.0
    assert math.isnan(r.hi)
    assert r.mover_share_hi == pytest.approx(1 - 0.05 ** (1 / 32), rel=1e-12)
    assert "8.9 %" in r.note()


def test_the_mover_share_bound_leaves_exactly_one_minus_ci_chance_of_seeing_no_mover():
    # at the bound p, n independent particles show no mover with probability (1 - p)^n = 1 - ci
    # (one-sided), and it is the rule of three for large n
    for n in (8, 32, 128, 4096):
        p = mover_share_bound(n, 0.95)
        assert (1 - p) ** n == pytest.approx(0.05, rel=1e-9)
    assert mover_share_bound(4096, 0.95) * 4096 == pytest.approx(3.0, rel=0.01)


def test_no_interval_of_D_has_zero_width():
    cases = {
        "still": np.zeros(64),
        "one mover": np.r_[1.0, np.zeros(63)],
        "identical movers": np.full(64, 2.0),
        "settling": -1e-5 * (1 + 0.1 * np.random.default_rng(3).random(64)),
        "still and settling": np.r_[np.zeros(60), -1e-5 * np.ones(4)],
    }
    for name, d in cases.items():
        r = _interval(d)
        assert not (r.lo == r.hi), (name, r)
    assert _interval(cases["identical movers"]).status == NO_SPREAD


def test_a_significantly_negative_D_is_an_estimator_failure_not_a_value():
    # particles whose MSD falls with the lag (settling in the fit window): every D_i < 0, or
    # most of them (Fig. 2 at 56.4 Hz: D = -7.4e-6 [-8.2e-6, -6.5e-6] mm²/s)
    z = np.random.default_rng(4).standard_normal(128)
    for d in (-7.4e-6 * (1 + 0.2 * z), -7.4e-6 + 5e-6 * z):
        r = _interval(d)
        assert r.status == FAILED and r.hi < 0 and not r.valued, r
        assert "estimator failed" in r.note()
    assert np.any(-7.4e-6 + 5e-6 * z > 0)  # the second holds movers: not "no mover"
    # a negative D whose CI reaches 0 is noise about 0, not a failure
    z = np.random.default_rng(5).standard_normal(128) * 1e-6
    noisy = z - z.mean() - 5e-8  # mean -5e-8, standard error ~9e-8
    assert _interval(noisy).status == OK


def test_the_rare_rule_carries_the_calibrated_coverage_read_from_its_calibration_file():
    cal = json.loads(CALIBRATION.read_text())
    for b in cal["coverage_by_n_eff"]:
        inside = b["n_eff_from"] + 0.25
        assert rare_coverage(inside, 0.95) == b["rule"]
    assert math.isnan(rare_coverage(2.0, 0.9))  # not calibrated at 90 %
    # 2 movers among 128 creepers: the rule applies and says its coverage is below nominal
    rng = np.random.default_rng(0)
    x = rare_movers(rng, 128, TIMES.size, 0.5, 2 / 128, "light")  # 2 movers, n_eff 1.3
    r = bootstrap_D(x, TIMES, n_resamples=400, seed=2, detail=True)
    assert r.status == RARE
    assert r.coverage == rare_coverage(r.n_eff, 0.95) < 0.95
    # an all-moving population keeps the nominal level
    y = rare_movers(rng, 128, TIMES.size, 0.5, 1.0, "light")
    full = bootstrap_D(y, TIMES, n_resamples=400, seed=2, detail=True)
    assert full.status == OK and full.coverage == 0.95


def test_detail_gives_the_same_interval_as_the_plain_call():
    rng = np.random.default_rng(7)
    x = rare_movers(rng, 128, TIMES.size, 0.5, 3 / 128, "heavy")
    kw = dict(n_resamples=300, seed=5)
    assert tuple(bootstrap_D(x, TIMES, **kw)) == bootstrap_D(x, TIMES, detail=True, **kw)[:3]
