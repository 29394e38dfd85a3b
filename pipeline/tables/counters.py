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

from ..store.study_store import StudyStore
from ..workflow.observables.counters import COUNTERS

__all__ = ["counters_table"]


def counters_table(store: StudyStore, done: np.ndarray) -> pd.DataFrame:
    """One row per (point, family): counters per particle per second, task wall time."""
    study = store.study
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
            seconds = store.read_done("chunk_seconds", fi, mi, done[fi, mi])
            row["task_seconds"] = float(np.nansum(seconds)) if seconds.size else 0.0
            rows.append(row)
    return pd.DataFrame(rows)

