"""Synthetic trajectory populations with a known per-particle D spread, mm and s.

They calibrate the ergodicity rule (``benchmarks/calibrations/ergodicity_calibration.py``,
docs/statistics.md) and its tests.  Each particle i gets its own D_i (mm²/s) drawn from a
Gamma distribution of mean ``D`` and coefficient of variation ``cv`` (cv = 0: all equal),
and moves by one of three ergodic laws, so that the only non-ergodicity is the spread of
D_i itself:

brownian    Gaussian increments of variance 2 D_i dt (EB at the Brownian level)
persistent  integrated Ornstein-Uhlenbeck velocity with correlation time ``tau`` s
            (velocity correlations, like the spiral modes' long flights: EB above the
            Brownian level at short runs, still falling like 1/T)
jumpy       compound Poisson walk: N(0, a²) jumps at a rate λ_i = 2 D_i / a² per s
            (few, large steps: EB far above the Brownian level, falling like 1/T)

``mixture`` mixes bouncing particles (D) with creeping ones (``D * creep``);
``rare_movers`` makes each particle a mover with probability p (the creeping band's few
particles that take off), light- or heavy-tailed, the rest creeping.
All return positions of shape (n_particles, n_samples) at times 0, dt, ..., sampled from
a ``numpy.random.Generator``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["gamma_D", "brownian", "persistent", "jumpy", "mixture", "rare_movers", "LAWS"]

_FLOAT = NDArray[np.float64]


def gamma_D(rng: np.random.Generator, n: int, D: float, cv: float) -> _FLOAT:
    """n per-particle D_i, mm²/s: Gamma with mean D and coefficient of variation cv."""
    if cv == 0:
        return np.full(n, float(D))
    shape = 1.0 / cv**2
    return rng.gamma(shape, D / shape, n)


def brownian(rng: np.random.Generator, d_i: _FLOAT, n_samples: int, dt: float) -> _FLOAT:
    """Brownian paths with per-particle D_i (mm²/s), x(0) = 0, spacing dt (s)."""
    steps = rng.standard_normal((d_i.size, n_samples - 1)) * np.sqrt(2.0 * d_i * dt)[:, None]
    return _cumulate(steps)


def persistent(rng: np.random.Generator, d_i: _FLOAT, n_samples: int, dt: float,
               tau: float = 2.0, substeps: int = 5) -> _FLOAT:
    """Integrated OU velocity, correlation time tau (s), D_i = <v²> tau; x(0) = 0.

    The velocity is advanced exactly on substeps of dt/substeps and integrated by the
    trapezoid rule (its error only rescales D slightly, the same for every particle)."""
    h = dt / substeps
    rho = np.exp(-h / tau)
    sigma_v = np.sqrt(d_i / tau)[:, None]
    n_fine = (n_samples - 1) * substeps
    kicks = rng.standard_normal((d_i.size, n_fine)) * np.sqrt(1.0 - rho**2)
    v = np.empty((d_i.size, n_fine + 1))
    v[:, 0] = rng.standard_normal(d_i.size)
    for k in range(n_fine):  # the recursion is sequential in time; particles are vectorised
        v[:, k + 1] = rho * v[:, k] + kicks[:, k]
    v *= sigma_v
    fine = 0.5 * h * (v[:, 1:] + v[:, :-1])
    return _cumulate(fine.reshape(d_i.size, n_samples - 1, substeps).sum(axis=2))


def jumpy(rng: np.random.Generator, d_i: _FLOAT, n_samples: int, dt: float,
          jump: float = 1.0) -> _FLOAT:
    """Compound Poisson walks: N(0, jump²) jumps (mm) at rate 2 D_i / jump² per s."""
    rate = 2.0 * d_i / jump**2
    counts = rng.poisson(rate[:, None] * dt, size=(d_i.size, n_samples - 1))
    return _cumulate(jump * np.sqrt(counts) * rng.standard_normal(counts.shape))


def mixture(rng: np.random.Generator, n: int, n_samples: int, dt: float, D: float,
            bouncing: float, creep: float = 0.01) -> _FLOAT:
    """Brownian population: a fraction ``bouncing`` of particles with D, the rest with
    D * creep (creeping particles barely move).  Per-particle CV = sqrt((1-q)/q) · (1 -
    creep) / (1 - (1 - q)(1 - creep)) ≈ sqrt((1 - q)/q) for q = bouncing."""
    n_b = int(round(bouncing * n))
    d_i = np.full(n, D * creep)
    d_i[rng.permutation(n)[:n_b]] = D
    return brownian(rng, d_i, n_samples, dt)


def rare_movers(rng: np.random.Generator, n: int, n_samples: int, dt: float, p: float,
                tails: str = "light", D: float = 1.0, creep: float = 1e-6) -> _FLOAT:
    """Each of n particles moves with probability p (mm, shape (n, n_samples)).  True
    ensemble D = p D + (1 - p) creep, mm²/s (the TAMSD fit is unbiased for both laws).

    tails "light": movers Brownian, D_i ~ Gamma(mean D, CV 0.5).
    tails "heavy": movers jumpy (3 mm jumps), D_i ~ lognormal(σ = 1.5) of mean D (per-particle
                   D spread CV ≈ 2.9, plus few-jump noise).
    Non-movers: Brownian with D = creep (mm²/s)."""
    moving = rng.random(n) < p
    x = brownian(rng, np.full(n, float(creep)), n_samples, dt)
    k = int(moving.sum())
    if k:
        if tails == "light":
            x[moving] = brownian(rng, gamma_D(rng, k, D, 0.5), n_samples, dt)
        elif tails == "heavy":
            s = 1.5
            d_i = D * rng.lognormal(-0.5 * s * s, s, k)
            x[moving] = jumpy(rng, d_i, n_samples, dt, jump=3.0)
        else:
            raise ValueError(f"tails = {tails!r}; allowed: light, heavy")
    return x


LAWS = {"brownian": brownian, "persistent": persistent, "jumpy": jumpy}


def _cumulate(steps: _FLOAT) -> _FLOAT:
    x = np.zeros((steps.shape[0], steps.shape[1] + 1))
    np.cumsum(steps, axis=1, out=x[:, 1:])
    return x
