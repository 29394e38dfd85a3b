"""Does D depend on the run length?  D from the first vs the second half of the analysed run.

A diffusion coefficient measured from runs of length T is only the paper's D (a t → ∞ limit)
if the motion is stationary over the run: a population that slowly decays from bouncing into
creeping, or that keeps spiralling outward, gives a D that changes with T.  The check:

* the analysed part of the run (after the transient ``discard``, exactly as
  :func:`bbb.analysis.stats.diffusion_coefficient` drops it) is cut into two halves of equal length
  T_h;
* in each half every particle's D_i is the OLS slope / 2 of its own time-averaged MSD over
  the lags fit_from·T_h … fit_to·T_h (the same *fractions* as the whole-run fit, so both
  halves and the whole run are fitted alike); D_half = mean_i D_i, which equals
  ``diffusion_coefficient`` on that half (OLS is linear in the data);
* ΔD = D_half2 − D_half1 gets a **paired** bootstrap CI over particles: a resample draws
  particles with replacement and takes the mean of their (D2_i − D1_i), so the correlation
  between the two halves of one trajectory is kept;
* the point is flagged **non-stationary** when the CI of ΔD excludes 0 by more than the
  tolerance: ``dD_lo > tol`` or ``dD_hi < −tol`` with
  ``tol = TOLERANCE · |D_ref| + D_FLOOR``, D_ref = (D_half1 + D_half2) / 2.

Tolerance, and why (rule fixed on synthetic data before looking at any store; Brownian
walks sampled like the Fig. 2 scene, 50 s at 0.5 s, discard 10 %, fit 5-25 %; diffusivity
constant, or growing linearly in time so that it is 1.5x or 2x at the end of the run;
400 ensembles per cell, 200 for 1024 particles and for the 2x column; fraction flagged):

=========  ======================  ==================  ==================
particles  stationary: tol 0 / 5 %  1.5x (D2/D1 ≈ 1.2)  2x (D2/D1 ≈ 1.34)
=========  ======================  ==================  ==================
64         7.5 % / 2.8 %           15 %                45 %
256        5.8 % / 0.8 %           46 %                96 %
1024       5.5 % / 0.0 %           96 %                100 %
=========  ======================  ==================  ==================

* TOLERANCE = 0.05: a 95 % CI of ΔD that merely excludes 0 flags ~5-7 % of stationary
  ensembles at every size, i.e. ~6 of the 124 frequencies of Fig. 2 for nothing, and with
  the paper's 4096 particles it would also flag drifts of 1-2 % that matter for no claim.
  Requiring the CI to clear 5 % of D keeps false flags ≤ 3 % (≤ 1 % from 256 particles on)
  and flags a diffusivity that doubles over the run in ≥ 96 % of ensembles of ≥ 256
  particles (the real case that prompted the check: at R = 25, 98 Hz, D from 50 s runs is
  about twice D from ~170 s runs).  What it reports: "D changes between the halves of the
  run by more than 5 %, beyond the CI".  tests/bbb/analysis/test_stationarity.py re-measures the
  stationary and the 2x cells.
* D_FLOOR = 1e-6 mm²/s: ensembles that never move give D ~ 1e-30 from rounding, whose
  difference is pure noise.

numpy only, and the public functions of :mod:`bbb.analysis.stats`.  Units: x in mm, t in s, D in mm²/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .stats import DEFAULT_DISCARD, DEFAULT_FIT_FROM, DEFAULT_FIT_TO, tamsd, unit_means

__all__ = ["TOLERANCE", "D_FLOOR", "Stationarity", "half_run_diffusion", "stationarity"]

#: relative change of D (of the mean of the halves) that the CI of ΔD must clear to flag
TOLERANCE = 0.05
#: absolute part of the tolerance, mm²/s (rounding noise of a still ensemble)
D_FLOOR = 1e-6

_F = NDArray[np.float64]


@dataclass(frozen=True)
class Stationarity:
    """First half vs second half of the analysed run.

    D_half1, D_half2 -- D of each half, mm²/s
    dD, dD_lo, dD_hi -- D_half2 − D_half1 and its paired bootstrap CI, mm²/s; the CI is NaN
                        when every particle's difference is the same (e.g. none moves): such a
                        sample has no spread to bound it with, and [dD, dD] would claim
                        certainty (the point then counts as stationary: nothing to flag)
    tolerance        -- what the CI must clear to flag, mm²/s (TOLERANCE·|D_ref| + D_FLOOR)
    half_duration    -- length of each half, s;  fit_lags: (lo, hi) fit lags of a half, s
    """

    D_half1: float
    D_half2: float
    dD: float
    dD_lo: float
    dD_hi: float
    tolerance: float
    half_duration: float
    fit_lags: tuple[float, float]

    @property
    def stationary(self) -> bool:
        """False when the CI of ΔD lies beyond ±tolerance (D depends on the run length)."""
        return not (self.dD_lo > self.tolerance or self.dD_hi < -self.tolerance)


def _ols_slope(t: _F, y: _F) -> _F:
    """OLS slope of every row of y (n_rows, n_t) against t (n_t,)."""
    tc = t - t.mean()
    return (y - y.mean(axis=1, keepdims=True)) @ tc / (tc @ tc)


def half_run_diffusion(x: ArrayLike, sample_times: ArrayLike, *,
                       discard: float = DEFAULT_DISCARD, fit_from: float = DEFAULT_FIT_FROM,
                       fit_to: float = DEFAULT_FIT_TO) -> tuple[_F, _F, float, tuple[float, float]]:
    """Per-particle D_i (mm²/s) in the first and the second half of the analysed run.

    x            -- positions, mm, shape (n_particles, n_samples), equally spaced in time
    sample_times -- s, shape (n_samples,)
    discard      -- fraction of the run dropped at the start (as bbb.analysis.stats)
    fit_from, fit_to -- fit lags as *fractions* of a half's duration
    Returns (D1_i, D2_i, half duration in s, (lowest, highest) fit lag in s).
    Raises ValueError if a half holds fewer than two fit lags.
    """
    xs = np.atleast_2d(np.asarray(x, dtype=np.float64))
    t = np.asarray(sample_times, dtype=np.float64).ravel()
    if t.size != xs.shape[1] or t.size < 4:
        raise ValueError(f"need ≥ 4 sample times matching x's {xs.shape[1]} columns, got {t.size}")
    if not (0.0 <= discard < 1.0 and 0.0 < fit_from < fit_to <= 1.0):
        raise ValueError(f"need 0 ≤ discard < 1 and 0 < fit_from < fit_to ≤ 1; got {discard}, "
                         f"{fit_from}, {fit_to}")
    dt = float(t[1] - t[0])
    start = int(np.searchsorted(t, t[0] + discard * (t[-1] - t[0]) - 1e-9 * dt))
    n_half = (t.size - start) // 2
    T_h = (n_half - 1) * dt
    lag_lo = max(1, math.ceil(fit_from * T_h / dt - 1e-9))
    lag_hi = min(n_half - 1, math.floor(fit_to * T_h / dt + 1e-9))
    if lag_hi - lag_lo + 1 < 2:
        raise ValueError(f"a half of {T_h:g} s holds {max(0, lag_hi - lag_lo + 1)} fit lag(s) "
                         f"of dt = {dt:g} s; the check needs at least 2 — record more samples")
    lags = np.arange(lag_lo, lag_hi + 1)
    out = []
    for a in (start, start + n_half):
        curves = tamsd(xs[:, a:a + n_half], lags)
        out.append(_ols_slope(lags * dt, curves) / 2.0)
    return out[0], out[1], T_h, (lag_lo * dt, lag_hi * dt)


def stationarity(x: ArrayLike, sample_times: ArrayLike, *, n_resamples: int,
                 seed: int | np.random.SeedSequence, ci: float = 0.95,
                 tolerance: float = TOLERANCE, floor: float = D_FLOOR,
                 discard: float = DEFAULT_DISCARD, fit_from: float = DEFAULT_FIT_FROM,
                 fit_to: float = DEFAULT_FIT_TO, units: ArrayLike | None = None) -> Stationarity:
    """D of the two halves of the analysed run and the paired bootstrap CI of their difference.

    Arguments as :func:`half_run_diffusion`; n_resamples (≥ 1) percentile-bootstrap resamples
    over particles at confidence ``ci``; ``seed`` makes the result deterministic;
    ``tolerance`` (relative) and ``floor`` (mm²/s) set the flag (module docstring);
    ``units``: labels of independent units of one size (mirror pairs), resampled instead of
    particles (:func:`bbb.analysis.stats.unit_means`).
    """
    if not 0.0 < ci < 1.0:
        raise ValueError(f"ci = {ci!r} must be in (0, 1)")
    if int(n_resamples) != n_resamples or n_resamples < 1:
        raise ValueError(f"n_resamples = {n_resamples!r} must be a positive integer")
    d1, d2, T_h, lags = half_run_diffusion(x, sample_times, discard=discard, fit_from=fit_from,
                                           fit_to=fit_to)
    diff = d2 - d1 if units is None else unit_means(d2 - d1, units)
    n = diff.size
    if n < 2:
        raise ValueError("the paired bootstrap over particles needs at least 2 particles")
    ss = seed if isinstance(seed, np.random.SeedSequence) else np.random.SeedSequence(seed)
    rng = np.random.default_rng(ss)
    boot = np.empty(int(n_resamples))
    block = max(1, 2_000_000 // n)
    for s in range(0, boot.size, block):
        m = min(block, boot.size - s)
        boot[s:s + m] = diff[rng.integers(0, n, size=(m, n))].mean(axis=1)
    a = 1.0 - ci
    lo, hi = (float(v) for v in np.quantile(boot, [a / 2, 1 - a / 2]))
    if not np.ptp(diff) > 0:  # no spread: no interval (module docstring of Stationarity)
        lo = hi = math.nan
    D1, D2 = float(d1.mean()), float(d2.mean())
    return Stationarity(D_half1=D1, D_half2=D2, dD=D2 - D1, dD_lo=lo, dD_hi=hi,
                        tolerance=tolerance * abs(0.5 * (D1 + D2)) + floor,
                        half_duration=T_h, fit_lags=lags)
