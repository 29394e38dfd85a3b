"""The protocol section of REPORT.md: its words, its records (the verdicts of claims 1, 2, 4 and
5 per protocol and of claim 16 per (T, definition), read from the table ``protocol_verdicts``),
the decomposition check, and a paragraph generated from the tables (``protocol_verdicts``,
``protocol_curves``; every number read from them)."""

from __future__ import annotations

import math
from collections.abc import Mapping

import pandas as pd

from bbb.analysis.period1 import frequency_at, gamma_prime
from bbb.params import Params

from ...claims.claim import POSITIVE, Row
from ...claims.section import Section, verdict_lines
from .claims import CURVE_CLAIMS, ERGODIC_CLAIM, reproducing
from .tables import MIXTURE

__all__ = ["SHORT", "WORDS", "LABELS", "SECTION", "verdicts", "further", "paragraph",
           "decomposition_text"]

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
    """How well D_all = share × D_moving holds: the points checked (every point for
    ``displaced``; those with a D for ``moving_time``), those within the bound the still
    particles allow, those resolved within D_all's CI."""
    parts = []
    for d in ("displaced", "moving_time"):
        t = curves[curves["definition"] == d]
        checked = t[t["residual"].notna()]
        parts.append(f"{d}: the identity holds within the still particles' bound at "
                     f"{int(checked['holds'].astype(bool).sum())} of the {len(checked)} points "
                     f"checked, and share × D_moving lies within D_all's 95 % CI at "
                     f"{int(checked['approx_ok'].astype(bool).sum())}")
    return "D_all = share × D_moving: " + "; ".join(parts) + "."


def _listed(v: pd.DataFrame, key: str, verdicts: tuple[str, ...], most: int = 3) -> str:
    """The protocols whose claim ``key`` has one of ``verdicts``, with what was measured, when
    there are at most ``most`` of them; else their number."""
    sel = v[(v["claim"].astype(str) == key) & v["verdict"].isin(verdicts)]
    if len(sel) > most:
        return f"{len(sel)} protocols"
    return "; ".join(f"{r['protocol']} ({r['measured']})" for _, r in sel.iterrows()) or "none"


def _first_rest(curves: pd.DataFrame) -> float:
    """The lowest f (Hz) at which a particle started at rest is displaced (any T), or NaN."""
    disp = curves[curves["definition"] == "displaced"]
    rest = disp[(disp["ensemble"] == "rest") & (disp["n_moving"] > 0)]
    return float(rest["f"].min()) if len(rest) else math.nan


def _onset_text(curves: pd.DataFrame) -> str:
    """Where particles start to move: the lowest f at which any particle started at rest is
    displaced, and the displaced mixture's D at the lowest f studied."""
    disp = curves[curves["definition"] == "displaced"]
    f_rest = _first_rest(curves)
    f0 = float(disp["f"].min())
    low = disp[(disp["ensemble"] == MIXTURE) & ((disp["f"] - f0).abs() < 1e-6)]["D"]
    out = (f"particles started at rest are first displaced beyond one arc period at "
           f"{f_rest:g} Hz" if math.isfinite(f_rest) else
           "no particle started at rest is displaced beyond one arc period at any f studied")
    if len(low) and low.notna().any():
        out += (f", while the displaced particles of the mixture already diffuse at the lowest "
                f"f studied ({f0:g} Hz: D = {low.min():.3g}–{low.max():.3g} mm²/s over T)")
    return out


