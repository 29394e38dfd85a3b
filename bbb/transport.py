"""Transport of an ensemble: drift velocity v (mm/s), D about the drift (mm²/s), Péclet v S / D.

A tilted or obliquely thrown floor (``Params.tilt``, ``Params.throw``) makes the particles
drift.  The drift is measured over the same lag window as D (:mod:`bbb.stats`):

* each particle's time-averaged mean displacement m_i(L) = mean over all time origins of
  x[i+L] − x[i] (after the discarded transient), for every fit lag L;
* its own drift v_i = the OLS slope of m_i(L) against L dt over the fit lags (the intercept
  absorbs the short-time ballistic offset, as the MSD fit's c does);
* v = mean of v_i (OLS is linear in the data, so this is also the slope of the ensemble mean
  displacement), with the bootstrap CI over particles of :func:`bbb.stats.bootstrap_mean`.

D about the drift is today's estimator (time-averaged MSD fit, bootstrap CI over particles)
applied to x − v t with the ensemble v: without the subtraction the MSD grows like v² Δ²
and its fitted "D" is a drift artefact.  v is held fixed within the bootstrap of D; its own
uncertainty shifts the MSD by (δv Δ)², of order D / (N T) · Δ² ≪ 2 D Δ for N particles.

Positions are ``(n_particles, n_samples)`` in mm at equally spaced times (s), as in bbb.stats.
Pure numpy; only public bbb.stats names.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from . import stats

__all__ = ["TransportEstimate", "per_particle_drift", "drift_velocity", "transport",
           "STEADY_REL", "STEADY_ABS"]

#: a drift is not steady when the CI of v(second half) − v(first half) lies beyond
#: ±(STEADY_REL |v| + STEADY_ABS) -- the rule and tolerance bbb.stationarity uses for D
STEADY_REL = 0.05
STEADY_ABS = 1e-6  # mm/s


@dataclass(frozen=True)
class TransportEstimate:
    """Drift and diffusion about it.

    v, v_lo, v_hi  -- drift velocity and its bootstrap CI over particles, mm/s
    D, D_lo, D_hi  -- D of x − v t and its bootstrap CI, mm²/s
    Pe             -- Péclet number v S / D (S the scatterer spacing), dimensionless
    fit_from, fit_to -- lag window of both fits, s
    dv, dv_lo, dv_hi -- v of the analysed run's second half minus its first half (each fitted
                      over the same fractions of a half), paired bootstrap CI, mm/s
    steady         -- False when the CI of dv lies beyond ±(STEADY_REL |v| + STEADY_ABS): an
                      acceleration, not a drift (a particle running away downhill has
                      dv ~ a T / 2); a noisy dv whose CI reaches the band is not flagged
    """

    v: float
    v_lo: float
    v_hi: float
    D: float
    D_lo: float
    D_hi: float
    Pe: float
    fit_from: float
    fit_to: float
    dv: float = math.nan
    dv_lo: float = math.nan
    dv_hi: float = math.nan
    steady: bool = True


def _window(xs: np.ndarray, times: np.ndarray, fit: dict) -> tuple[int, int, int, float]:
    """(start, lag_lo, lag_hi, dt) of the fit regime of bbb.stats.diffusion_coefficient."""
    est = stats.diffusion_coefficient(xs[:1], times, **fit)  # one particle: the regime only
    dt = float(times[1] - times[0])
    start = int(np.searchsorted(times, est.t_start - 1e-9 * dt))
    return start, round(est.fit_from / dt), round(est.fit_to / dt), dt


def per_particle_drift(x: ArrayLike, sample_times: ArrayLike, **fit) -> np.ndarray:
    """Each particle's drift v_i, mm/s, shape (n_particles,) (module docstring); ``fit``:
    ``fit_from``, ``fit_to``, ``discard`` as in :func:`bbb.stats.diffusion_coefficient`."""
    xs = np.atleast_2d(np.asarray(x, dtype=np.float64))
    times = np.asarray(sample_times, dtype=np.float64)
    start, lo, hi, dt = _window(xs, times, fit)
    xk = xs[:, start:] - xs[:, start : start + 1]  # origin at 0: less cancellation in the sums
    n = xk.shape[1]
    c = np.zeros((xk.shape[0], n + 1))
    np.cumsum(xk, axis=1, out=c[:, 1:])  # c[:, k] = Σ_{i<k} x[i]
    lags = np.arange(lo, hi + 1)
    # Σ_{i<n-L} (x[i+L] − x[i]) = (c[n] − c[L]) − c[n−L]
    m = ((c[:, n : n + 1] - c[:, lags]) - c[:, n - lags]) / (n - lags)
    t = lags * dt
    tc = t - t.mean()
    return (m - m.mean(axis=1, keepdims=True)) @ tc / (tc @ tc)


def drift_velocity(x: ArrayLike, sample_times: ArrayLike, *, n_resamples: int, ci: float = 0.95,
                   seed: int | np.random.SeedSequence, method: str = "percentile",
                   **fit) -> stats.BootstrapCI:
    """v, mm/s, with its bootstrap CI over particles (unpacks as ``v, lo, hi``)."""
    v_i = per_particle_drift(x, sample_times, **fit)
    return stats.bootstrap_mean(v_i, n_resamples=n_resamples, ci=ci, seed=seed, method=method)


def transport(x: ArrayLike, sample_times: ArrayLike, S: float, *, n_resamples: int,
              ci: float = 0.95, seed: int | np.random.SeedSequence,
              method: str = "percentile", **fit) -> TransportEstimate:
    """v (mm/s), D about the drift (mm²/s), each with a bootstrap CI, and Pe = v S / D.

    S -- scatterer spacing, mm (the Péclet length);  ``fit``: fit_from, fit_to, discard
    (bbb.stats.diffusion_coefficient).  The two bootstraps use independent child seeds.
    """
    ss = seed if isinstance(seed, np.random.SeedSequence) else np.random.SeedSequence(seed)
    s_v, s_d = ss.spawn(2)
    xs = np.atleast_2d(np.asarray(x, dtype=np.float64))
    times = np.asarray(sample_times, dtype=np.float64)
    v = drift_velocity(xs, times, n_resamples=n_resamples, ci=ci, seed=s_v, method=method, **fit)
    d = stats.bootstrap_D(xs - v[0] * times[None, :], times, n_resamples=n_resamples, ci=ci,
                          seed=s_d, method=method, **fit)
    est = stats.diffusion_coefficient(xs[:1], times, **fit)
    pe = v[0] * S / d.D if d.D > 0 else math.nan
    dv = drift_change(xs, times, n_resamples=n_resamples, ci=ci, seed=ss.spawn(1)[0],
                      method=method, **fit)
    tol = STEADY_REL * abs(v[0]) + STEADY_ABS
    return TransportEstimate(v=v[0], v_lo=v[1], v_hi=v[2], D=d.D, D_lo=d.lo, D_hi=d.hi, Pe=pe,
                             fit_from=est.fit_from, fit_to=est.fit_to, dv=dv[0], dv_lo=dv[1],
                             dv_hi=dv[2], steady=not (dv[1] > tol or dv[2] < -tol))


def drift_change(x: ArrayLike, sample_times: ArrayLike, *, n_resamples: int, ci: float = 0.95,
                 seed: int | np.random.SeedSequence, method: str = "percentile",
                 discard: float = stats.DEFAULT_DISCARD, fit_from: float | None = None,
                 fit_to: float | None = None) -> stats.BootstrapCI:
    """v(second half) − v(first half) of the analysed run, mm/s, with a paired bootstrap CI
    over particles; the lag window of each half is the given one halved (fit_from, fit_to in
    s; None: the default fractions of a half)."""
    xs = np.atleast_2d(np.asarray(x, dtype=np.float64))
    times = np.asarray(sample_times, dtype=np.float64)
    start, _, _, _ = _window(xs, times, dict(discard=discard, fit_from=fit_from, fit_to=fit_to))
    mid = start + (xs.shape[1] - 1 - start) // 2
    half = {"discard": 0.0, "fit_from": None if fit_from is None else fit_from / 2.0,
            "fit_to": None if fit_to is None else fit_to / 2.0}
    v1 = per_particle_drift(xs[:, start : mid + 1], times[start : mid + 1] - times[start], **half)
    v2 = per_particle_drift(xs[:, mid:], times[mid:] - times[mid], **half)
    return stats.bootstrap_mean(v2 - v1, n_resamples=n_resamples, ci=ci, seed=seed,
                                method=method)
