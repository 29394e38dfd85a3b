"""The impact-phase claims as data, judged from the scene's ``impacts`` table.

Rules, fixed before the data (registered in the commit named by each claim's ``registered``):

upward phase  (I1) At every frequency of the scene from :data:`F_FROM` on (particles diffuse
              there: the paper finds ergodic motion for f ≥ 58 Hz) and for each family, the
              share of the collisions while the floor moves up (ω t mod 2π in (π/2, 3π/2),
              the floor at −A sin ω t), ``up_share``, with its bootstrap interval over
              particles: the impacts cluster in the upward phase where the whole interval
              lies above 0.5 (a uniform phase gives 0.5: the floor moves up half of the
              period).  Each (f, family) is a part; the parts are combined by the generic rule
              (all agree: agrees; a mix: partly); a part in scope without a value or an
              interval makes the claim 'not measured' (the rule is stated over all parts).
lag-1 sign    (I2) At the same (f, family), the correlation of the post-collision vx one
              collision apart about each particle's own mean, ``vx_within_1``, with its
              bootstrap interval: negative (the horizontal velocity reverses more often than it
              keeps its sign from one collision to the next) where the whole interval lies
              below 0.  The pooled correlation ``vx_corr_1`` is not judged: differences between
              the particles' mean vx push it toward +1.  Parts and combination as for I1.

Expectations, stated before the data: I1 is the kinematics of a floor moving into the
particle (collisions are more frequent while the floor approaches; Sci. Rep. 2020,
"Collision-enhanced friction of a bouncing ball on a rough vibrating surface", finds impacts
cluster in the upward phase of a rough vibrating surface).  For I2 the literature on rough
vibrated floors (Prevost, Egolf & Urbach, PRL 89, 084301, 2002) leads to a negative
correlation; the paper's own model says nothing of the sign (its spiral argument assumes the
collisions lose their memory, a correlation of 0): the data judge.
"""

from __future__ import annotations

import math

import pandas as pd

from ...claims.claim import Band, Claim, Measured, Part, Quantity, measure
from .cases import lag_cases, phase_cases

__all__ = ["SCENE", "F_FROM", "CLAIMS", "context", "in_scope"]

SCENE = "impacts"
#: Hz: the claims' frequencies start here (the paper: ergodic motion for f ≥ 58 Hz)
F_FROM = 60.0
_CI = "bootstrap over particles"


def in_scope(t: pd.DataFrame, f_from: float) -> pd.DataFrame:
    """The rows of the table the claims judge: f ≥ ``f_from``, by f and family."""
    return t[t["f"] >= f_from].sort_values(["f", "family"], kind="stable")


@measure("impacts.column_by_f")
def column_by_f(claim: Claim, ctx) -> Measured:
    """One part per (f, family) in scope: the claim's column with its interval; a part
    without a value or an interval is a part 'not measured' (its status says why)."""
    t = ctx["tables"].get(claim.scene)
    col = claim.options["column"]
    if t is None or col not in t:
        return Measured(missing=f"no {claim.scene} table with {col}")
    f_from = float(claim.options.get("f_from", F_FROM))
    rows = in_scope(t, f_from)
    if rows.empty:
        return Measured(missing=f"no frequency f ≥ {f_from:g} Hz in the {claim.scene} table")
    parts, blank = [], []
    for _, r in rows.iterrows():
        label = f"{r['f']:g} Hz {r['family']}"
        v, lo, hi = (float(r.get(c, math.nan)) for c in (col, f"{col}_lo", f"{col}_hi"))
        if math.isnan(v) or math.isnan(lo) or math.isnan(hi):
            why = str(r.get("impacts_status", "")) if pd.notna(r.get("impacts_status")) else ""
            blank.append(f"{label}: {why or 'blank'}")
            parts.append(Part(label, Quantity(math.nan), "not measured"))
            continue
        parts.append(Part(label, Quantity(v, lo, hi, "", _CI), f"{v:.3f} [{lo:.3f}, {hi:.3f}]"))
    note = ("Not measured at " + "; ".join(blank) + ".") if blank else ""
    return Measured(parts, note=note)


_SCOPE = {"scenes": [SCENE], "families": ["rest", "launched"],
          "frequencies": f"the scene's f ≥ {F_FROM:g} Hz"}
_REG = "2026-11-28 5aa025c"
CLAIMS = [
    Claim("Impacts cluster in the floor's upward phase: more than half of the collisions "
          "while the floor moves up, at each f where particles diffuse", column_by_f, SCENE,
          Band(0.5, math.inf, "a uniform floor phase puts half of the impacts in the upward "
               "half period; clustering means the whole bootstrap interval above 0.5"),
          f0=F_FROM, options={"column": "up_share", "f_from": F_FROM}, id="I1",
          registered=_REG, scope=_SCOPE, all_parts=True, cases=phase_cases),
    Claim("The horizontal velocity reverses across a collision: the lag-1 correlation of "
          "the post-collision vx about each particle's own mean is negative, at each f where "
          "particles diffuse", column_by_f, SCENE,
          Band(-math.inf, 0.0, "no memory across a collision gives 0; negative means the "
               "whole bootstrap interval below 0"),
          f0=F_FROM, options={"column": "vx_within_1", "f_from": F_FROM}, id="I2",
          registered=_REG, scope=_SCOPE, all_parts=True, cases=lag_cases),
]


def context(tables, stores=None) -> dict:
    """The context the claims are judged in: the scene's impacts table."""
    return {"tables": {SCENE: tables.get(SCENE)}}
