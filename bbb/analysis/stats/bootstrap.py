"""Bootstrap confidence intervals for D over particles (percentile, basic, BCa), mm²/s."""

from __future__ import annotations

from statistics import NormalDist
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .fit import DEFAULT_DISCARD, fit_regime, per_particle_fit
from .inputs import as_positions, as_times
from .interval import DInterval, d_interval

__all__ = ["BootstrapCI", "bootstrap_D", "bootstrap_mean", "with_rare_movers", "unit_means"]

_FLOAT = NDArray[np.float64]
# Largest number of resample indices held at once in the bootstrap (≈ 32 MB).
_BOOT_BLOCK_VALUES = 4_000_000


class BootstrapCI(NamedTuple):
    """D with a bootstrap confidence interval, all in mm²/s (unpacks as ``D, lo, hi``)."""

    D: float
    lo: float
    hi: float


_METHODS = ("percentile", "basic", "bca")


def bootstrap_D(
    x: ArrayLike,
    sample_times: ArrayLike,
    *,
    n_resamples: int,
    ci: float = 0.95,
    seed: int | np.random.SeedSequence,
    method: str = "percentile",
    fit_from: float | None = None,
    fit_to: float | None = None,
    discard: float = DEFAULT_DISCARD,
    rare: bool = True,
    detail: bool = False,
    units: ArrayLike | None = None,
) -> BootstrapCI | DInterval:
    """D, mm²/s, with a bootstrap confidence interval over particles.

    Particles are resampled with replacement (they are independent; time origins within a
    trajectory are not, so they are never resampled).  D and the fit regime are exactly
    those of :func:`diffusion_coefficient` (same ``fit_from``, ``fit_to``, ``discard``).

    Each particle's TAMSD curve over the fit lags is computed once and reduced to its own
    OLS slope D_i; since least squares is linear in the data, the fit of a resample's mean
    TAMSD equals the resample mean of D_i, so all resamples are fitted at once as
    (resample index matrix) gathers of D_i — no loop over particles.

    n_resamples -- number of bootstrap resamples (≥ 1; ~1000–10000 for a 95 % CI)
    ci          -- confidence level in (0, 1)
    seed        -- int or SeedSequence; the result is a deterministic function of it
    method      -- "percentile" (default), "basic" (reverse percentile) or "bca"
                   (bias-corrected and accelerated, acceleration from the jackknife)
    rare        -- apply the rare-mover rule (default): when the effective number of movers
                   n_eff = (Σ c_i)² / Σ c_i² (c_i = max(D_i, 0)) is below 40 and 25 % of the
                   particles, the CI is the hull of the bootstrap CI and the Fay-Feuer gamma
                   interval (:mod:`bbb.analysis.stats.rare`; the bootstrap alone covers < 90 % there)
    detail      -- return the :class:`~bbb.analysis.stats.interval.DInterval` (status, coverage) instead
    units       -- None (particles are independent), or labels (n_particles,) of the
                   independent units, all of one size (e.g. mirror pairs): the bootstrap and
                   the rare-mover rule then run over the units' means (:func:`unit_means`)

    Returns ``BootstrapCI(D, lo, hi)``: hi is NaN when no particle has D_i > 0 (no mover: the
    data bound the share of movers, not D; :mod:`bbb.analysis.stats.interval`).
    """
    if method not in _METHODS:
        raise ValueError(f"method = {method!r}; allowed: {', '.join(_METHODS)}")
    if not 0.0 < ci < 1.0:
        raise ValueError(f"ci = {ci!r} must be a confidence level in (0, 1)")
    if int(n_resamples) != n_resamples or n_resamples < 1:
        raise ValueError(f"n_resamples = {n_resamples!r} must be a positive integer")
    xs = as_positions(x)
    if xs.shape[0] < 2:
        raise ValueError("bootstrap over particles needs at least 2 particles")
    times = as_times(sample_times, xs.shape[1])
    reg = fit_regime(xs.shape[1], times, fit_from, fit_to, discard)
    d_i, _ = per_particle_fit(xs, reg)
    if units is not None:
        d_i = unit_means(d_i, units)
    boot = bootstrap_mean_unchecked(d_i, int(n_resamples), ci, _rng(seed), method)
    res = d_interval(d_i, boot, ci, rare=rare)
    return res if detail else BootstrapCI(res.D, res.lo, res.hi)


def with_rare_movers(d_i: ArrayLike, boot: BootstrapCI, ci: float) -> BootstrapCI:
    """``boot`` (the bootstrap CI of mean(D_i), mm²/s), widened to the hull with the
    Fay-Feuer gamma interval when few particles carry D (:func:`bbb.analysis.stats.rare.is_rare`);
    hi NaN when no D_i > 0 (:func:`bbb.analysis.stats.interval.d_interval`)."""
    res = d_interval(d_i, boot, ci)
    return BootstrapCI(res.D, res.lo, res.hi)


