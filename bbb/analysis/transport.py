"""Transport of an ensemble: drift velocity v (mm/s), D about the drift (mm²/s), Péclet v S / D.

A tilted or obliquely thrown floor (``Params.tilt``, ``Params.throw``) makes the particles
drift.  The drift is measured over the same lag window as D (:mod:`bbb.analysis.stats`):

* each particle's time-averaged mean displacement m_i(L) = mean over all time origins of
  x[i+L] − x[i] (after the discarded transient), for every fit lag L;
* its own drift v_i = the OLS slope of m_i(L) against L dt over the fit lags (the intercept
  absorbs the short-time ballistic offset, as the MSD fit's c does);
* v = mean of v_i (OLS is linear in the data, so this is also the slope of the ensemble mean
  displacement), with the bootstrap CI over particles of :func:`bbb.analysis.stats.bootstrap_mean`.

D about the drift is today's estimator (time-averaged MSD fit, bootstrap CI over particles)
applied to x − v t with the ensemble v: without the subtraction the MSD grows like v² Δ²
and its fitted "D" is a drift artefact.  v is held fixed within the bootstrap of D; its own
uncertainty shifts the MSD by (δv Δ)², of order D / (N T) · Δ² ≪ 2 D Δ for N particles.

Mirror pairs (``pairing``, :data:`PAIRING`): on a mirror-symmetric floor every particle's
image (bbb.ensemble.mirrored) moves as its reflection, so an ensemble that counts the images
has v = 0 and dv = 0 exactly (odd in x), and every even quantity (D, the MSD slope ratio) is the
particles' own: "mirror symmetry".  With simulated pairs ("pairs": a particle and its partner,
bbb.ensemble.mirror_pairs) every bootstrap resamples pairs (``units``, the pair labels).

What v means on the row, ``v_status`` (:func:`v_status`, in this order):

* "no mover" -- no particle left its cell (:func:`bbb.analysis.moving.displaced`: none got
  farther than S from its position at the start of the analysed part).  The particles rock
  on their arcs or sit still, x changing by rounding at most: v's CI, D about the drift,
  its CI and Pe are NaN (nothing about a drift or a diffusion is measured), ``steady`` and
  ``diffusive`` untested (None); v keeps the sample's mean (rounding-level);
* "by construction" -- mirror symmetry (``pairing``): v = 0 exactly, not an estimate;
* "not measured" -- the halves' drift change dv could not be estimated (NaN), so whether v
  is a drift is unknown: v's CI and Pe are NaN;
* "accelerating" -- ``steady`` is False: the halves' drifts differ beyond the calibrated
  band, so v is no drift.  The row reports the acceleration a = 2 dv / T_a instead (T_a the
  analysed duration; exact for a uniform acceleration x = a t²/2 + ..., whose mean
  displacement over a stretch of length T_h starting at t_s has slope a (t_s + T_h/2), so
  the halves differ by a T_a/2), with dv's paired CI scaled alike.  v is kept: it is the mean
  velocity over the analysed part (for a uniform acceleration exactly the velocity at its
  middle), which places the point on a v(f) curve; its CI and Pe are NaN (a CI over
  particles of a window-dependent number is no drift's CI);
* "ok" -- a steady drift: v with its CI.

Two checks say when the numbers are transport coefficients (rules calibrated on synthetic
ensembles by benchmarks/calibrations/transport_rules.py; their numbers are read from transport_rules.json):

* steady -- False when the paired CI of dv = v(second half) − v(first half) lies beyond
  ±(STEADY_REL |v| + k SE(v) + STEADY_ABS): a change of v larger than 5 % of it and than k
  standard errors of v itself (k from the calibration) is an acceleration, not a drift;
* diffusive -- False when the CI of the MSD's slope ratio -- the slope of the ensemble TAMSD
  of x − v t over the upper half of the fit lags over its slope over the lower half -- lies
  above 1 + the calibrated tolerance: a population of particles running at different speeds
  (some stuck, the rest running) spreads ballistically, MSD ~ σ²Δ², and its "D about the
  drift" is that spread, not a diffusion; a velocity memory as long as the fit lags also
  steepens the MSD there (D_drift is then a window's slope, below the diffusion's).  The
  ratio is 1 for every MSD linear in Δ, whatever its intercept; the log-log exponent of the
  MSD is not (a persistent walk, MSD ≈ 2D(Δ − τ), reads Δ/(Δ − τ) > 1: 1.24 over the fit
  lags for τ = 1 s, although its slope is 2D there).  A ratio below 1 (bounded motion of
  locked particles) is not flagged here.

Positions are ``(n_particles, n_samples)`` in mm at equally spaced times (s), as in bbb.analysis.stats.
Pure numpy; only public bbb.analysis.stats names.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from importlib import resources
from statistics import NormalDist

import numpy as np
from numpy.typing import ArrayLike

from . import stats
from .moving import displaced
from .stats.interval import FAILED, NO_MOVER, OK, DInterval
from .stats.rare import mover_share_bound

__all__ = ["TransportEstimate", "per_particle_drift", "drift_velocity", "drift_change",
           "msd_slope_ratio", "transport", "steady_tolerance", "STEADY_REL", "STEADY_ABS",
           "STEADY_SE", "CURVATURE_TOL", "RULES", "SYMMETRY", "PAIRS", "INDEPENDENT", "PAIRING",
           "V_OK", "ACCELERATING", "NO_MOVER", "BY_CONSTRUCTION", "NOT_MEASURED", "V_STATUSES",
           "v_status", "no_mover_note"]

#: how an estimate counts a family's particles (Study.pairing, the column v_by): images counted
#: by the floor's mirror symmetry (odd quantities such as v are 0 exactly), simulated mirror
#: pairs (resampled as units, bbb.ensemble.mirror_pairs), or independent particles
SYMMETRY, PAIRS, INDEPENDENT = "mirror symmetry", "pairs", "independent"
PAIRING = (SYMMETRY, PAIRS, INDEPENDENT)
#: what v means on a row (module docstring); NO_MOVER is bbb.analysis.stats.interval's word
V_OK, ACCELERATING, BY_CONSTRUCTION, NOT_MEASURED = "ok", "accelerating", "by construction", \
    "not measured"
V_STATUSES = (V_OK, ACCELERATING, NO_MOVER, BY_CONSTRUCTION, NOT_MEASURED)

#: the calibrated rules (benchmarks/calibrations/transport_rules.py wrote them, with their error rates)
RULES: dict = json.loads(resources.files(__package__).joinpath("transport_rules.json")
                         .read_text(encoding="utf-8"))
#: a drift is not steady when the CI of v(second half) − v(first half) lies beyond
#: ±(STEADY_REL |v| + STEADY_SE · SE(v) + STEADY_ABS), SE(v) read off v's CI
STEADY_REL = 0.05
STEADY_ABS = 1e-6  # mm/s: the rounding of an ensemble at rest
STEADY_SE: float = RULES["steady"]["se_factor"]
#: D about the drift is not diffusive when the CI of the MSD's slope ratio lies above 1 + this
CURVATURE_TOL: float = RULES["diffusive"]["tolerance"]


@dataclass(frozen=True)
class TransportEstimate:
    """Drift and diffusion about it.

    v, v_lo, v_hi  -- drift velocity and its bootstrap CI over particles (pairs), mm/s; with
                      v_by = "mirror symmetry" 0, 0, 0 exactly: a property of the ensemble's
                      design, not an estimate
    v_by           -- how the particles were counted (:data:`PAIRING`)
    D, D_lo, D_hi  -- D of x − v t and its bootstrap CI, mm²/s; NaN where the estimator
                      failed (the CI lies below 0: the MSD about the drift falls with the lag)
    D_status       -- "ok", or the failed fit's numbers (bbb.analysis.stats.interval's wording),
                      or the no-mover note (:func:`no_mover_note`)
    Pe             -- Péclet number v S / D (S the scatterer spacing), dimensionless; NaN
                      unless v_status is "ok" or "by construction"
    fit_from, fit_to -- lag window of both fits, s
    dv, dv_lo, dv_hi -- v of the analysed run's second half minus its first half (each fitted
                      over the same fractions of a half), paired bootstrap CI, mm/s
    dv_tol         -- the band the CI of dv must leave to flag, mm/s (:func:`steady_tolerance`)
    steady         -- False when the CI of dv lies beyond ±dv_tol: an acceleration, not a drift
                      (a particle running away downhill has dv ~ a T / 2); None: untested
                      (no mover, or dv not measured)
    a, a_lo, a_hi  -- the acceleration 2 dv / T_a (T_a the analysed duration, s) with dv's CI
                      scaled alike, mm/s² (module docstring); NaN with dv
    v_status       -- what v means (module docstring, :data:`V_STATUSES`)
    n_moving       -- particles that left their cell (:func:`bbb.analysis.moving.displaced`)
    curvature, curvature_lo, curvature_hi -- the slope ratio of the MSD about the drift over
                      the upper / lower half of the fit lags (:func:`msd_slope_ratio`), with
                      its bootstrap CI (NaN: nothing moves)
    diffusive      -- False when curvature_lo > 1 + CURVATURE_TOL (the MSD still steepens over
                      the fit lags); None: untested
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
    steady: bool | None = True
    v_by: str = INDEPENDENT
    dv_tol: float = math.nan
    curvature: float = math.nan
    curvature_lo: float = math.nan
    curvature_hi: float = math.nan
    diffusive: bool | None = None
    D_status: str = OK
    a: float = math.nan
    a_lo: float = math.nan
    a_hi: float = math.nan
    v_status: str = V_OK
    n_moving: int = -1


