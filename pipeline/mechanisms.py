"""The mechanisms table of a store with ``[observables.jumps]`` and/or ``[observables.lyapunov]``:
how much of D is memory, and how chaotic the motion is.  One row per frequency, the
families pooled (as in the diffusion table):

=================  =============================================================================
f, Gamma           floor frequency (Hz), peak floor acceleration
n_jump_particles   particles in the expansion (done chunks)                       [jumps]
D_0, D_1, D_5      the Taylor–Green–Kubo sums D_n per floor period (bbb.greenkubo), mm²/s, with
                   ``_lo``/``_hi``: bootstrap CI over particles                    [jumps]
D_inf              the converged sum D_∞ = D_{lag − 1} and its CI (the stopping rule re-applied
                   in every resample), mm²/s                                       [jumps]
lag, lag_s         first lag K from which |C(k)| stays in its noise (periods; and K/f in s)
converged          False: |C| never fell into the noise below max_lag (D_inf = D_max_lag)
max_lag            largest lag summed, periods (min(jumps/4, 1000))
lam, lam_lo, lam_hi  largest Lyapunov exponent, 1/s, mean over particles and its CI [lyapunov]
lam_coll, lam_coll_lo, lam_coll_hi  the same per collision
n_lyapunov, n_collapsed  particles measured, and of them those whose separation became 0
                   (left out of the mean)
frac_creep         fraction of post-collision states in the creeping band v_y⁺ ≤ 1.1 A 2π f
                   (bbb.locking), pooled                                           [collisions]
=================  =============================================================================

The expansion uses the jumps after the transient ``[analysis] discard`` (a fraction of the
floor periods, rounded up): it assumes stationary jumps.
"""

from __future__ import annotations

import math
import zlib

import numpy as np
import pandas as pd

from .store import StudyStore
from .store_layout import n_periods

__all__ = ["mechanisms_table", "MECHANISM_ORDERS"]

#: the truncations D_n written as columns
MECHANISM_ORDERS = (0, 1, 5)


def mechanisms_table(store: StudyStore, done: np.ndarray) -> pd.DataFrame:
    """One row per frequency (columns in the module docstring)."""
    study = store.study
    obs = study.observables
    rows = []
    for fi, f in enumerate(study.frequencies):
        row: dict = {"f": f, "Gamma": study.params(f).gamma}
        seed = np.random.SeedSequence(study.seed, spawn_key=(round(f * 1000),
                                                             zlib.crc32(b"mechanisms")))
        if obs.jumps:
            row.update(_expansion_columns(store, fi, f, done, seed))
        if obs.lyapunov:
            row.update(_lyapunov_columns(store, fi, done, seed))
        if obs.collisions:
            row["frac_creep"] = _frac_creep(store, f)
        rows.append(row)
    df = pd.DataFrame(rows)
    if "converged" in df:
        df["converged"] = df["converged"].astype("boolean")
    return df


def _pooled(store: StudyStore, name: str, fi: int, done: np.ndarray) -> np.ndarray:
    return np.concatenate([store.read_done(name, fi, mi, done[fi, mi])
                           for mi in range(len(store.study.families))])


def _expansion_columns(store: StudyStore, fi: int, f: float, done: np.ndarray,
                       seed: np.random.SeedSequence) -> dict:
    from bbb.greenkubo import expansion

    study = store.study
    P = n_periods(study.accuracy.t_max, f)
    dx = _pooled(store, "jumps", fi, done)[:, :P].astype(np.float64)
    skip = int(math.ceil(study.analysis.discard * P - 1e-9))
    if dx.shape[0] < 2 or P - skip < 8:
        return {"n_jump_particles": dx.shape[0]}
    gk = expansion(dx[:, skip:], 1.0 / f, n_resamples=study.accuracy.n_resamples,
                   ci=study.analysis.ci, seed=int(seed.generate_state(1)[0]))
    out: dict = {"n_jump_particles": gk.n_particles}
    for n in MECHANISM_ORDERS:
        if n < gk.D_n.size:
            out[f"D_{n}"], out[f"D_{n}_lo"], out[f"D_{n}_hi"] = gk.at(n)
    out.update(D_inf=gk.D_inf, D_inf_lo=gk.D_inf_lo, D_inf_hi=gk.D_inf_hi, lag=gk.lag,
               lag_s=gk.lag / f, converged=gk.converged, max_lag=gk.D_n.size - 1)
    return out


def _lyapunov_columns(store: StudyStore, fi: int, done: np.ndarray,
                      seed: np.random.SeedSequence) -> dict:
    study = store.study
    lam = _pooled(store, "lyapunov", fi, done)
    per = _pooled(store, "lyapunov_per_collision", fi, done)
    measured = ~np.isnan(lam)
    ok = measured & np.isfinite(lam)
    rng_seed = int(seed.generate_state(2)[1])
    out = {"n_lyapunov": int(measured.sum()), "n_collapsed": int((measured & ~ok).sum())}
    for name, v in (("lam", lam[ok]), ("lam_coll", per[ok])):
        out[name], out[f"{name}_lo"], out[f"{name}_hi"] = _mean_ci(
            v, study.accuracy.n_resamples, study.analysis.ci, rng_seed)
    return out


def _mean_ci(v: np.ndarray, n_resamples: int, ci: float, seed: int) -> tuple[float, float, float]:
    """Mean and its percentile-bootstrap CI over the entries (NaN when empty)."""
    if v.size == 0:
        return math.nan, math.nan, math.nan
    rng = np.random.default_rng(np.random.SeedSequence(seed))
    boot = v[rng.integers(0, v.size, size=(n_resamples, v.size))].mean(axis=1)
    q = (1.0 - ci) / 2.0
    lo, hi = np.quantile(boot, [q, 1.0 - q])
    return float(v.mean()), float(lo), float(hi)


def _frac_creep(store: StudyStore, f: float) -> float:
    from bbb.locking import creep_speed

    from .collisions import states

    p = store.study.params(f)
    v = np.concatenate([states(store, f, fam.name, ("vy",))["vy"].ravel()
                        for fam in store.study.families])
    v = v[np.isfinite(v)]
    return float(np.mean(v <= creep_speed(p.A, f))) if v.size else math.nan
