"""D, mm²/s, from a least-squares line through the time-averaged MSD, and the fit regime.

D comes from an ordinary least-squares fit ``MSD(Δ) = 2 D Δ + c`` over a linear regime of
lags (see :func:`diffusion_coefficient` for the default regime and why).  Ensemble
quantities weight every particle equally.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .inputs import as_positions, as_times, sample_spacing
from .msd import tamsd_unchecked

__all__ = [
    "DEFAULT_DISCARD",
    "DEFAULT_FIT_FROM",
    "DEFAULT_FIT_TO",
    "DiffusionEstimate",
    "fit_diffusion",
    "first_kept",
    "diffusion_coefficient",
    "per_particle_D",
]

#: Fraction of the run (by duration) dropped at the start as a transient.
DEFAULT_DISCARD = 0.10
#: Default fit regime: lags from this fraction of the analysed duration ...
DEFAULT_FIT_FROM = 0.05
#: ... up to this fraction (inclusive).
DEFAULT_FIT_TO = 0.25

_FLOAT = NDArray[np.float64]


@dataclass(frozen=True)
class DiffusionEstimate:
    """D of an ensemble from the time-averaged MSD.

    D          -- diffusion coefficient, mm²/s: half the slope of the ensemble TAMSD fit
    c          -- intercept of the fit MSD(Δ) = 2 D Δ + c, mm²
    fit_from   -- smallest lag used in the fit, s (an integer multiple of dt)
    fit_to     -- largest lag used in the fit, s (inclusive)
    t_start    -- first sample time kept after discarding the transient, s
    D_last     -- single-origin Einstein estimate ⟨(x(t_end) - x(t_first))²⟩ / (2 (t_end -
                  t_first)) over the whole run (no transient discarded), mm²/s — the
                  paper's Eq. (10) at the last recorded time
    n_particles -- number of trajectories
    n_lags     -- number of lags in the fit
    """

    D: float
    c: float
    fit_from: float
    fit_to: float
    t_start: float
    D_last: float
    n_particles: int
    n_lags: int


def fit_diffusion(
    lags_s: ArrayLike, msd: ArrayLike, lag_range: tuple[float, float]
) -> tuple[float, float]:
    """Least-squares fit of MSD(Δ) = 2 D Δ + c over the lags in ``lag_range``.

    lags_s    -- lags Δ, s, shape (n_lags,)
    msd       -- MSD at those lags, mm², shape (n_lags,)
    lag_range -- (lo, hi) in s; lags with lo ≤ Δ ≤ hi are used (inclusive, up to a
                 relative rounding tolerance of 1e-9 so that L * dt hits its end points)

    Returns ``(D, c)``: D in mm²/s, intercept c in mm².  Unweighted ordinary least
    squares; needs at least two distinct lags in range.
    """
    t = np.asarray(lags_s, dtype=np.float64)
    y = np.asarray(msd, dtype=np.float64)
    if t.ndim != 1 or y.shape != t.shape:
        raise ValueError(
            f"lags_s and msd must be 1-D of equal length, got shapes {t.shape} and {y.shape}"
        )
    lo, hi = (float(v) for v in lag_range)
    if not lo <= hi:
        raise ValueError(f"lag_range = {lag_range!r} must satisfy lo ≤ hi (seconds)")
    eps = 1e-9 * max(abs(lo), abs(hi), 1e-300)
    sel = (t >= lo - eps) & (t <= hi + eps)
    if np.unique(t[sel]).size < 2:
        raise ValueError(
            f"lag_range = ({lo:g}, {hi:g}) s holds {np.unique(t[sel]).size} distinct lag(s); "
            "the fit needs at least 2"
        )
    slope, intercept = _linfit(t[sel], y[sel][None, :])
    return float(slope[0] / 2.0), float(intercept[0])


def _linfit(t: _FLOAT, y: _FLOAT) -> tuple[_FLOAT, _FLOAT]:
    """OLS line y ≈ a t + b for every row of y (shape (n_rows, n_t)); returns (a, b)."""
    tc = t - t.mean()
    ym = y.mean(axis=1)
    slope = (y - ym[:, None]) @ tc / (tc @ tc)
    return slope, ym - slope * t.mean()


@dataclass(frozen=True)
class FitRegime:
    """Samples and lags analysed: x[:, start:] with fit lags L_lo..L_hi (inclusive)."""

    start: int
    dt: float
    lag_lo: int
    lag_hi: int

    @property
    def lags(self) -> NDArray[np.int64]:
        return np.arange(self.lag_lo, self.lag_hi + 1, dtype=np.int64)


def first_kept(n_samples: int, discard: float) -> int:
    """Index of the first sample kept after dropping the fraction ``discard`` of a run of
    ``n_samples`` samples as a transient (rounded up, within rounding of the fraction)."""
    return math.ceil(discard * (n_samples - 1) - 1e-9)


def fit_regime(
    n_samples: int,
    sample_times: _FLOAT,
    fit_from: float | None,
    fit_to: float | None,
    discard: float,
) -> FitRegime:
    """The regime :func:`diffusion_coefficient` fits (arguments as there, sample_times already
    checked): the samples kept after ``discard`` and the fit lags; raises where it is empty."""
    dt = sample_spacing(sample_times, n_samples)
    if not (math.isfinite(discard) and 0.0 <= discard < 1.0):
        raise ValueError(f"discard = {discard!r} must be a fraction of the run in [0, 1)")
    start = first_kept(n_samples, discard)
    n_kept = n_samples - start
    duration = (n_kept - 1) * dt
    lo = DEFAULT_FIT_FROM * duration if fit_from is None else float(fit_from)
    hi = DEFAULT_FIT_TO * duration if fit_to is None else float(fit_to)
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 <= lo <= hi):
        raise ValueError(f"fit range ({lo!r}, {hi!r}) s must satisfy 0 ≤ fit_from ≤ fit_to")
    lag_lo = max(0, math.ceil(lo / dt - 1e-9))
    lag_hi = math.floor(hi / dt + 1e-9)
    if lag_hi > n_kept - 1:
        raise ValueError(
            f"fit_to = {hi:g} s exceeds the analysed duration {duration:g} s "
            f"(run after discarding the first {discard:.0%})"
        )
    if lag_hi - lag_lo < 1:
        raise ValueError(
            f"fit range [{lo:g}, {hi:g}] s holds {max(0, lag_hi - lag_lo + 1)} lag(s) of "
            f"dt = {dt:g} s; the fit needs at least 2 — record more samples or widen the range"
        )
    return FitRegime(start=start, dt=dt, lag_lo=lag_lo, lag_hi=lag_hi)


def per_particle_fit(x: _FLOAT, reg: FitRegime) -> tuple[_FLOAT, _FLOAT]:
    """Per-particle (D_i, c_i) from each trajectory's own TAMSD over the fit lags.

    OLS is linear in the data, so the fit of the particle-mean TAMSD is exactly the
    particle mean of these: D = mean(D_i), c = mean(c_i).
    """
    lags = reg.lags
    curves = tamsd_unchecked(x[:, reg.start :], lags)
    slope, intercept = _linfit(lags * reg.dt, curves)
    return slope / 2.0, intercept


def diffusion_coefficient(
    x: ArrayLike,
    sample_times: ArrayLike,
    *,
    fit_from: float | None = None,
    fit_to: float | None = None,
    discard: float = DEFAULT_DISCARD,
) -> DiffusionEstimate:
    """D, mm²/s, from a linear fit to the ensemble time-averaged MSD.

    x            -- positions, mm, shape (n_particles, n_samples)
    sample_times -- equally spaced sample times, s, shape (n_samples,)
    fit_from, fit_to -- lag range of the fit, s (inclusive); default 5 % and 25 % of the
                    analysed duration T = t_end - t_start
    discard      -- fraction of the run duration dropped at the start as a transient
                    (default 0.10): samples before t_first + discard (t_end - t_first)
                    are not used for the TAMSD

    Default regime, and why: the first 10 % of the run is dropped so that particles
    forget their initial-condition family (settling onto an attractor, leaving a creeping
    start); the fit then uses every lag Δ with 0.05 T ≤ Δ ≤ 0.25 T.  The lower end sits
    well above the ballistic/correlated short-time regime (flights and collisions last
    ~1/f ≈ 0.02 s, while runs are many seconds), whose offset the intercept c absorbs.
    The upper end keeps at least T/Δ ≥ 4 independent windows per trajectory: the relative
    variance of a single TAMSD grows like 4/3 · Δ/T (Brownian motion), so lags beyond
    ~T/4 are few-window, noisy and strongly correlated, and would only add noise.

    Returns a :class:`DiffusionEstimate` (also holding D_last, the paper's single-origin
    MSD(t)/(2t) at the last time over the whole run).
    """
    xs = as_positions(x)
    times = as_times(sample_times, xs.shape[1])
    reg = fit_regime(xs.shape[1], times, fit_from, fit_to, discard)
    d_i, c_i = per_particle_fit(xs, reg)
    disp = xs[:, -1] - xs[:, 0]
    d_last = float(np.mean(disp * disp) / (2.0 * (times[-1] - times[0])))
    return DiffusionEstimate(
        D=float(d_i.mean()),
        c=float(c_i.mean()),
        fit_from=reg.lag_lo * reg.dt,
        fit_to=reg.lag_hi * reg.dt,
        t_start=float(times[reg.start]),
        D_last=d_last,
        n_particles=xs.shape[0],
        n_lags=reg.lag_hi - reg.lag_lo + 1,
    )


def per_particle_D(
    x: ArrayLike,
    sample_times: ArrayLike,
    *,
    fit_from: float | None = None,
    fit_to: float | None = None,
    discard: float = DEFAULT_DISCARD,
) -> _FLOAT:
    """Each particle's own D_i, mm²/s, shape (n_particles,): half the OLS slope of its TAMSD
    over the fit lags of :func:`diffusion_coefficient` (same arguments).  The ensemble D is
    their mean; the bootstrap resamples them."""
    xs = as_positions(x)
    times = as_times(sample_times, xs.shape[1])
    return per_particle_fit(xs, fit_regime(xs.shape[1], times, fit_from, fit_to, discard))[0]