def _window(xs: np.ndarray, times: np.ndarray, fit: dict) -> tuple[int, int, int, float]:
    """(start, lag_lo, lag_hi, dt) of the fit regime of bbb.analysis.stats.diffusion_coefficient."""
    est = stats.diffusion_coefficient(xs[:1], times, **fit)  # one particle: the regime only
    dt = float(times[1] - times[0])
    start = int(np.searchsorted(times, est.t_start - 1e-9 * dt))
    return start, round(est.fit_from / dt), round(est.fit_to / dt), dt


def per_particle_drift(x: ArrayLike, sample_times: ArrayLike, **fit) -> np.ndarray:
    """Each particle's drift v_i, mm/s, shape (n_particles,) (module docstring); ``fit``:
    ``fit_from``, ``fit_to``, ``discard`` as in :func:`bbb.analysis.stats.diffusion_coefficient`."""
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
                   units: ArrayLike | None = None, **fit) -> stats.BootstrapCI:
    """v, mm/s, with its bootstrap CI over particles, or over ``units`` (mirror-pair labels,
    :func:`bbb.analysis.stats.bootstrap_mean`); unpacks as ``v, lo, hi``."""
    v_i = per_particle_drift(x, sample_times, **fit)
    return stats.bootstrap_mean(v_i, n_resamples=n_resamples, ci=ci, seed=seed, method=method,
                                units=units)


