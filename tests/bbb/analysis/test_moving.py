"""The definitions of "moving" on synthetic windows with known answers: creeping particles
(rocking within their arc) and Brownian ones.  The error rates measured here are the
calibration the definitions' thresholds (one arc period S, blocks of 0.5 s) rest on."""

from __future__ import annotations

import numpy as np
import pytest

from bbb.analysis.moving import (
    BLOCK,
    displaced,
    moving_blocks,
    moving_share,
    still_bound,
    synthetic_positions,
    window,
)

S = 2.0  # mm, the paper's arc period
DT = 0.05  # s, the protocol scene's sample spacing
T = 5.0  # s, the shortest window analysed
#: the smallest D (mm²/s) the definitions are asked to resolve as moving: 1 % of the
#: ~500 mm²/s that bouncing particles reach near onset (the ergodicity scene), below the
#: 1 %-of-max onset threshold of the claims
D_SLOW = 5.0


def test_creeping_and_diffusing_are_told_apart():
    """500 creepers, 500 Brownian particles at D_SLOW over the shortest window: every
    creeper still, at least 99 % of the diffusers displaced."""
    x, truth = synthetic_positions(500, 500, D_SLOW, T, DT, S, seed=1)
    got = displaced(x, S)
    assert not got[~truth].any()
    assert got[truth].mean() >= 0.99


def test_moving_time_counts_the_time_a_particle_moves():
    """Diffusers that stop halfway through the window: their moving-time share is the share
    of the analysed part before they stopped, ± one block; creepers have none.  At D = 100
    mm²/s (a fifth of the bouncing D) at least 99 % of the blocks of a running particle
    move."""
    x, truth = synthetic_positions(200, 200, 100.0, 20.0, DT, S, seed=2, stop_at=11.0)
    phi = moving_share(x, DT, S)
    assert np.all(phi[~truth] == 0)
    analysed = 20.0 - 0.1 * 20.0  # s, after bbb reduce's 10 % discard
    expected = (11.0 - 2.0) / analysed
    assert np.all(np.abs(phi[truth] - expected) <= BLOCK / analysed + 1e-12)
    x, truth = synthetic_positions(0, 300, 100.0, 20.0, DT, S, seed=3)
    assert moving_blocks(x, DT, S).mean() >= 0.99


def test_a_creeper_beyond_its_arc_is_not_still():
    """The threshold is S, not more: a particle rocking with amplitude 0.6 S (beyond its cell)
    is displaced, so the creepers above are told apart by S, not by luck."""
    x, truth = synthetic_positions(300, 0, D_SLOW, T, DT, S, seed=4, rock=0.6)
    assert displaced(x, S).mean() > 0.5


def test_still_bound_bounds_a_confined_particle():
    """No curve confined to [0, 4 S²] has a larger OLS half-slope than still_bound, and the
    extreme curve (0 below the mean lag, 4 S² above) attains it."""
    rng = np.random.default_rng(5)
    lo, hi = 5, 25
    t = np.arange(lo, hi + 1) * DT
    tc = t - t.mean()
    b = still_bound(S, lo, hi, DT)
    y = rng.uniform(0, 4 * S * S, (2000, t.size))
    half = (y - y.mean(axis=1, keepdims=True)) @ tc / (tc @ tc) / 2
    assert np.abs(half).max() <= b
    ext = np.where(tc > 0, 4 * S * S, 0.0)
    assert (ext - ext.mean()) @ tc / (tc @ tc) / 2 == pytest.approx(b)


def test_window_is_the_first_T_seconds():
    x = np.arange(101.0)[None, :]
    assert window(x, 0.5, 5.0).shape == (1, 11)
    with pytest.raises(ValueError):
        window(x, 0.5, 5.2)
    with pytest.raises(ValueError):
        window(x, 0.5, 60.0)
