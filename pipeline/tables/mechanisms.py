"""The mechanisms table of a store with ``[observables.jumps]`` and/or ``[observables.lyapunov]``:
how much of D is memory, which part makes D differ between neighbouring frequencies, and how
chaotic the motion is.  One row per frequency, the families pooled (as in the diffusion table):

=================  =============================================================================
f, Gamma           floor frequency (Hz), peak floor acceleration
n_jump_particles   particles in the expansion (done chunks)                       [jumps]
D_0, D_1, D_5      the Taylor–Green–Kubo sums D_n per floor period (bbb.analysis.greenkubo), mm²/s, with
                   ``_lo``/``_hi``: bootstrap CI over particles                    [jumps]
D_inf              the converged sum D_∞ = D_{lag − 1} and its CI (the stopping rule re-applied
                   in every resample), mm²/s                                       [jumps]
lag, lag_s         first lag K from which |C(k)| stays in its noise (periods; and K/f in s)
converged          False: |C| never fell into the noise below max_lag (D_inf = D_max_lag)
max_lag            largest lag summed, periods (min(jumps/4, 1000))
n_left_cell        particles whose x at the period ends of the analysed window spans ≥ S: they
                   left their cell (the cusp or arc they sat on)                   [jumps]
D_0_coll, D_1_coll, D_inf_coll (+ _lo, _hi), lag_coll, converged_coll, max_lag_coll
                   the same expansion per collision: jumps x_{n+1} − x_n (mm) between recorded
                   collisions, step τ̄                                             [x_jumps]
tau_coll           τ̄, the mean time between collisions of the jumps used, s
n_coll_jumps       jumps per particle used: the fewest recorded among the particles kept
n_coll_particles, n_coll_excluded  particles kept; left out for recording fewer than half
                   the median number of jumps (a particle held on the floor for long)
f_dn, f_up         the grid neighbours below and above f (Hz; NaN at the ends)
ln_D{s}_{side}     ln D_∞(f)/D_∞(neighbour), s = "" per period or "_coll" per collision, side
                   "dn" or "up", with ``_lo``/``_hi``; and its parts: ``ln_walk`` = ln of the
                   D_0 ratio (random walk), ``ln_mem`` = ln of the (D_∞/D_0) ratio (memory),
                   ``share_mem`` = ln_mem / ln_D (bbb.analysis.gk_contrast: paired bootstrap CIs at the
                   calibrated level, bbb.analysis.gk_contrast.calibrated_rule()["ci"]); NaN where a D_0 or
                   D_∞ replicate is ≤ 0 or either expansion did not converge
lam, lam_lo, lam_hi  largest Lyapunov exponent, 1/s, mean over particles and its CI [lyapunov]
lam_coll, lam_coll_lo, lam_coll_hi  the same per collision
n_lyapunov, n_collapsed  particles measured, and of them those whose separation became 0
                   (left out of the mean)
lam_move, lam_conf (+ _lo, _hi)  λ (1/s) of the moving particles (x at the period ends of λ's
                   window spans ≥ S) and of the confined ones (spans < S: rattling at a cusp or
                   held), with n_lam_move, n_lam_conf                              [lyapunov]
lam{,_move,_conf}_distinct, _tie  distinct per-particle values (equal to 1e-4 relative), and
                   the size of the largest group of equal ones
lam{,_move,_conf}_degenerate  True where that CI is degenerate: fewer than 5 distinct values,
                   or one value shared by more than half of the particles (they sit in one
                   periodic orbit), or a zero-width CI; its ``_lo``/``_hi`` are then NaN
frac_creep         fraction of post-collision states in the creeping band v_y⁺ ≤ 1.1 A 2π f
                   (bbb.analysis.locking), pooled                                           [collisions]
still              True where no particle left its cell (n_left_cell = 0: D is zero at the
                   scene's resolution) or every recorded state creeps (frac_creep = 1)
=================  =============================================================================

The expansions use the jumps after the transient ``[analysis] discard`` (per period: that
fraction of the floor periods, rounded up; per collision: the recording starts at
``[observables.collisions] record_from``): they assume stationary jumps.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..store.study_store import StudyStore
from ..workflow.identity import mechanisms_seed
from ..workflow.observables.jumps import n_periods

__all__ = ["mechanisms_table", "MECHANISM_ORDERS", "DEGENERATE_DISTINCT", "degenerate",
           "distinct_values"]

#: the truncations D_n written as columns (per period; per collision the first two)
MECHANISM_ORDERS = (0, 1, 5)
#: a CI over particles with fewer distinct values than this is degenerate (module docstring)
DEGENERATE_DISTINCT = 5
_SIDES = (("dn", -1), ("up", 1))


def mechanisms_table(store: StudyStore, done: np.ndarray) -> pd.DataFrame:
    """One row per point (columns in the module docstring; a grid's axes follow f); the
    contrasts with the neighbours are along f within each grid line."""
    study = store.study
    obs = study.observables
    lines: dict[tuple, tuple[list, dict]] = {}
    for fi, point in enumerate(study.points):
        f = point.f
        rows, gks = lines.setdefault(point.grid, ([], {"": {}, "_coll": {}}))
        row: dict = {**point.columns(), "Gamma": point.params.gamma}
        seed = mechanisms_seed(study, f)
        if obs.jumps:
            cols, gks[""][f] = _expansion_columns(store, fi, f, done, seed)
            row.update(cols)
        if obs.collisions_x_jumps:
            cols, gks["_coll"][f] = _collision_columns(store, fi, done, seed)
            row.update(cols)
        if obs.lyapunov:
            row.update(_lyapunov_columns(store, fi, done, seed))
        if obs.collisions:
            row["frac_creep"] = _frac_creep(store, fi)
        rows.append(row)
    frames = []
    for rows, gks in lines.values():
        line = pd.DataFrame(rows).sort_values("f", kind="stable").reset_index(drop=True)
        if obs.jumps or obs.collisions_x_jumps:
            line = _with_contrasts(line, gks)
        frames.append(line)
    df = pd.concat(frames, ignore_index=True) if len(frames) > 1 else frames[0]
    if "n_left_cell" in df or "frac_creep" in df:
        still = pd.Series(False, index=df.index)
        if "n_left_cell" in df:
            still |= df["n_left_cell"] == 0
        if "frac_creep" in df:
            still |= df["frac_creep"] >= 1.0
        df["still"] = still
    for col in ("converged", "converged_coll"):
        if col in df:
            df[col] = df[col].astype("boolean")
    return df


def _pooled(store: StudyStore, name: str, fi: int, done: np.ndarray) -> np.ndarray:
    return np.concatenate([store.read_done(name, fi, mi, done[fi, mi])
                           for mi in range(len(store.study.families))])


def _expansion(store: StudyStore, dx: np.ndarray, step, seed: int):
    from bbb.analysis.greenkubo import expansion

    study = store.study
    return expansion(dx, step, n_resamples=study.accuracy.n_resamples, ci=study.analysis.ci,
                     seed=seed)


def _expansion_columns(store: StudyStore, fi: int, f: float, done: np.ndarray,
                       seed: np.random.SeedSequence) -> tuple[dict, object]:
    study = store.study
    P = n_periods(study.accuracy.t_max, f)
    dx = _pooled(store, "jumps", fi, done)[:, :P].astype(np.float64)
    skip = int(math.ceil(study.analysis.discard * P - 1e-9))
    if dx.shape[0] < 2 or P - skip < 8:
        return {"n_jump_particles": dx.shape[0]}, None
    gk = _expansion(store, dx[:, skip:], 1.0 / f, int(seed.generate_state(1)[0]))
    out: dict = {"n_jump_particles": gk.n_particles}
    for n in MECHANISM_ORDERS:
        if n < gk.D_n.size:
            out[f"D_{n}"], out[f"D_{n}_lo"], out[f"D_{n}_hi"] = gk.at(n)
    out.update(D_inf=gk.D_inf, D_inf_lo=gk.D_inf_lo, D_inf_hi=gk.D_inf_hi, lag=gk.lag,
               lag_s=gk.lag / f, converged=gk.converged, max_lag=gk.D_n.size - 1)
    # x at the period ends of the analysed window, relative to its start
    x = np.concatenate([np.zeros((dx.shape[0], 1)), np.cumsum(dx[:, skip:], axis=1)], axis=1)
    out["n_left_cell"] = int(np.count_nonzero(np.ptp(x, axis=1) >= study.params(f).S))
    return out, gk


def _collision_columns(store: StudyStore, fi: int, done: np.ndarray,
                       seed: np.random.SeedSequence) -> tuple[dict, object]:
    dx = _pooled(store, "collision_dx", fi, done).astype(np.float64)
    dt = _pooled(store, "collision_dt", fi, done).astype(np.float64)
    n_valid = np.isfinite(dx).sum(axis=1)  # the valid jumps of a particle come first
    keep = n_valid >= 0.5 * (np.median(n_valid) if n_valid.size else 0)
    out: dict = {"n_coll_particles": int(keep.sum()), "n_coll_excluded": int((~keep).sum())}
    n = int(n_valid[keep].min()) if keep.any() else 0
    out["n_coll_jumps"] = n
    if keep.sum() < 2 or n < 8:
        return out, None
    steps = dt[keep, :n].sum(axis=1) / n
    gk = _expansion(store, dx[keep, :n], steps, int(seed.generate_state(3)[2]))
    for k in MECHANISM_ORDERS[:2]:
        out[f"D_{k}_coll"], out[f"D_{k}_coll_lo"], out[f"D_{k}_coll_hi"] = gk.at(k)
    out.update(D_inf_coll=gk.D_inf, D_inf_coll_lo=gk.D_inf_lo, D_inf_coll_hi=gk.D_inf_hi,
               tau_coll=gk.step, lag_coll=gk.lag, converged_coll=gk.converged,
               max_lag_coll=gk.D_n.size - 1)
    return out, gk


def _with_contrasts(df: pd.DataFrame, gks: dict) -> pd.DataFrame:
    """The log contrasts against the grid neighbours (bbb.analysis.gk_contrast), per step kind."""
    from bbb.analysis.gk_contrast import calibrated_rule, contrast

    level = float(calibrated_rule()["ci"])
    f = df["f"].to_numpy()
    cols: dict[str, list] = {}
    for side, d in _SIDES:
        nb = np.roll(f, -d).astype(float)
        nb[0 if d < 0 else -1] = np.nan
        cols[f"f_{side}"] = list(nb)
        for step, by_f in gks.items():
            if not by_f:
                continue
            for i, fi in enumerate(f):
                a, b = by_f.get(fi), by_f.get(nb[i])
                ok = a is not None and b is not None and a.converged and b.converged
                c = contrast(a, b, level) if ok else None
                for q in ("D", "walk", "mem", "share_mem"):
                    name = f"{'ln_' if q != 'share_mem' else ''}{q}{step}_{side}"
                    attr = {"D": "total", "walk": "walk", "mem": "memory",
                            "share_mem": "share"}[q]
                    v = getattr(c, attr) if c is not None else (math.nan,) * 3
                    for suffix, x in zip(("", "_lo", "_hi"), v, strict=True):
                        cols.setdefault(name + suffix, []).append(x)
    return pd.concat([df, pd.DataFrame(cols, index=df.index)], axis=1)


def _lyapunov_columns(store: StudyStore, fi: int, done: np.ndarray,
                      seed: np.random.SeedSequence) -> dict:
    study = store.study
    lam = _pooled(store, "lyapunov", fi, done)
    per = _pooled(store, "lyapunov_per_collision", fi, done)
    measured = ~np.isnan(lam)
    ok = measured & np.isfinite(lam)
    rng_seed = int(seed.generate_state(2)[1])
    out = {"n_lyapunov": int(measured.sum()), "n_collapsed": int((measured & ~ok).sum())}
    groups = {"lam": ok, "lam_coll": ok}
    if "lyapunov_x_range" in store.group():
        moves = _pooled(store, "lyapunov_x_range", fi, done) >= study.points[fi].params.S
        groups.update(lam_move=ok & moves, lam_conf=ok & ~moves)
        out.update(n_lam_move=int((ok & moves).sum()), n_lam_conf=int((ok & ~moves).sum()))
    for name, sel in groups.items():
        v = (per if name == "lam_coll" else lam)[sel]
        mean, lo, hi = _mean_ci(v, study.accuracy.n_resamples, study.analysis.ci, rng_seed)
        out[name] = mean
        if name == "lam_coll":
            out[f"{name}_lo"], out[f"{name}_hi"] = lo, hi
            continue
        distinct, tie = distinct_values(v)
        bad = degenerate(v, lo, hi)
        out[f"{name}_lo"], out[f"{name}_hi"] = (math.nan, math.nan) if bad else (lo, hi)
        out[f"{name}_distinct"], out[f"{name}_tie"] = distinct, tie
        out[f"{name}_degenerate"] = bool(bad)
    return out


def degenerate(v: np.ndarray, lo: float, hi: float) -> bool:
    """Whether the CI [lo, hi] of the mean of ``v`` is degenerate (module docstring)."""
    distinct, tie = distinct_values(v)
    return v.size > 0 and (distinct < DEGENERATE_DISTINCT or tie > v.size / 2 or not hi > lo)


def distinct_values(v: np.ndarray) -> tuple[int, int]:
    """(distinct values, size of the largest group of equal ones): equal to 4 significant digits
    (1e-4 relative), as the λ of particles held in one periodic orbit are (they differ by what
    their transients left, ~1e-5)."""
    if v.size == 0:
        return 0, 0
    s = np.sort(v)
    new = np.abs(np.diff(s)) > 1e-4 * np.maximum(np.abs(s[1:]), np.abs(s[:-1]))
    starts = np.flatnonzero(np.concatenate([[True], new]))
    sizes = np.diff(np.concatenate([starts, [s.size]]))
    return int(starts.size), int(sizes.max())


def _mean_ci(v: np.ndarray, n_resamples: int, ci: float, seed: int) -> tuple[float, float, float]:
    """Mean and its percentile-bootstrap CI over the entries (NaN when empty)."""
    if v.size == 0:
        return math.nan, math.nan, math.nan
    rng = np.random.default_rng(np.random.SeedSequence(seed))
    boot = v[rng.integers(0, v.size, size=(n_resamples, v.size))].mean(axis=1)
    q = (1.0 - ci) / 2.0
    lo, hi = np.quantile(boot, [q, 1.0 - q])
    return float(v.mean()), float(lo), float(hi)


def _frac_creep(store: StudyStore, fi: int) -> float:
    from bbb.analysis.locking import creep_speed

    from .collisions import states

    p = store.study.points[fi].params
    f = p.f
    v = np.concatenate([states(store, f, fam.name, ("vy",), point=fi)["vy"].ravel()
                        for fam in store.study.families])
    v = v[np.isfinite(v)]
    return float(np.mean(v <= creep_speed(p.A, f))) if v.size else math.nan