def bootstrap_mean(values: ArrayLike, *, n_resamples: int, ci: float = 0.95,
                   seed: int | np.random.SeedSequence, method: str = "percentile",
                   units: ArrayLike | None = None) -> BootstrapCI:
    """The mean of per-particle ``values`` (any unit) with the bootstrap CI over particles that
    :func:`bootstrap_D` gives D (same resampling, levels and methods; ``units`` as there)."""
    if method not in _METHODS:
        raise ValueError(f"method = {method!r}; allowed: {', '.join(_METHODS)}")
    if not 0.0 < ci < 1.0:
        raise ValueError(f"ci = {ci!r} must be a confidence level in (0, 1)")
    v = np.asarray(values, dtype=np.float64).ravel()
    if units is not None:
        v = unit_means(v, units)
    if v.size < 2 or not np.all(np.isfinite(v)):
        raise ValueError("bootstrap over particles needs at least 2 finite values")
    return bootstrap_mean_unchecked(v, int(n_resamples), ci, _rng(seed), method)


def unit_means(values: ArrayLike, units: ArrayLike) -> _FLOAT:
    """The mean of ``values`` over each unit (labels ``units``, same shape, every unit of one
    size), in the order of the sorted labels: what a bootstrap over independent units (e.g.
    the two particles of a mirror pair) resamples.  Their mean is the mean of ``values``."""
    v = np.asarray(values, dtype=np.float64).ravel()
    u = np.asarray(units).ravel()
    if u.shape != v.shape:
        raise ValueError(f"units holds {u.size} labels for {v.size} values")
    _, inv, counts = np.unique(u, return_inverse=True, return_counts=True)
    if counts.min() != counts.max():
        raise ValueError(f"units of unequal size ({counts.min()} to {counts.max()} values); "
                         "allowed: every unit the same size")
    return np.bincount(inv, weights=v) / counts


def _rng(seed: int | np.random.SeedSequence) -> np.random.Generator:
    ss = seed if isinstance(seed, np.random.SeedSequence) else np.random.SeedSequence(seed)
    return np.random.default_rng(ss)


def bootstrap_mean_unchecked(
    values: _FLOAT, n_resamples: int, ci: float, rng: np.random.Generator, method: str
) -> BootstrapCI:
    """:func:`bootstrap_mean` of values already checked (1-D, finite, at least 2), drawing
    from the generator ``rng``; ``method`` one of "percentile", "basic", "bca"."""
    n = values.size
    est = float(values.mean())
    boot = np.empty(n_resamples)
    block = max(1, _BOOT_BLOCK_VALUES // n)
    for start in range(0, n_resamples, block):  # blocks of resamples, each pure numpy
        m = min(block, n_resamples - start)
        idx = rng.integers(0, n, size=(m, n))
        boot[start : start + m] = values[idx].mean(axis=1)
    alpha = 1.0 - ci
    if method == "bca":
        q_lo, q_hi = _bca_levels(values, boot, est, alpha)
    else:
        q_lo, q_hi = alpha / 2.0, 1.0 - alpha / 2.0
    lo, hi = (float(v) for v in np.quantile(boot, [q_lo, q_hi]))
    if method == "basic":
        lo, hi = 2.0 * est - hi, 2.0 * est - lo
    return BootstrapCI(est, lo, hi)


def _bca_levels(values: _FLOAT, boot: _FLOAT, est: float, alpha: float) -> tuple[float, float]:
    nd = NormalDist()
    below = (np.count_nonzero(boot < est) + 0.5 * np.count_nonzero(boot == est)) / boot.size
    if below <= 0.0 or below >= 1.0:  # degenerate (e.g. all values equal)
        return alpha / 2.0, 1.0 - alpha / 2.0
    z0 = nd.inv_cdf(below)
    # Jackknife of a mean: θ̄ - θ_(i) ∝ (v_i - mean), so the acceleration is a skewness.
    dev = values - values.mean()
    ss = float(dev @ dev)
    accel = float(np.sum(dev**3)) / (6.0 * ss**1.5) if ss > 0 else 0.0
    levels = []
    for z_a in (nd.inv_cdf(alpha / 2.0), nd.inv_cdf(1.0 - alpha / 2.0)):
        z = z0 + (z0 + z_a) / (1.0 - accel * (z0 + z_a))
        levels.append(nd.cdf(z))
    return levels[0], levels[1]