def steady_tolerance(v: float, v_lo: float, v_hi: float, ci: float = 0.95) -> float:
    """The band ±tol (mm/s) the CI of dv must leave to call a drift v [v_lo, v_hi] (its CI at
    level ``ci``) not steady: STEADY_REL |v| + STEADY_SE · SE(v) + STEADY_ABS."""
    se = (v_hi - v_lo) / (2.0 * NormalDist().inv_cdf(0.5 + ci / 2.0))
    return STEADY_REL * abs(v) + STEADY_SE * se + STEADY_ABS


def transport(x: ArrayLike, sample_times: ArrayLike, S: float, *, n_resamples: int,
              ci: float = 0.95, seed: int | np.random.SeedSequence,
              method: str = "percentile", pairing: str = INDEPENDENT,
              units: ArrayLike | None = None, **fit) -> TransportEstimate:
    """v (mm/s), D about the drift (mm²/s), each with a bootstrap CI, Pe = v S / D, and the
    steady and diffusive checks.

    S -- scatterer spacing, mm (the Péclet length);  ``fit``: fit_from, fit_to, discard
    (bbb.analysis.stats.diffusion_coefficient);  ``pairing`` (:data:`PAIRING`) with ``units`` (the pair
    labels, only for "pairs").  The bootstraps use independent child seeds of ``seed``.
    """
    if pairing not in PAIRING:
        raise ValueError(f"pairing = {pairing!r}; allowed: {', '.join(PAIRING)}")
    if (units is not None) != (pairing == PAIRS):
        raise ValueError("units (the pair labels) go with pairing = 'pairs', and only with it")
    ss = seed if isinstance(seed, np.random.SeedSequence) else np.random.SeedSequence(seed)
    s_v, s_d, s_dv, s_a = ss.spawn(4)
    xs = np.atleast_2d(np.asarray(x, dtype=np.float64))
    times = np.asarray(sample_times, dtype=np.float64)
    kw = dict(n_resamples=n_resamples, ci=ci, method=method, units=units)
    if pairing == SYMMETRY:  # every image counted: v and dv are 0 exactly (module docstring)
        v = dv = stats.BootstrapCI(0.0, 0.0, 0.0)
        xd = xs
    else:
        v = drift_velocity(xs, times, seed=s_v, **kw, **fit)
        dv = drift_change(xs, times, seed=s_dv, **kw, **fit)
        xd = xs - v[0] * times[None, :]
    est = stats.diffusion_coefficient(xs[:1], times, **fit)
    n_moving = int(np.count_nonzero(displaced(xs, S, fit.get("discard", stats.DEFAULT_DISCARD))))
    tol = steady_tolerance(*v, ci=ci)
    status = v_status(n_moving, pairing, dv, tol)
    span = times[-1] - est.t_start  # T_a, s: the halves differ by a T_a / 2
    acc = tuple(2.0 * q / span for q in dv)
    common = dict(v=v[0], fit_from=est.fit_from, fit_to=est.fit_to, dv=dv[0], dv_lo=dv[1],
                  dv_hi=dv[2], v_by=pairing, dv_tol=tol, a=acc[0], a_lo=acc[1], a_hi=acc[2],
                  v_status=status, n_moving=n_moving)
    if status == NO_MOVER:  # nothing left its cell: no drift, no diffusion measured
        nan = math.nan
        return TransportEstimate(v_lo=nan, v_hi=nan, D=nan, D_lo=nan, D_hi=nan, Pe=nan,
                                 steady=None, D_status=no_mover_note(xs.shape[0], ci),
                                 **common)
    d = stats.bootstrap_D(xd, times, seed=s_d, **kw, **fit)
    d, d_status = _unless_failed(d, xs.shape[0])
    drift = status in (V_OK, BY_CONSTRUCTION)
    pe = v[0] * S / d.D if d.D > 0 and drift else math.nan
    a = msd_slope_ratio(xd, times, n_resamples=n_resamples, ci=ci, seed=s_a, units=units, **fit)
    return TransportEstimate(v_lo=v[1] if drift else math.nan, v_hi=v[2] if drift else math.nan,
                             D=d.D, D_lo=d.lo, D_hi=d.hi, Pe=pe,
                             steady=None if status == NOT_MEASURED else status != ACCELERATING,
                             curvature=a[0], curvature_lo=a[1], curvature_hi=a[2],
                             diffusive=None if math.isnan(a[1]) else not a[1] > 1.0 + CURVATURE_TOL,
                             D_status=d_status, **common)


