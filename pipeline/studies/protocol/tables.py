"""The protocol table: per frequency, initial ensemble, analysis run length T and definition
of "moving", the share that moves and D (all particles, the moving ones) with their
intervals, read off the protocol store's positions by :func:`bbb.analysis.moving_d.decompose`.

A window of T s is the first T s of the stored 50 s run, analysed as ``bbb reduce`` analyses
a run of length T (first 10 % dropped, fit lags 5–25 % of the rest): the kernel draws no
random number after the initial condition, so it *is* a run of length T: the same positions
bit for bit but at the window's last sample, which a run ending there computes on another
path and which differs by rounding (~1e-16 mm; tests/pipeline/studies/protocol/
test_tables.py checks this on the kernel).  The transient therefore needs no separate runs.
The ensembles are the scene's families and :data:`MIXTURE`, all families pooled.  Bootstrap
seeds are keyed by (study seed, f, ensemble, T): the table is a function of the store alone.
"""

from __future__ import annotations

import os

import numpy as np
import pandas as pd

from bbb.analysis.moving import DEFINITIONS
from bbb.analysis.moving_d import decompose

from ...tables.collisions import as_store
from ...workflow.identity import f_key, label_key

__all__ = ["WINDOWS", "MIXTURE", "DEFINITIONS", "COLUMNS", "COLUMN_UNITS", "protocol_table",
           "protocol_name"]

#: s, the analysis run lengths T
WINDOWS = (5.0, 10.0, 20.0, 50.0)
#: the pooled families
MIXTURE = "mixture"
#: the table's columns, in order (units: f Hz, T s, shares 1, D mm²/s)
COLUMNS = ("f", "Gamma", "ensemble", "T", "definition", "n", "n_moving", "share", "share_lo",
           "share_hi", "D", "D_lo", "D_hi", "D_status", "D_all", "D_all_lo", "D_all_hi",
           "residual", "bound", "holds", "approx_ok")

#: the units of the study's own columns (protocol_curves and protocol_verdicts) that the
#: engine's map (pipeline.tables.units) does not know; CI bounds follow their column
COLUMN_UNITS = {"ensemble": "", "T": "s", "definition": "", "n": "1", "share": "1",
                "residual": "mm^2/s", "bound": "mm^2/s", "holds": "", "approx_ok": "",
                "protocol": "", "claim": "", "measured": ""}


def protocol_name(ensemble: str, T: float, definition: str) -> str:
    """A protocol's label: 'launched, T = 10 s, displaced'."""
    return f"{ensemble}, T = {T:g} s, {definition}"


def _seed(study_seed: int, f: float, ensemble: str, T: float) -> np.random.SeedSequence:
    return np.random.SeedSequence(study_seed, spawn_key=(f_key(f), label_key("protocol"),
                                                         label_key(ensemble), f_key(T)))


def protocol_table(store: str | os.PathLike, windows: tuple[float, ...] = WINDOWS
                   ) -> pd.DataFrame:
    """One row per (f, ensemble, T, definition) of the windows that fit in the run
    (:data:`COLUMNS`; ``approx_ok``: |D_all − share · D| within the half-width of D_all's
    95 % CI, the decomposition resolved at the data's precision)."""
    st = as_store(store)
    study = st.study
    dt, t_max = study.accuracy.sample_dt, study.accuracy.t_max
    n_res = study.accuracy.n_resamples
    S = study.params(study.frequencies[0]).S
    done = st.done()
    names = [m.name for m in study.families]
    rows = []
    for fi, f in enumerate(study.frequencies):
        fams = {names[mi]: st.read_done("positions", fi, mi, done[fi, mi])
                for mi in range(len(names))}
        fams = {k: v for k, v in fams.items() if v.shape[0] >= 2}
        if not fams:
            continue
        ens = {**fams, MIXTURE: np.concatenate(list(fams.values()))} if len(fams) > 1 else fams
        gamma = study.params(f).gamma
        for name, x in ens.items():
            for T in windows:
                if T > t_max + 1e-9:
                    continue
                for d in decompose(x, dt, S, T, n_resamples=n_res,
                                   seed=_seed(study.seed, f, name, T)):
                    half = (d.D_all_hi - d.D_all_lo) / 2
                    rows.append({"f": f, "Gamma": gamma, "ensemble": name, "T": T,
                                 **d._asdict(),
                                 "approx_ok": bool(abs(d.residual) <= half)
                                 if np.isfinite(d.residual) and np.isfinite(half) else False})
    df = pd.DataFrame(rows)
    if df.empty:
        return pd.DataFrame(columns=list(COLUMNS))
    df = df.rename(columns={"status": "D_status"})
    return df[list(COLUMNS)]
