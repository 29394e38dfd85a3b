"""Impacts: the floor phase at the collisions and the horizontal velocity's memory across them.

Per particle, over its first ``[observables.impacts] collisions`` recorded collisions (from
``[observables.collisions] record_from`` when that table is given, else from t = 0):

- ``impact_phase_counts``: how many fell in each of :data:`BINS` equal bins of the floor
  phase ω t mod 2π (bbb.record's ``phase`` field, f t_floor mod 1, times 2π); the floor is at
  −A sin(ω t) there, so it moves up for ω t mod 2π in (π/2, 3π/2): bins 6 … 17;
- ``impact_vx_moments``: for each lag ℓ = 1 … ``lags``, the sums over the pairs (a, b) =
  (vx after collision i, vx after collision i + ℓ): (n, Σa, Σb, Σa², Σb², Σab), mm/s and
  their squares.

Both are sums, so the (point, family) table adds them over every done particle and the
pooled statistics are exact functions of them: the share of impacts in the upward half of
the period, the Pearson correlation of the pooled pairs at each lag and the correlation about
each particle's own means (``vx_within``: the memory within a trajectory, which differences
between the particles' mean vx do not enter), each with a percentile
bootstrap interval over particles (independent by construction; ``[analysis] ci``,
``[accuracy] n_resamples``).  A statistic that cannot be measured (no impacts, no pairs, no
variance) is blank and ``impacts_status`` says why; an interval of zero width is blank too.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from bbb.record import COLLISION_FIELDS

from ..identity import table_seed
from ..schema import key
from .contract import Array, Chunk, Coord, Observable

__all__ = ["Impacts", "ImpactsTable", "BINS", "MOMENTS", "UP_BINS"]

#: equal bins of the floor phase ω t mod 2π over one period (15° each)
BINS = 24
#: the bins in which the floor moves up (ω t mod 2π in (π/2, 3π/2)): 6 … 17
UP_BINS = slice(BINS // 4, 3 * BINS // 4)
#: the sums kept per lag, in storage order, and their units
MOMENTS = ("n", "sum_a", "sum_b", "sum_aa", "sum_bb", "sum_ab")
MOMENT_UNITS = ("1", "mm/s", "mm/s", "mm^2/s^2", "mm^2/s^2", "mm^2/s^2")
_VX, _PHASE = COLLISION_FIELDS.index("vx"), COLLISION_FIELDS.index("phase")


@dataclass(frozen=True)
class ImpactsTable:
    collisions: int = key(1000, "collisions per particle whose floor phase and vx are used "
                          "(from [observables.collisions] record_from, else from t = 0)",
                          units="collisions per particle", ge=2, le=1e6)
    lags: int = key(5, "largest lag (in collisions) of the vx correlation", ge=1, le=100,
                    note="below collisions")


class Impacts(Observable):
    name = "impacts"
    doc = ("floor phase at the collisions (24 bins of ω t mod 2π) and the correlation of the "
           "post-collision vx across 1 … lags collisions")
    scene = ImpactsTable
    when = "stores with `[observables.impacts]`"
    columns = (
        ("n_particles", False, "1", "particles of done chunks"),
        ("n_impacts", False, "1", "collisions counted, pooled over the particles"),
        ("up_share", True, "1", "share of them while the floor moves up (ω t mod 2π in "
         "(π/2, 3π/2))"),
        ("phase_<n>", False, "1", "share of them with ω t mod 2π in [2π n/24, 2π (n+1)/24)"),
        ("vx_corr_<n>", True, "1", "Pearson correlation of the post-collision vx n "
         "collisions apart, pooled pairs (differences between the particles' mean vx count)"),
        ("vx_within_<n>", True, "1", "the same about each particle's own means (covariances "
         "and variances summed over the particles): the memory within a trajectory"),
        ("impacts_status", False, "", "why a blank statistic is blank (empty: all measured)"),
    )

    def _lags(self, study) -> int:
        return int(self.settings(study.observables)["lags"])

    def rows(self, study) -> int:
        return int(self.settings(study.observables)["collisions"])

    def coords(self, study):
        return (Coord("impact_phase_bin", np.arange(BINS), "int64", "",
                      f"floor phase bin b: ω t mod 2π in [2π b/{BINS}, 2π (b+1)/{BINS})"),
                Coord("impact_lag", np.arange(1, self._lags(study) + 1), "int64", "",
                      "lag in collisions"),
                Coord("impact_moment", list(MOMENTS), str, ", ".join(MOMENT_UNITS),
                      "sum over the pairs (a, b) = (vx after collision i, after i + lag)"))

    def arrays(self, study):
        k = self._lags(study)
        return (Array("impact_phase_counts", (("impact_phase_bin", BINS),), "int64", 0, "1",
                      "collisions per floor phase bin"),
                Array("impact_vx_moments", (("impact_lag", k), ("impact_moment", len(MOMENTS))),
                      "float64", np.nan, ", ".join(MOMENT_UNITS),
                      "sums over the pairs of post-collision vx a lag apart"))

    def compute(self, chunk: Chunk):
        R, k = self.rows(chunk.study), self._lags(chunk.study)
        rec = chunk.run.collisions_dense[:, :R]
        n = np.minimum(chunk.run.n_recorded, R)
        return {"impact_phase_counts": phase_counts(rec[..., _PHASE], n),
                "impact_vx_moments": pair_moments(rec[..., _VX], n, k)}

    def table(self, store, done):
        import pandas as pd

        study = store.study
        rows = []
        for fi, point in enumerate(study.points):
            for mi, fam in enumerate(study.families):
                counts = store.read_done("impact_phase_counts", fi, mi, done[fi, mi])
                moments = store.read_done("impact_vx_moments", fi, mi, done[fi, mi])
                rng = np.random.default_rng(table_seed(study, point.f, fam.name, self.name))
                rows.append({**point.columns(), "family": fam.name, "initial": fam.initial,
                             **impact_row(counts, moments, rng, study.accuracy.n_resamples,
                                          study.analysis.ci)})
        return pd.DataFrame(rows)


def phase_counts(phase: np.ndarray, n: np.ndarray) -> np.ndarray:
    """Collisions per phase bin, per particle: ``phase`` (particle, row), f t mod 1; the first
    ``n`` rows of each particle count.  int64 (particle, BINS)."""
    valid = np.arange(phase.shape[1]) < n[:, None]
    b = np.minimum((np.where(valid, phase, 0.0) * BINS).astype(np.int64), BINS - 1)
    flat = np.arange(phase.shape[0])[:, None] * BINS + b
    return np.bincount(flat[valid], minlength=phase.shape[0] * BINS).reshape(-1, BINS)


def pair_moments(vx: np.ndarray, n: np.ndarray, lags: int) -> np.ndarray:
    """Per particle and lag ℓ = 1 … lags, the sums (n, Σa, Σb, Σa², Σb², Σab) over the pairs
    (a, b) = (vx[i], vx[i + ℓ]) with i + ℓ < n: float64 (particle, lags, 6)."""
    out = np.zeros((vx.shape[0], lags, len(MOMENTS)))
    valid = np.arange(vx.shape[1]) < n[:, None]
    for j, lag in enumerate(range(1, lags + 1)):
        ok = valid[:, lag:]  # b valid implies a valid (the valid rows are a prefix)
        a = np.where(ok, vx[:, :-lag], 0.0) if lag < vx.shape[1] else np.zeros((vx.shape[0], 0))
        b = np.where(ok, vx[:, lag:], 0.0)
        out[:, j] = np.stack([ok.sum(axis=1), a.sum(1), b.sum(1), (a * a).sum(1),
                              (b * b).sum(1), (a * b).sum(1)], axis=1)
    return out


def pearson(m: np.ndarray) -> np.ndarray:
    """The Pearson correlation of pooled pairs from their sums (..., 6) (NaN: fewer than two
    pairs or no variance)."""
    n, sa, sb, saa, sbb, sab = np.moveaxis(m, -1, 0)
    with np.errstate(invalid="ignore", divide="ignore"):
        cov = sab - sa * sb / n
        va, vb = saa - sa * sa / n, sbb - sb * sb / n
        r = cov / np.sqrt(va * vb)
    return np.where((n >= 2) & (va > 0) & (vb > 0), r, np.nan)


def centred(m: np.ndarray) -> np.ndarray:
    """Each particle's pair sums about its own means, from its sums m (particle, lags, 6):
    (cov, var_a, var_b) = (Σab − Σa Σb / n, Σa² − (Σa)² / n, Σb² − (Σb)² / n), 0 without a
    pair: float64 (3, particle, lags).  A particle counted k times has k times each."""
    n, sa, sb, saa, sbb, sab = np.moveaxis(m, -1, 0)
    with np.errstate(invalid="ignore", divide="ignore"):
        out = np.stack([sab - sa * sb / n, saa - sa * sa / n, sbb - sb * sb / n])
    return np.where(n > 0, out, 0.0)


def within(c: np.ndarray) -> np.ndarray:
    """The correlation about each particle's own means from summed centred sums c (3, ...):
    Σ cov / sqrt(Σ var_a Σ var_b) (NaN: no variance)."""
    cov, va, vb = c
    with np.errstate(invalid="ignore", divide="ignore"):
        r = cov / np.sqrt(va * vb)
    return np.where((va > 0) & (vb > 0), r, np.nan)


def impact_row(counts: np.ndarray, moments: np.ndarray, rng: np.random.Generator,
               n_resamples: int, ci: float) -> dict:
    """The table's columns of one (point, family) from its particles' sums: counts
    (particle, BINS), moments (particle, lags, 6)."""
    P, lags = counts.shape[0], moments.shape[1]
    total = counts.sum(axis=0)
    n = int(total.sum())
    row: dict = {"n_particles": P, "n_impacts": n}
    why = []
    share = total / n if n else np.full(BINS, np.nan)
    row["up_share"] = float(share[UP_BINS].sum()) if n else np.nan
    corr = pearson(moments.sum(axis=0)) if P else np.full(lags, np.nan)
    # the bootstrap over particles: the same resamples for every statistic
    w = rng.multinomial(P, np.full(P, 1.0 / P), size=n_resamples) if P else None
    q = (1 - ci) / 2
    if n:
        up = w @ counts[:, UP_BINS].sum(axis=1) / np.maximum(w @ counts.sum(axis=1), 1)
        row["up_share_lo"], row["up_share_hi"] = _bounds(up, q, "up_share", why)
    else:
        row["up_share_lo"] = row["up_share_hi"] = np.nan
        why.append("no impacts")
    for b in range(BINS):
        row[f"phase_{b}"] = float(share[b])
    boot = pearson(np.einsum("rp,plm->rlm", w, moments)) if P else None
    _lagged(row, "vx_corr", corr, boot, q, why)
    c = centred(moments)
    mine = within(c.sum(axis=1)) if P else np.full(lags, np.nan)
    boot_w = within(np.einsum("rp,cpl->crl", w, c)) if P else None
    _lagged(row, "vx_within", mine, boot_w, q, why)
    row["impacts_status"] = "; ".join(why)
    return row


def _lagged(row: dict, name: str, values: np.ndarray, boot: np.ndarray | None, q: float,
            why: list[str]) -> None:
    """Columns ``<name>_<lag>`` (+ CI) for lags 1, 2, …: blank and said where not measured."""
    for j, v in enumerate(values):
        col = f"{name}_{j + 1}"
        row[col] = float(v)
        if np.isnan(v):
            row[f"{col}_lo"] = row[f"{col}_hi"] = np.nan
            why.append(f"{col}: fewer than two pairs or no variance")
            continue
        row[f"{col}_lo"], row[f"{col}_hi"] = _bounds(boot[:, j], q, col, why)


def _bounds(values: np.ndarray, q: float, name: str, why: list[str]) -> tuple[float, float]:
    """The percentile interval of bootstrap ``values``; blank (and said) when some resample
    could not measure it or when it has zero width."""
    if np.isnan(values).any():
        why.append(f"{name}: interval not measured (a resample without pairs or variance)")
        return np.nan, np.nan
    lo, hi = np.quantile(values, [q, 1 - q])
    if not hi > lo:
        why.append(f"{name}: interval of zero width")
        return np.nan, np.nan
    return float(lo), float(hi)