def v_status(n_moving: int, pairing: str, dv: tuple[float, float, float], tol: float) -> str:
    """What v means (module docstring): "no mover" where no particle left its cell, "by
    construction" under mirror symmetry, "not measured" where the CI of dv (mm/s) is NaN,
    "accelerating" where it lies beyond ±tol (mm/s, :func:`steady_tolerance`), else "ok"."""
    if n_moving == 0:
        return NO_MOVER
    if pairing == SYMMETRY:
        return BY_CONSTRUCTION
    if math.isnan(dv[1]) or math.isnan(dv[2]):
        return NOT_MEASURED
    return ACCELERATING if (dv[1] > tol or dv[2] < -tol) else V_OK


def no_mover_note(n: int, ci: float = 0.95) -> str:
    """The status of a D (or v) with no particle that left its cell among ``n``: the
    one-sided bound on the share of such particles at level ``ci``."""
    return (f"{NO_MOVER} among {n}: no particle left its cell (moved more than S from its "
            f"start); mover share < {100 * mover_share_bound(n, ci):.2g} % (one-sided)")


def _unless_failed(d: stats.BootstrapCI, n: int) -> tuple[stats.BootstrapCI, str]:
    """(D, lo, hi) and OK, or NaNs and the failure's note where the CI lies below 0 (a D
    significantly below 0 is an estimator failure, never a value with a CI)."""
    if not d.hi < 0.0:
        return d, OK
    note = DInterval(d.D, d.lo, d.hi, FAILED, n, 0.0, math.nan, math.nan).note()
    return stats.BootstrapCI(math.nan, math.nan, math.nan), note


