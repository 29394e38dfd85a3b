"""The basins study's tables, read off the scene's store (the ``states`` observable's arrays):

states   the observable's own table (final-state shares with Wilson intervals, lifetimes,
         escape rates, D of each class), one row per (f, family);
shares   the share of each state at the end of every window T (Wilson intervals), one row per
         (f, family, T, state);
dmix     D_mix(f, T) = Σ_c share_c(T) · D_c over the classes c (stuck, locked 1/1, locked
         period-k, irregular) with D_c of the particles holding class c through the run's
         second half, and a percentile bootstrap interval over particles (shares and D_c from
         the same resamples); one row per (f, family, T);
peak     per (family, T) of :data:`PEAK_TIMES`: the frequency of D_mix's largest value along f,
         with the percentile interval of that location over bootstrap resamples (each
         frequency's particles resampled independently);
entropy  the basin entropy of each final-state grid (boxes of :data:`BOX` × BOX cells): S_b,
         S_bb, and whether S_bb exceeds ln 2 (a fractal boundary, Daza et al. 2016).

Every bootstrap draws from the (study, f, family, table) seed: the tables depend only on the
store.  A value that cannot be measured is NaN and its ``status`` says why.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from bbb.analysis import basins as bs
from bbb.analysis import states as st
from bbb.analysis.stats.proportion import wilson

__all__ = ["SCENE", "BOX", "PEAK_TIMES", "COLUMN_UNITS", "NOT_COMPUTED", "make_tables",
           "store_tables", "grids", "dmix_boot"]

SCENE = "basins"
#: cells per side of a basin-entropy box
BOX = 4
#: a grid cell whose chunk is not done: no state at all (not the classifier's 'unknown', which
#: is a computed particle whose window could not be labelled)
NOT_COMPUTED = -1
#: the run lengths (s) at which D_mix's maximum along f is located (claim B1's ensembles)
PEAK_TIMES = (5.0, 10.0, 20.0)
_LABELS = [name for code, name in enumerate(st.LABELS)]
#: units of the study's own columns (the states table's are the observable's)
COLUMN_UNITS = {
    "T": "s", "state": "", "share": "1", "n": "1", "D_mix": "mm^2/s", "dmix_status": "",
    "f_max": "Hz", "D_max": "mm^2/s", "at_edge": "", "peak_status": "", "S_b": "1", "S_bb": "1",
    "boundary_boxes": "1", "boxes": "1", "fractal": "", "entropy_status": "",
}


def make_tables(stores, echo=print) -> dict[str, pd.DataFrame]:
    """The study's tables from its scene's store."""
    from ...store.study_store import StudyStore

    return store_tables(StudyStore.open(stores[SCENE]), echo)


def _arrays(store, fi: int, mi: int, done) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(labels, x at the edges, lattice index) of the done particles of (fi, mi)."""
    lab = store.read_done("state_label", fi, mi, done[fi, mi])
    x = store.read_done("state_x", fi, mi, done[fi, mi])
    n = store.study.accuracy.chunk_size
    idx = np.concatenate([np.arange(c * n, (c + 1) * n) for c in np.flatnonzero(done[fi, mi])]
                         ) if done[fi, mi].any() else np.zeros(0, np.int64)
    return lab, x, idx


