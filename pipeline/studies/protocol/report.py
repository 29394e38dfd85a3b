"""The protocol section of REPORT.md: the verdicts of claims 1, 2, 4 and 5 per protocol and of
claim 16 per (T, definition), the decomposition check, and a paragraph generated from the
tables (``protocol_verdicts``, ``protocol_curves``; every number read from them)."""

from __future__ import annotations

import math
from collections.abc import Mapping

import pandas as pd

from ...claims.markdown import md_cell
from .claims import CURVE_CLAIMS, ERGODIC_CLAIM, POSITIVE, reproducing
from .tables import MIXTURE

__all__ = ["SHORT", "report_lines", "paragraph", "decomposition_text"]

#: the claims' short names (by their number in the paper's list)
SHORT = {"1": "the onset near 50 Hz", "2": "the maximum near 54 Hz",
         "4": "the minimum near 58 Hz", "5": "the VHO maximum at 60 Hz"}


def _names(ps) -> str:
    return "; ".join(ps) if len(ps) else "none"


def _pct(x: float) -> str:
    return f"{100 * x:.0f} %" if math.isfinite(x) else "–"


def _value(curves: pd.DataFrame, ensemble: str, T: float, definition: str, f: float,
           col: str) -> float:
    t = curves[(curves["ensemble"] == ensemble) & (curves["T"] == T)
               & (curves["definition"] == definition) & ((curves["f"] - f).abs() < 1e-6)]
    return float(t[col].iloc[0]) if len(t) else math.nan


def _d(x: float) -> str:
    return f"{x:.3g}" if math.isfinite(x) else "no D"


def decomposition_text(curves: pd.DataFrame) -> str:
    """How well D_all = share × D_moving holds: checked points, those within the bound the
    still particles allow, those resolved within D_all's CI."""
    parts = []
    for d in ("displaced", "moving_time"):
        t = curves[curves["definition"] == d]
        checked = t[t["residual"].notna()]
        parts.append(f"{d}: the identity holds within the still particles' bound at "
                     f"{int(checked['holds'].astype(bool).sum())} of {len(checked)} points with "
                     f"a D, and share × D_moving lies within D_all's 95 % CI at "
                     f"{int(checked['approx_ok'].astype(bool).sum())}")
    return "D_all = share × D_moving: " + "; ".join(parts) + "."


