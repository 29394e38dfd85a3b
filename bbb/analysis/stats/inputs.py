"""Input checks shared by the statistics modules: positions, lags, sample times.

Positions are float arrays of shape (n_particles, n_samples), mm; sample times in s.  The
checks are public names for the other modules of bbb.analysis.stats, not part of the package's
``__all__``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

_FLOAT = NDArray[np.float64]


def as_positions(x: ArrayLike) -> _FLOAT:
    """x as float positions of shape (n_particles, n_samples) (1-D: one particle), all finite."""
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


def as_lags(lags: ArrayLike, n_samples: int) -> NDArray[np.int64]:
    """lags as a non-empty 1-D integer array of sample spacings in [0, n_samples - 1]."""
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


def as_times(sample_times: ArrayLike, n_samples: int) -> _FLOAT:
    """sample_times (s) as a finite float array of shape (n_samples,)."""
    times = np.asarray(sample_times, dtype=np.float64)
    if times.shape != (n_samples,):
        raise ValueError(
            f"sample_times must have shape ({n_samples},) to match x, got {times.shape}"
        )
    if not np.all(np.isfinite(times)):
        raise ValueError("sample_times holds non-finite values")
    return times


def sample_spacing(times: _FLOAT, n_samples: int) -> float:
    """The spacing dt (s) of strictly increasing, equally spaced (to 1e-6 dt) sample times."""
    steps = np.diff(times)
    dt = float((times[-1] - times[0]) / (n_samples - 1))
    if not dt > 0 or np.max(np.abs(steps - dt)) > 1e-6 * dt:
        raise ValueError("sample_times must be strictly increasing and equally spaced")
    return dt
