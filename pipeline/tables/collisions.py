"""Post-collision states read from a study store, and the locking table made from them.

A store with ``[observables.collisions]`` holds ``collisions[frequency, family, particle,
collision, field]`` (NaN-padded).  Fields are looked up by name in the store's ``field``
coordinate (t, x, y, vx, vy and, in newer stores, phase), so this module reads either layout.
Only particles of chunks marked done are used.

:func:`locking_table` applies :mod:`bbb.analysis.locking` to every (frequency, family) of a store:

=========  ====================================================================
f          floor frequency, Hz
family     initial-condition family name
n_states   finite post-collision states
frac_creep fraction of them in the creeping band v_y⁺ ≤ v_creep
v_creep    upper edge of the creeping band, (1 + 0.1) A 2π f, mm/s
v_max      maximal v_y⁺ of the spiral: 0.99 quantile above the band, mm/s
k_max      2 v_max f / g
v_peak     dominant peak (KDE mode) of v_y⁺ above the band, mm/s
k_peak     2 v_peak f / g
t_max      0.99 quantile of the free-flight times, s
n_flights  free flights t_max was computed from
loops      f t_max: turns of the spiral approximation over t_c ∈ [0, t_max]
v_max_lo, v_max_hi, k_max_lo, k_max_hi, v_peak_lo, v_peak_hi, k_peak_lo, k_peak_hi
           95 % percentile-bootstrap CIs over particles (:func:`bbb.analysis.locking.bootstrap_locking`,
           LOCK_RESAMPLES resamples)
=========  ====================================================================
"""

from __future__ import annotations

import os
from collections.abc import Iterable

import numpy as np
import pandas as pd

from bbb.analysis.locking import bootstrap_locking, flight_times, locking_estimate

from ..store.study_store import StudyStore
from ..workflow.identity import table_seed

__all__ = ["as_store", "field_names", "states", "locking_table", "LOCKING_COLUMNS"]

LOCKING_COLUMNS = ("f", "family", "initial", "n_states", "frac_creep", "v_creep", "v_max", "k_max",
                   "v_peak", "k_peak", "t_max", "n_flights", "loops", "v_max_lo", "v_max_hi",
                   "k_max_lo", "k_max_hi", "v_peak_lo", "v_peak_hi", "k_peak_lo", "k_peak_hi")
#: bootstrap resamples of the locking CIs: their ends differ by ≤ 0.013 in k from 2000 resamples
#: (measured at 8 frequencies x 2 families, 32 particles), and cost ~0.1 s per (frequency, family)
LOCK_RESAMPLES = 200


def as_store(store: str | os.PathLike | StudyStore) -> StudyStore:
    """A StudyStore from a path (opened read-only) or an already opened one."""
    return store if isinstance(store, StudyStore) else StudyStore.open(os.fspath(store))


def field_names(store: StudyStore) -> tuple[str, ...]:
    """Names of the collision fields in the store, in storage order."""
    g = store.group()
    if "field" not in g:
        return ()
    return tuple(str(v) for v in np.asarray(g["field"][...]))


def states(store: str | os.PathLike | StudyStore, f: float, family: str,
           names: Iterable[str] = ("t", "y", "vy"), point: int | None = None
           ) -> dict[str, np.ndarray]:
    """Post-collision fields at frequency ``f`` (Hz, nearest stored) of one family; on a
    grid store at the point of store index ``point`` (f is then that point's).

    Returns {field: float64 array (particle, collision)} for the particles of done chunks,
    NaN-padded; units: t s, x and y mm, vx and vy mm/s, phase in floor periods.
    Raises KeyError for a field the store does not hold.
    """
    st = as_store(store)
    study = st.study
    fields = field_names(st)
    if not fields:
        raise KeyError(f"{st.path}: the store records no collisions")
    if point is not None:
        fi = point
    elif study.grid:
        raise KeyError(f"{st.path}: a grid store: name the point (point=index)")
    else:
        fi = int(np.argmin(np.abs(np.asarray(study.frequencies) - f)))
    fams = [fam.name for fam in study.families]
    if family not in fams:
        raise KeyError(f"{st.path}: no family {family!r}; has {', '.join(fams)}")
    mi = fams.index(family)
    block = st.read_done("collisions", fi, mi)
    out = {}
    for name in names:
        if name not in fields:
            raise KeyError(f"{st.path}: no collision field {name!r}; has {', '.join(fields)}")
        out[name] = block[:, :, fields.index(name)]
    return out


def locking_table(store: str | os.PathLike | StudyStore) -> pd.DataFrame:
    """One row per (frequency, family) of a store with collisions (columns in the module doc)."""
    st = as_store(store)
    study = st.study
    rows = []
    for fi, point in enumerate(study.points):
        p, f = point.params, point.f
        for fam in study.families:
            s = states(st, f, fam.name, point=fi)
            fl = flight_times(s["t"], s["y"], s["vy"], p.g) if s["t"].size else np.zeros(0)
            est = locking_estimate(s["vy"], p.A, f, p.g, flights=fl)
            seed = table_seed(study, f, fam, "locking")
            ci = bootstrap_locking(s["vy"], p.A, f, p.g, n_resamples=LOCK_RESAMPLES, seed=seed)
            rows.append({
                **point.columns(), "family": fam.name, "initial": fam.initial, "n_states": est.n,
                "frac_creep": est.frac_creep, "v_creep": est.v_creep, "v_max": est.v_max,
                "k_max": est.k_max, "v_peak": est.v_peak, "k_peak": est.k_peak, "t_max": est.t_max,
                "n_flights": est.n_flights, "loops": f * est.t_max, **vars(ci),
            })
    axes = [a for a, _ in study.grid]
    return pd.DataFrame(rows, columns=["f", *axes, *LOCKING_COLUMNS[1:]])
