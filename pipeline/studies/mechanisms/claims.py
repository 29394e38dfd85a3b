"""The mechanisms claims as data (judged from the mechanisms table and the scene's diffusion table).

Rules, fixed before the data:

extremum carrier  (M1–M5) The paper's extremum of D at f0 (Klages et al. 2004: maxima at 54,
               60 and 80 Hz, minima at 58 and 62 Hz) against each grid neighbour f_nb:
               ln D_∞(f0)/D_∞(f_nb) = random walk (ln of the D_0 ratio) + memory (ln of the
               D_∞/D_0 ratio), with paired bootstrap CIs (pipeline.tables.mechanisms,
               bbb.analysis.gk_contrast).  Each side gets ``gk_contrast.carrier`` (memory share of
               the contrast ≥ θ: "memory", ≤ 1 − θ: "random walk", within: "both", CI across an
               edge: "undecided"; θ and the CI level read from the calibration,
               ``bbb.analysis.gk_contrast.calibrated_rule``), the sides are combined by
               ``combine_sides`` ("no extremum" if a side has the wrong sign), once per floor
               period and once per collision.  The verdict is the one both step choices give;
               where they differ it is "undecided" (the split depends on what a step is), where
               one is not measured the other's.  "not measured": f0 is still (no particle left
               its cell: the MSD D is zero at the scene's resolution; or every state creeps),
               the MSD D's CI reaches 0, or the expansion at f0 has not converged.
both sides     (M1b–M5b) the rule of M1–M5 stated over both neighbours and both step choices
               as it reads: a side not measured (a still neighbour, a D ≤ 0, no convergence) or
               not resolved makes the step's verdict that ('not measured' before 'not
               resolved'), never the other side's alone; a step choice not measured makes the
               claim 'not measured'.  (M1–M5 combine with ``combine_sides``, which takes the
               other side alone: kept, frozen, beside them.)
λ ratio        (M6) r = mean λ of the moving particles (x spans ≥ S in λ's window) over the
               scene's f ≥ 66 Hz (the spiral regime) / theirs at 60 Hz (the VHO): larger means
               r > 1 with its CI (ends: mean of the lows / λ_hi(60), mean of the highs /
               λ_lo(60)); frequencies whose λ CI is degenerate or has no moving particle are
               left out of the mean and named.
"""

from __future__ import annotations

import math

import pandas as pd

from bbb.analysis.gk_contrast import Contrast, calibrated_rule, carrier, combine_sides

from ...claims.claim import Band, Claim, Measured, Part, Quantity, measure
from ...claims.measures import row_at
from .cases import (
    carrier_cases,
    lyapunov_cases,
)

__all__ = ["CLAIMS", "EXTREMA", "SIDES", "STEPS", "neighbour_moves", "context", "WORDS",
           "side_contrast", "combine_both_sides"]

#: the paper's extrema of D(f) (Fig. 2 and its text) and their kind
EXTREMA = ((54.0, "max"), (58.0, "min"), (60.0, "max"), (62.0, "min"), (80.0, "max"))
SPIRAL_FROM = 66.0  # Hz: the spiral regime (klages2004 claims)
VHO = 60.0
#: the step choices of the expansion: column suffix -> name
STEPS = {"_coll": "per collision", "": "per period"}
SIDES = ("dn", "up")


def side_contrast(row: pd.Series, step: str, side: str) -> Contrast:
    """The contrast of ``row``'s f with its neighbour on ``side``, from the table's columns."""
    def trio(name: str) -> tuple[float, float, float]:
        return tuple(float(row.get(f"{name}{step}_{side}{s}", math.nan)) for s in ("", "_lo", "_hi"))
    return Contrast(trio("ln_D"), trio("ln_walk"), trio("ln_mem"), trio("share_mem"),
                    float(calibrated_rule()["ci"]))


def neighbour_moves(t: pd.DataFrame, row: pd.Series, side: str) -> bool:
    """Whether ``row``'s f has a neighbour on ``side`` that is not still."""
    f_nb = row.get(f"f_{side}", math.nan)
    nb = None if pd.isna(f_nb) else row_at(t, float(f_nb))
    return nb is not None and not bool(nb.get("still", False))


def _side(t: pd.DataFrame, row: pd.Series, step: str, side: str, kind: str,
          theta: float) -> tuple[str, str]:
    """(verdict, text) of one side: the carrier rule, "not measured" against a still neighbour."""
    f_nb = row.get(f"f_{side}", math.nan)
    if pd.isna(f_nb):
        return "not measured", f"no neighbour {'below' if side == 'dn' else 'above'}"
    nb = row_at(t, float(f_nb))
    if nb is not None and bool(nb.get("still", False)):
        return "not measured", f"vs {f_nb:g} Hz: still there, not measured"
    c = side_contrast(row, step, side)
    if not c.measured:
        return "not measured", f"vs {f_nb:g} Hz: not measured (a D ≤ 0 or not converged)"
    v = carrier(c, kind, theta)
    q = {k: Quantity(*getattr(c, a)).text(".2f") for k, a in
         (("ln D", "total"), ("walk", "walk"), ("memory", "memory"), ("share", "share"))}
    return v, (f"vs {f_nb:g} Hz: ln D ratio {q['ln D']} = walk {q['walk']} + memory "
               f"{q['memory']}, memory share {q['share']} → {v}")


