"""Shares and D of the moving particles on synthetic ensembles with known answers."""

from __future__ import annotations

import math

import pytest

from bbb.analysis.moving import synthetic_positions
from bbb.analysis.moving_d import NO_TIME, TOO_FEW, decompose
from bbb.analysis.stats.proportion import wilson

S, DT = 2.0, 0.05


def _by_name(decs):
    return {d.definition: d for d in decs}


def test_wilson_never_has_zero_width():
    for k, n in ((0, 10), (10, 10), (0, 1), (3, 7)):
        p, lo, hi = wilson(k, n)
        assert lo <= p <= hi and hi - lo > 0
    assert wilson(0, 512)[2] == pytest.approx(3.84 / (512 + 3.84), rel=1e-2)


def test_a_mixed_ensemble_decomposes_into_its_movers():
    """A quarter diffusing at D = 200, the rest creeping: the displaced share's CI holds 1/4,
    D of the displaced particles' CI holds 200, and D_all = share × D_moving within the still
    particles' bound; the moving-time decomposition is exact."""
    x, truth = synthetic_positions(384, 128, 200.0, 20.0, DT, S, seed=7)
    d = _by_name(decompose(x, DT, S, 20.0, n_resamples=500, seed=1))
    disp = d["displaced"]
    assert disp.n_moving == 128 and disp.share_lo <= 0.25 <= disp.share_hi
    assert disp.D_lo <= 200.0 <= disp.D_hi
    assert disp.holds and abs(disp.residual) <= disp.bound
    assert d["all"].D_lo <= 50.0 <= d["all"].D_hi
    mt = d["moving_time"]
    assert mt.holds and mt.share == pytest.approx(0.25, abs=0.01)
    assert mt.D_lo <= 200.0 <= mt.D_hi


def test_moving_time_divides_by_the_time_moving():
    """Diffusers (D = 200) that stop after half of the analysed part: D_all halves, D per
    moving time does not; a creeping-only ensemble has no moving time and no D."""
    x, _ = synthetic_positions(0, 256, 200.0, 50.0, DT, S, seed=8, stop_at=27.5)
    d = _by_name(decompose(x, DT, S, 50.0, n_resamples=500, seed=2))
    mt = d["moving_time"]
    assert mt.share == pytest.approx(0.5, abs=0.02)
    assert mt.D_lo <= 200.0 <= mt.D_hi
    assert d["displaced"].share == 1.0
    x, _ = synthetic_positions(64, 0, 1.0, 10.0, DT, S, seed=9)
    d = _by_name(decompose(x, DT, S, 10.0, n_resamples=200, seed=3))
    assert d["moving_time"].status == NO_TIME and math.isnan(d["moving_time"].D)
    assert d["moving_time"].share_hi > 0  # the Wilson bound, not a zero-width interval
    assert d["displaced"].status == TOO_FEW and d["displaced"].share_hi > 0
    assert d["displaced"].holds


def test_same_seed_same_numbers():
    x, _ = synthetic_positions(100, 100, 50.0, 10.0, DT, S, seed=11)
    a = decompose(x, DT, S, 10.0, n_resamples=200, seed=5)
    b = decompose(x, DT, S, 10.0, n_resamples=200, seed=5)
    assert a == b