def paragraph(verdicts: pd.DataFrame, curves: pd.DataFrame) -> str:
    """Which protocol (if any) reproduces onset, maximum, minimum and VHO maximum together,
    and what the shares and D say about how the paper measured D."""
    ok, missing = reproducing(verdicts)
    n = len(ok) + len(missing)
    v = verdicts[verdicts["claim"].astype(str) != "16"]
    per = {k: list(dict.fromkeys(v["protocol"][(v["claim"].astype(str) == k)
                                              & v["verdict"].isin(POSITIVE)])) for k in SHORT}
    if ok:
        text = (f"Of {n} protocols, {len(ok)} reproduce{'s' if len(ok) == 1 else ''} "
                f"{', '.join(SHORT.values())} together: {_names(ok)}. ")
        defs = set(v[v["protocol"].isin(ok)]["definition"])
        ens = set(v[v["protocol"].isin(ok)]["ensemble"])
        Ts = sorted(set(v[v["protocol"].isin(ok)]["T"].astype(float)))
        text += ("Every one of them " + ("counts only moving particles" if "all" not in defs
                                          else "includes the plain average over all particles")
                 + ", starts from " + ", ".join(sorted(ens)) + " and analyses runs of "
                 + ", ".join(f"{T:g}" for T in Ts) + " s. ")
    else:
        one = {p: m for p, m in missing.items() if len(m) == 1}
        text = (f"None of the {n} protocols reproduces {', '.join(SHORT.values())} together. "
                + ("Closest (all but one): " + "; ".join(
                    f"{p} (not {SHORT[m[0]]})" for p, m in one.items()) + ". " if one else ""))
    text += ("Each claim alone: " + "; ".join(f"{SHORT[k]} under {len(ps)}" for k, ps in
                                              per.items()) + " protocols. ")
    onset_ens = set(v[v["protocol"].isin(per["1"])]["ensemble"])
    max_ens = set(v[v["protocol"].isin(per["2"])]["ensemble"])
    if per["1"] and per["2"] and not onset_ens & max_ens:
        text += (f"The onset near 50 Hz comes only from {', '.join(sorted(onset_ens))}, the "
                 f"maximum near 54 Hz only from {', '.join(sorted(max_ens))}: no single initial "
                 "ensemble gives both. ")
    Ts = sorted(set(curves["T"].astype(float)))
    if Ts and (curves["ensemble"] == MIXTURE).any():
        T0, T1 = Ts[0], Ts[-1]
        sh = {(T, f): _value(curves, MIXTURE, T, "displaced", f, "share")
              for T in (T0, T1) for f in (50.0, 54.0, 58.0)}
        dm = {(T, f): _value(curves, MIXTURE, T, "displaced", f, "D")
              for T in (T0, T1) for f in (50.0, 54.0, 58.0)}
        text += ("In the mixture of all families the share displaced beyond one arc period is "
                 + "; ".join(f"{_pct(sh[T, 50.0])}, {_pct(sh[T, 54.0])}, {_pct(sh[T, 58.0])} "
                             f"at 50, 54, 58 Hz for T = {T:g} s" for T in (T0, T1))
                 + ", and the displaced particles' D is "
                 + "; ".join(f"{_d(dm[T, 50.0])}, {_d(dm[T, 54.0])}, {_d(dm[T, 58.0])} mm²/s "
                             f"(T = {T:g} s)" for T in (T0, T1)) + ". ")
    if ok:
        text += ("So the paper's landmarks near onset are those of a D measured under such a "
                 "protocol; with the plain average over particles at rest (Fig. 2's) they are not.")
    else:
        text += ("So the paper's D near onset is not what any one of these ensembles, run "
                 "lengths and definitions of moving gives: its landmarks 50, 54 and 58 Hz "
                 "cannot all be read off one such measurement of this model.")
    return text


def report_lines(tables: Mapping[str, pd.DataFrame]) -> list[str]:
    """The REPORT.md section from the tables ``protocol_verdicts`` and ``protocol_curves``."""
    verdicts, curves = tables.get("protocol_verdicts"), tables.get("protocol_curves")
    L = ["", "## Protocol: how the paper may have measured D near onset", ""]
    if verdicts is None or curves is None or verdicts.empty:
        return L + ["Not measured: no protocol tables (scene protocol).", ""]
    claim = verdicts["claim"].astype(str)
    L += ["Scene `pipeline/studies/protocol/scenes/protocol.toml`: five initial-condition "
          "families (rest; dropped from 0–2 and 2–10 mm; launched at 0–200 and 200–400 mm/s) "
          "and their mixture, 46–62 Hz, each run's first T s analysed as bbb reduce analyses a "
          "run of length T, and D averaged over all particles or over the moving ones under "
          "two definitions fixed before the data (`bbb.analysis.moving`). Verdicts by the "
          "paper's claim records and rules above, unchanged, with each protocol's D(f) as the "
          "Fig. 2 curve.", "",
          "| protocol | " + " | ".join(f"{k}: {SHORT[k]}" for k in CURVE_CLAIMS) + " |",
          "| --- |" + " --- |" * len(CURVE_CLAIMS)]
    v = verdicts[claim != "16"]
    for p in dict.fromkeys(v["protocol"]):
        rows = v[v["protocol"] == p].set_index(v[v["protocol"] == p]["claim"].astype(str))
        L.append(f"| {md_cell(p)} | " + " | ".join(
            f"**{rows.loc[k, 'verdict']}**: {md_cell(rows.loc[k, 'measured'])}"
            if k in rows.index else "–" for k in CURVE_CLAIMS) + " |")
    L += ["", f"Claim 16, {ERGODIC_CLAIM.text}, judged on the five families' curves:", "",
          "| protocol | verdict | measured |", "| --- | --- | --- |"]
    for _, r in verdicts[claim == "16"].iterrows():
        L.append(f"| {md_cell(r['protocol'])} | **{r['verdict']}** | {md_cell(r['measured'])} |")
    L += ["", decomposition_text(curves), "", paragraph(verdicts, curves), ""]
    return L
