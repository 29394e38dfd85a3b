"""The ratchet section's own words, the facts they name, and the lines after its verdicts: the
collisions at each current reversal and the tilted conveyor's reversals beside them, all read
off the committed tables."""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import pandas as pd

from bbb.analysis.stats.proportion import wilson

from .claims import CENTRE, SCENE, TABLE, map_lines
from .mechanism import STATES_TABLE

__all__ = ["WORDS", "facts", "further"]

#: the section's own words
WORDS = ("Drift v with its 95 % bootstrap CI over particles (bbb.analysis.transport) on a level "
         "sawtooth floor vibrated vertically (teeth 0.3 mm deep on S = 2 mm), over the peak "
         "position p = {peaks} (fraction of S from the left valley) and α = {alphas}, at "
         "{freqs} frequencies {f_lo}–{f_hi} Hz ({points} points, {particles} particles from "
         "rest each, independent: no mirror pairs). p = 0.5 is the symmetric control; the "
         "mirror pairs are 0.2/0.8, 0.3/0.7 and 0.4/0.6 (x → −x takes the teeth p to 1 − p). "
         "{unsteady} points have no steady drift and are left out of every rule. "
         "pipeline/studies/ratchet/claims.py states the rules.")


def facts(tables: Mapping[str, pd.DataFrame], verdicts=None) -> dict:
    """What the words name, read off the map's diffusion table."""
    t = tables.get(TABLE)
    if t is None or t.empty:
        return {"peaks": "–", "alphas": "–", "freqs": 0, "f_lo": "–", "f_hi": "–",
                "points": 0, "particles": 0, "unsteady": 0}
    steady = t["steady"].fillna(True).astype(bool) if "steady" in t else pd.Series(True, t.index)
    return {"peaks": ", ".join(f"{p:g}" for p in sorted(t["peak"].unique())),
            "alphas": ", ".join(f"{a:g}" for a in sorted(t["alpha"].unique())),
            "freqs": t["f"].nunique(), "f_lo": f"{t['f'].min():g}", "f_hi": f"{t['f'].max():g}",
            "points": len(t), "particles": int(t["n_particles"].max()),
            "unsteady": int((~steady).sum())}


def _num(x, fmt: str = ".2f") -> str:
    return "blank" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:{fmt}}"


def _ci(r, col: str, fmt: str = ".2f") -> str:
    v, lo, hi = r[col], r[f"{col}_lo"], r[f"{col}_hi"]
    if any(pd.isna(x) for x in (v, lo, hi)):
        return f"{_num(float(v), fmt)} (no CI)" if not pd.isna(v) else "blank"
    return f"{v:{fmt}} [{lo:{fmt}}, {hi:{fmt}}]"


def _states(r) -> str:
    s = r.get("states")
    return "not run" if s is None or (isinstance(s, float) and math.isnan(s)) or s == "" else s


def _span(t: pd.DataFrame) -> str:
    """"all between 58 and 82 Hz, 10 + → −, 0 − → +" of rows with f_a, f_b, sign_after."""
    if t.empty:
        return "none"
    down, up = int((t["sign_after"] < 0).sum()), int((t["sign_after"] > 0).sum())
    return (f"all between {t['f_a'].min():g} and {t['f_b'].max():g} Hz, {down} + → −, "
            f"{up} − → +")


def states_summary(rev: pd.DataFrame, particles: float | None = None) -> str:
    """How many reversal ends the states scene ran and what their particles end in, and the
    ranges of the collisions' numbers there, from the reversal table."""
    ran = rev[rev["states"].fillna("").astype(str) != ""]
    n_iv = len(rev.drop_duplicates(["alpha", "peak", "f_a", "f_b"]))
    rng = "; ".join(f"{name} {rev[c].min():.3g}–{rev[c].max():.3g}" for name, c in (
        ("collisions per period", "per_period"), ("ρ", "rho"), ("vx lag-1 corr.", "vx_within_1"))
        if rev[c].notna().any())
    if ran.empty:
        return (f"The states scene ran at none of the {n_iv} reversals' ends. At the ends: "
                f"{rng}.")
    top = ran["states"].astype(str).str.split(",").str[0].str.rsplit(" ", n=1).str[0]
    counts = ", ".join(f"{k} at {v}" for k, v in top.value_counts().items())
    n = int(particles) if particles else 0
    ci = (f" ({n} particles per point: all {n} in one state is a share of 1 with the 95 % "
          f"Wilson interval [{wilson(n, n)[1]:.3f}, 1]; every share's interval is in "
          "ratchet_states_classes.csv)") if n else ""
    return (f"The states scene ran at {len(ran)} of the {2 * n_iv} reversal ends (those of the "
            f"lines p < 0.5; their mirror partners are their images): the commonest state "
            f"there is {counts}{ci}. At all ends: {rng}.")


