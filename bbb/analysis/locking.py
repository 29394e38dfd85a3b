"""Frequency locking from post-collision states: k = T_p / T_f = 2 v_y⁺ f / g (paper Eq. 7).

The paper reads two numbers off its phase-space plots (y, v_y⁺): the "maximal v_y⁺ of the
spiral" (k ≈ 1.47, 2.5, 3.43, 4.5 at f ≈ 60, 72, 80, 90) and the position of a dense spot
(the 1/1 locking spot at v_y⁺ ≈ 100 near f = 54, the VHO at v_y⁺ ≈ 70 near f = 60); and it
bounds the flight times of the spiral approximation by t_max(f) from the simulated
distribution of collision times.  This module defines all three robustly:

creeping band
    A particle creeping along the floor leaves each collision with about the floor's own
    velocity, |v_y⁺| ≤ A 2π f: the "incomplete ellipses around v_y⁺ = 0".  Points with
    v_y⁺ ≤ v_creep = (1 + CREEP_MARGIN) A 2π f (10 % margin) are the creeping band; everything
    below is computed from the points above it only.
maximal v_y⁺ (:func:`spiral_vmax`)
    The MAX_QUANTILE = 0.99 quantile of v_y⁺ over the points above the creeping band: the top
    of the spiral, insensitive to the rare outliers a plain maximum would pick.
dominant peak (:func:`dominant_peak`)
    The mode of a Gaussian kernel density estimate of v_y⁺ above the creeping band
    (Silverman's bandwidth, evaluated on a fine binned grid).
confidence intervals (:func:`bootstrap_locking`)
    Percentile bootstrap over particles (they are independent; collisions of one particle
    are not): a resample draws particles with replacement and recomputes the maximal v_y⁺
    and the dominant peak from all their states.  The KDE bandwidth is held at the full
    sample's value (the peak's position, not the bandwidth rule, is what is resampled).
t_max(f) (:func:`flight_times`, :func:`flight_time_max`)
    Flight times are differences of consecutive collision times of one particle, kept only
    where the recorded landing height is the free-flight parabola from the previous
    collision (|y₀ + v_y⁺ Δt - g Δt²/2 - y₁| ≤ FLIGHT_TOL = 1e-6 mm): an interval in which the
    particle stuck to the floor and was carried is not a flight.  t_max is the
    TMAX_QUANTILE = 0.99 quantile of the flight times.

Pure numpy.  Units: v in mm/s, A and y in mm, f in Hz, g in mm/s², t in s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .approx import locking_ratio

__all__ = [
    "CREEP_MARGIN",
    "MAX_QUANTILE",
    "TMAX_QUANTILE",
    "FLIGHT_TOL",
    "MIN_POINTS",
    "LockingEstimate",
    "creep_speed",
    "spiral_vmax",
    "dominant_peak",
    "flight_times",
    "flight_time_max",
    "locking_estimate",
    "LockingCI",
    "bootstrap_locking",
]

#: relative margin of the creeping band above the floor's peak speed A 2π f
CREEP_MARGIN = 0.10
#: quantile of v_y⁺ (above the creeping band) taken as the spiral's maximal v_y⁺
MAX_QUANTILE = 0.99
#: quantile of the flight times taken as the upper end t_max(f) of their distribution
TMAX_QUANTILE = 0.99
#: largest miss (mm) of the free-flight parabola for an interval to count as a flight
FLIGHT_TOL = 1e-6
#: fewest points above the creeping band for a quantile or a peak (else NaN)
MIN_POINTS = 20

_F = NDArray[np.float64]


@dataclass(frozen=True)
class LockingEstimate:
    """The locking numbers at one frequency.

    f          -- floor frequency, Hz
    n          -- finite post-collision states given
    n_above    -- of them above the creeping band
    v_creep    -- upper edge of the creeping band, mm/s
    v_max, k_max   -- maximal v_y⁺ of the spiral (mm/s) and its k = 2 v f / g
    v_peak, k_peak -- dominant peak of v_y⁺ above the creeping band (mm/s) and its k
    t_max      -- upper end of the flight-time distribution, s (NaN if not given)
    n_flights  -- flight times that t_max was computed from
    """

    f: float
    n: int
    n_above: int
    v_creep: float
    v_max: float
    k_max: float
    v_peak: float
    k_peak: float
    t_max: float = math.nan
    n_flights: int = 0

    @property
    def frac_creep(self) -> float:
        """Fraction of the post-collision states in the creeping band."""
        return 1.0 - self.n_above / self.n if self.n else math.nan


def creep_speed(A: float, f: float, margin: float = CREEP_MARGIN) -> float:
    """Upper edge of the creeping band, mm/s: (1 + margin) A 2π f."""
    if not (math.isfinite(A) and A >= 0 and math.isfinite(f) and f > 0 and margin >= 0):
        raise ValueError(f"need A ≥ 0 (mm), f > 0 (Hz), margin ≥ 0; got A={A!r}, f={f!r}, "
                         f"margin={margin!r}")
    return (1.0 + margin) * A * 2.0 * math.pi * f


def _above(v: ArrayLike, v_creep: float) -> _F:
    v = np.asarray(v, dtype=np.float64).ravel()
    return v[np.isfinite(v) & (v > v_creep)]


def spiral_vmax(v: ArrayLike, v_creep: float, quantile: float = MAX_QUANTILE,
                min_points: int = MIN_POINTS) -> float:
    """Maximal v_y⁺ of the spiral, mm/s: the ``quantile`` of the v_y⁺ above ``v_creep``.

    NaN if fewer than ``min_points`` values lie above the creeping band.
    """
    if not 0.0 < quantile <= 1.0:
        raise ValueError(f"quantile = {quantile!r}; allowed: 0 < quantile ≤ 1")
    x = _above(v, v_creep)
    return float(np.quantile(x, quantile)) if x.size >= max(min_points, 1) else math.nan


def _silverman(x: _F) -> float:
    sd = float(np.std(x, ddof=1))
    q75, q25 = np.quantile(x, [0.75, 0.25])
    spread = min(sd, (q75 - q25) / 1.349) if q75 > q25 else sd
    return 0.9 * spread * x.size ** -0.2


def dominant_peak(v: ArrayLike, v_creep: float, bandwidth: float | None = None,
                  min_points: int = MIN_POINTS) -> float:
    """Mode of the v_y⁺ distribution above the creeping band, mm/s.

    A Gaussian kernel density estimate (``bandwidth`` in mm/s; default Silverman's rule)
    evaluated on a grid of bandwidth/8 spacing by binning and convolution; the mode is the
    grid point of largest density, refined by a parabola through it and its neighbours.
    NaN if fewer than ``min_points`` values lie above ``v_creep``.
    """
    x = _above(v, v_creep)
    if x.size < max(min_points, 2):
        return math.nan
    h = _silverman(x) if bandwidth is None else float(bandwidth)
    if not (math.isfinite(h) and h > 0):  # all values equal
        return float(np.median(x))
    step = h / 8.0
    lo, hi = x.min() - 4.0 * h, x.max() + 4.0 * h
    n_bins = int(math.ceil((hi - lo) / step))
    counts, edges = np.histogram(x, bins=n_bins, range=(lo, lo + n_bins * step))
    half = int(math.ceil(4.0 * h / step))
    u = np.arange(-half, half + 1) * step
    kernel = np.exp(-0.5 * (u / h) ** 2)
    density = np.convolve(counts.astype(np.float64), kernel, mode="same")
    i = int(np.argmax(density))
    centre = 0.5 * (edges[i] + edges[i + 1])
    if 0 < i < density.size - 1:
        d0, d1, d2 = density[i - 1], density[i], density[i + 1]
        curv = d0 - 2.0 * d1 + d2
        if curv < 0:
            centre += 0.5 * (d0 - d2) / curv * step
    return float(centre)


def _as_rows(a: ArrayLike) -> _F:
    a = np.asarray(a, dtype=np.float64)
    if a.ndim == 1:
        return a[None, :]
    if a.ndim != 2:
        raise ValueError(f"expected (collision,) or (particle, collision) arrays, got shape {a.shape}")
    return a


def flight_times(t: ArrayLike, y: ArrayLike, vy: ArrayLike, g: float,
                 tol: float = FLIGHT_TOL) -> _F:
    """Free-flight times, s, between consecutive recorded collisions of each particle.

    t, y, vy -- post-collision time (s), height (mm) and vertical velocity (mm/s), shaped
                (collision,) for one particle or (particle, collision), NaN-padded at the end
    g        -- gravitational acceleration, mm/s²
    tol      -- an interval counts as a flight only if the parabola from the earlier
                collision lands within ``tol`` mm of the later one's height (a particle that
                stuck to the floor in between does not)
    Returns a 1-D array of the flight times (order: particle by particle).
    """
    t, y, vy = _as_rows(t), _as_rows(y), _as_rows(vy)
    if not (t.shape == y.shape == vy.shape):
        raise ValueError(f"t, y, vy must have the same shape, got {t.shape}, {y.shape}, {vy.shape}")
    if not (math.isfinite(g) and g > 0):
        raise ValueError(f"g = {g!r} must be finite and > 0 (mm/s²)")
    dt = np.diff(t, axis=1)
    landing = y[:, :-1] + vy[:, :-1] * dt - 0.5 * g * dt * dt
    with np.errstate(invalid="ignore"):
        ok = np.isfinite(dt) & (dt > 0) & (np.abs(landing - y[:, 1:]) <= tol)
    return dt[ok]


def flight_time_max(flights: ArrayLike, quantile: float = TMAX_QUANTILE,
                    min_points: int = MIN_POINTS) -> float:
    """Upper end t_max of the flight-time distribution, s: its ``quantile`` (NaN if too few)."""
    if not 0.0 < quantile <= 1.0:
        raise ValueError(f"quantile = {quantile!r}; allowed: 0 < quantile ≤ 1")
    x = np.asarray(flights, dtype=np.float64).ravel()
    x = x[np.isfinite(x)]
    return float(np.quantile(x, quantile)) if x.size >= max(min_points, 1) else math.nan


def locking_estimate(vy: ArrayLike, A: float, f: float, g: float, *,
                     flights: ArrayLike | None = None, margin: float = CREEP_MARGIN,
                     quantile: float = MAX_QUANTILE, t_quantile: float = TMAX_QUANTILE,
                     min_points: int = MIN_POINTS) -> LockingEstimate:
    """All locking numbers at one frequency from its post-collision v_y⁺ (mm/s).

    A (mm), f (Hz), g (mm/s²) set the creeping band and k; ``flights`` (s), if given, the
    flight times for t_max.
    """
    v = np.asarray(vy, dtype=np.float64).ravel()
    v = v[np.isfinite(v)]
    vc = creep_speed(A, f, margin)
    v_max = spiral_vmax(v, vc, quantile, min_points)
    v_peak = dominant_peak(v, vc, min_points=min_points)
    fl = np.zeros(0) if flights is None else np.asarray(flights, dtype=np.float64).ravel()
    return LockingEstimate(
        f=float(f), n=int(v.size), n_above=int(np.count_nonzero(v > vc)), v_creep=vc,
        v_max=v_max, k_max=float(locking_ratio(v_max, f, g)),
        v_peak=v_peak, k_peak=float(locking_ratio(v_peak, f, g)),
        t_max=flight_time_max(fl, t_quantile, min_points) if fl.size else math.nan,
        n_flights=int(np.count_nonzero(np.isfinite(fl))),
    )


@dataclass(frozen=True)
class LockingCI:
    """Bootstrap CIs (over particles) of the locking numbers at one frequency.

    v_max_lo, v_max_hi, v_peak_lo, v_peak_hi -- mm/s;  k_*: the same as k = 2 v f / g.
    NaN where more than half the tail a bound is read from has too few states above the band.
    """

    v_max_lo: float
    v_max_hi: float
    v_peak_lo: float
    v_peak_hi: float
    k_max_lo: float
    k_max_hi: float
    k_peak_lo: float
    k_peak_hi: float


def _kde_modes(counts: _F, step: float, h: float, lo: float) -> _F:
    """Mode (grid centre refined by a parabola) of the Gaussian-smoothed rows of ``counts``."""
    half = int(math.ceil(4.0 * h / step))
    u = np.arange(-half, half + 1) * step
    kernel = np.exp(-0.5 * (u / h) ** 2)
    n = counts.shape[1] + kernel.size - 1
    nfft = 1 << (n - 1).bit_length()
    dens = np.fft.irfft(np.fft.rfft(counts, nfft, axis=1) * np.fft.rfft(kernel, nfft), nfft,
                        axis=1)[:, half:half + counts.shape[1]]
    i = np.argmax(dens, axis=1)
    centre = lo + (i + 0.5) * step
    inner = (i > 0) & (i < dens.shape[1] - 1)
    r = np.arange(dens.shape[0])[inner]
    ii = i[inner]
    d0, d1, d2 = dens[r, ii - 1], dens[r, ii], dens[r, ii + 1]
    curv = d0 - 2.0 * d1 + d2
    shift = np.where(curv < 0, 0.5 * (d0 - d2) / np.where(curv < 0, curv, -1.0) * step, 0.0)
    centre[inner] += shift
    return centre


def bootstrap_locking(vy: ArrayLike, A: float, f: float, g: float, *, n_resamples: int,
                      seed: int | np.random.SeedSequence, ci: float = 0.95,
                      margin: float = CREEP_MARGIN, quantile: float = MAX_QUANTILE,
                      min_points: int = MIN_POINTS) -> LockingCI:
    """Percentile bootstrap CIs over particles of v_max, v_peak (mm/s) and their k.

    vy -- post-collision v_y⁺, mm/s, shape (particle, collision), NaN-padded
    A (mm), f (Hz), g (mm/s²) set the creeping band and k; ``seed`` makes it deterministic.
    """
    if not 0.0 < ci < 1.0:
        raise ValueError(f"ci = {ci!r} must be in (0, 1)")
    if int(n_resamples) != n_resamples or n_resamples < 1:
        raise ValueError(f"n_resamples = {n_resamples!r} must be a positive integer")
    rows = _as_rows(vy)
    vc = creep_speed(A, f, margin)
    nan = LockingCI(*([math.nan] * 8))
    n_p = rows.shape[0]
    above = [_above(r, vc) for r in rows]
    allx = np.concatenate(above) if n_p else np.zeros(0)
    if n_p < 2 or allx.size < max(min_points, 2):
        return nan
    ss = seed if isinstance(seed, np.random.SeedSequence) else np.random.SeedSequence(seed)
    idx = np.random.default_rng(ss).integers(0, n_p, size=(int(n_resamples), n_p))
    w = np.stack([np.bincount(r, minlength=n_p) for r in idx])  # (resample, particle) weights
    sizes = w @ np.array([a.size for a in above])
    ok = sizes >= max(min_points, 2)
    # v_max: the quantile of each resample's states (particles repeated by their weight)
    vmax = np.full(w.shape[0], np.nan)
    for j in np.flatnonzero(ok):
        vmax[j] = np.quantile(np.concatenate([np.repeat(above[p], w[j, p])
                                              for p in np.flatnonzero(w[j])]), quantile)
    # v_peak: per-particle histograms on the full sample's grid, summed with the weights
    h = _silverman(allx)
    vpeak = np.full(w.shape[0], np.nan)
    if math.isfinite(h) and h > 0:
        step = h / 8.0
        lo = allx.min() - 4.0 * h
        n_bins = int(math.ceil((allx.max() + 4.0 * h - lo) / step))
        hist = np.stack([np.histogram(a, bins=n_bins, range=(lo, lo + n_bins * step))[0]
                         for a in above]).astype(np.float64)
        vpeak[ok] = _kde_modes(w[ok] @ hist, step, h, lo)
    a = 1.0 - ci

    def bounds(b: _F) -> tuple[float, float]:
        if np.count_nonzero(~np.isfinite(b)) > 0.5 * a / 2 * b.size:
            return math.nan, math.nan
        lo_, hi_ = np.nanquantile(b, [a / 2, 1 - a / 2])
        return float(lo_), float(hi_)

    (m_lo, m_hi), (p_lo, p_hi) = bounds(vmax), bounds(vpeak)
    k = [float(locking_ratio(v, f, g)) for v in (m_lo, m_hi, p_lo, p_hi)]
    return LockingCI(m_lo, m_hi, p_lo, p_hi, *k)