def store_tables(store, echo=print) -> dict[str, pd.DataFrame]:
    from ...tables.reduce import reduce_store
    from ...workflow.identity import table_seed
    from ...workflow.observables.registry import by_name

    study = store.study
    states_table = reduce_store(store, echo=echo)["states"]
    obs = by_name("states")
    window = float(obs.settings(study.observables)["window"])
    edges = obs.edges(study)
    ci, B = study.analysis.ci, study.accuracy.n_resamples
    done = store.done()
    shares, dmix, ent, boots = [], [], [], {}
    for fi, point in enumerate(study.points):
        for mi, fam in enumerate(study.families):
            lab, x, idx = _arrays(store, fi, mi, done)
            key = {"f": point.f, "family": fam.name}
            for q, T in enumerate(edges[1:]):
                col = lab[:, q]
                known = col != st.UNKNOWN
                for code, name in enumerate(_LABELS):
                    n = int(known.sum()) if code != st.UNKNOWN else col.size
                    v, lo, hi = wilson(int(np.sum(col == code)), n, ci)
                    shares.append({**key, "T": T, "state": name, "share": v, "share_lo": lo,
                                   "share_hi": hi, "n": n})
            rng = np.random.default_rng(table_seed(study, point.f, fam.name, "basins_dmix"))
            est, boot, status = dmix_boot(lab, x, window, rng, B)
            boots[(point.f, fam.name)] = boot
            q_lo, q_hi = (1 - ci) / 2, (1 + ci) / 2
            for q, T in enumerate(edges[1:]):
                b = boot[:, q]
                ok = np.isfinite(b).all() and math.isfinite(est[q])
                lo, hi = (np.quantile(b, [q_lo, q_hi]) if ok else (math.nan, math.nan))
                why = status[q]
                if ok and not hi > lo:
                    lo, hi, why = math.nan, math.nan, "interval of zero width"
                dmix.append({**key, "T": T, "D_mix": est[q], "D_mix_lo": lo, "D_mix_hi": hi,
                             "dmix_status": why})
            shape = tuple(int(v) for v in fam.lattice) if fam.lattice is not None else None
            if shape and idx.size == shape[0] * shape[1]:
                grid = np.full(shape[0] * shape[1], st.UNKNOWN, np.int8)
                grid[idx] = st.final_state(lab)
                s_b, s_bb, nb, nbox = bs.basin_entropy(grid.reshape(shape), BOX)
                why = "" if nbox else "no box without an unknown cell"
            else:
                s_b = s_bb = math.nan
                nb = nbox = 0
                why = "not a complete lattice (chunks not done, or random draws)"
            ent.append({**key, "S_b": s_b, "S_bb": s_bb, "boundary_boxes": nb, "boxes": nbox,
                        "fractal": bool(s_bb > bs.LOG2) if math.isfinite(s_bb) else None,
                        "entropy_status": why})
    dmix_t = pd.DataFrame(dmix)
    return {"states": states_table, "shares": pd.DataFrame(shares), "dmix": dmix_t,
            "peak": peak_table(dmix_t, boots, edges, ci), "entropy": pd.DataFrame(ent)}


def dmix_boot(lab: np.ndarray, x: np.ndarray, window: float, rng: np.random.Generator,
              B: int) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """D_mix at the end of every window (the estimate (window,), B bootstrap resamples over the
    particles (B, window), and why each is not measured: '' where it is).  D_mix(T) =
    Σ_c share_c(T) D_c, share over the particles with a known label at T, D_c the mean
    dx²/(2Δt) of those holding class c through the second half; a class present at T without
    a D_c makes D_mix(T) not measured."""
    P, nw = lab.shape
    if P == 0:
        return np.full(nw, np.nan), np.full((B, nw), np.nan), ["no particle"] * nw
    held, d_i = bs.held_classes(lab, x, window)
    cls = bs.classes(lab)  # (P, nw)
    K = len(bs.CLASSES)
    onehot_held = (held[:, None] == np.arange(K)[None, :]).astype(float)  # (P, K)
    W = np.vstack([np.ones(P), rng.multinomial(P, np.full(P, 1.0 / P), size=B)])  # (1+B, P)
    n_c = W @ onehot_held  # (1+B, K)
    with np.errstate(invalid="ignore", divide="ignore"):
        D_c = (W @ (onehot_held * d_i[:, None])) / n_c  # (1+B, K), NaN where no particle
    out = np.full((1 + B, nw), np.nan)
    status = []
    for q in range(nw):
        oh = (cls[:, q][:, None] == np.arange(K)[None, :]).astype(float)  # (P, K)
        cnt = W @ oh  # (1+B, K)
        known = cnt[:, 1:].sum(axis=1)
        with np.errstate(invalid="ignore", divide="ignore"):
            share = cnt[:, 1:] / known[:, None]
        present = share > 0
        contrib = np.where(present, share * np.nan_to_num(D_c[:, 1:], nan=0.0), 0.0)
        missing = present & np.isnan(D_c[:, 1:])
        val = contrib.sum(axis=1)
        val[missing.any(axis=1) | (known == 0)] = np.nan
        out[:, q] = val
        if known[0] == 0:
            status.append("every label unknown")
        elif missing[0].any():
            names = [bs.CLASSES[c + 1] for c in np.flatnonzero(missing[0])]
            status.append(f"no particle holds {', '.join(names)} through the second half")
        else:
            status.append("")
    return out[0], out[1:], status


