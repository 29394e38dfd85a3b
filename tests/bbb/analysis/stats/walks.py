"""Synthetic trajectories with known statistics for the bbb.analysis.stats tests.

Brownian trajectories (Gaussian increments of variance 2 D dt) have a known D, a known
time-averaged MSD 2 D Δ and a known ergodicity-breaking parameter ≈ 4/3 Δ/T.
"""

from __future__ import annotations

import numpy as np

DT = 0.01  # s


def brownian(
    rng: np.random.Generator, n_particles: int, n_samples: int, D: float, dt: float = DT
) -> np.ndarray:
    """Positions (mm) of Brownian particles with diffusion coefficient D (mm²/s), x(0) = 0."""
    steps = rng.normal(scale=np.sqrt(2.0 * D * dt), size=(n_particles, n_samples - 1))
    x = np.zeros((n_particles, n_samples))
    np.cumsum(steps, axis=1, out=x[:, 1:])
    return x


def times(n_samples: int, dt: float = DT) -> np.ndarray:
    return np.arange(n_samples) * dt


def jumps(rng: np.random.Generator, n_particles: int, n_samples: int, rate: float,
          dt: float = DT) -> np.ndarray:
    """Compound Poisson walks: N(0, 1) mm jumps at `rate` per second.  Ergodic (every
    particle has the same D = rate/2), but its increments are far from Gaussian at lags
    ~ 1/rate, so EB sits above the Brownian level and still falls like 1/T."""
    steps = rng.standard_normal((n_particles, n_samples - 1))
    steps *= rng.random((n_particles, n_samples - 1)) < rate * dt
    return np.concatenate([np.zeros((n_particles, 1)), np.cumsum(steps, axis=1)], axis=1)