def _unmeasured(r: pd.Series, diff: pd.DataFrame | None, f0: float) -> str:
    """Why the extremum at f0 cannot be split ('' if it can)."""
    if bool(r.get("still", False)):
        return (f"f = {f0:g} Hz is still: {int(r.get('n_left_cell', -1))} particles left their "
                f"cell, creeping fraction {r.get('frac_creep', math.nan):.3g} (D zero at the "
                "scene's resolution)")
    d = row_at(diff, f0) if diff is not None else None
    if d is not None and not d["D_lo"] > 0:
        return f"the MSD D = {d['D']:.3g} [{d['D_lo']:.3g}, {d['D_hi']:.3g}] mm²/s reaches 0"
    conv = [name for step, name in STEPS.items() if f"converged{step}" in r
            and not pd.isna(r[f"converged{step}"]) and not bool(r[f"converged{step}"])]
    if conv:
        return f"the expansion at {f0:g} Hz has not converged ({', '.join(conv)})"
    return ""


def combine_both_sides(verdicts) -> str:
    """One verdict from both sides' carrier verdicts, each side required (M1b–M5b): 'no
    extremum' if a side has the wrong sign; else 'not measured' if a side is, 'not resolved'
    if a side is; else ``combine_sides``."""
    if "wrong sign" in verdicts:
        return "no extremum"
    for gap in ("not measured", "not resolved"):
        if gap in verdicts:
            return gap
    return combine_sides(verdicts)


@measure("extremum_carrier")
def extremum_carrier(claim: Claim, ctx) -> Measured:
    t = ctx["tables"].get(claim.scene)
    if t is None or "ln_D_dn" not in t:
        return Measured(missing="no mechanisms table with contrasts")
    r = row_at(t, claim.f0)
    if r is None:
        return Measured(missing=f"f = {claim.f0:g} not in the mechanisms table")
    why = _unmeasured(r, ctx["tables"].get(f"{claim.scene}_diffusion"), claim.f0)
    if why:
        return Measured(missing=why)
    theta, kind = float(calibrated_rule()["theta"]), claim.options["kind"]
    both = bool(claim.options.get("both_sides"))
    texts, by_step = [], {}
    for step, name in STEPS.items():
        if f"ln_D{step}_dn" not in t:
            if both:
                texts.append(f"{name} — no contrasts in the table")
                by_step[name] = "not measured"
            continue
        sides = [_side(t, r, step, s, kind, theta) for s in SIDES]
        by_step[name] = (combine_both_sides if both else combine_sides)([v for v, _ in sides])
        texts.append(f"{name} — " + "; ".join(x for _, x in sides) + f" ⇒ {by_step[name]}")
    if both:
        gaps = [v for v in ("not measured", "not resolved") if v in by_step.values()]
        if gaps:
            return Measured(text=". ".join(texts), verdict=gaps[0],
                            note="Judged against both neighbours under both step choices: "
                                 f"{', '.join(k for k, v in by_step.items() if v in gaps)} "
                                 f"{gaps[0]}.")
    decided = {k: v for k, v in by_step.items() if v != "not measured"}
    if not decided:
        return Measured(missing="not measured against either neighbour: " + ". ".join(texts))
    verdicts = set(decided.values())
    verdict = verdicts.pop() if len(verdicts) == 1 else "undecided"
    note = ("" if len(set(decided.values())) == 1 else
            "The two step choices split the contrast differently ("
            + ", ".join(f"{k}: {v}" for k, v in decided.items()) + "): undecided.")
    if len(decided) < len(by_step):
        note += " Only " + ", ".join(decided) + " measured."
    return Measured(text=". ".join(texts), verdict=verdict, note=note.strip())