#: the peak table's columns (also when no run reaches a time of PEAK_TIMES: a draft's table is
#: empty but keeps them, so its CSV reads back)
PEAK_COLUMNS = ["family", "T", "f_max", "f_max_lo", "f_max_hi", "D_max", "at_edge", "peak_status"]


def peak_table(dmix: pd.DataFrame, boots: dict, edges: np.ndarray, ci: float) -> pd.DataFrame:
    """Per (family, T in PEAK_TIMES): D_mix's largest value along f, where, and the percentile
    interval of that location over the resamples."""
    rows = []
    if dmix.empty:
        return pd.DataFrame(rows, columns=PEAK_COLUMNS)
    fs = np.array(sorted(dmix["f"].unique()))
    for fam in dmix["family"].unique():
        for T in PEAK_TIMES:
            q = int(np.argmin(np.abs(edges[1:] - T)))
            if abs(edges[1:][q] - T) > 1e-9:
                continue
            sub = dmix[(dmix["family"] == fam) & np.isclose(dmix["T"], T)].set_index("f")
            est = sub["D_mix"].reindex(fs).to_numpy()
            row = {"family": fam, "T": T}
            if not np.isfinite(est).all():
                bad = fs[~np.isfinite(est)]
                rows.append({**row, "f_max": math.nan, "f_max_lo": math.nan, "f_max_hi": math.nan,
                             "D_max": math.nan, "peak_status": "D_mix not measured at "
                             + ", ".join(f"{f:g}" for f in bad) + " Hz"})
                continue
            B = np.stack([boots[(f, fam)][:, q] for f in fs], axis=1)  # (B, f)
            ok = np.isfinite(B).all(axis=1)
            at = fs[np.argmax(B[ok], axis=1)]
            i = int(np.argmax(est))
            lo, hi = np.quantile(at, [(1 - ci) / 2, (1 + ci) / 2]) if at.size else (math.nan,) * 2
            why = "" if ok.all() else f"{int((~ok).sum())} resamples without a value left out"
            rows.append({**row, "f_max": float(fs[i]), "f_max_lo": float(lo),
                         "f_max_hi": float(hi), "D_max": float(est[i]),
                         "at_edge": bool(i in (0, fs.size - 1)), "peak_status": why})
    return pd.DataFrame(rows, columns=PEAK_COLUMNS)


def grids(store) -> dict[tuple[float, str], np.ndarray]:
    """{(f, family): final-state grid (n_phase, n_value)} of the lattice families: a state code
    of bbb.analysis.states, :data:`NOT_COMPUTED` where a chunk is not done."""
    study, done = store.study, store.done()
    out = {}
    for fi, point in enumerate(study.points):
        for mi, fam in enumerate(study.families):
            if fam.lattice is None:
                continue
            shape = tuple(int(v) for v in fam.lattice)
            lab, _x, idx = _arrays(store, fi, mi, done)
            grid = np.full(shape[0] * shape[1], NOT_COMPUTED, np.int8)
            grid[idx] = st.final_state(lab)
            out[(point.f, fam.name)] = grid.reshape(shape)
    return out
