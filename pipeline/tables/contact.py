"""The contact table of a store with ``[observables.contact]``: per (frequency, family) the
fraction of the run a particle spends held at rest on the floor and sliding on an arc.

``contact.parquet`` / ``contact.csv``, one row per (frequency, family):

f, family, initial   frequency (Hz), family name and kind
n_particles          particles of done chunks
held_frac, held_frac_lo, held_frac_hi     mean over particles of held_time / t_max, with its
                     percentile bootstrap CI over particles (the study's ``n_resamples`` and
                     ``ci``)
slide_frac, slide_frac_lo, slide_frac_hi  the same for sliding_time (0 under ``stick``)
contact_frac         held_frac + slide_frac

The fractions are of the whole run (0 to t_max), transient included: they say where the
particles are, not only how they move once stationary.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..store.study_store import StudyStore
from ..workflow.identity import table_seed

__all__ = ["contact_table", "bootstrap_mean", "FRACTIONS"]

#: table column -> stored array of per-particle times (s)
FRACTIONS = {"held_frac": "held_time", "slide_frac": "sliding_time"}


def bootstrap_mean(x: np.ndarray, n_resamples: int, ci: float,
                   seed: np.random.SeedSequence) -> tuple[float, float, float]:
    """(mean, lo, hi) of ``x`` with the percentile bootstrap CI at level ``ci`` over its
    entries, ``n_resamples`` resamples; NaNs with no entries, the mean twice with one."""
    x = np.asarray(x, dtype=np.float64)
    if x.size == 0:
        return math.nan, math.nan, math.nan
    m = float(x.mean())
    if x.size == 1:
        return m, m, m
    rng = np.random.default_rng(seed)
    means = np.empty(n_resamples)
    block = max(1, 2**22 // x.size)  # at most ~4e6 indices in memory at once
    for s in range(0, n_resamples, block):
        k = min(block, n_resamples - s)
        means[s:s + k] = x[rng.integers(0, x.size, size=(k, x.size))].mean(axis=1)
    lo, hi = np.quantile(means, [(1 - ci) / 2, (1 + ci) / 2])
    return m, float(min(lo, m)), float(max(hi, m))


def contact_table(store: StudyStore, done: np.ndarray) -> pd.DataFrame:
    """One row per (point, family) (columns in the module docstring)."""
    study = store.study
    acc, an = study.accuracy, study.analysis
    rows = []
    for fi, point in enumerate(study.points):
        f = point.f
        for mi, fam in enumerate(study.families):
            row: dict = {**point.columns(), "family": fam.name, "initial": fam.initial}
            times = {col: store.read_done(arr, fi, mi, done[fi, mi])
                     for col, arr in FRACTIONS.items()}
            row["n_particles"] = len(times["held_frac"])
            for col, t in times.items():
                seed = table_seed(study, f, fam, col)
                m, lo, hi = bootstrap_mean(t / acc.t_max, acc.n_resamples, an.ci, seed)
                row.update({col: m, f"{col}_lo": lo, f"{col}_hi": hi})
            row["contact_frac"] = row["held_frac"] + row["slide_frac"]
            rows.append(row)
    return pd.DataFrame(rows)
