"""The counters table of every store: one row per (frequency, family).

``counters.parquet`` / ``counters.csv`` (every store), one row per (frequency, family):
collisions, sticks, liftoffs (and any other bbb counter) per particle per second, and the
summed simulation time of its chunks (s, from chunk_seconds).

Units of every column: :mod:`pipeline.tables.units`.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..store.layout import COUNTERS
from ..store.study_store import StudyStore

__all__ = ["counters_table"]


def counters_table(store: StudyStore, done: np.ndarray) -> pd.DataFrame:
    """One row per (point, family): counters per particle per second, task wall time."""
    study = store.study
    seconds = store.group()["chunk_seconds"]
    rows = []
    for fi, point in enumerate(study.points):
        for mi, fam in enumerate(study.families):
            counts = {name: store.read_done(f"n_{name}", fi, mi, done[fi, mi])
                      for name in COUNTERS}
            n = len(counts[COUNTERS[0]])
            row = {**point.columns(), "family": fam.name, "initial": fam.initial, "n_particles": n,
                   "t_max": study.accuracy.t_max}
            for name, arr in counts.items():
                per = arr / study.accuracy.t_max
                row[f"{name}_per_s"] = float(per.mean()) if n else math.nan
            row["task_seconds"] = _done_seconds(seconds, fi, mi, done[fi, mi])
            rows.append(row)
    return pd.DataFrame(rows)


def _done_seconds(seconds, fi: int, mi: int, done_fm: np.ndarray) -> float:
    """Summed chunk_seconds of the done chunks of (fi, mi), s.  Reads only from the first to
    the last done chunk: an adaptive store leaves most of its chunk axis unused, and reading
    all of it (one file per chunk) took longer than the counters themselves."""
    idx = np.flatnonzero(done_fm)
    if idx.size == 0:
        return 0.0
    part = np.asarray(seconds[fi, mi, idx[0]:idx[-1] + 1])
    return float(np.nansum(part[idx - idx[0]]))
