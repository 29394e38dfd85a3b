"""The states the particles end in at the ends of the ratchet's current reversals, from the
scene ``scenes/ratchet_states.toml`` (every collision recorded from t = 0) and the state
classifier :mod:`bbb.analysis.states` (its thresholds calibrated on known cases,
bbb/analysis/states_rule.json): each particle's run cut into windows of :data:`WINDOW` s,
each window labelled unknown, stuck (held or creeping), locked_1 (one bounce per floor
period, repeating), locked_k (a cycle of k collisions over several periods), chaotic (in one
cell) or diffusing (crossing a cell edge); a locked state repeats its offset within the cell,
so a particle that walks one tooth per cycle is locked.  Per point (α, p, f) the share of the
particles in each state at the run's end (the last window's label,
:func:`bbb.analysis.states.final_state`) with a Wilson interval, and the commonest cycle of
the locked_k particles in floor periods (:func:`states_table`).  An unknown share (the
recording ran out) is named, never counted as a state.
"""

from __future__ import annotations

import os

import numpy as np
import pandas as pd

from bbb.analysis.states import LABELS, LOCKED_K, classify, final_state
from bbb.analysis.stats.proportion import wilson
from bbb.record import COLLISION_FIELDS

from ...tables.collisions import as_store, field_names

__all__ = ["STATES_SCENE", "WINDOW", "states_table", "STATE_COLUMNS", "STATE_UNITS"]

STATES_SCENE = "ratchet_states"
#: s: the classifier's window (at least 4 floor periods, longer than any flight here)
WINDOW = 0.5
STATE_COLUMNS = ["alpha", "peak", "f", "n_particles",
                 *(f"{lab}{s}" for lab in LABELS for s in ("", "_lo", "_hi")), "period_k"]
#: the units of the columns the units map does not hold (shares and a cycle length: "1")
STATE_UNITS = {**{f"{lab}{s}": "1" for lab in LABELS for s in ("", "_lo", "_hi")}, "period_k": "1"}


def states_table(store: str | os.PathLike) -> pd.DataFrame:
    """One row per point of the states scene's store: alpha, peak, f, n_particles, the share
    of the particles in each state of :data:`~bbb.analysis.states.LABELS` at the run's end
    with its 95 % Wilson interval (``<label>``, ``<label>_lo``, ``<label>_hi``), and
    ``period_k``: the commonest cycle (floor periods) of the locked_k particles (NaN: none)."""
    st = as_store(store)
    study = st.study
    names = field_names(st)
    order = [names.index(c) for c in COLLISION_FIELDS]
    rows = []
    for fi, point in enumerate(study.points):
        rec = st.read_done("collisions", fi, 0)[..., order]
        n = st.read_done("n_recorded", fi, 0)
        p = point.params
        labels, period, _ = classify(rec, n, study.accuracy.t_max, WINDOW, p.f, p.A, p.S)
        fin = final_state(labels)
        row = {"alpha": p.alpha, "peak": p.peak, "f": p.f, "n_particles": int(fin.size)}
        for code, lab in enumerate(LABELS):
            share, lo, hi = wilson(int((fin == code).sum()), int(fin.size))
            row |= {lab: share, f"{lab}_lo": lo, f"{lab}_hi": hi}
        k = period[:, -1][fin == LOCKED_K] if period.shape[1] else np.array([], np.int8)
        row["period_k"] = float(np.bincount(k).argmax()) if k.size else np.nan
        rows.append(row)
    return pd.DataFrame(rows, columns=STATE_COLUMNS)