def _decay_text(curves: pd.DataFrame) -> str:
    """The mixture's share of time moving at 54 and 57 Hz for the shortest and longest T,
    beside the flat-floor limit of the 1/1 orbit."""
    Ts = sorted(set(curves["T"].astype(float)))
    if not Ts or not (curves["ensemble"] == MIXTURE).any():
        return ""
    p = Params.preset("klages2004", f=60.0)
    f2 = frequency_at(gamma_prime(p.alpha), p.A, p.g)
    sh = {(T, f): _value(curves, MIXTURE, T, "moving_time", f, "share")
          for T in (Ts[0], Ts[-1]) for f in (54.0, 57.0)}
    return ("The mixture's share of time spent moving is " + "; ".join(
        f"{_pct(sh[T, 54.0])} at 54 Hz and {_pct(sh[T, 57.0])} at 57 Hz for T = {T:g} s"
        for T in (Ts[0], Ts[-1])) + f" (the flat floor's 1/1 orbit is stable up to "
        f"{f2:.1f} Hz): above it the bouncing state decays within a run, so only short runs "
        "keep moving particles there. ")


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
        sel = v[v["protocol"].isin(ok)]
        text += ("Every one of them " + ("counts only moving particles"
                                          if "all" not in set(sel["definition"]) else
                                          "includes the plain average over all particles")
                 + ", starts from " + ", ".join(sorted(set(sel["ensemble"])))
                 + " and analyses runs of "
                 + ", ".join(f"{T:g}" for T in sorted(set(sel["T"].astype(float)))) + " s. ")
    else:
        one = {p: m for p, m in missing.items() if len(m) == 1}
        text = (f"None of the {n} protocols reproduces {', '.join(SHORT.values())} together. "
                + ("Closest (all but one): " + "; ".join(
                    f"{p} (not {SHORT.get(m[0], 'claim ' + m[0])})" for p, m in one.items()) + ". "
                   if one else ""))
    text += ("Each claim alone: " + "; ".join(f"{SHORT[k]} under {len(ps)}" for k, ps in
                                              per.items()) + " protocols. ")
    text += (f"The maximum near 54 Hz is found under {_listed(v, '2', POSITIVE)}, inconclusive "
             f"under {_listed(v, '2', ('inconclusive',))}. ")
    if not per["1"]:
        text += f"No onset lies near 50 Hz: {_onset_text(curves)}. "
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
                             f"(T = {T:g} s)" for T in (T0, T1))
                 + ": the share does not rise enough to turn the falling D of the moving "
                   "particles into a maximum. " if dm[T1, 54.0] < dm[T1, 50.0] else ". ")
    text += _decay_text(curves)
    if ok:
        text += ("So the paper's landmarks near onset are those of a D measured under such a "
                 "protocol; with the plain average over particles at rest (Fig. 2's) they are not.")
    else:
        text += ("So the paper's D near onset is not what any one of these ensembles, run "
                 "lengths and definitions of moving gives: its landmarks 50, 54 and 58 Hz "
                 "cannot all be read off one such measurement of this model.")
        p = Params.preset("klages2004", f=60.0)
        f1 = math.sqrt(p.g / p.A) / (2 * math.pi)
        near = sorted(set(v[(v["claim"].astype(str) == "2") & v["verdict"].isin(
            (*POSITIVE, "inconclusive"))]["definition"]))
        if near:
            text += (f" A maximum near 54 Hz comes closest under {', '.join(near)} (the moving "
                     "particles' D over short runs); the paper's onset near 50 Hz sits where "
                     f"Γ = 1 (f = {f1:.1f} Hz) first lets a particle at rest lift off, which "
                     "suggests an ensemble started at rest, whose particles here do not leave "
                     f"their arc below {_first_rest(curves):g} Hz.")
    return text


#: the section's own words
WORDS = ("Scene `pipeline/studies/protocol/scenes/protocol.toml`: five initial-condition "
         "families (rest; dropped from 0–2 and 2–10 mm; launched at 0–200 and 200–400 mm/s) "
         "and their mixture, 46–62 Hz, each run's first T s analysed as bbb reduce analyses a "
         "run of length T, and D averaged over all particles or over the moving ones under "
         "two definitions fixed before the data (`bbb.analysis.moving`). Verdicts by the "
         "paper's claim records and rules above, unchanged, with each protocol's D(f) as the "
         "Fig. 2 curve.")
#: the claims' names in the verdict table
LABELS = tuple(f"{k}: {SHORT[k]}" for k in CURVE_CLAIMS)
SECTION = Section("Protocol: how the paper may have measured D near onset", WORDS,
                  layout="by line", claim_header="protocol")


def _records(verdicts: pd.DataFrame | None, keys) -> dict[str, list[Row]]:
    """{protocol: its rows of the claims ``keys``} of the verdicts table (its records)."""
    if verdicts is None or verdicts.empty:
        return {}
    v = verdicts.assign(claim=verdicts["claim"].astype(str))
    v = v[v["claim"].isin(keys)]
    claims = {**CURVE_CLAIMS, "16": ERGODIC_CLAIM}
    out: dict[str, list[Row]] = {}
    for p in dict.fromkeys(v["protocol"]):
        rows = v[v["protocol"] == p].set_index("claim")
        out[p] = [Row(claims[k].text, str(rows.loc[k, "measured"]), str(rows.loc[k, "verdict"]),
                      id=k) if k in rows.index else
                  Row(claims[k].text, "no row in the verdicts table", "not measured", id=k)
                  for k in keys]
    return out


def verdicts(tables: Mapping[str, pd.DataFrame]) -> dict[str, list[Row]]:
    """The records of claims 1, 2, 4 and 5 per protocol, from the table ``protocol_verdicts``
    (judged while drawing, :func:`~.claims.verdicts_table`)."""
    return _records(tables.get("protocol_verdicts"), tuple(CURVE_CLAIMS))


def further(tables: Mapping[str, pd.DataFrame], records=None) -> list[str]:
    """After the verdicts: claim 16 per (T, definition), the decomposition check and the
    paragraph generated from the tables; or why nothing was measured."""
    v, curves = tables.get("protocol_verdicts"), tables.get("protocol_curves")
    if v is None or curves is None or v.empty:
        return ["Not measured: no protocol tables (scene protocol).", ""]
    c16 = _records(v, ("16",))
    return (["", f"Claim 16, {ERGODIC_CLAIM.text}, judged on the five families' curves:", ""]
            + verdict_lines(SECTION, c16)
            + ["", decomposition_text(curves), "", paragraph(v, curves), ""])
