"""Time-averaged mean squared displacement (TAMSD) of trajectories, mm².

The TAMSD of one trajectory at lag L (sample spacings) is the average over all
``n_samples - L`` time origins (sliding windows) ``δ²(L) = mean_i (x[i+L] - x[i])²``; the
ensemble MSD is the mean of δ² over particles (as kinisi and MDAnalysis do).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .inputs import as_lags, as_positions

__all__ = ["tamsd", "msd_time_averaged"]

_FLOAT = NDArray[np.float64]
# Largest number of complex FFT values held at once when computing the TAMSD (≈ 64 MB).
_FFT_BLOCK_VALUES = 4_000_000


def tamsd(x: ArrayLike, lags: ArrayLike) -> _FLOAT:
    """Time-averaged MSD δ²(L) of each trajectory, mm².

    x    -- positions, mm, shape (n_particles, n_samples) (1-D: one particle)
    lags -- integer lags L in sample spacings, each 0 ≤ L < n_samples

    Returns shape (n_particles, n_lags): ``δ²[p, j] = mean_i (x[p, i+L_j] - x[p, i])²``
    over all n_samples - L_j origins.  Uses direct sums for a few lags and an FFT
    autocorrelation (O(n log n) for all lags at once) for many; both are exact up to
    rounding and are applied to mean-subtracted positions to limit cancellation.
    """
    xs = as_positions(x)
    lag_idx = as_lags(lags, xs.shape[1])
    return tamsd_unchecked(xs, lag_idx)


def msd_time_averaged(x: ArrayLike, dt: float, lags: ArrayLike) -> tuple[_FLOAT, _FLOAT]:
    """Ensemble- and time-averaged MSD: the particle mean of :func:`tamsd`.

    x    -- positions, mm, shape (n_particles, n_samples)
    dt   -- sample spacing, s
    lags -- integer lags in sample spacings

    Returns ``(lags_s, msd)``: lags in s and the MSD in mm², both shape (n_lags,).
    """
    if not (math.isfinite(dt) and dt > 0):
        raise ValueError(f"dt = {dt!r} must be finite and > 0 (sample spacing in s)")
    xs = as_positions(x)
    lag_idx = as_lags(lags, xs.shape[1])
    return lag_idx * float(dt), tamsd_unchecked(xs, lag_idx).mean(axis=0)


def tamsd_unchecked(x: _FLOAT, lags: NDArray[np.int64]) -> _FLOAT:
    """:func:`tamsd` of positions and lags already checked (inputs.as_positions, as_lags)."""
    n_samples = x.shape[1]
    # The FFT costs ~ n log n per particle whatever the number of lags; a direct sum
    # costs ~ n per lag.  Break-even measured near 5 log2(2n) lags.
    if lags.size <= 4 * math.log2(2 * n_samples):
        return _tamsd_direct(x, lags)
    return _tamsd_fft(x, lags)


def _tamsd_direct(x: _FLOAT, lags: NDArray[np.int64]) -> _FLOAT:
    n_samples = x.shape[1]
    out = np.empty((x.shape[0], lags.size))
    for j, lag in enumerate(lags):  # loop over lags only; particles and origins are vectorised
        if lag == 0:
            out[:, j] = 0.0
            continue
        d = x[:, lag:] - x[:, : n_samples - lag]
        out[:, j] = np.einsum("ij,ij->i", d, d) / (n_samples - lag)
    return out


def _tamsd_fft(x: _FLOAT, lags: NDArray[np.int64]) -> _FLOAT:
    # Σ_i (x[i+L] - x[i])² = Σ_{i≥L} x[i]² + Σ_{i<n-L} x[i]² - 2 Σ_i x[i] x[i+L]; the last
    # term is the autocorrelation, from |rfft|² of the zero-padded series.
    n_particles, n_samples = x.shape
    nfft = _next_fast_len(2 * n_samples)
    block = max(1, _FFT_BLOCK_VALUES // (nfft // 2 + 1))
    out = np.empty((n_particles, lags.size))
    for start in range(0, n_particles, block):
        xb = x[start : start + block]
        xb = xb - xb.mean(axis=1, keepdims=True)
        spec = np.fft.rfft(xb, nfft, axis=1)
        acf = np.fft.irfft(spec.real**2 + spec.imag**2, nfft, axis=1)[:, lags]
        sq = np.zeros((xb.shape[0], n_samples + 1))
        np.cumsum(xb * xb, axis=1, out=sq[:, 1:])  # sq[:, k] = Σ_{i<k} x[i]²
        total = sq[:, n_samples : n_samples + 1]
        sums = (total - sq[:, lags]) + sq[:, n_samples - lags] - 2.0 * acf
        out[start : start + block] = np.maximum(sums, 0.0) / (n_samples - lags)
    out[:, lags == 0] = 0.0
    return out


def _next_fast_len(n: int) -> int:
    """Smallest 2^a 3^b 5^c ≥ n (fast sizes for pocketfft)."""
    best = 1 << max(0, (n - 1).bit_length())
    p5 = 1
    while p5 < best:
        p35 = p5
        while p35 < best:
            p = p35
            while p < n:
                p *= 2
            best = min(best, p)
            p35 *= 3
        p5 *= 5
    return best