def _sign(k) -> str:
    return "− → +" if int(k) > 0 else "+ → −"


def reversal_lines(rev: pd.DataFrame | None, states: pd.DataFrame | None = None) -> list[str]:
    """The table of the reversals with the collisions at both ends."""
    L = ["", "### The collisions at each current reversal", "",
         "Each reversal of an off-centre line (claim R4's intervals) with, at its two ends "
         "(the last significant f of one sign and the first of the other), the drift, the "
         "collisions per floor period (1: one bounce per period; below: longer flights; "
         "above: chatter), the phase locking ρ of the collisions (mean resultant length of "
         "the floor phase at the collisions from 5 s on: 1 all at one phase, 0 spread evenly) "
         "and the lag-1 correlation of the post-collision vx about each particle's own mean "
         "(near +1: a particle keeps its horizontal velocity, a walking state; near 0 or "
         "below: it loses it at each collision), and the states the particles end in there "
         "(scene ratchet_states: every collision recorded from t = 0, each particle's last "
         "0.5 s window labelled by the calibrated state classifier bbb.analysis.states; "
         "shares ≥ 0.05; locked states repeat their offset in the cell, so a particle walking "
         "a tooth per cycle is locked).", ""]
    if rev is None or rev.empty:
        return L + ["No current reversal on any off-centre line.", ""]
    n = None if states is None or states.empty else float(states["n_particles"].min())
    L += [states_summary(rev, n), "",
          "| α | p | reversal (Hz) | sign | v (mm/s) at f_a; f_b | collisions / period | ρ | "
          "vx lag-1 corr. (within) at f_a; f_b | states at f_a; f_b |",
          "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for (a, p, fa, fb), g in rev.groupby(["alpha", "peak", "f_a", "f_b"], sort=True):
        ends = g.sort_values("end").to_dict("records")
        L.append(f"| {a:g} | {p:g} | {fa:g}–{fb:g} | {_sign(ends[0]['sign_after'])} | "
                 + "; ".join(_ci(r, "v", ".3g") for r in ends) + " | "
                 + " → ".join(_num(float(r["per_period"]), ".3g") for r in ends) + " | "
                 + " → ".join(_num(float(r["rho"])) for r in ends) + " | "
                 + "; ".join(_ci(r, "vx_within_1") for r in ends) + " | "
                 + "; ".join(_states(r) for r in ends) + " |")
    return L + [""]


def conveyor_lines(conv: pd.DataFrame | None, rev: pd.DataFrame | None) -> list[str]:
    """The tilted conveyor's reversals (transport study's committed tables) beside the
    ratchet's."""
    L = ["", "### Beside the tilted conveyor's reversals", ""]
    if conv is None or conv.empty:
        return L + ["Not compared: the transport study's committed tables "
                    "(transport_diffusion.csv, transport_reversal_diffusion.csv) are absent.", ""]
    found = conv.dropna(subset=["f_a"])
    quiet = len(conv) - len(found)
    parts = []
    for src, g in found.groupby("source", sort=False):
        parts.append(f"{src}: " + "; ".join(
            f"φ = {r.tilt:g}°, ψ = {r.throw:g}°, {r.contact}: {r.f_a:g}–{r.f_b:g} Hz "
            f"({_sign(r.sign_after)})" for r in g.itertuples(index=False)))
    n_lines = conv.groupby(["source", "tilt", "throw", "contact"]).ngroups
    L.append(f"The conveyor (the transport study's committed tables, the same sign rules): "
             f"{len(found)} reversals along f on {n_lines} lines ({quiet} lines without one), "
             + _span(found) + ". " + ". ".join(parts) + ".")
    if rev is not None and not rev.empty:
        r_iv = rev.drop_duplicates(["alpha", "peak", "f_a", "f_b"])
        L.append("")
        L.append(f"The ratchet (level, vibrated vertically): {len(r_iv)} reversals, "
                 + _span(r_iv) + ".")
    return L + [""]


def further(tables: Mapping[str, pd.DataFrame], verdicts=None) -> list[str]:
    """After the verdicts: the reversal table with the collisions and the conveyor beside it;
    or why nothing was measured."""
    t = tables.get(TABLE)
    if t is None or t.empty:
        return ["Not measured: no ratchet table (scene ratchet).", ""]
    lines = map_lines(t)
    off = [k for k in lines if not np.isclose(k[1], CENTRE)]
    rev = tables.get(f"{SCENE}_reversals")
    return (["", f"{len(off)} off-centre lines judged."]
            + reversal_lines(rev, tables.get(STATES_TABLE))
            + conveyor_lines(tables.get(f"{SCENE}_conveyor"), rev))
