"""Taylor–Green–Kubo expansion of D: the random-walk term plus jump–jump correlations.

For a stationary sequence of jumps Δx_n (one per step of duration T, per particle),
    C(k) = ⟨Δx_n Δx_{n+k}⟩                       (mm², averaged over origins n and particles)
    D_n  = (1 / 2T) [C(0) + 2 Σ_{k=1..n} C(k)]   (mm²/s)
D_0 is the random-walk (uncorrelated-jump) value, D_n − D_0 the memory of n jumps, and
D_∞ = lim D_n equals the MSD-based D whenever C is summable (Klages & Korabel 2002;
Mátyás & Klages 2004 for the bouncing ball billiard).  Three step choices:

* per floor period: Δx_n = x((n+1)/f) − x(n/f), T = 1/f (:func:`period_jumps`);
* per collision, in mm: Δx_n = x_{n+1} − x_n between successive post-collision states, T = the
  mean time between collisions τ̄ (:func:`collision_jumps`);
* per collision, in cells: jumps between cells (arcs) in units of S, T = τ̄
  (:func:`cell_jumps`), as Mátyás & Klages did (a particle rattling in a cusp touches the
  left and the right arc in turn: ±1 cell at collisions with no net motion).

Where the sum stops ("D_∞"): at the first lag K ≥ 1 from which |C(k)| stays within
``noise_z`` standard errors (over particles) of zero for ``noise_window`` consecutive lags;
D_∞ = D_{K−1}.  If that never happens below ``max_lag``, the expansion is reported as not
converged and D_∞ = D_{max_lag}.  Everything here is numpy: arrays in, a dataclass out.

Why D differs between two frequencies: :mod:`bbb.analysis.gk_contrast` splits ln D_∞(a)/D_∞(b) into the
random-walk part ln D_0(a)/D_0(b) and the memory part, from the bootstrap replicates kept here.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["CollisionJumps", "GreenKubo", "cell_jumps", "collision_jumps", "expansion",
           "period_jumps"]

_FLOAT = NDArray[np.float64]
# particles per FFT block when computing per-particle correlations (bounds memory)
_FFT_BLOCK = 256


@dataclass(frozen=True)
class GreenKubo:
    """The expansion D_n for n = 0 … max_lag with bootstrap CIs over particles.

    step        -- step time T (s): 1/f per period, τ̄ per collision (the mean over particles
                   when each particle has its own)
    C           -- C(k), k = 0 … max_lag, in (jump unit)² (mm² here)
    C_se        -- standard error of C(k) over particles (the noise level)
    D_n, D_lo, D_hi -- D_n and its CI, mm²/s, n = 0 … max_lag
    lag         -- K: first lag from which |C| stays within noise (D_∞ = D_{K−1})
    converged   -- False if |C| never fell into the noise below max_lag
    D_inf, D_inf_lo, D_inf_hi -- D_∞ and its CI (the rule re-applied in every resample), mm²/s
    n_particles, n_steps -- particles and jumps per particle used
    D0_boot, D_inf_boot -- D_0 and D_∞ in each bootstrap resample (mm²/s), both from the same
                   resample of particles (paired): what :mod:`bbb.analysis.gk_contrast` combines
    """

    step: float
    C: _FLOAT
    C_se: _FLOAT
    D_n: _FLOAT
    D_lo: _FLOAT
    D_hi: _FLOAT
    lag: int
    converged: bool
    D_inf: float
    D_inf_lo: float
    D_inf_hi: float
    n_particles: int
    n_steps: int
    D0_boot: _FLOAT = field(repr=False, default_factory=lambda: np.zeros(0))
    D_inf_boot: _FLOAT = field(repr=False, default_factory=lambda: np.zeros(0))

    def at(self, n: int) -> tuple[float, float, float]:
        """(D_n, lo, hi) in mm²/s; n beyond max_lag is refused."""
        if not 0 <= n < self.D_n.size:
            raise ValueError(f"n = {n} is out of range; allowed: 0 … {self.D_n.size - 1}")
        return float(self.D_n[n]), float(self.D_lo[n]), float(self.D_hi[n])


@dataclass(frozen=True)
class CollisionJumps:
    """Jumps between cells at successive collisions.

    jumps       -- float64 (n_particles, n_jumps): cell index differences, units of S
    tau         -- mean time between collisions τ̄ over the jumps used, s
    n_excluded  -- particles left out for having fewer than n_jumps + 1 recorded collisions
    """

    jumps: _FLOAT
    tau: float
    n_excluded: int


def period_jumps(positions: ArrayLike, discard: int = 0) -> _FLOAT:
    """Displacements (mm) over every floor period from positions sampled at t = n/f.

    positions -- (n_particles, n_samples) x in mm at n/f, n = 0 … n_samples − 1
    discard   -- number of leading periods dropped as a transient (the expansion assumes
                 stationarity: start-up jumps must not enter C)
    Returns (n_particles, n_samples − 1 − discard).
    """
    x = np.asarray(positions, dtype=np.float64)
    if x.ndim != 2 or x.shape[1] < 2:
        raise ValueError(f"positions must be (n_particles, n_samples ≥ 2), got {x.shape}")
    if not 0 <= discard < x.shape[1] - 1:
        raise ValueError(f"discard = {discard} is out of range; allowed: 0 … {x.shape[1] - 2}")
    return np.diff(x[:, discard:], axis=1)


def cell_jumps(collisions: ArrayLike, n_recorded: ArrayLike, S: float,
               n_jumps: int | None = None) -> CollisionJumps:
    """Cell-to-cell jumps (units of S) at successive recorded collisions.

    collisions -- (n_particles, n_rows, ≥ 2) post-collision rows (t s, x mm, …) as in
                  ``SimRun.collisions_dense`` (record from after the transient)
    n_recorded -- valid rows per particle
    S          -- scatterer spacing, mm; the cell of x is the nearest arc centre round(x/S)
    n_jumps    -- jumps per particle (default: the smallest count over particles with at
                  least 2 rows); particles with fewer rows are excluded and counted
    """
    rows = np.asarray(collisions, dtype=np.float64)
    nrec = np.asarray(n_recorded, dtype=np.int64)
    if rows.ndim != 3 or rows.shape[2] < 2 or nrec.shape != rows.shape[:1]:
        raise ValueError("collisions must be (n_particles, n_rows, ≥ 2) with n_recorded per particle")
    if n_jumps is None:
        ok = nrec >= 2
        if not ok.any():
            raise ValueError("no particle has two recorded collisions")
        n_jumps = int(nrec[ok].min()) - 1
    if n_jumps < 1 or n_jumps + 1 > rows.shape[1]:
        raise ValueError(f"n_jumps = {n_jumps} is out of range; allowed: 1 … {rows.shape[1] - 1}")
    keep = nrec >= n_jumps + 1
    if not keep.any():
        raise ValueError(f"no particle has {n_jumps + 1} recorded collisions")
    r = rows[keep, : n_jumps + 1]
    cell = np.floor(r[:, :, 1] / S + 0.5)
    t = r[:, :, 0]
    tau = float(np.mean(t[:, -1] - t[:, 0]) / n_jumps)
    return CollisionJumps(np.diff(cell, axis=1), tau, int(np.count_nonzero(~keep)))


def collision_jumps(collisions: ArrayLike, n_recorded: ArrayLike) -> tuple[_FLOAT, _FLOAT]:
    """Horizontal jumps (mm) and their durations (s) between successive recorded collisions.

    collisions -- (n_particles, n_rows, ≥ 2) post-collision rows (t s, x mm, …) as in
                  ``SimRun.collisions_dense``;  n_recorded -- valid rows per particle
    Returns (dx, dt), each (n_particles, n_rows − 1): dx[i, n] = x_{n+1} − x_n and
    dt[i, n] = t_{n+1} − t_n for n < n_recorded[i] − 1, NaN beyond.
    """
    rows = np.asarray(collisions, dtype=np.float64)
    nrec = np.asarray(n_recorded, dtype=np.int64)
    if rows.ndim != 3 or rows.shape[2] < 2 or rows.shape[1] < 2 or nrec.shape != rows.shape[:1]:
        raise ValueError("collisions must be (n_particles, n_rows ≥ 2, ≥ 2) with n_recorded per "
                         "particle")
    valid = np.arange(rows.shape[1] - 1)[None, :] < (nrec[:, None] - 1)
    dx = np.where(valid, np.diff(rows[:, :, 1], axis=1), np.nan)
    dt = np.where(valid, np.diff(rows[:, :, 0], axis=1), np.nan)
    return dx, dt


def expansion(
    jumps: ArrayLike,
    step: float | ArrayLike,
    *,
    max_lag: int | None = None,
    n_resamples: int = 1000,
    ci: float = 0.95,
    seed: int = 0,
    noise_z: float = 2.0,
    noise_window: int = 5,
) -> GreenKubo:
    """The Taylor–Green–Kubo expansion of D from jumps (n_particles, n_steps).

    jumps   -- per-particle stationary jump sequences (transient already removed), in mm
               (or any length unit: C and D follow it)
    step    -- duration T of one step, s; or one per particle (its window's duration / n_steps,
               as per collision): T is then their mean, recomputed in every resample
    max_lag -- largest lag n of D_n (default min(n_steps // 4, 1000))
    n_resamples, ci, seed -- percentile bootstrap over particles (deterministic in seed)
    noise_z, noise_window -- the convergence rule (module docstring)
    """
    dx = np.asarray(jumps, dtype=np.float64)
    if dx.ndim != 2 or dx.shape[0] < 2 or dx.shape[1] < 2:
        raise ValueError(f"jumps must be (n_particles ≥ 2, n_steps ≥ 2), got {dx.shape}")
    if not np.all(np.isfinite(dx)):
        raise ValueError("jumps must be finite (drop particles with missing samples first)")
    n_p, n = dx.shape
    steps = np.broadcast_to(np.asarray(step, dtype=np.float64), (n_p,)) if np.ndim(step) == 0 \
        else np.asarray(step, dtype=np.float64)
    if steps.shape != (n_p,) or not np.all(np.isfinite(steps) & (steps > 0)):
        raise ValueError(f"step must be a positive time (s), or one per particle ({n_p}); "
                         f"got {np.asarray(step).shape} values, min {np.min(step)!r}")
    T = float(steps.mean())
    if max_lag is None:
        max_lag = min(n // 4, 1000)
    if not 1 <= max_lag <= n - 1:
        raise ValueError(f"max_lag = {max_lag} is out of range; allowed: 1 … {n - 1}")
    if not 0.0 < ci < 1.0:
        raise ValueError(f"ci = {ci!r} must be in (0, 1)")
    c_i = _autocorrelation(dx, max_lag)  # (n_p, max_lag + 1)
    s_i = _partial_sums(c_i)
    counts = _resample_counts(n_p, n_resamples, seed)  # (n_resamples, n_p)
    C, C_se = (a[0] for a in _mean_se(c_i, np.ones((1, n_p))))
    D_n = s_i.mean(axis=0) / (2.0 * T)
    # τ̄ of a resample: the mean step of its particles (1/f exactly when all steps are equal)
    boot = (counts @ s_i / n_p) / (2.0 * (counts @ steps / n_p))[:, None]
    q = (1.0 - ci) / 2.0
    D_lo, D_hi = np.quantile(boot, [q, 1.0 - q], axis=0)
    lag = _converged_lag(C[None], C_se[None], noise_z, noise_window)[0]
    converged = lag < max_lag
    # D_∞'s CI re-applies the rule in every resample: the choice of K varies with the data
    # too, and a CI at fixed K was measured 1.2–1.8× too narrow on AR(1) sequences
    C_b, se_b = _mean_se(c_i, counts)
    lag_b = _converged_lag(C_b, se_b, noise_z, noise_window)
    inf_b = boot[np.arange(boot.shape[0]), np.where(lag_b < max_lag, lag_b - 1, max_lag)]
    n_inf = lag - 1 if converged else max_lag
    inf_lo, inf_hi = np.quantile(inf_b, [q, 1.0 - q])
    return GreenKubo(
        step=T, C=C, C_se=C_se, D_n=D_n, D_lo=D_lo, D_hi=D_hi,
        lag=int(lag) if converged else max_lag, converged=bool(converged),
        D_inf=float(D_n[n_inf]), D_inf_lo=float(inf_lo), D_inf_hi=float(inf_hi),
        n_particles=n_p, n_steps=n, D0_boot=boot[:, 0].copy(), D_inf_boot=inf_b,
    )


def _autocorrelation(dx: _FLOAT, max_lag: int) -> _FLOAT:
    """Per-particle c_i(k) = mean over n of Δx_n Δx_{n+k}, k = 0 … max_lag (FFT)."""
    n_p, n = dx.shape
    size = 1 << (2 * n - 1).bit_length()  # zero padding ≥ 2n − 1: no wrap-around
    counts = n - np.arange(max_lag + 1)
    out = np.empty((n_p, max_lag + 1))
    for a in range(0, n_p, _FFT_BLOCK):
        F = np.fft.rfft(dx[a : a + _FFT_BLOCK], size, axis=1)
        out[a : a + _FFT_BLOCK] = np.fft.irfft(F * F.conj(), size, axis=1)[:, : max_lag + 1]
    return out / counts


def _partial_sums(c: _FLOAT) -> _FLOAT:
    """C(0) + 2 Σ_{k=1..n} C(k) (length²; D_n is this over 2T), row by row."""
    return 2.0 * np.cumsum(c, axis=1) - c[:, :1]


def _resample_counts(n: int, n_resamples: int, seed: int) -> _FLOAT:
    """How often each of n particles is drawn in each resample (with replacement)."""
    if int(n_resamples) != n_resamples or n_resamples < 1:
        raise ValueError(f"n_resamples = {n_resamples!r} must be a positive integer")
    rng = np.random.default_rng(np.random.SeedSequence(seed))
    return rng.multinomial(n, np.full(n, 1.0 / n), size=int(n_resamples)).astype(np.float64)


def _mean_se(c: _FLOAT, counts: _FLOAT) -> tuple[_FLOAT, _FLOAT]:
    """Per resample (rows of counts): mean of the drawn rows of c and its standard error."""
    n = c.shape[0]
    mean = counts @ c / n
    var = np.maximum(counts @ (c * c) / n - mean * mean, 0.0) * n / (n - 1)
    return mean, np.sqrt(var / n)


def _converged_lag(C: _FLOAT, se: _FLOAT, z: float, window: int) -> NDArray[np.int64]:
    """Per row: the first K ≥ 1 with |C(k)| ≤ z·se(k) for k = K … K + window − 1,
    or the last lag (C.shape[1] − 1) when there is none."""
    loud = (np.abs(C) > z * se)[:, 1:].astype(np.int64)
    # loud lags in each window [k, k + window): differences of a cumulative sum
    csum = np.concatenate([np.zeros((C.shape[0], 1), np.int64), np.cumsum(loud, axis=1)], axis=1)
    n_win = loud.shape[1] - window + 1
    if n_win < 1:
        return np.full(C.shape[0], C.shape[1] - 1)
    quiet = (csum[:, window : window + n_win] - csum[:, :n_win]) == 0
    first = np.argmax(quiet, axis=1) + 1
    return np.where(quiet.any(axis=1), first, C.shape[1] - 1)
