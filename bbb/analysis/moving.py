"""Which particles move: operational definitions of the paper's "moving particles", fixed
before any scene was analysed with them.  Positions in mm, times in s, D in mm²/s.

Klages, Barna & Mátyás (2004) call their D "an ensemble average over *moving* particles" and
define neither the ensemble nor "moving".  A particle that creeps (held on the floor, or
rocking in tiny hops on its arc) stays within its arc; one that bounces leaves it.  The
definitions below read that off the positions of one analysis window: the first ``T`` s of
a run (a run of length T: the kernel draws no random number after the initial condition),
of which the first :data:`~bbb.analysis.stats.fit.DEFAULT_DISCARD` is dropped as
``bbb reduce`` drops it; the rest, from t_a = discard · T to T, is the *analysed part*.

Definitions (thresholds set before any data: one arc period S of the floor, the width of the
cell a creeping particle cannot leave; blocks of :data:`BLOCK` s, long enough that a
diffusing particle with D well below the bouncing D (tests/bbb/analysis/test_moving.py
measures how far below) leaves its arc within one block):

``all``
    every particle; D is bbb reduce's estimator (mean of the per-particle TAMSD slopes D_i).
``displaced`` (not creeping over the analysed part)
    max over the analysed part of |x(t) − x(t_a)| > S.  D_moving is the mean D_i over the
    displaced particles; the share is theirs among all particles.
``moving_time`` (time counted only while moving)
    the analysed part cut into blocks of :data:`BLOCK` s (an incomplete last block dropped);
    a block is moving when the particle's range max x − min x within it exceeds S.  φ_i is
    particle i's share of moving blocks; D_moving = mean D_i / mean φ_i, the ensemble's
    diffusion per unit of time spent moving; the share is mean φ_i (a time share).

``displaced`` is also what ``bbb reduce`` counts as a mover -- the same function, so its
meaning here is unchanged: the D(f) table's ``n_moving`` (the displaced particles of a point,
all families pooled), its "no mover" in ``D_status`` / ``D_drift_status`` / ``v_status`` where
none is displaced (:mod:`bbb.analysis.transport`, pipeline.tables.diffusion).  Why this
definition there: a particle farther than S from where it stood has crossed a cusp (an
interval longer than the period S holds one), so it left its arc; a particle rocking on its
arc, held still, or changing x by rounding (1e-13 mm on a conveyor below lift-off) never gets
that far.  It undercounts on purpose: a particle that crossed one cusp and stays within S of
its start is not counted, as the table cannot tell it from one rocking across a cusp.

The decomposition D_all = share · D_moving holds *exactly* for ``moving_time`` (by
construction) and for ``displaced`` up to the still particles' own D: D_all = share ·
D_moving + (1 − share) · D_still, where a still particle never gets farther than S from
x(t_a), so each of its squared displacements is below (2S)² and |D_still| is at most
:func:`still_bound` (the OLS slope of a curve confined to [0, 4S²]).  :mod:`.moving_d`
estimates the shares and D with their intervals; :func:`synthetic_positions` makes
creeping and diffusing particles with known answers, on which the thresholds are checked.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .stats.fit import DEFAULT_DISCARD, first_kept

__all__ = ["DEFINITIONS", "BLOCK", "analysed_start", "window", "displaced", "moving_blocks",
           "moving_share", "still_bound", "synthetic_positions"]

#: the averagings, in order: every particle, and the two definitions of "moving"
DEFINITIONS = ("all", "displaced", "moving_time")
#: s, the blocks of ``moving_time``
BLOCK = 0.5

_FLOAT = NDArray[np.float64]


def analysed_start(n_samples: int, discard: float = DEFAULT_DISCARD) -> int:
    """Index of the first analysed sample of a window of ``n_samples`` samples: the sample
    :func:`bbb.analysis.stats.fit.fit_regime` keeps first."""
    return first_kept(n_samples, discard)


def window(x: ArrayLike, dt: float, T: float) -> _FLOAT:
    """The first ``T`` s of positions ``x`` (n_particles, n_samples) sampled every ``dt`` s:
    samples 0 .. T/dt inclusive; T must be a multiple of dt within the run."""
    xs = np.asarray(x, dtype=np.float64)
    n = round(T / dt)
    if not (n >= 1 and abs(n * dt - T) <= 1e-9 * max(T, 1.0)):
        raise ValueError(f"T = {T!r} s is not a positive multiple of dt = {dt!r} s")
    if n + 1 > xs.shape[-1]:
        raise ValueError(f"T = {T:g} s is longer than the run ({(xs.shape[-1] - 1) * dt:g} s)")
    return xs[..., : n + 1]


def displaced(x: ArrayLike, S: float, discard: float = DEFAULT_DISCARD) -> NDArray[np.bool_]:
    """``displaced`` of each particle of the window ``x`` (n_particles, n_samples), mm: its
    largest distance from x(t_a) over the analysed part exceeds S (mm)."""
    xs = np.atleast_2d(np.asarray(x, dtype=np.float64))
    a = xs[:, analysed_start(xs.shape[1], discard):]
    return np.max(np.abs(a - a[:, :1]), axis=1) > S


def moving_blocks(x: ArrayLike, dt: float, S: float, block: float = BLOCK,
                  discard: float = DEFAULT_DISCARD) -> NDArray[np.bool_]:
    """Per particle and block of ``block`` s of the analysed part: is its range within the
    block above S?  Shape (n_particles, n_blocks); a block spans block/dt intervals and its
    two end samples; an incomplete last block is dropped."""
    xs = np.atleast_2d(np.asarray(x, dtype=np.float64))
    a = xs[:, analysed_start(xs.shape[1], discard):]
    m = round(block / dt)
    if m < 1 or abs(m * dt - block) > 1e-9 * block:
        raise ValueError(f"block = {block!r} s is not a multiple of dt = {dt!r} s")
    nb = (a.shape[1] - 1) // m
    if nb < 1:
        raise ValueError(f"the analysed part ({(a.shape[1] - 1) * dt:g} s) is shorter than "
                         f"one block ({block:g} s)")
    idx = np.arange(nb)[:, None] * m + np.arange(m + 1)[None, :]  # (nb, m + 1)
    seg = a[:, idx]  # (n, nb, m + 1)
    return (seg.max(axis=2) - seg.min(axis=2)) > S


def moving_share(x: ArrayLike, dt: float, S: float, block: float = BLOCK,
                 discard: float = DEFAULT_DISCARD) -> _FLOAT:
    """φ_i: each particle's share of moving blocks (:func:`moving_blocks`), in [0, 1]."""
    return moving_blocks(x, dt, S, block, discard).mean(axis=1)


