"""Input checks shared by the statistics modules: positions, lags, sample times.

Positions are float arrays of shape (n_particles, n_samples), mm; sample times in s.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

_FLOAT = NDArray[np.float64]


def _as_positions(x: ArrayLike) -> _FLOAT:
    xs = np.asarray(x, dtype=np.float64)
    if xs.ndim == 1:
        xs = xs[None, :]
    if xs.ndim != 2:
        raise ValueError(f"x must have shape (n_particles, n_samples), got {xs.shape}")
    if xs.shape[0] < 1 or xs.shape[1] < 2:
        raise ValueError(f"x needs ≥ 1 particle and ≥ 2 samples, got shape {xs.shape}")
    if not np.all(np.isfinite(xs)):
        raise ValueError("x holds non-finite positions (NaN or inf)")
    return xs


def _as_lags(lags: ArrayLike, n_samples: int) -> NDArray[np.int64]:
    arr = np.atleast_1d(np.asarray(lags))
    if arr.ndim != 1 or arr.size == 0:
        raise ValueError(f"lags must be a non-empty 1-D sequence of integers, got {lags!r}")
    as_int = arr.astype(np.int64)
    if not np.array_equal(as_int, arr):
        raise ValueError("lags must be integers (numbers of sample spacings)")
    if as_int.min() < 0 or as_int.max() >= n_samples:
        raise ValueError(
            f"lags must lie in [0, n_samples - 1] = [0, {n_samples - 1}], "
            f"got [{as_int.min()}, {as_int.max()}]"
        )
    return as_int


def _as_times(sample_times: ArrayLike, n_samples: int) -> _FLOAT:
    times = np.asarray(sample_times, dtype=np.float64)
    if times.shape != (n_samples,):
        raise ValueError(
            f"sample_times must have shape ({n_samples},) to match x, got {times.shape}"
        )
    if not np.all(np.isfinite(times)):
        raise ValueError("sample_times holds non-finite values")
    return times


def _spacing(times: _FLOAT, n_samples: int) -> float:
    steps = np.diff(times)
    dt = float((times[-1] - times[0]) / (n_samples - 1))
    if not dt > 0 or np.max(np.abs(steps - dt)) > 1e-6 * dt:
        raise ValueError("sample_times must be strictly increasing and equally spaced")
    return dt