def drift_change(x: ArrayLike, sample_times: ArrayLike, *, n_resamples: int, ci: float = 0.95,
                 seed: int | np.random.SeedSequence, method: str = "percentile",
                 units: ArrayLike | None = None, discard: float = stats.DEFAULT_DISCARD,
                 fit_from: float | None = None, fit_to: float | None = None) -> stats.BootstrapCI:
    """v(second half) − v(first half) of the analysed run, mm/s, with a paired bootstrap CI
    over particles (or ``units``); the lag window of each half is the given one halved
    (fit_from, fit_to in s; None: the default fractions of a half)."""
    xs = np.atleast_2d(np.asarray(x, dtype=np.float64))
    times = np.asarray(sample_times, dtype=np.float64)
    start, _, _, _ = _window(xs, times, dict(discard=discard, fit_from=fit_from, fit_to=fit_to))
    mid = start + (xs.shape[1] - 1 - start) // 2
    half = {"discard": 0.0, "fit_from": None if fit_from is None else fit_from / 2.0,
            "fit_to": None if fit_to is None else fit_to / 2.0}
    v1 = per_particle_drift(xs[:, start : mid + 1], times[start : mid + 1] - times[start], **half)
    v2 = per_particle_drift(xs[:, mid:], times[mid:] - times[mid], **half)
    return stats.bootstrap_mean(v2 - v1, n_resamples=n_resamples, ci=ci, seed=seed,
                                method=method, units=units)


def msd_slope_ratio(x: ArrayLike, sample_times: ArrayLike, *, n_resamples: int,
                    ci: float = 0.95, seed: int | np.random.SeedSequence,
                    units: ArrayLike | None = None, **fit) -> tuple[float, float, float]:
    """(ρ, lo, hi): the slope of the ensemble TAMSD of ``x`` over the upper half of the fit
    lags divided by its slope over the lower half (OLS each, the middle lag in both),
    dimensionless, with a percentile bootstrap CI over particles (or ``units``).  1 for any
    MSD linear in the lag -- whatever its intercept, so a persistent walk's MSD ≈ 2D(Δ − τ)
    passes -- and (b + c)/(a + b) for ballistic spread σ²Δ² over lags [a, c] split at b (1.9
    over the default fit lags).  NaNs when the lower half's slope is below 2 D_FLOOR
    (bbb.analysis.stationarity: nothing moves beyond rounding).  ``fit`` as :func:`per_particle_drift`."""
    from .stationarity import D_FLOOR

    xs = np.atleast_2d(np.asarray(x, dtype=np.float64))
    times = np.asarray(sample_times, dtype=np.float64)
    start, lo, hi, dt = _window(xs, times, fit)
    lags = np.arange(lo, hi + 1)
    nan = (math.nan,) * 3
    if lags.size < 4:
        return nan
    curves = stats.tamsd(xs[:, start:], lags)  # (n_particles, n_lags), mm²
    if units is not None:
        curves = np.stack([stats.unit_means(c, units) for c in curves.T], axis=1)
    h = lags.size // 2
    w = np.zeros((2, lags.size))  # OLS slope weights of the two halves (mm²/s per mm²)
    for k, sl in enumerate((slice(0, h + 1), slice(h, None))):
        t = lags[sl] * dt
        w[k, sl] = (t - t.mean()) / ((t - t.mean()) @ (t - t.mean()))

    def ratio(mean_curves: np.ndarray) -> np.ndarray:  # (m, n_lags) -> (m,)
        s = mean_curves @ w.T
        with np.errstate(divide="ignore", invalid="ignore"):
            return s[:, 1] / s[:, 0]

    mean = curves.mean(axis=0)
    if not (mean @ w[0]) >= 2.0 * D_FLOOR:
        return nan
    rng = np.random.default_rng(seed)
    n = curves.shape[0]
    boot = np.empty(int(n_resamples))
    block = max(1, 4_000_000 // (n * lags.size))
    for b in range(0, boot.size, block):
        m = min(block, boot.size - b)
        boot[b : b + m] = ratio(curves[rng.integers(0, n, size=(m, n))].mean(axis=1))
    a = 1.0 - ci
    q = np.nanquantile(boot, [a / 2, 1 - a / 2])
    return float(ratio(mean[None, :])[0]), float(q[0]), float(q[1])
