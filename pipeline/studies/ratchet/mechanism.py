"""What the particles do where the ratchet current reverses, and the tilted conveyor's
reversals beside them -- tables made from the map's tables, no claim.

Each current reversal of an off-centre line (:func:`.claims.line_reversals`: from the last
significant f of one sign, f_a, to the first of the other, f_b) gets a row per end
(:func:`reversal_table`) with what the collisions say there, from the map's impacts and
counters tables:

per_period   collisions per floor period (collisions per particle-s / f): 1 for a particle
             locked to one bounce per period, below 1 for longer flights, above 1 for
             chatter
rho          the phase locking of the collisions: the length of the mean resultant of the
             floor phase ω t mod 2π at the collisions (from the 24-bin histogram): 1 all in one
             bin, 0 spread evenly; with ``phase``, the mean floor phase (degrees)
vx_within_1  the lag-1 correlation of the post-collision vx about each particle's own mean,
             with its bootstrap CI (the impacts table's): near +1 a particle keeps its
             horizontal velocity from collision to collision (a walking state), near 0 or
             below it loses it (chaotic hopping)

state        with the states scene's table (:mod:`.reversal_states`): the states the
             particles end in there, each with its share (``states``: "diffusing 0.94,
             chaotic 0.06"; blank where the scene has no such point)

The conveyor's reversals (:func:`conveyor_reversals`) are read from the transport study's
committed diffusion tables beside REPORT.md (a committed file is the interface between
studies) with the same sign rules (:mod:`pipeline.claims.signs`).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pandas as pd

from bbb.analysis.states import LABELS

from ...claims.signs import reversal_intervals, significant_signs, steady_rows
from .claims import CENTRE, SCENE, line_reversals, map_lines
from .reversal_states import STATES_SCENE

__all__ = ["BINS", "STATES_TABLE", "resultant", "states_text", "reversal_table",
           "conveyor_reversals", "CONVEYOR_FILES", "REVERSAL_UNITS"]

#: the key of the states scene's table (:func:`.reversal_states.states_table`)
STATES_TABLE = f"{STATES_SCENE}_classes"

BINS = 24
#: the units of the reversal and conveyor tables' columns the units map does not hold ("": not
#: a quantity; a reversal lies between f_a and f_b; sign_after is -1 or +1; phase in degrees)
REVERSAL_UNITS = {"source": "", "f_a": "Hz", "f_b": "Hz", "sign_after": "1", "end": "",
                  "per_period": "1", "rho": "1", "phase": "degree", "states": ""}
#: the transport study's committed map tables read for the comparison, and their line axes
CONVEYOR_FILES = {"transport_reversal_diffusion.csv": ("tilt", "throw", "contact"),
                  "transport_diffusion.csv": ("tilt", "throw")}


def resultant(shares) -> tuple[float, float]:
    """(ρ, mean phase in degrees in [0, 360)) of a phase histogram (``shares`` over BINS equal
    bins of ω t mod 2π, summing to 1); NaN for a blank or empty histogram."""
    s = np.asarray(shares, dtype=float)
    if s.size != BINS or np.isnan(s).any() or s.sum() <= 0:
        return float("nan"), float("nan")
    theta = (np.arange(BINS) + 0.5) * 2 * np.pi / BINS
    z = np.sum(s * np.exp(1j * theta)) / s.sum()
    return float(abs(z)), float(np.degrees(np.angle(z)) % 360.0)


def _at(t: pd.DataFrame | None, alpha: float, peak: float, f: float) -> pd.Series | None:
    if t is None:
        return None
    m = t[np.isclose(t["alpha"], alpha) & np.isclose(t["peak"], peak) & np.isclose(t["f"], f)]
    return None if m.empty else m.iloc[0]


def states_text(r: pd.Series | None, floor: float = 0.05) -> str:
    """"diffusing 0.94, chaotic 0.06": the states of a states-table row with a share of at
    least ``floor``, commonest first (locked_k with its cycle in floor periods); "" for none."""
    if r is None:
        return ""
    shares = sorted(((float(r[lab]), lab) for lab in LABELS if pd.notna(r.get(lab))),
                    reverse=True)
    k = r.get("period_k")
    return ", ".join(f"{lab}{f' (k = {int(k)})' if lab == 'locked_k' and pd.notna(k) else ''} "
                     f"{x:.2f}" for x, lab in shares if x >= floor)


def reversal_table(tables: Mapping[str, pd.DataFrame]) -> pd.DataFrame:
    """One row per (reversal, end): alpha, peak, f_a, f_b, sign_after (+1: v turns positive
    with f), end ('a' or 'b'), f, v, v_lo, v_hi, per_period, rho, phase, vx_within_1 and its
    CI (NaN where the impacts or counters table lacks the point: named blank, never 0), and
    states (:func:`states_text` of the states scene's table, "" where it lacks the point)."""
    lines = map_lines(tables.get(f"{SCENE}_diffusion"))
    imp, cnt = tables.get(f"{SCENE}_impacts"), tables.get(f"{SCENE}_counters")
    sts = tables.get(STATES_TABLE)
    rows = []
    for (a, p), t in lines.items():
        if np.isclose(p, CENTRE):
            continue
        for fa, fb, k in line_reversals(t)[0]:
            for end, f in (("a", fa), ("b", fb)):
                d = t[np.isclose(t["f"], f)].iloc[0]
                i, c = _at(imp, a, p, f), _at(cnt, a, p, f)
                rho, phase = (resultant([i[f"phase_{b}"] for b in range(BINS)])
                              if i is not None else (np.nan, np.nan))
                rows.append({"states": states_text(_at(sts, a, p, f)),
                             "alpha": a, "peak": p, "f_a": fa, "f_b": fb, "sign_after": k,
                             "end": end, "f": f, "v": d["v"], "v_lo": d["v_lo"],
                             "v_hi": d["v_hi"],
                             "per_period": (c["collisions_per_s"] / f) if c is not None
                             else np.nan, "rho": rho, "phase": phase,
                             **{col: (i[col] if i is not None and col in i else np.nan)
                                for col in ("vx_within_1", "vx_within_1_lo",
                                            "vx_within_1_hi")}})
    return pd.DataFrame(rows, columns=["alpha", "peak", "f_a", "f_b", "sign_after", "end", "f",
                                       "v", "v_lo", "v_hi", "per_period", "rho", "phase",
                                       "vx_within_1", "vx_within_1_lo", "vx_within_1_hi",
                                       "states"])


def conveyor_reversals(committed: Mapping[str, pd.DataFrame]) -> pd.DataFrame:
    """The sign changes of v along f on every line of the transport study's committed map
    tables ``committed`` ({file name: table}, :data:`CONVEYOR_FILES`): rows (source, tilt,
    throw, contact, f_a, f_b, sign_after, n_f) -- one per reversal, and a row with f_a, f_b
    NaN for a line without one (n_f: the line's steady frequencies)."""
    rows = []
    for name, axes in CONVEYOR_FILES.items():
        t = committed.get(name)
        if t is None or "v" not in t:
            continue
        for key, g in t.groupby(list(axes), sort=True):
            vals = dict(zip(axes, key if isinstance(key, tuple) else (key,), strict=True))
            s_rows = steady_rows(g)
            if s_rows is None or s_rows.empty:
                continue
            s = significant_signs(s_rows["v"], s_rows["v_lo"], s_rows["v_hi"])
            found = reversal_intervals(s_rows["f"].to_numpy(float), s)
            base = {"source": name.removesuffix(".csv"), "tilt": float(vals["tilt"]),
                    "throw": float(vals["throw"]), "contact": vals.get("contact", "stick"),
                    "n_f": len(s_rows)}
            rows += ([{**base, "f_a": fa, "f_b": fb, "sign_after": k} for fa, fb, k in found]
                     or [{**base, "f_a": np.nan, "f_b": np.nan, "sign_after": 0}])
    return pd.DataFrame(rows, columns=["source", "tilt", "throw", "contact", "f_a", "f_b",
                                       "sign_after", "n_f"])
