"""The paper's onset claims re-judged under each measuring protocol (initial ensemble × analysis
run length T × definition of "moving"), and the verdicts table the paper's claim 2 reads.

Per protocol, its D(f) curve (``D``: the moving particles' D; for the definition ``all``,
bbb reduce's D) plays the Fig. 2 curve of :func:`pipeline.studies.klages2004.claims.evaluate`,
and claims 1 (onset ≈ 50 Hz), 2 (maximum ≈ 54 Hz), 4 (minimum ≈ 58 Hz) and 5 (the VHO maximum
at 60 Hz) are judged by their own records and rules, unchanged.  Claim 16 (non-ergodic only
near 55 Hz) compares families, so it is judged once per (T, definition), the families' curves
playing the ergodicity scene's.  A protocol *reproduces the onset structure* when claims 1, 2,
4 and 5 are all positive ("agrees" or "agrees within the CI").  Claim 3 (the 1/1 spot in the
post-collision states) needs collisions, which this scene does not record.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import pandas as pd

from bbb.params import Params

from ...claims.claim import POSITIVE, evaluate
from ..registry import claim, study
from .tables import DEFINITIONS, MIXTURE, WINDOWS, protocol_name

__all__ = ["SCENES", "CURVE_CLAIMS", "ERGODIC_CLAIM", "KEYS", "protocols",
           "curve_table", "families_table", "verdicts_table", "reproducing"]

#: the scene whose store the study reads
SCENES = ("protocol",)
#: the paper's claims re-judged per protocol: records of the claims registry, keyed by their id
#: (their number in the paper's list); 16 on the families' curves, the others on each curve
CURVE_CLAIMS = {k: claim("klages2004", k) for k in ("1", "2", "4", "5")}
ERGODIC_CLAIM = claim("klages2004", "16")
KEYS = (*CURVE_CLAIMS, "16")


def _judged_in(tables, f_gamma1: float, params: dict) -> dict:
    """The paper's context (its study's, from the registry) of ``tables``, with the preset's
    f(Γ = 1) and parameters for the notes."""
    return {**study("klages2004").context(tables, {}), "f_gamma1": f_gamma1, "params": params}


def _context() -> tuple[float, dict]:
    p = Params.preset("klages2004", f=60.0)
    return math.sqrt(p.g / p.A) / (2 * math.pi), p.as_dict()


def protocols(curves: pd.DataFrame) -> list[tuple[str, float, str]]:
    """(ensemble, T, definition) of every protocol in the table, ensembles in the scene's
    order then the mixture, T ascending, definitions in :data:`DEFINITIONS` order."""
    ens = list(dict.fromkeys(e for e in curves["ensemble"] if e != MIXTURE))
    ens += [MIXTURE] if (curves["ensemble"] == MIXTURE).any() else []
    Ts = sorted(set(curves["T"].astype(float)))
    return [(e, T, d) for e in ens for T in Ts for d in DEFINITIONS
            if ((curves["ensemble"] == e) & (curves["T"] == T) & (curves["definition"] == d)).any()]


def _select(curves: pd.DataFrame, ensemble: str, T: float, definition: str) -> pd.DataFrame:
    t = curves[(curves["ensemble"] == ensemble) & (curves["T"] == T)
               & (curves["definition"] == definition)]
    return t.sort_values("f").reset_index(drop=True)


def curve_table(curves: pd.DataFrame, ensemble: str, T: float, definition: str) -> pd.DataFrame:
    """One protocol's D(f) as a Fig. 2 table: f, D, D_lo, D_hi (mm²/s)."""
    t = _select(curves, ensemble, T, definition)
    return t[["f", "D", "D_lo", "D_hi"]].copy()


def families_table(curves: pd.DataFrame, T: float, definition: str) -> pd.DataFrame:
    """The families' D(f) at (T, definition) as an ergodicity table: f, D_<fam>, D_<fam>_lo,
    D_<fam>_hi for every family (not the mixture), eb_ok (not judged here: True)."""
    out = None
    for e in dict.fromkeys(curves["ensemble"]):
        if e == MIXTURE:
            continue
        t = _select(curves, e, T, definition)[["f", "D", "D_lo", "D_hi"]]
        t = t.rename(columns={"D": f"D_{e}", "D_lo": f"D_{e}_lo", "D_hi": f"D_{e}_hi"})
        out = t if out is None else out.merge(t, on="f", how="outer")
    out = out.sort_values("f").reset_index(drop=True)
    out["eb_ok"] = True
    return out


def _short(measured: str) -> str:
    """A claim row's measured text for this study: the curve's label dropped, the position
    range's explanation left to the judged-by column."""
    text = measured.replace("rest (Fig. 2 scene): ", "")
    return text.split(" (position range")[0] + (text[text.index(", D ="):].split(" ⚠")[0]
                                                if " (position range" in text else "")


def verdicts_table(curves: pd.DataFrame) -> pd.DataFrame:
    """Per protocol and claim (1, 2, 4, 5) and per (T, definition) for claim 16: protocol,
    ensemble, T, definition, claim, verdict, measured (text of the claim's own measure)."""
    f_gamma1, params = _context()
    rows = []
    for e, T, d in protocols(curves):
        res = evaluate(list(CURVE_CLAIMS.values()),
                       _judged_in({"figure2": curve_table(curves, e, T, d)}, f_gamma1, params))
        for key, r in zip(CURVE_CLAIMS, res, strict=True):
            rows.append({"protocol": protocol_name(e, T, d), "ensemble": e, "T": T,
                         "definition": d, "claim": key, "verdict": r.verdict,
                         "measured": _short(r.measured)})
    for T in sorted(set(curves["T"].astype(float))):
        for d in DEFINITIONS:
            res = evaluate([ERGODIC_CLAIM],
                           _judged_in({"ergodicity": families_table(curves, T, d)}, f_gamma1,
                                      params))
            rows.append({"protocol": protocol_name("families", T, d), "ensemble": "families",
                         "T": T, "definition": d, "claim": "16", "verdict": res[0].verdict,
                         "measured": res[0].measured})
    return pd.DataFrame(rows)


def reproducing(verdicts: pd.DataFrame) -> tuple[list[str], dict[str, list[str]]]:
    """(the protocols with claims 1, 2, 4 and 5 all positive, {protocol: the claims it
    misses} for every other protocol), protocols in table order."""
    v = verdicts[verdicts["claim"].astype(str) != "16"]
    ok, missing = [], {}
    for p in dict.fromkeys(v["protocol"]):
        rows = v[v["protocol"] == p]
        bad = [str(c) for c, x in zip(rows["claim"], rows["verdict"], strict=True)
               if x not in POSITIVE]
        (missing.__setitem__(p, bad) if bad else ok.append(p))
    return ok, missing


def windows_of(verdicts: Mapping | pd.DataFrame) -> tuple[float, ...]:
    """The run lengths T (s) the verdicts cover (default :data:`~.tables.WINDOWS`)."""
    Ts = sorted(set(pd.DataFrame(verdicts)["T"].astype(float))) if len(verdicts) else WINDOWS
    return tuple(Ts)