@measure("lyapunov_ratio")
def lyapunov_ratio(claim: Claim, ctx) -> Measured:
    t = ctx["tables"].get(claim.scene)
    col = claim.options.get("column", "lam_move")
    if t is None or col not in t:
        return Measured(missing=f"no mechanisms table with {col}")
    vho = row_at(t, VHO)
    sp = t[t["f"] >= SPIRAL_FROM]
    use = sp[sp[f"{col}_lo"].notna() & sp[col].notna()]
    left = sp[~sp.index.isin(use.index)]
    if vho is None or use.empty or not vho[f"{col}_lo"] > 0:
        why = "degenerate CI or no moving particle" if vho is not None else "not in the table"
        return Measured(missing=f"λ of the moving particles at {VHO:g} Hz ({why}) or at "
                        f"f ≥ {SPIRAL_FROM:g} Hz not measured")
    q = Quantity(use[col].mean() / vho[col], use[f"{col}_lo"].mean() / vho[f"{col}_hi"],
                 use[f"{col}_hi"].mean() / vho[f"{col}_lo"], "", "ends of the λ CIs")
    txt = (f"moving particles: mean λ(f ≥ {SPIRAL_FROM:g}, {len(use)} f) = {use[col].mean():.3g} "
           f"1/s, λ({VHO:g}) = {vho[col]:.3g} [{vho[f'{col}_lo']:.3g}, {vho[f'{col}_hi']:.3g}] "
           f"1/s ({int(vho.get('n_lam_move', -1))} moving particles); ratio {q.text('.3f')}")
    if not left.empty:
        txt += "; left out (degenerate CI or no moving particle): " + ", ".join(
            f"{f:g}" for f in left["f"]) + " Hz"
    return Measured([Part("λ ratio", q, txt)])


def _rule_why() -> str:
    rule = calibrated_rule()
    return (f"rule: the memory share of each neighbour's log contrast, CI at "
            f"{rule['ci']:.0%}, against θ = {rule['theta']:.3g} (bbb.analysis.gk_contrast; calibrated on "
            f"AR(1) sequences with a known split: worst wrong-verdict rate "
            f"{rule['worst_wrong']:.2f}, {rule['source']})")


_SCOPE = {"scenes": ["mechanisms"], "families": ["rest"],
          "frequencies": "f0 and its grid neighbours"}
_REG_M, _REG_M6 = "2026-11-25 0e548ac", "2026-11-23 8178e6b"
_REG_NEW = "2026-11-28 e570863"
CLAIMS = [
    Claim(f"The {kind}imum of D at {f0:g} Hz: carried by the random walk (D_0) or by the "
          "memory (D_∞/D_0), against both grid neighbours", extremum_carrier, "mechanisms",
          Band(-math.inf, math.inf, _rule_why()), f0=f0, options={"kind": kind},
          id=f"M{i}", registered=_REG_M, scope=_SCOPE, cases=carrier_cases(f0, kind))
    for i, (f0, kind) in enumerate(EXTREMA, 1)
] + [
    Claim(f"The {kind}imum of D at {f0:g} Hz: carried by the random walk (D_0) or by the "
          "memory (D_∞/D_0), judged against both grid neighbours under both step choices",
          extremum_carrier, "mechanisms",
          Band(-math.inf, math.inf, _rule_why() + "; both sides and both step choices "
               "required: a side or step not measured (not resolved) makes the claim so"),
          f0=f0, options={"kind": kind, "both_sides": True}, id=f"M{i}b",
          registered=_REG_NEW, supersedes=f"M{i}", scope=_SCOPE,
          cases=carrier_cases(f0, kind, both=True))
    for i, (f0, kind) in enumerate(EXTREMA, 1)
] + [
    Claim(f"λ is larger in the spiral regime (f ≥ {SPIRAL_FROM:g} Hz) than at the VHO "
          f"({VHO:g} Hz), for the particles that move", lyapunov_ratio, "mechanisms",
          Band(1.0, math.inf, "rule: ratio of the mean λ of moving particles over f ≥ 66 Hz "
               "to theirs at 60 Hz above 1"), f0=VHO, id="M6", registered=_REG_M6,
          scope={**_SCOPE, "frequencies": "60 Hz and f ≥ 66 Hz"}, cases=lyapunov_cases),
]
CLAIMS.sort(key=lambda c: (int(c.id[1:].rstrip("b")), c.id))


def context(tables, stores=None) -> dict:
    """The context the claims are judged in: the scene's mechanisms and diffusion tables."""
    return {"tables": {"mechanisms": tables.get("mechanisms"),
                       "mechanisms_diffusion": tables.get("mechanisms_diffusion")}}


#: the section's own words
WORDS = ("M1–M5 split the contrast of D between each paper extremum and its grid neighbours, "
         "ln D_∞(f0)/D_∞(f_nb) = ln D_0 ratio (random walk) + ln (D_∞/D_0) ratio (memory), "
         "per floor period and per collision, with paired bootstrap CIs; the verdict names the "
         "part that carries the extremum: **memory**, **random walk**, **both**, **undecided** "
         "(a CI across the rule's edges, or the two step choices differ), **no extremum** (a "
         "neighbour's contrast has the wrong sign), **not resolved** (no contrast resolved), "
         "**not measured** (nothing moves at f0, or the expansion has not converged). "
         "pipeline/studies/mechanisms/claims.py states the rules.")