def still_bound(S: float, lag_lo: int, lag_hi: int, dt: float) -> float:
    """The largest |D_i| (mm²/s) that a particle never farther than S (mm) from x(t_a) can
    have under the OLS fit over lags lag_lo..lag_hi (samples of dt s): its TAMSD lies in
    [0, 4 S²], and the OLS slope of such a curve is at most 4 S² Σ_{t_c > 0} t_c / Σ t_c²
    (t_c the centred lags); D is half the slope."""
    t = np.arange(lag_lo, lag_hi + 1, dtype=np.float64) * dt
    tc = t - t.mean()
    return float(2.0 * S * S * tc[tc > 0].sum() / (tc @ tc))


def synthetic_positions(n_creep: int, n_diffuse: int, D: float, T: float, dt: float,
                        S: float, seed: int, rock: float = 0.45,
                        stop_at: float | None = None) -> tuple[_FLOAT, NDArray[np.bool_]]:
    """Synthetic windows with known answers: ``n_creep`` creeping particles (each rocking
    about its start within ± ``rock`` · S, a random smooth wiggle of a few Hz) followed by
    ``n_diffuse`` Brownian particles with diffusion coefficient D (mm²/s), sampled every dt
    s over T s; with ``stop_at`` (s), the diffusing particles stop there for good (they
    moved for stop_at s of the window).  Returns (positions (n, n_samples) in mm, True for
    the diffusing particles)."""
    rng = np.random.default_rng(seed)
    n_s = round(T / dt) + 1
    t = np.arange(n_s) * dt
    x0 = rng.uniform(0.0, 100.0 * S, n_creep + n_diffuse)
    freq = rng.uniform(1.0, 5.0, (n_creep, 1))
    phase = rng.uniform(0.0, 2 * np.pi, (n_creep, 1))
    creep = x0[:n_creep, None] + rock * S * np.sin(2 * np.pi * freq * t[None, :] + phase)
    steps = rng.normal(0.0, math.sqrt(2.0 * D * dt), (n_diffuse, n_s - 1))
    if stop_at is not None:
        steps[:, round(stop_at / dt):] = 0.0
    walk = x0[n_creep:, None] + np.concatenate([np.zeros((n_diffuse, 1)),
                                                np.cumsum(steps, axis=1)], axis=1)
    truth = np.r_[np.zeros(n_creep, bool), np.ones(n_diffuse, bool)]
    return np.concatenate([creep, walk]), truth
